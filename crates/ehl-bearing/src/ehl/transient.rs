//! Transient EHL point contact coupled to the equation of motion of the ball.
//!
//! Reynolds with the squeeze term, in the steady solver's scaling (X = x/a_x, P = p/p_h,
//! H = h·Rx/a_x²) and the time T = t·u_m/a_x (u_m = u_s/2, so that the lubricant travels one
//! a_x per unit T):
//!
//! ∂/∂X(ε ∂P/∂X) + κ²·∂/∂Y(ε ∂P/∂Y) − ∂(ρ̄H)/∂X − ∂(ρ̄H)/∂T = 0.
//!
//! The Hertz scales are those of the operating load w0 and stay fixed while the load varies.
//! Time discretization: second-order backward differences (BDF2), implicit, for the squeeze term
//! ∂(ρ̄H)/∂T ≈ (3/2·(ρ̄H)ⁿ − 2·(ρ̄H)ⁿ⁻¹ + 1/2·(ρ̄H)ⁿ⁻²)/ΔT and for the ball's equation of motion
//! m·δ̈ = w(t) − ∬p dA, written for h0 = −δ as a first-order system (H0, V = dH0/dT), both
//! derivatives by BDF2. The force balance of the steady problem becomes, per time step,
//! ∬P dX dY = (2π/3)·(w/w0 + μ·d²H0/dT²) with μ = m·u_s²/(4·Rx·w0): linear in H0ⁿ
//! (∬P = g + γ·H0ⁿ), which the multigrid H0 update solves with the same FAS machinery as the
//! steady force balance. The history part of the squeeze term enters as the right-hand side on
//! the finest grid. Each step starts from P extrapolated quadratically from the last three time
//! levels and H0 cubically from the last four (lower orders on the first steps), and runs FAS
//! cycles until the steady solver's tolerances are met.
//!
//! BDF2 is A-stable (no step-size limit) but damps free oscillations numerically, by a relative
//! amount per step of order (ωΔt)⁴ and with a period error of order (ωΔt)²; the measured effect
//! is in docs/contact.md.

use super::multigrid::{Hierarchy, MgParams, Problem};
use super::steady::{bilinear, params, setup, solve_steady, Scales};
use super::{EhlContact, EhlError, EhlSettings, EhlSolution};
use std::f64::consts::PI;

/// One time step of a transient run, SI units.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TransientStep {
    /// Time at the end of the step, s (0 = the steady start).
    pub time: f64,
    /// External load w(t) on the ball at this time, N.
    pub load: f64,
    /// Approach of distant points δ = −h0, m.
    pub approach: f64,
    /// Approach rate δ̇, m/s.
    pub velocity: f64,
    /// Film force ∬p dA, N.
    pub film_force: f64,
    /// Central film thickness at x = y = 0, m.
    pub h_central: f64,
    /// Minimum film thickness, m.
    pub h_min: f64,
    /// Maximum pressure, Pa.
    pub p_max: f64,
    /// Relative Reynolds residual at the end of the step.
    pub residual: f64,
    /// Relative error of the discrete equation of motion (force balance with inertia), in units
    /// of w0.
    pub force_residual: f64,
    /// FAS cycles used in this step.
    pub cycles: usize,
    /// True when the step met the steady solver's tolerances.
    pub converged: bool,
}

/// Transient solver for one contact; keeps its multigrid hierarchy (and FFT plans) between steps.
pub struct TransientSolver {
    pr: Problem,
    sc: Scales,
    prm: MgParams,
    s: EhlSettings,
    /// Wall-time budget of the run (None: none), [`TransientSolver::with_deadline`].
    deadline: Option<crate::budget::Deadline>,
    max_cycles: usize,
    hier: Hierarchy,
    w0: f64,
    /// Ball mass, kg.
    mass: f64,
    /// Time step, s, and its dimensionless value ΔT = Δt·u_m/a_x.
    dt: f64,
    dtt: f64,
    /// μ = m·u_s²/(4·Rx·w0).
    mu: f64,
    /// (ρ̄H) at the current and the previous time level (finest grid).
    rh_now: Vec<f64>,
    rh_prev: Vec<f64>,
    /// H0 and V = dH0/dT at the previous time level (the current ones: `hier.h0`, `v_now`).
    h0_prev: f64,
    v_prev: f64,
    v_now: f64,
    time: f64,
    source: Vec<f64>,
    /// Pressure at the previous time level (for the predictor).
    p_prev: Vec<f64>,
    /// P two steps back (quadratic predictor), valid once `steps` ≥ 2.
    p_prev2: Vec<f64>,
    /// H0 two and three steps back (cubic predictor of H0, valid once `steps` ≥ 3).
    h0_prev2: f64,
    h0_prev3: f64,
    /// Steps taken.
    steps: usize,
    steady: EhlSolution,
}

impl TransientSolver {
    /// Starts from the steady solution at the contact's load `c.load` (= w0, N), solved here with
    /// `settings`; `mass` is the ball's mass (kg, > 0), `dt` the time step (s, > 0),
    /// `initial_velocity` the approach rate δ̇ at t = 0 (m/s; 0 for a ball at rest), and
    /// `max_cycles_per_step` the largest number of FAS cycles per step (≥ 1).
    ///
    /// Errors: invalid inputs; a steady start that diverges or does not converge.
    pub fn new(
        c: &EhlContact,
        settings: &EhlSettings,
        mass: f64,
        dt: f64,
        initial_velocity: f64,
        max_cycles_per_step: usize,
    ) -> Result<Self, EhlError> {
        let steady = solve_steady(c, settings)?;
        Self::from_steady(
            c,
            settings,
            steady,
            mass,
            dt,
            initial_velocity,
            max_cycles_per_step,
        )
    }

    /// As [`TransientSolver::new`], from a steady solution of the same contact and settings
    /// (for example, one the caller already has).
    pub fn from_steady(
        c: &EhlContact,
        settings: &EhlSettings,
        steady: EhlSolution,
        mass: f64,
        dt: f64,
        initial_velocity: f64,
        max_cycles_per_step: usize,
    ) -> Result<Self, EhlError> {
        let bad = |field, value, range| EhlError::Invalid {
            field,
            value,
            range,
        };
        if !(mass.is_finite() && mass > 0.0) {
            return Err(bad("mass [kg]", mass, "finite and > 0"));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(bad("time step [s]", dt, "finite and > 0"));
        }
        if !initial_velocity.is_finite() {
            return Err(bad("initial velocity [m/s]", initial_velocity, "finite"));
        }
        if !(1..=1000).contains(&max_cycles_per_step) {
            return Err(bad(
                "max_cycles_per_step",
                max_cycles_per_step as f64,
                "1 to 1000",
            ));
        }
        if !steady.converged {
            return Err(EhlError::NotConverged {
                stage: "steady start of the transient run",
                residual: steady.residual,
                force_residual: steady.force_balance_residual,
            });
        }
        let (pr, sc) = setup(c, settings)?;
        let mut prm = params(settings);
        prm.h0_relax *= pr.h0_gain_scale;
        let mut hier = Hierarchy::new(&pr, settings.grid, settings.coarsest);
        let top = hier.levels.len() - 1;
        if steady.fields.p_dimensionless.len() != hier.levels[top].p.len()
            || (steady.fields.x[0] - hier.levels[top].x[0] * sc.ax).abs() > 1e-9 * sc.ax
        {
            return Err(bad(
                "steady start grid",
                steady.fields.p_dimensionless.len() as f64,
                "the steady solution must come from the same contact and settings",
            ));
        }
        hier.levels[top]
            .p
            .copy_from_slice(&steady.fields.p_dimensionless);
        let length = sc.ax * sc.ax / sc.rx; // m per unit H
        hier.h0 = -steady.approach / length;
        let h0 = hier.h0;
        hier.levels[top].update_film(&pr, h0);
        let um = 0.5 * c.sum_velocity;
        let dtt = dt * um / sc.ax;
        // V = dH0/dT = −δ̇ / (length · u_m / a_x)
        let v0 = -initial_velocity / (length * um / sc.ax);
        let rh = hier.levels[top].rho_h();
        let n = rh.len();
        Ok(TransientSolver {
            mu: mass * c.sum_velocity * c.sum_velocity / (4.0 * c.rx * c.load),
            pr,
            sc,
            prm,
            s: *settings,
            deadline: None,
            max_cycles: max_cycles_per_step,
            w0: c.load,
            mass,
            dt,
            dtt,
            rh_prev: rh.clone(),
            rh_now: rh,
            h0_prev: h0 - v0 * dtt,
            v_prev: v0,
            v_now: v0,
            time: 0.0,
            hier,
            source: vec![0.0; n],
            p_prev: steady.fields.p_dimensionless.clone(),
            p_prev2: steady.fields.p_dimensionless.clone(),
            h0_prev2: h0,
            h0_prev3: h0,
            steps: 0,
            steady,
        })
    }

    /// Sets the start's approach acceleration δ̈(0) (m/s², finite; the constructors assume 0),
    /// so that the BDF2 history of the equation of motion is that of a motion with the start's
    /// rate and this acceleration (for a start on a periodic response, e.g. at a load extremum).
    /// Call before the first step.
    pub fn with_initial_acceleration(mut self, acceleration: f64) -> Result<Self, EhlError> {
        if !acceleration.is_finite() || self.time != 0.0 {
            return Err(EhlError::Invalid {
                field: "initial acceleration [m/s²] (before the first step)",
                value: acceleration,
                range: "finite",
            });
        }
        let length = self.sc.ax * self.sc.ax / self.sc.rx;
        let um_over_ax = self.dtt / self.dt;
        // A = d²H0/dT² = −δ̈ / (length · (u_m/a_x)²)
        let a = -acceleration / (length * um_over_ax * um_over_ax);
        let (h0, v, dtt) = (self.hier.h0, self.v_now, self.dtt);
        self.h0_prev = h0 - v * dtt + 0.5 * a * dtt * dtt;
        self.v_prev = v - a * dtt;
        Ok(self)
    }

    /// Sets the per-step film tolerance (relative change of h_c and H0 over the last cycle,
    /// finite and > 0; initially the settings' `tol_film`), e.g. looser for steps that only
    /// settle a start transient.
    pub fn set_tol_film(&mut self, tol_film: f64) -> Result<(), EhlError> {
        if !(tol_film.is_finite() && tol_film > 0.0) {
            return Err(EhlError::Invalid {
                field: "tol_film",
                value: tol_film,
                range: "finite and > 0",
            });
        }
        self.s.tol_film = tol_film;
        Ok(())
    }

    /// The run with a wall-time budget: checked before every step and every cycle; when it has
    /// passed a step ends with [`EhlError::TimeLimit`] (None: no budget).
    pub fn with_deadline(mut self, deadline: Option<crate::budget::Deadline>) -> Self {
        self.deadline = deadline;
        self
    }

    /// The steady solution the run started from.
    pub fn steady(&self) -> &EhlSolution {
        &self.steady
    }

    /// Ball mass, kg.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Time step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Dimensionless time step ΔT = Δt·u_m/a_x (travel of the lubricant per step in units of a_x).
    pub fn dt_dimensionless(&self) -> f64 {
        self.dtt
    }

    /// Time of the current state, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The film along the centre line y = 0 of the current state: (x in m, h in m).
    pub fn centre_line_film(&self) -> (Vec<f64>, Vec<f64>) {
        let lv = self.hier.levels.last().expect("at least one level");
        let j = lv.ny / 2;
        let x = lv.x.iter().map(|v| v * self.sc.ax).collect();
        let h = lv.h[j * lv.nx..(j + 1) * lv.nx]
            .iter()
            .map(|v| self.sc.h(*v))
            .collect();
        (x, h)
    }

    /// The relative Reynolds residual on the finest grid and the error of the discrete equation
    /// of motion ∬P = g + γ·H0 (relative to the target 2π/3) of the current state.
    fn residuals(&mut self, g: f64) -> (f64, f64) {
        let target = 2.0 * PI / 3.0;
        let h0 = self.hier.h0;
        let lv = self.hier.levels.last_mut().expect("at least one level");
        let (sr, sw) = lv.residual(&self.pr);
        let residual = if sw > 0.0 { sr / sw } else { f64::INFINITY };
        (
            residual,
            (g + self.pr.load_slope * h0 - lv.integral()).abs() / target,
        )
    }

    /// Advances one time step to t + Δt under the external load `load` (N, finite) at the new
    /// time. A step that stops at the cycle limit is returned with `converged: false`; a step
    /// whose iteration produces non-finite numbers is an error.
    pub fn step(&mut self, load: f64) -> Result<TransientStep, EhlError> {
        self.check_step(load)?;
        let (g, prev) = self.new_time_level(load);
        self.predict(&prev);
        let it = self.iterate_step(g)?;
        let v = self.shift_motion(&prev);
        Ok(self.report(load, v, &it))
    }

    /// The checks before a step: `load` (N) finite, the wall-time budget not passed.
    fn check_step(&self, load: f64) -> Result<(), EhlError> {
        if !load.is_finite() {
            return Err(EhlError::Invalid {
                field: "load [N]",
                value: load,
                range: "finite",
            });
        }
        if let Some(d) = self.deadline.filter(|d| d.expired()) {
            return Err(EhlError::TimeLimit {
                limit_s: d.limit_seconds(),
                seconds: d.elapsed_seconds(),
                cycles: 0,
                m: self.sc.m,
                l: self.sc.l,
                ratio: self.sc.ratio,
                residual_history: Vec::new(),
            });
        }
        Ok(())
    }

    /// Sets up the discrete equations of the new time level under the external load `load` (N):
    /// shifts the (ρ̄H) history, writes the history part of the BDF2 squeeze term as the finest
    /// level's right-hand side and the equation of motion as the force target ∬P = g + γ·H0ⁿ.
    /// Returns g and the H0, V of the two previous time levels.
    fn new_time_level(&mut self, load: f64) -> (f64, PreviousLevels) {
        let top = self.hier.levels.len() - 1;
        let dtt = self.dtt;
        // Shift the history: the current state becomes level n−1.
        let rh_cur = self.hier.levels[top].rho_h();
        std::mem::swap(&mut self.rh_prev, &mut self.rh_now);
        self.rh_now = rh_cur;
        let prev = PreviousLevels {
            h0: [self.hier.h0, self.h0_prev],
            v: [self.v_now, self.v_prev],
        };
        let [h0_1, h0_2] = prev.h0;
        let [v_1, v_2] = prev.v;
        // Right-hand side: history part of BDF2, (−2(ρ̄H)ⁿ⁻¹ + ½(ρ̄H)ⁿ⁻²)/ΔT.
        for (f, (a, b)) in self
            .source
            .iter_mut()
            .zip(self.rh_now.iter().zip(&self.rh_prev))
        {
            *f = (-2.0 * a + 0.5 * b) / dtt;
        }
        // d²H0/dT² = a·H0ⁿ + b.
        let a = 2.25 / (dtt * dtt);
        let b = (1.5 * (-2.0 * h0_1 + 0.5 * h0_2) / dtt - 2.0 * v_1 + 0.5 * v_2) / dtt;
        // h0 = −δ and m·δ̈ = w − F give F = w + m·ḧ0, i.e. ∬P = (2π/3)·(w/w0 + μ·H0'')
        // = g + γ·H0ⁿ.
        let target = 2.0 * PI / 3.0;
        self.pr.squeeze = 1.5 / dtt;
        self.pr.load_slope = target * self.mu * a;
        let g = target * (load / self.w0 + self.mu * b);
        let lv = &mut self.hier.levels[top];
        lv.set_source(&self.source);
        lv.g = g;
        (g, prev)
    }

    /// The predictor of the new time level: P extrapolated from the last time levels and H0
    /// from the previous ones (`prev` the two before the new level), then the film updated.
    fn predict(&mut self, prev: &PreviousLevels) {
        let top = self.hier.levels.len() - 1;
        let [h0_1, h0_2] = prev.h0;
        // Predictor: quadratic extrapolation of P (kept ≥ 0) from the last three time levels
        // (linear on the first two steps) and cubic extrapolation of H0 from the last four
        // (quadratic on the third step). On the seed contact at 64 steps per period the quadratic
        // P starts a step 3× closer than the linear one (3.6 → 2.4 cycles per step at the same
        // film tolerance); the cubic H0 cuts the H0 error ≈ 10× (1.4e-4 → 1.3e-5 of H0), and with
        // it the systematic lag of the unconverged remainder: at `step_tol_film` 7e-5 the law of
        // the 22 seed contacts at 3000 rpm is as close to that of tight steps as with the
        // quadratic H0 at 3e-5, in 15 % fewer cycles (docs/contact.md). A cubic P
        // amplifies the iteration noise of the pressure (4.0 cycles per step).
        let quad = self.steps >= 2;
        for ((p, q), q2) in self.hier.levels[top]
            .p
            .iter_mut()
            .zip(self.p_prev.iter_mut())
            .zip(self.p_prev2.iter_mut())
        {
            let p1 = *p;
            *p = if quad {
                3.0 * p1 - 3.0 * *q + *q2
            } else {
                2.0 * p1 - *q
            }
            .max(0.0);
            *q2 = *q;
            *q = p1;
        }
        self.hier.h0 = if self.steps >= 3 {
            4.0 * h0_1 - 6.0 * h0_2 + 4.0 * self.h0_prev2 - self.h0_prev3
        } else if quad {
            3.0 * h0_1 - 3.0 * h0_2 + self.h0_prev2
        } else {
            2.0 * h0_1 - h0_2
        };
        let h0 = self.hier.h0;
        self.hier.levels[top].update_film(&self.pr, h0);
    }

    /// FAS cycles on the new time level (force target g) until the tolerances are met, the
    /// cycle limit or the wall-time budget is reached; an error when the iterate is not finite.
    fn iterate_step(&mut self, g: f64) -> Result<StepIteration, EhlError> {
        let top = self.hier.levels.len() - 1;
        let centre = |h: &Hierarchy| {
            let lv = &h.levels[top];
            bilinear(&lv.h, &lv.x, &lv.y, 0.0, 0.0)
        };
        let mut it = StepIteration {
            converged: false,
            residual: f64::NAN,
            force_residual: f64::NAN,
            cycles: 0,
        };
        // Whether `residual` and `force_residual` describe the current state.
        let mut evaluated = false;
        for cycle in 0..self.max_cycles {
            if crate::budget::expired(&self.deadline) {
                break;
            }
            let hc_old = centre(&self.hier);
            let h0_old = self.hier.h0;
            self.hier.cycle(&self.pr, &self.prm, top);
            it.cycles += 1;
            evaluated = false;
            let h0 = self.hier.h0;
            let hc = centre(&self.hier);
            if !(h0.is_finite() && hc.is_finite()) {
                return Err(self.diverged(it.cycles, f64::NAN));
            }
            let scale = hc.abs().max(1e-12);
            let dh = ((hc - hc_old).abs() / scale).max((h0 - h0_old).abs() / h0.abs().max(scale));
            // The Reynolds residual and the force balance (a full pass over the finest grid) are
            // evaluated only when the film has settled, and after the last cycle for the report.
            if dh >= self.s.tol_film && cycle + 1 < self.max_cycles {
                continue;
            }
            (it.residual, it.force_residual) = self.residuals(g);
            evaluated = true;
            if !it.residual.is_finite() {
                return Err(self.diverged(it.cycles, it.residual));
            }
            if it.residual < self.s.tol_residual
                && it.force_residual < self.s.tol_force
                && dh < self.s.tol_film
            {
                it.converged = true;
                break;
            }
        }
        if !evaluated && it.cycles > 0 {
            // Stopped by the deadline after a cycle whose residual was not evaluated.
            (it.residual, it.force_residual) = self.residuals(g);
        }
        Ok(it)
    }

    /// [`EhlError::Diverged`] of this contact after `cycles` cycles of a step.
    fn diverged(&self, cycles: usize, residual: f64) -> EhlError {
        EhlError::Diverged {
            cycles,
            m: self.sc.m,
            l: self.sc.l,
            ratio: self.sc.ratio,
            residual,
        }
    }

    /// Closes the step in the equation of motion's history: V = dH0/dT of the new level by BDF2
    /// (returned), the H0 and V of the previous levels (`prev`) moved back one level, the time
    /// advanced by Δt.
    fn shift_motion(&mut self, prev: &PreviousLevels) -> f64 {
        let [h0_1, h0_2] = prev.h0;
        let [v_1, _] = prev.v;
        let h0 = self.hier.h0;
        let v = (1.5 * h0 - 2.0 * h0_1 + 0.5 * h0_2) / self.dtt;
        self.h0_prev3 = self.h0_prev2;
        self.h0_prev2 = h0_2;
        self.h0_prev = h0_1;
        self.steps += 1;
        self.v_prev = v_1;
        self.v_now = v;
        self.time += self.dt;
        v
    }

    /// The step's record in SI units: the new state under `load` (N) with the dimensionless
    /// approach rate `v` = dH0/dT and the iteration's outcome `it`.
    fn report(&self, load: f64, v: f64, it: &StepIteration) -> TransientStep {
        let target = 2.0 * PI / 3.0;
        let h0 = self.hier.h0;
        let lv = self.hier.levels.last().expect("at least one level");
        let length = self.sc.ax * self.sc.ax / self.sc.rx;
        let um_over_ax = self.dtt / self.dt; // u_m/a_x, 1/s
        let hc = bilinear(&lv.h, &lv.x, &lv.y, 0.0, 0.0);
        let hmin = lv.h.iter().cloned().fold(f64::INFINITY, f64::min);
        let pmax = lv.p.iter().cloned().fold(0.0, f64::max);
        TransientStep {
            time: self.time,
            load,
            approach: -h0 * length,
            velocity: -v * length * um_over_ax,
            film_force: lv.integral() / target * self.w0,
            h_central: self.sc.h(hc),
            h_min: self.sc.h(hmin),
            p_max: pmax * self.sc.ph,
            residual: it.residual,
            force_residual: it.force_residual,
            cycles: it.cycles,
            converged: it.converged,
        }
    }
}

/// H0 and V = dH0/dT (dimensionless) of the two time levels before the new one: index 0 the
/// level n−1, index 1 the level n−2.
struct PreviousLevels {
    h0: [f64; 2],
    v: [f64; 2],
}

/// Outcome of the FAS cycles of one time step.
struct StepIteration {
    /// Whether the tolerances were met.
    converged: bool,
    /// Relative Reynolds residual and error of the discrete equation of motion (units of w0).
    residual: f64,
    force_residual: f64,
    /// FAS cycles used.
    cycles: usize,
}
