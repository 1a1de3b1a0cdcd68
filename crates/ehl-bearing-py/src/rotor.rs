//! Bindings of the rotor time integrator (`ehl_bearing::rotor`): `RotorModel`.

use crate::{element_of, err, square};
use ehl_bearing::rotor::{
    BearingSite, CageMotion, Coupling, RotorMatrices, RotorModel, RotorProgress, SpeedProfile,
    Start, StaticSolution, TimeOptions, TimeResponse, Unbalance,
};
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A rotor (mass, damping, gyroscopic and stiffness matrices without bearings, SI) on our force
/// elements, with unbalances and a constant force (gravity), solved in Rust. Equation of motion
/// (ROSS's, with the bearings added): M q̈ + (C + Ω·G) q̇ + K q = f_const + f_unbalance(t)
/// − Σ_b L_bᵀ·R_b(L_b q + o_b, L_b q̇), R_b the bearing's reaction (load on its inner ring).
#[pyclass(module = "ehl_bearing._native", name = "RotorModel")]
pub struct PyRotorModel {
    matrices: RotorMatrices,
    constant_force: Vec<f64>,
    bearings: Vec<BearingSite>,
    unbalances: Vec<Unbalance>,
}

impl PyRotorModel {
    fn model(&self) -> PyResult<RotorModel> {
        RotorModel::new(
            self.matrices.clone(),
            self.bearings.clone(),
            self.unbalances.clone(),
            self.constant_force.clone(),
        )
        .map_err(err)
    }
}

fn arr5(v: Vec<f64>, what: &str) -> PyResult<[f64; 5]> {
    let n = v.len();
    v.try_into()
        .map_err(|_| err(format!("{what}: expected 5 values, got {n}")))
}

fn global<'py>(py: Python<'py>, v: &[f64], n: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows: Vec<Vec<f64>> = v.chunks(n).map(|r| r.to_vec()).collect();
    PyArray2::from_vec2_bound(py, &rows).map_err(err)
}

fn blocks<'py>(py: Python<'py>, m: &[[[f64; 5]; 5]]) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let v: Vec<Vec<Vec<f64>>> = m
        .iter()
        .map(|b| b.iter().map(|r| r.to_vec()).collect())
        .collect();
    PyArray3::from_vec3_bound(py, &v).map_err(err)
}

fn fives<'py>(py: Python<'py>, m: &[[f64; 5]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let v: Vec<Vec<f64>> = m.iter().map(|r| r.to_vec()).collect();
    PyArray2::from_vec2_bound(py, &v).map_err(err)
}

fn static_dict<'py>(py: Python<'py>, s: &StaticSolution) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new_bound(py);
    d.set_item(
        "displacement",
        PyArray1::from_slice_bound(py, &s.displacement),
    )?;
    d.set_item("bearing_displacement", fives(py, &s.bearing_displacement)?)?;
    d.set_item("reactions", fives(py, &s.reactions)?)?;
    d.set_item("bearing_stiffness", blocks(py, &s.bearing_stiffness)?)?;
    d.set_item("bearing_damping", blocks(py, &s.bearing_damping)?)?;
    d.set_item("iterations", s.iterations)?;
    d.set_item("residual_n", s.residual_n)?;
    Ok(d)
}

fn vec_n(a: Option<PyReadonlyArray1<'_, f64>>, n: usize, what: &str) -> PyResult<Vec<f64>> {
    match a {
        None => Ok(vec![0.0; n]),
        Some(a) => {
            // Any layout (e.g. the real part of a complex array, a column): copy element-wise.
            let v: Vec<f64> = a.as_array().iter().copied().collect();
            if v.len() != n {
                return Err(err(format!("{what}: expected {n} values, got {}", v.len())));
            }
            Ok(v)
        }
    }
}

#[pymethods]
impl PyRotorModel {
    /// A rotor from its n×n matrices (numpy, SI) without bearings: `mass` M, `damping` C,
    /// `gyroscopic` G per unit shaft speed (the damping at speed Ω is C + Ω·G, as ROSS's
    /// `rotor.G()`), `stiffness` K; `constant_force` (n,) in N and N·m (e.g. gravity).
    #[new]
    #[pyo3(signature = (mass, damping, gyroscopic, stiffness, constant_force = None))]
    fn new(
        mass: PyReadonlyArray2<'_, f64>,
        damping: PyReadonlyArray2<'_, f64>,
        gyroscopic: PyReadonlyArray2<'_, f64>,
        stiffness: PyReadonlyArray2<'_, f64>,
        constant_force: Option<PyReadonlyArray1<'_, f64>>,
    ) -> PyResult<Self> {
        let n = mass.shape()[0];
        let matrices = RotorMatrices::new(
            n,
            square(&mass, n, "mass")?,
            square(&damping, n, "damping")?,
            square(&gyroscopic, n, "gyroscopic")?,
            square(&stiffness, n, "stiffness")?,
        )
        .map_err(err)?;
        let constant_force = vec_n(constant_force, n, "constant_force")?;
        Ok(PyRotorModel {
            matrices,
            constant_force,
            bearings: Vec::new(),
            unbalances: Vec::new(),
        })
    }

    /// Number of rotor DOFs n.
    #[getter]
    fn dofs(&self) -> usize {
        self.matrices.dofs
    }

    /// Number of bearings.
    #[getter]
    fn bearing_count(&self) -> usize {
        self.bearings.len()
    }

    /// Put force element `element` (a `LawElement` or `TrendForceElement`) between the rotor and
    /// the ground (outer ring fixed, inner ring turning with the shaft): `dofs` are the rotor DOF
    /// indices carrying our x (axial), y, z, θy, θz (None: that bearing DOF held at its offset);
    /// `signs` ±1 per DOF (bearing DOF = offset + sign·rotor DOF; a bearing mounted the other
    /// way round: x, θy, θz negated); `offset` the bearing displacement when the rotor DOFs are
    /// zero (m, m, m, rad, rad; e.g. the axial preload approach).
    #[pyo3(signature = (element, dofs, signs = None, offset = None))]
    fn add_bearing(
        &mut self,
        element: &Bound<'_, PyAny>,
        dofs: Vec<Option<usize>>,
        signs: Option<Vec<f64>>,
        offset: Option<Vec<f64>>,
    ) -> PyResult<()> {
        let e = element_of(element)?;
        let n = dofs.len();
        let dofs: [Option<usize>; 5] = dofs
            .try_into()
            .map_err(|_| err(format!("dofs: expected 5 indices, got {n}")))?;
        let mut site = BearingSite::new(e, dofs);
        if let Some(s) = signs {
            site.signs = arr5(s, "signs")?;
        }
        if let Some(o) = offset {
            site = site.with_offset(arr5(o, "offset")?);
        }
        let mut bearings = self.bearings.clone();
        bearings.push(site);
        // Validate now (indices, signs, offsets), so that the error points at this call.
        RotorModel::new(
            self.matrices.clone(),
            bearings.clone(),
            self.unbalances.clone(),
            self.constant_force.clone(),
        )
        .map_err(err)?;
        self.bearings = bearings;
        Ok(())
    }

    /// An unbalance `mass_eccentricity_kg_m` (kg·m) on a node's two lateral DOFs `dofs` (ROSS x,
    /// y; the shaft turns from the first toward the second), phase `phase_rad` at rotation angle
    /// 0: force m·e·[Ω²·(cos φ, sin φ) + Ω̇·(−sin φ, cos φ)], φ = rotation angle + phase.
    #[pyo3(signature = (dofs, mass_eccentricity_kg_m, phase_rad = 0.0))]
    fn add_unbalance(
        &mut self,
        dofs: (usize, usize),
        mass_eccentricity_kg_m: f64,
        phase_rad: f64,
    ) -> PyResult<()> {
        let mut unbalances = self.unbalances.clone();
        unbalances.push(Unbalance {
            dofs: [dofs.0, dofs.1],
            mass_eccentricity_kg_m,
            phase_rad,
        });
        RotorModel::new(
            self.matrices.clone(),
            self.bearings.clone(),
            unbalances.clone(),
            self.constant_force.clone(),
        )
        .map_err(err)?;
        self.unbalances = unbalances;
        Ok(())
    }

    /// Static equilibrium at shaft speed `speed_rad_s` under the constant force (no unbalance):
    /// a dict with `displacement` (n,), per bearing `bearing_displacement` and `reactions`
    /// (B, 5; ours), `bearing_stiffness`, `bearing_damping` (B, 5, 5), `iterations`,
    /// `residual_n`.
    fn static_equilibrium(&self, py: Python<'_>, speed_rad_s: f64) -> PyResult<PyObject> {
        let m = self.model()?;
        let s = py
            .allow_threads(|| m.static_equilibrium(speed_rad_s))
            .map_err(err)?;
        Ok(static_dict(py, &s)?.into_any().unbind())
    }

    /// The rotor linearized about its static equilibrium at `speed_rad_s`: a dict with `mass`,
    /// `damping` (C + Σ bearing C), `gyroscopic`, `stiffness` (K + Σ bearing K), all (n, n),
    /// and `static` (the equilibrium, as `static_equilibrium`). Simulating these matrices with
    /// no bearings and no constant force gives the motion about that equilibrium.
    fn linearized(&self, py: Python<'_>, speed_rad_s: f64) -> PyResult<PyObject> {
        let m = self.model()?;
        let (lin, s) = py
            .allow_threads(|| m.linearized(speed_rad_s))
            .map_err(err)?;
        let n = lin.dofs;
        let d = PyDict::new_bound(py);
        d.set_item("mass", global(py, &lin.mass, n)?)?;
        d.set_item("damping", global(py, &lin.damping, n)?)?;
        d.set_item("gyroscopic", global(py, &lin.gyroscopic, n)?)?;
        d.set_item("stiffness", global(py, &lin.stiffness, n)?)?;
        d.set_item("static", static_dict(py, &s)?)?;
        Ok(d.into_any().unbind())
    }

    /// Time response (Newmark average acceleration, in Rust; releases the GIL).
    ///
    /// Speed: constant `speed_rad_s`, or a run-up `ramp = (start_rad_s, end_rad_s, duration_s)`
    /// (then constant). `step_s`, `duration_s` in s; every `record_every`-th step recorded (the
    /// initial state always), the DOFs `record_dofs` (default all). `coupling`: "implicit" (the
    /// bearing forces at the new time, Newton on the bearing DOFs; stable) or "lagged" (the
    /// previous step's forces as an explicit load, as ROSS's `add_to_RHS`). `cage_angle_rad`:
    /// None lets every cage roll at its bearing's operating cage speed (the load-weighted mean
    /// orbital speed of its balls, updated every step; ball passes at Z·f_cage), a number holds
    /// them there. Start: the static equilibrium at the initial speed, or `start_displacement`
    /// and `start_velocity` (n,). `progress(step, steps, time_s)` is called about a hundred
    /// times; an exception it raises stops the run and is raised from `simulate` (so a callback
    /// can cancel), as is Ctrl-C (KeyboardInterrupt). `time_limit_s` bounds the wall time:
    /// beyond it the run stops with `EhlBearingError` naming the step and time reached.
    ///
    /// Returns a dict of numpy arrays: `time_s`, `speed_rad_s` (R,), `record_dofs`,
    /// `displacement` (R, len(record_dofs)), `cage_angle_rad` and `cage_speed_rad_s` (R, B; the
    /// operating cage speed, rad/s), `bearing_displacement`
    /// and `bearing_reaction` (R, B, 5; ours), and `steps`, `newton_iterations`,
    /// `max_newton_iterations`, `steps_outside_range`, `breakdown` (dict: `total_s`,
    /// `bearing_s`, `factorization_s`). Raises `EhlBearingError` if a step's Newton iteration
    /// fails or the response diverges (with the step and time).
    #[pyo3(signature = (step_s, duration_s, speed_rad_s = None, ramp = None, record_every = 1, record_dofs = None, coupling = "implicit", cage_angle_rad = None, start_displacement = None, start_velocity = None, progress = None, time_limit_s = None))]
    // The arguments are the Python keyword interface of `RotorModel.simulate`.
    #[allow(clippy::too_many_arguments)]
    fn simulate(
        &self,
        py: Python<'_>,
        step_s: f64,
        duration_s: f64,
        speed_rad_s: Option<f64>,
        ramp: Option<(f64, f64, f64)>,
        record_every: usize,
        record_dofs: Option<Vec<usize>>,
        coupling: &str,
        cage_angle_rad: Option<f64>,
        start_displacement: Option<PyReadonlyArray1<'_, f64>>,
        start_velocity: Option<PyReadonlyArray1<'_, f64>>,
        progress: Option<PyObject>,
        time_limit_s: Option<f64>,
    ) -> PyResult<PyObject> {
        if let Some(t) = time_limit_s {
            if !(t.is_finite() && t > 0.0) {
                return Err(err(format!(
                    "time_limit_s = {t}: expected a finite number of seconds > 0"
                )));
            }
        }
        let profile = speed_profile(speed_rad_s, ramp)?;
        let options = TimeOptions {
            step_s,
            duration_s,
            record_every,
            record_dofs: record_dofs.unwrap_or_default(),
            coupling: coupling_of(coupling)?,
            cage: match cage_angle_rad {
                None => CageMotion::Rolling,
                Some(a) => CageMotion::Fixed { angle_rad: a },
            },
            start: start_of(start_displacement, start_velocity, self.matrices.dofs)?,
            ..TimeOptions::default()
        };
        let m = self.model()?;
        let r = simulate_interruptible(py, &m, &profile, &options, progress, time_limit_s)?;
        Ok(response_dict(py, &r, self.bearings.len())?
            .into_any()
            .unbind())
    }
}

/// The shaft speed of `simulate`: constant `speed_rad_s`, or the run-up `ramp`
/// (start_rad_s, end_rad_s, duration_s); exactly one of them.
fn speed_profile(
    speed_rad_s: Option<f64>,
    ramp: Option<(f64, f64, f64)>,
) -> PyResult<SpeedProfile> {
    match (speed_rad_s, ramp) {
        (Some(s), None) => Ok(SpeedProfile::Constant { speed_rad_s: s }),
        (None, Some((a, b, d))) => Ok(SpeedProfile::Ramp {
            start_rad_s: a,
            end_rad_s: b,
            duration_s: d,
        }),
        (None, None) => Err(err(
            "no shaft speed given: pass speed_rad_s (constant speed, rad/s) or ramp = \
             (start_rad_s, end_rad_s, duration_s) (a run-up)",
        )),
        (Some(s), Some(r)) => Err(err(format!(
            "both speed_rad_s = {s} and ramp = {r:?} given: pass one of them \
             (speed_rad_s for a constant speed, ramp for a run-up)"
        ))),
    }
}

/// The coupling option by its name, "implicit" or "lagged".
fn coupling_of(name: &str) -> PyResult<Coupling> {
    match name {
        "implicit" => Ok(Coupling::Implicit),
        "lagged" => Ok(Coupling::Lagged),
        other => Err(err(format!(
            "coupling = {other:?}: expected \"implicit\" or \"lagged\""
        ))),
    }
}

/// The initial state: the given displacements and rates (n each, zeros for the one not
/// given), or the static equilibrium when neither is given.
fn start_of(
    displacement: Option<PyReadonlyArray1<'_, f64>>,
    velocity: Option<PyReadonlyArray1<'_, f64>>,
    n: usize,
) -> PyResult<Start> {
    Ok(if displacement.is_some() || velocity.is_some() {
        Start::Given {
            displacement: vec_n(displacement, n, "start_displacement")?,
            velocity: vec_n(velocity, n, "start_velocity")?,
        }
    } else {
        Start::StaticEquilibrium
    })
}

/// `m.simulate` without the GIL. The library calls back every min(steps/100, 1000) steps: the
/// user's `progress(step, steps, time_s)` sees about a hundred of them; every one checks Ctrl-C
/// and `time_limit_s` (s). A Python exception (the callback's, or KeyboardInterrupt) stops the
/// run and is raised as it is; the time limit stops it with a message saying where.
fn simulate_interruptible(
    py: Python<'_>,
    m: &RotorModel,
    profile: &SpeedProfile,
    options: &TimeOptions,
    progress: Option<PyObject>,
    time_limit_s: Option<f64>,
) -> PyResult<TimeResponse> {
    let clock = std::time::Instant::now();
    let mut raised: Option<PyErr> = None;
    let mut out_of_time = false;
    let result = py.allow_threads(|| {
        let mut cb = |p: &RotorProgress| {
            let user_every = (p.steps / 100).max(1);
            let stop = Python::with_gil(|py| {
                py.check_signals()?;
                if let Some(f) = &progress {
                    if p.step % user_every == 0 || p.step == p.steps {
                        f.call1(py, (p.step, p.steps, p.time_s))?;
                    }
                }
                Ok::<(), PyErr>(())
            });
            if let Err(e) = stop {
                raised = Some(e);
                return std::ops::ControlFlow::Break(());
            }
            if time_limit_s.is_some_and(|t| clock.elapsed().as_secs_f64() > t) {
                out_of_time = true;
                return std::ops::ControlFlow::Break(());
            }
            std::ops::ControlFlow::Continue(())
        };
        m.simulate(profile, options, Some(&mut cb))
    });
    if let Some(e) = raised {
        return Err(e);
    }
    match result {
        Err(ehl_bearing::rotor::RotorError::Cancelled {
            step,
            steps,
            time_s,
        }) if out_of_time => Err(err(format!(
            "time limit of {} s reached at step {step} of {steps} (t = {time_s} s); \
             raise time_limit_s or shorten duration_s",
            time_limit_s.unwrap_or(f64::NAN)
        ))),
        r => r.map_err(err),
    }
}

/// The time response `r` of a rotor with `nb` bearings as the dict of numpy arrays that
/// `simulate` returns.
fn response_dict<'py>(
    py: Python<'py>,
    r: &TimeResponse,
    nb: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new_bound(py);
    d.set_item("time_s", PyArray1::from_slice_bound(py, &r.time_s))?;
    d.set_item(
        "speed_rad_s",
        PyArray1::from_slice_bound(py, &r.speed_rad_s),
    )?;
    d.set_item("record_dofs", r.record_dofs.clone())?;
    let rows = r.time_s.len();
    let cols = r.record_dofs.len();
    let disp: Vec<f64> = r.displacement.iter().flatten().copied().collect();
    d.set_item(
        "displacement",
        PyArray1::from_vec_bound(py, disp)
            .reshape([rows, cols])
            .map_err(err)?,
    )?;
    let cage: Vec<f64> = r.cage_angle_rad.iter().flatten().copied().collect();
    d.set_item(
        "cage_angle_rad",
        PyArray1::from_vec_bound(py, cage)
            .reshape([rows, nb])
            .map_err(err)?,
    )?;
    let cage_speed: Vec<f64> = r.cage_speed_rad_s.iter().flatten().copied().collect();
    d.set_item(
        "cage_speed_rad_s",
        PyArray1::from_vec_bound(py, cage_speed)
            .reshape([rows, nb])
            .map_err(err)?,
    )?;
    let flat5 = |v: &Vec<Vec<[f64; 5]>>| -> Vec<f64> {
        v.iter().flatten().flat_map(|x| x.iter().copied()).collect()
    };
    d.set_item(
        "bearing_displacement",
        PyArray1::from_vec_bound(py, flat5(&r.bearing_displacement))
            .reshape([rows, nb, 5])
            .map_err(err)?,
    )?;
    d.set_item(
        "bearing_reaction",
        PyArray1::from_vec_bound(py, flat5(&r.bearing_reaction))
            .reshape([rows, nb, 5])
            .map_err(err)?,
    )?;
    d.set_item("steps", r.steps)?;
    d.set_item("newton_iterations", r.newton_iterations)?;
    d.set_item("max_newton_iterations", r.max_newton_iterations)?;
    d.set_item("steps_outside_range", r.steps_outside_range)?;
    let b = PyDict::new_bound(py);
    b.set_item("total_s", r.breakdown.total_s)?;
    b.set_item("bearing_s", r.breakdown.bearing_s)?;
    b.set_item("factorization_s", r.breakdown.factorization_s)?;
    d.set_item("breakdown", b)?;
    Ok(d)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRotorModel>()
}
