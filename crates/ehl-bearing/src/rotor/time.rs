//! Time response: Newmark average acceleration with the bearing forces implicit (Newton on the
//! bearing DOFs of the condensed rotor) or lagged by one step.

use super::model::{check_speed, check_vector, RotorModel};
use super::RotorError;
use crate::force_element::{ElementOutput, ElementState};
use nalgebra::{DMatrix, DVector};
use std::ops::ControlFlow;
use std::time::Instant;

/// Shaft speed over time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpeedProfile {
    /// Constant speed, rad/s.
    Constant {
        /// Shaft speed, rad/s.
        speed_rad_s: f64,
    },
    /// Linear run-up (or run-down) from `start_rad_s` to `end_rad_s` over `duration_s`, then
    /// constant.
    Ramp {
        /// Speed at t = 0, rad/s.
        start_rad_s: f64,
        /// Speed from t = duration_s on, rad/s.
        end_rad_s: f64,
        /// Ramp duration, s.
        duration_s: f64,
    },
}

impl SpeedProfile {
    fn validate(&self) -> Result<(), RotorError> {
        match *self {
            SpeedProfile::Constant { speed_rad_s } => check_speed(speed_rad_s),
            SpeedProfile::Ramp {
                start_rad_s,
                end_rad_s,
                duration_s,
            } => {
                check_speed(start_rad_s)?;
                check_speed(end_rad_s)?;
                if !(duration_s.is_finite() && duration_s > 0.0) {
                    return Err(RotorError::Range {
                        field: "ramp duration_s",
                        value: duration_s,
                        unit: "",
                        expected: "finite and > 0",
                    });
                }
                Ok(())
            }
        }
    }

    /// Speed (rad/s) at time `t` (s).
    pub fn speed(&self, t: f64) -> f64 {
        match *self {
            SpeedProfile::Constant { speed_rad_s } => speed_rad_s,
            SpeedProfile::Ramp {
                start_rad_s,
                end_rad_s,
                duration_s,
            } => start_rad_s + (end_rad_s - start_rad_s) * (t / duration_s).clamp(0.0, 1.0),
        }
    }

    /// Angular acceleration (rad/s²) at time `t` (s).
    pub fn acceleration(&self, t: f64) -> f64 {
        match *self {
            SpeedProfile::Constant { .. } => 0.0,
            SpeedProfile::Ramp {
                start_rad_s,
                end_rad_s,
                duration_s,
            } => {
                if t < duration_s {
                    (end_rad_s - start_rad_s) / duration_s
                } else {
                    0.0
                }
            }
        }
    }

    /// Shaft rotation angle (rad) at time `t` (s), zero at t = 0.
    pub fn angle(&self, t: f64) -> f64 {
        match *self {
            SpeedProfile::Constant { speed_rad_s } => speed_rad_s * t,
            SpeedProfile::Ramp {
                start_rad_s,
                end_rad_s,
                duration_s,
            } => {
                let a = (end_rad_s - start_rad_s) / duration_s;
                if t < duration_s {
                    start_rad_s * t + 0.5 * a * t * t
                } else {
                    0.5 * (start_rad_s + end_rad_s) * duration_s + end_rad_s * (t - duration_s)
                }
            }
        }
    }
}

/// How the bearing forces enter a time step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Coupling {
    /// At the new time, by Newton's method on the bearing DOFs (the default; stable).
    #[default]
    Implicit,
    /// From the previous step, as an explicit load (ROSS's `add_to_RHS`): diverges for stiff,
    /// lightly damped contacts unless the step is far below their period.
    Lagged,
}

/// How the cages move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum CageMotion {
    /// Each cage turns at its bearing's operating cage speed (the load-weighted mean orbital
    /// speed of its balls in the bearing model, updated every step): the balls pass the load
    /// zone at Z·f_cage (varying compliance).
    #[default]
    Rolling,
    /// Every cage held at this angle, rad: a time-invariant bearing.
    Fixed {
        /// Cage angle, rad.
        angle_rad: f64,
    },
}

/// Initial state of a time response.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Start {
    /// The static equilibrium at the initial speed, at rest.
    #[default]
    StaticEquilibrium,
    /// Given displacements (SI, n) and rates (n).
    Given {
        /// Rotor displacements q(0).
        displacement: Vec<f64>,
        /// Rotor rates q̇(0).
        velocity: Vec<f64>,
    },
}

/// Options of a time response.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeOptions {
    /// Time step h, s.
    pub step_s: f64,
    /// Simulated time, s.
    pub duration_s: f64,
    /// Record every this many steps (≥ 1); the initial state is always recorded.
    pub record_every: usize,
    /// Rotor DOFs to record (empty: all).
    pub record_dofs: Vec<usize>,
    /// How the bearing forces enter a step.
    pub coupling: Coupling,
    /// How the cages move.
    pub cage: CageMotion,
    /// Initial state.
    pub start: Start,
    /// Newton tolerance on the bearing DOFs' residual, m (or rad): |y − L·q(y)|∞.
    pub newton_tolerance_m: f64,
    /// Newton iteration budget per step.
    pub max_newton_iterations: usize,
    /// A bearing translation beyond this (m) ends the run as diverged.
    pub divergence_limit_m: f64,
    /// A bearing tilt beyond this (rad) ends the run as diverged.
    pub divergence_limit_rad: f64,
}

impl Default for TimeOptions {
    fn default() -> Self {
        TimeOptions {
            step_s: 1e-5,
            duration_s: 0.1,
            record_every: 1,
            record_dofs: Vec::new(),
            coupling: Coupling::Implicit,
            cage: CageMotion::Rolling,
            start: Start::StaticEquilibrium,
            newton_tolerance_m: 1e-13,
            max_newton_iterations: 30,
            divergence_limit_m: 1e-3,
            divergence_limit_rad: 0.1,
        }
    }
}

impl TimeOptions {
    fn validate(&self, n: usize) -> Result<usize, RotorError> {
        let positive = |field: &'static str, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(RotorError::Range {
                    field,
                    value,
                    unit: "",
                    expected: "finite and > 0",
                })
            }
        };
        positive("step_s", self.step_s)?;
        positive("duration_s", self.duration_s)?;
        positive("newton_tolerance_m", self.newton_tolerance_m)?;
        positive("divergence_limit_m", self.divergence_limit_m)?;
        positive("divergence_limit_rad", self.divergence_limit_rad)?;
        let steps = (self.duration_s / self.step_s).round();
        if !(1.0..=1e9).contains(&steps) {
            return Err(RotorError::Range {
                field: "duration_s / step_s",
                value: steps,
                unit: " steps",
                expected: "1 to 1e9",
            });
        }
        if self.record_every == 0 {
            return Err(RotorError::Range {
                field: "record_every",
                value: 0.0,
                unit: "",
                expected: "≥ 1",
            });
        }
        if self.max_newton_iterations == 0 {
            return Err(RotorError::Range {
                field: "max_newton_iterations",
                value: 0.0,
                unit: "",
                expected: "≥ 1",
            });
        }
        if let Some(&i) = self.record_dofs.iter().find(|&&i| i >= n) {
            return Err(RotorError::RecordDof { dof: i, n });
        }
        // The record is kept in memory: refuse one that cannot fit before any step (1e9 steps
        // recorded every step asked for hundreds of GB).
        let rows = steps / self.record_every as f64 + 1.0;
        let per_row = if self.record_dofs.is_empty() {
            n
        } else {
            self.record_dofs.len()
        };
        let bytes = rows * (per_row as f64 + 2.0) * 8.0;
        if bytes > MAX_RECORD_BYTES {
            return Err(RotorError::RecordTooLarge {
                rows,
                per_row,
                bytes,
                max_bytes: MAX_RECORD_BYTES,
            });
        }
        if let CageMotion::Fixed { angle_rad } = self.cage {
            if !angle_rad.is_finite() {
                return Err(RotorError::Range {
                    field: "cage angle_rad",
                    value: angle_rad,
                    unit: "",
                    expected: "finite",
                });
            }
        }
        if let Start::Given {
            displacement,
            velocity,
        } = &self.start
        {
            check_vector("start displacement", displacement, n, "")?;
            check_vector("start velocity", velocity, n, "")?;
        }
        Ok(steps as usize)
    }
}

/// Where the wall time of a run went, s.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct TimeBreakdown {
    /// Whole run.
    pub total_s: f64,
    /// Bearing force-element evaluations.
    pub bearing_s: f64,
    /// Factorizations of the effective matrix and the condensation onto the bearing DOFs.
    pub factorization_s: f64,
}

/// The caller's progress callback of [`RotorModel::simulate`]: `Break` stops the run.
pub type ProgressCallback<'a> = dyn FnMut(&RotorProgress) -> ControlFlow<()> + 'a;

/// Largest time-response record held in memory, bytes (recorded DOFs and time and speed; the
/// bearing records add to it).
pub const MAX_RECORD_BYTES: f64 = 1e9;

/// Progress of a run, passed to the caller's callback every min(steps/100, 1000) steps (at
/// least every step), which may stop the run by returning [`ControlFlow::Break`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotorProgress {
    /// Steps done.
    pub step: usize,
    /// Steps in all.
    pub steps: usize,
    /// Simulated time reached, s.
    pub time_s: f64,
}

/// A time response (its record: `report::RotorRunReport`).
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct TimeResponse {
    /// Recorded times, s.
    pub time_s: Vec<f64>,
    /// Shaft speed at each recorded time, rad/s.
    pub speed_rad_s: Vec<f64>,
    /// The recorded rotor DOFs.
    pub record_dofs: Vec<usize>,
    /// Per recorded time: the recorded rotor displacements (SI).
    pub displacement: Vec<Vec<f64>>,
    /// Per recorded time, per bearing: cage angle, rad.
    pub cage_angle_rad: Vec<Vec<f64>>,
    /// Per recorded time, per bearing: the bearing's operating cage speed at that state (the
    /// load-weighted mean orbital speed of its balls, whether or not the cage rolls), rad/s.
    pub cage_speed_rad_s: Vec<Vec<f64>>,
    /// Per recorded time, per bearing: bearing displacement (x, y, z, θy, θz), m and rad.
    pub bearing_displacement: Vec<Vec<[f64; 5]>>,
    /// Per recorded time, per bearing: reaction (load on the inner ring), N and N·m.
    pub bearing_reaction: Vec<Vec<[f64; 5]>>,
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations summed over the steps (bearing evaluations per bearing).
    pub newton_iterations: usize,
    /// Largest Newton iteration count of one step.
    pub max_newton_iterations: usize,
    /// Steps in which a contact lay outside its law's fitted range (or the speed outside a
    /// trend element's range).
    pub steps_outside_range: usize,
    /// Where the time went.
    pub breakdown: TimeBreakdown,
}

/// Newmark average acceleration (β = 1/4, γ = 1/2).
const BETA: f64 = 0.25;
const GAMMA: f64 = 0.5;

/// The effective matrix of a step condensed onto the bearing DOFs, for one speed.
struct Condensed {
    speed: f64,
    /// D = C + Ω·G.
    damping: DMatrix<f64>,
    /// LU of S = c0·M + c1·D + K.
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    /// W = S⁻¹·Lᵀ (n × m).
    w: DMatrix<f64>,
    /// A = L·W (m × m).
    a: DMatrix<f64>,
}

/// The bearing DOFs that are mapped to rotor DOFs: (bearing, bearing DOF, rotor DOF, sign).
struct BearingDofs(Vec<(usize, usize, usize, f64)>);

impl BearingDofs {
    fn of(model: &RotorModel) -> Self {
        let mut v = Vec::new();
        for (b, site) in model.bearings.iter().enumerate() {
            for k in 0..5 {
                if let Some(i) = site.dofs[k] {
                    v.push((b, k, i, site.signs[k]));
                }
            }
        }
        BearingDofs(v)
    }

    fn len(&self) -> usize {
        self.0.len()
    }

    /// L·x (m).
    fn gather(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(self.0.len(), self.0.iter().map(|&(_, _, i, s)| s * x[i]))
    }

    /// The mapped reaction components (m) of the bearing outputs.
    fn reactions(&self, outs: &[ElementOutput]) -> DVector<f64> {
        DVector::from_iterator(
            self.0.len(),
            self.0.iter().map(|&(b, k, _, _)| outs[b].reaction[k]),
        )
    }

    /// Block-diagonal ∂R/∂y + c·∂R/∂ẏ on the mapped DOFs (m × m).
    fn tangent(&self, outs: &[ElementOutput], c: f64) -> DMatrix<f64> {
        let m = self.0.len();
        let mut t = DMatrix::zeros(m, m);
        for (r, &(br, kr, _, _)) in self.0.iter().enumerate() {
            for (col, &(bc, kc, _, _)) in self.0.iter().enumerate() {
                if br == bc {
                    t[(r, col)] = outs[br].stiffness[kr][kc] + c * outs[br].damping[kr][kc];
                }
            }
        }
        t
    }
}

impl RotorModel {
    /// The shaft speed's time response under `profile`: see the module documentation for the
    /// equation and the scheme. `progress` is called every min(steps/100, 1000) steps with the
    /// steps done; returning [`ControlFlow::Break`] stops the run with
    /// [`RotorError::Cancelled`] (a caller's cancel button or wall-time limit).
    /// Ends with an error carrying the step, the time and the residual history when a step's
    /// Newton iteration does not converge, when a bearing element fails, or when the response
    /// diverges (beyond `divergence_limit_m`).
    pub fn simulate(
        &self,
        profile: &SpeedProfile,
        options: &TimeOptions,
        mut progress: Option<&mut ProgressCallback<'_>>,
    ) -> Result<TimeResponse, RotorError> {
        let clock = Instant::now();
        profile.validate()?;
        let n = self.dofs();
        let steps = options.validate(n)?;
        let run = Integrator {
            model: self,
            profile,
            options,
            newmark: Newmark::new(options.step_s),
            dofs: BearingDofs::of(self),
            cages: Cages::new(self, options.cage, profile),
        };
        let mut state = run.initial_state()?;
        let mut response = TimeResponse {
            record_dofs: if options.record_dofs.is_empty() {
                (0..n).collect()
            } else {
                options.record_dofs.clone()
            },
            ..TimeResponse::default()
        };
        run.record(&mut response, 0.0, &state);

        let mut condensed: Option<Condensed> = None;
        let progress_every = (steps / 100).clamp(1, 1000);
        for step in 1..=steps {
            let t = step as f64 * options.step_s;
            let speed = profile.speed(t);
            if !matches!(&condensed, Some(c) if c.speed == speed) {
                let t0 = Instant::now();
                let (c0, c1) = (run.newmark.c0, run.newmark.c1);
                condensed = Some(self.condense(&run.dofs, speed, c0, c1, t)?);
                response.breakdown.factorization_s += t0.elapsed().as_secs_f64();
            }
            let cond = condensed.as_ref().expect("condensed just set");
            run.step(step, cond, &mut state, &mut response)?;
            if step % options.record_every == 0 {
                run.record(&mut response, t, &state);
            }
            if let Some(p) = progress.as_deref_mut() {
                if step % progress_every == 0 || step == steps {
                    let at = RotorProgress {
                        step,
                        steps,
                        time_s: t,
                    };
                    if p(&at).is_break() {
                        return Err(RotorError::Cancelled {
                            step,
                            steps,
                            time_s: t,
                        });
                    }
                }
            }
        }
        response.steps = steps;
        response.breakdown.total_s = clock.elapsed().as_secs_f64();
        Ok(response)
    }

    /// f_const + unbalance forces at time `t`.
    fn external_force(&self, profile: &SpeedProfile, t: f64) -> DVector<f64> {
        let mut f = self.constant_force.clone();
        let (angle, speed, accel) = (profile.angle(t), profile.speed(t), profile.acceleration(t));
        for u in &self.unbalances {
            let [fx, fy] = u.force(angle, speed, accel);
            f[u.dofs[0]] += fx;
            f[u.dofs[1]] += fy;
        }
        f
    }

    /// Factorize S at `speed` and condense it onto the bearing DOFs.
    fn condense(
        &self,
        dofs: &BearingDofs,
        speed: f64,
        c0: f64,
        c1: f64,
        t: f64,
    ) -> Result<Condensed, RotorError> {
        let n = self.dofs();
        let damping = &self.damping + &self.gyroscopic * speed;
        let s = &self.mass * c0 + &damping * c1 + &self.stiffness;
        let lu = s.lu();
        let mut lt = DMatrix::zeros(n, dofs.len());
        for (col, &(_, _, i, sign)) in dofs.0.iter().enumerate() {
            lt[(i, col)] = sign;
        }
        let w = lu.solve(&lt).ok_or(RotorError::Singular {
            what: "effective",
            time_s: t,
        })?;
        let mut a = DMatrix::zeros(dofs.len(), dofs.len());
        for (r, &(_, _, i, sign)) in dofs.0.iter().enumerate() {
            for col in 0..dofs.len() {
                a[(r, col)] = sign * w[(i, col)];
            }
        }
        Ok(Condensed {
            speed,
            damping,
            lu,
            w,
            a,
        })
    }

    /// Rotor-sized vectors holding the bearing DOFs `y` and their rates c1·y + L·e_v (only the
    /// mapped entries are used by the bearings).
    fn rotor_state_from_bearing(
        &self,
        dofs: &BearingDofs,
        y: &DVector<f64>,
        lv: &DVector<f64>,
        c1: f64,
        n: usize,
    ) -> (DVector<f64>, DVector<f64>) {
        let mut q = DVector::zeros(n);
        let mut v = DVector::zeros(n);
        for (k, &(_, _, i, sign)) in dofs.0.iter().enumerate() {
            q[i] = sign * y[k];
            v[i] = sign * (c1 * y[k] + lv[k]);
        }
        (q, v)
    }

    /// Evaluate every bearing at rotor state (q, v).
    fn evaluate_all(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
        speed: f64,
        angles: &[f64],
        states: &mut [ElementState],
        t: f64,
    ) -> Result<Vec<ElementOutput>, RotorError> {
        states
            .iter_mut()
            .enumerate()
            .map(|(b, state)| self.evaluate_bearing(b, (q, v), (speed, angles[b]), state, t))
            .collect()
    }

    fn check_divergence(
        &self,
        dofs: &BearingDofs,
        y: &DVector<f64>,
        options: &TimeOptions,
        step: usize,
        t: f64,
    ) -> Result<(), RotorError> {
        for (&(_, k, _, _), v) in dofs.0.iter().zip(y.iter()) {
            let limit = if k < 3 {
                options.divergence_limit_m
            } else {
                options.divergence_limit_rad
            };
            if !v.is_finite() || v.abs() > limit {
                return Err(RotorError::Diverged {
                    step,
                    time_s: t,
                    displacement_m: *v,
                    limit_m: limit,
                });
            }
        }
        Ok(())
    }
}

/// The coefficients of Newmark's average-acceleration rule for a step h (s): with the new
/// displacements q1, a1 = c0·q1 + e_a and v1 = c1·q1 + e_v, where
/// e_a = −c0·q − c2·v − c3·a and e_v = −c1·q + c4·v + c5·a.
#[derive(Debug, Clone, Copy)]
struct Newmark {
    /// Step h, s.
    h: f64,
    /// 1/(β·h²), 1/s².
    c0: f64,
    /// γ/(β·h), 1/s.
    c1: f64,
    /// 1/(β·h), 1/s.
    c2: f64,
    /// 1/(2β) − 1.
    c3: f64,
    /// 1 − γ/β.
    c4: f64,
    /// h·(1 − γ/(2β)), s.
    c5: f64,
}

impl Newmark {
    fn new(h: f64) -> Self {
        Newmark {
            h,
            c0: 1.0 / (BETA * h * h),
            c1: GAMMA / (BETA * h),
            c2: 1.0 / (BETA * h),
            c3: 1.0 / (2.0 * BETA) - 1.0,
            c4: 1.0 - GAMMA / BETA,
            c5: h * (1.0 - GAMMA / (2.0 * BETA)),
        }
    }
}

/// How the cage angles move. Each rolling cage turns at its bearing's operating cage speed,
/// the load-weighted mean orbital speed of its balls from the bearing model
/// (`ElementOutput::cage_speed`), taken from the last converged evaluation as a ratio to the
/// shaft speed and applied to the exact shaft rotation of the step:
/// θ(t + h) = θ(t) + (ω_c/Ω)(t)·(φ(t + h) − φ(t)). It follows the operating point (loads,
/// run-ups) with a lag of one step; at constant speed and load it is the equilibrium's cage
/// speed to within its ripple over a ball pass. Before any evaluation, or at Ω = 0, the no-load
/// ratio at the free contact angle (`ForceElement::cage_speed`).
struct Cages<'a> {
    motion: CageMotion,
    profile: &'a SpeedProfile,
    /// Per bearing, the no-load ratio of cage to shaft speed.
    free_ratio: Vec<f64>,
}

impl<'a> Cages<'a> {
    fn new(model: &RotorModel, motion: CageMotion, profile: &'a SpeedProfile) -> Self {
        let free_ratio = model
            .bearings
            .iter()
            .map(|s| s.element.cage_speed(1.0, 0.0))
            .collect();
        Cages {
            motion,
            profile,
            free_ratio,
        }
    }

    /// The cage angles at t = 0, rad.
    fn initial(&self) -> Vec<f64> {
        let nb = self.free_ratio.len();
        match self.motion {
            CageMotion::Rolling => vec![0.0; nb],
            CageMotion::Fixed { angle_rad } => vec![angle_rad; nb],
        }
    }

    /// Per bearing, the ratio of the cage speed in `outs` to the shaft speed `speed` (rad/s),
    /// or the no-load ratio where it is undefined.
    fn ratios(&self, outs: &[ElementOutput], speed: f64) -> Vec<f64> {
        outs.iter()
            .zip(&self.free_ratio)
            .map(|(o, &free)| {
                let r = o.cage_speed / speed;
                if speed != 0.0 && r.is_finite() {
                    r
                } else {
                    free
                }
            })
            .collect()
    }

    /// The cage angles (rad) at `t1` from `angles` at `t0` (s), the cages turning at the
    /// ratios of `outs` to the shaft speed at `t0`.
    fn advance(&self, angles: &[f64], outs: &[ElementOutput], t0: f64, t1: f64) -> Vec<f64> {
        let ratios = self.ratios(outs, self.profile.speed(t0));
        match self.motion {
            CageMotion::Rolling => {
                let dphi = self.profile.angle(t1) - self.profile.angle(t0);
                angles
                    .iter()
                    .zip(&ratios)
                    .map(|(a, r)| a + r * dphi)
                    .collect()
            }
            CageMotion::Fixed { angle_rad } => vec![angle_rad; self.free_ratio.len()],
        }
    }
}

/// The fixed parts of one time integration: the rotor, the speed profile and options, the
/// Newmark coefficients, the bearing DOFs and the cage motion.
struct Integrator<'a> {
    model: &'a RotorModel,
    profile: &'a SpeedProfile,
    options: &'a TimeOptions,
    newmark: Newmark,
    dofs: BearingDofs,
    cages: Cages<'a>,
}

/// The rotor's state after a step: displacements q (SI), rates v and accelerations a, the cage
/// angles (rad), the bearings' outputs at (q, v) and their warm-start states.
struct RotorState {
    q: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    angles: Vec<f64>,
    outs: Vec<ElementOutput>,
    elements: Vec<ElementState>,
}

/// What a step's bearing solve starts from: the step, its time t (s) and shaft speed (rad/s),
/// the condensed effective matrix, u0 = S⁻¹·r (the new displacements without the bearing
/// forces) and e_v (the part of the new rates that does not depend on the new displacements).
struct StepStart<'a> {
    step: usize,
    t: f64,
    speed: f64,
    cond: &'a Condensed,
    u0: DVector<f64>,
    e_v: DVector<f64>,
}

impl Integrator<'_> {
    /// The initial state by `options.start`, with the accelerations from
    /// M·a = f(0) − (C + Ω·G)·v − K·q − Σ (bearing reactions).
    fn initial_state(&self) -> Result<RotorState, RotorError> {
        let m = self.model;
        let n = m.dofs();
        let mut elements = vec![ElementState::default(); m.bearings.len()];
        let speed0 = self.profile.speed(0.0);
        let (q, v) = match &self.options.start {
            Start::StaticEquilibrium => {
                let eq = m.static_equilibrium(speed0)?;
                (DVector::from_vec(eq.displacement), DVector::zeros(n))
            }
            Start::Given {
                displacement,
                velocity,
            } => (
                DVector::from_column_slice(displacement),
                DVector::from_column_slice(velocity),
            ),
        };
        let angles = self.cages.initial();
        let outs = m.evaluate_all(&q, &v, speed0, &angles, &mut elements, 0.0)?;
        let force0 = m.external_force(self.profile, 0.0);
        let mut rhs = force0 - (&m.damping + &m.gyroscopic * speed0) * &v - &m.stiffness * &q;
        for (b, o) in outs.iter().enumerate() {
            m.scatter_force(b, &o.reaction.map(|r| -r), &mut rhs);
        }
        let a = m
            .mass
            .clone()
            .lu()
            .solve(&rhs)
            .ok_or(RotorError::Singular {
                what: "mass",
                time_s: 0.0,
            })?;
        Ok(RotorState {
            q,
            v,
            a,
            angles,
            outs,
            elements,
        })
    }

    /// Append the state `s` at time `t` (s) to `response`.
    fn record(&self, response: &mut TimeResponse, t: f64, s: &RotorState) {
        response.time_s.push(t);
        response.speed_rad_s.push(self.profile.speed(t));
        response
            .displacement
            .push(response.record_dofs.iter().map(|&i| s.q[i]).collect());
        response.cage_angle_rad.push(s.angles.to_vec());
        response
            .cage_speed_rad_s
            .push(s.outs.iter().map(|o| o.cage_speed).collect());
        response.bearing_displacement.push(
            self.model
                .bearings
                .iter()
                .map(|b| b.displacement(&s.q))
                .collect(),
        );
        response
            .bearing_reaction
            .push(s.outs.iter().map(|o| o.reaction).collect());
    }

    /// Step `step` (from t − h to t = step·h) with the condensed effective matrix `cond`:
    /// advance the cages, solve for the new displacements with the bearing forces as the
    /// coupling option says, then the new rates and accelerations. Counts the Newton
    /// iterations, the steps outside a law's range and the bearing time in `response`.
    fn step(
        &self,
        step: usize,
        cond: &Condensed,
        s: &mut RotorState,
        response: &mut TimeResponse,
    ) -> Result<(), RotorError> {
        let Newmark {
            h,
            c0,
            c1,
            c2,
            c3,
            c4,
            c5,
        } = self.newmark;
        let m = self.model;
        let t = step as f64 * h;
        let t_prev = (step - 1) as f64 * h;
        s.angles = self.cages.advance(&s.angles, &s.outs, t_prev, t);
        // q1 = u0 − W·R, a1 = c0·q1 + e_a, v1 = c1·q1 + e_v.
        let e_a = -(&s.q * c0) - &s.v * c2 - &s.a * c3;
        let e_v = -(&s.q * c1) + &s.v * c4 + &s.a * c5;
        let r = m.external_force(self.profile, t) - &m.mass * &e_a - &cond.damping * &e_v;
        let u0 = cond.lu.solve(&r).ok_or(RotorError::Singular {
            what: "effective",
            time_s: t,
        })?;
        let start = StepStart {
            step,
            t,
            speed: self.profile.speed(t),
            cond,
            u0,
            e_v,
        };
        let q1 = match self.options.coupling {
            Coupling::Lagged => self.lagged(&start, s, response)?,
            Coupling::Implicit => self.implicit(&start, s, response)?,
        };
        if s.outs
            .iter()
            .any(|o| !o.outside_range.is_empty() || o.speed_outside)
        {
            response.steps_outside_range += 1;
        }
        let a1 = &q1 * c0 + &e_a;
        let v1 = &q1 * c1 + &start.e_v;
        s.q = q1;
        s.v = v1;
        s.a = a1;
        if s.q.iter().any(|x| !x.is_finite()) {
            return Err(RotorError::Diverged {
                step,
                time_s: t,
                displacement_m: f64::NAN,
                limit_m: self.options.divergence_limit_m,
            });
        }
        Ok(())
    }

    /// The new displacements with the previous step's bearing forces as an explicit load; the
    /// bearings are then evaluated there (one evaluation, counted as one Newton iteration).
    fn lagged(
        &self,
        k: &StepStart<'_>,
        s: &mut RotorState,
        response: &mut TimeResponse,
    ) -> Result<DVector<f64>, RotorError> {
        let m = self.model;
        let reaction = self.dofs.reactions(&s.outs);
        let q1 = &k.u0 - &k.cond.w * &reaction;
        m.check_divergence(
            &self.dofs,
            &self.dofs.gather(&q1),
            self.options,
            k.step,
            k.t,
        )?;
        let v1 = &q1 * self.newmark.c1 + &k.e_v;
        let t0 = Instant::now();
        s.outs = m.evaluate_all(&q1, &v1, k.speed, &s.angles, &mut s.elements, k.t)?;
        response.breakdown.bearing_s += t0.elapsed().as_secs_f64();
        response.newton_iterations += 1;
        response.max_newton_iterations = response.max_newton_iterations.max(1);
        Ok(q1)
    }

    /// The new displacements with the bearing forces at the new time: Newton on the bearing
    /// DOFs y of g(y) = y − L·u0 + A·R(y) = 0 from the predictor L·(q + h·v + h²/2·a), to
    /// |g|∞ ≤ `newton_tolerance_m`; an error with the update history if it does not get there.
    fn implicit(
        &self,
        k: &StepStart<'_>,
        s: &mut RotorState,
        response: &mut TimeResponse,
    ) -> Result<DVector<f64>, RotorError> {
        let (m, dofs, options) = (self.model, &self.dofs, self.options);
        let (h, c1) = (self.newmark.h, self.newmark.c1);
        let n = m.dofs();
        let b = dofs.gather(&k.u0);
        let lv = dofs.gather(&k.e_v);
        // Predictor: y ≈ L·(q + h·v + h²/2·a).
        let mut y = dofs.gather(&(&s.q + &s.v * h + &s.a * (0.5 * h * h)));
        let mut history = Vec::new();
        let mut converged = false;
        for iteration in 1..=options.max_newton_iterations {
            m.check_divergence(dofs, &y, options, k.step, k.t)?;
            let (qy, vy) = m.rotor_state_from_bearing(dofs, &y, &lv, c1, n);
            let t0 = Instant::now();
            s.outs = m.evaluate_all(&qy, &vy, k.speed, &s.angles, &mut s.elements, k.t)?;
            response.breakdown.bearing_s += t0.elapsed().as_secs_f64();
            let reaction = dofs.reactions(&s.outs);
            let g = &y - &b + &k.cond.a * &reaction;
            let g_max = g.amax();
            history.push(g_max);
            response.newton_iterations += 1;
            response.max_newton_iterations = response.max_newton_iterations.max(iteration);
            if g_max <= options.newton_tolerance_m {
                converged = true;
                break;
            }
            let jac =
                DMatrix::identity(dofs.len(), dofs.len()) + &k.cond.a * dofs.tangent(&s.outs, c1);
            let dy = jac.lu().solve(&g).ok_or(RotorError::Singular {
                what: "bearing Newton",
                time_s: k.t,
            })?;
            y -= dy;
        }
        if !converged {
            return Err(RotorError::StepNotConverged {
                step: k.step,
                time_s: k.t,
                iterations: options.max_newton_iterations,
                update_history: history,
            });
        }
        Ok(&k.u0 - &k.cond.w * dofs.reactions(&s.outs))
    }
}
