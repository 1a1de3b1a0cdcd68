//! Steady isothermal elastohydrodynamic (EHL) point contact.
//!
//! The solver follows Venner & Lubrecht, *Multilevel Methods in Lubrication* (2000): the
//! Reynolds equation with cavitation by projection (p ≥ 0), the film
//! h = h0 + x²/2Rx + y²/2Ry + v(x, y) with the elastic deformation v of the half-space, and the
//! force balance through h0, made dimensionless with the Hertz semi-axes (a_x along the rolling
//! direction x, a_y transverse) and the Hertz pressure p_h; FAS multigrid with a full-multigrid
//! start, line relaxation along the rolling direction (Gauss–Seidel / Jacobi-distributive), the
//! deformation by DC-FFT on every level, load continuation when the direct start fails.
//! Everything in SI at the interface; see `docs/ehl.md` for the validation.
//!
//! Moes' groups (used for inputs and outputs; the seed paper's eq. 7 is wrong): W = w/(E′Rx²),
//! U = η0·u_s/(E′Rx) with the SUM velocity u_s = u1 + u2, G = αE′, M = W·U^(−3/4),
//! L = G·U^(1/4), H_Moes = (h/Rx)·U^(−1/2).

pub mod deformation;
pub mod formulas;
mod multigrid;
mod rheology;
mod steady;
mod transient;

use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use crate::material::{DensityModel, ViscosityModel};
pub(crate) use steady::validate_settings;
pub use steady::{
    film_resolution, solve_moes, solve_moes_within, solve_steady, solve_steady_extrapolated,
    solve_steady_extrapolated_within, solve_steady_from, solve_steady_from_within,
    solve_steady_starts, solve_steady_within, start_order, FILM_RESOLUTION_MIN, MOES_L_MAX,
};
pub use transient::{TransientSolver, TransientStep};

/// Errors of the EHL solver.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EhlError {
    /// An input is out of its valid range.
    #[error("invalid EHL input: {field} = {value} (valid range: {range})")]
    Invalid {
        /// Name of the offending input.
        field: &'static str,
        /// Its value (in the unit of the field).
        value: f64,
        /// The valid range, in words.
        range: &'static str,
    },
    /// The iteration produced non-finite numbers or blew up in every start, including the load
    /// and α continuations.
    #[error(
        "EHL solver diverged after {cycles} cycles (M = {m:.4}, L = {l:.4}, Ry/Rx = {ratio:.4}, \
         lowest relative residual reached {residual:e})"
    )]
    Diverged {
        /// Multigrid cycles done.
        cycles: usize,
        /// Moes load parameter of the case.
        m: f64,
        /// Moes material parameter of the case.
        l: f64,
        /// Ry/Rx of the case.
        ratio: f64,
        /// Lowest relative residual reached before the divergence (NaN if none).
        residual: f64,
    },
    /// The wall-time budget (the `deadline` argument of [`solve_steady_within`] and the other `_within` solves, or
    /// [`TransientSolver::with_deadline`]) ran out before the solve converged.
    #[error(
        "EHL solve stopped at its time limit of {limit_s} s after {seconds:.1} s and {cycles} \
         cycles (M = {m:.4}, L = {l:.4}, Ry/Rx = {ratio:.4}; relative residual after each cycle \
         of the last start: {})",
        format_history(residual_history)
    )]
    TimeLimit {
        /// The budget, s.
        limit_s: f64,
        /// Time spent, s.
        seconds: f64,
        /// Multigrid cycles done on the finest grid.
        cycles: usize,
        /// Moes load parameter of the case.
        m: f64,
        /// Moes material parameter of the case.
        l: f64,
        /// Ry/Rx of the case.
        ratio: f64,
        /// Relative residual after each finest-grid cycle of the last start that ran cycles.
        residual_history: Vec<f64>,
    },
    /// A stage that must converge before the next can start did not.
    #[error(
        "EHL {stage} did not converge (relative residual {residual:e}, force-balance residual \
         {force_residual:e})"
    )]
    NotConverged {
        /// What did not converge.
        stage: &'static str,
        /// Relative Reynolds residual reached.
        residual: f64,
        /// Relative force-balance residual reached.
        force_residual: f64,
    },
}

/// A residual history in a message: all values when short, else the first and last few
/// (for the messages of the time-limit errors).
pub fn format_history(h: &[f64]) -> String {
    let f = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.2e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match h.len() {
        0 => "none".into(),
        n if n <= 8 => format!("[{}]", f(h)),
        n => format!("[{}, …, {}] ({n} cycles)", f(&h[..3]), f(&h[n - 3..])),
    }
}

/// Multigrid cycle type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CycleType {
    /// V-cycle: one coarse-grid correction per level.
    V,
    /// W-cycle: two coarse-grid corrections per level (more robust, ~1.5× the work).
    W,
}

/// Numerical settings of the steady solver. Lengths of the domain are in units of the Hertz
/// semi-axis of the respective direction (a_x along x, a_y along y).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EhlSettings {
    /// Grid points per side on the finest level, 2^k + 1, from 17 to 1025 (default 257).
    pub grid: usize,
    /// Points per side on the coarsest level, 2^k + 1 ≥ 9 (default 33; if larger than `grid`,
    /// the finest grid is the only level).
    pub coarsest: usize,
    /// Inlet length upstream of the contact centre, in a_x. `None` (default): automatic,
    /// max(e − max(e − 6, 0)·f, min(30, 1 + 3.5·√(2·H_est))) with e = min(10.5, 3 + 1.5·a_y/a_x),
    /// f = clamp(log10(M/100), 0, 1) and H_est the NVM central film in units a_x²/Rx: 4.5 for a
    /// circular contact at moderate load; for Ry/Rx ≳ 12 10.5 at M ≤ 100 falling to 6 at
    /// M ≥ 1000; longer at light load (domain-convergence study in docs/ehl.md). The x-line
    /// relaxation wants (inlet + outlet)/(2·half_width) ≲ a_y/a_x.
    pub inlet: Option<f64>,
    /// Outlet length downstream of the centre, in a_x (default 1.5).
    pub outlet: f64,
    /// Transverse half-width of the domain, in a_y. `None` (default): automatic,
    /// clamp(3.5 − 0.5·a_y/a_x, 2, 3), i.e. 3 for a circular contact, 2 from Ry/Rx ≈ 4 on.
    pub half_width: Option<f64>,
    /// Largest number of multigrid cycles on the finest grid (default 40).
    pub max_cycles: usize,
    /// Convergence: relative residual Σ|r|/Σ|∂(ρ̄H)/∂X| below this (dimensionless, default 1e-4).
    pub tol_residual: f64,
    /// Convergence: relative force-balance error |∬p − w|/w below this (default 1e-5).
    pub tol_force: f64,
    /// Convergence: relative change of h_c and h0 over the last cycle below this (default 1e-4:
    /// with the residual criterion the measured iteration error of H_c is then ≤ 8e-5 and of δ
    /// ≤ 5e-6, 20–200× below the 257² discretization error; 1e-5 before, which cost 1–4 more
    /// cycles per solution, docs/ehl.md §2).
    pub tol_film: f64,
    /// Stopping rule that follows the discretization error (cold starts, which solve the next
    /// coarser grid first in the full-multigrid start): stop as soon as the estimated algebraic
    /// error of both H_c and H0 is below this fraction of their estimated discretization error,
    /// and the force-balance error below the same fraction of it (dimensionless, default 0.25;
    /// 0 turns the rule off and leaves only the fixed tolerances above, which also stop a solve
    /// when they are met first). The discretization error of a quantity is estimated as
    /// |q_h − q_2h|/3 (second order, q_2h its value on the next coarser grid at the end of the
    /// full-multigrid start), limited to [`DISCRETIZATION_FLOOR`]…[`DISCRETIZATION_CAP`]; the algebraic
    /// error as Δ·ρ/(1 − ρ), Δ the change over the last cycle and ρ < 0.9 the observed
    /// convergence factor, the largest of Δ/Δ_previous, the ratio of the last two residuals and
    /// 0.3 (so never after the first finest-grid cycle).
    /// The relative Reynolds residual must also be below [`DISCRETIZATION_RESIDUAL_GUARD`].
    /// Warm starts ([`solve_steady_from`]) have no coarse-grid value: they use the estimate of
    /// the solution they start from, and the fixed tolerances if it has none (docs/ehl.md §2).
    #[serde(default = "default_discretization_fraction")]
    pub discretization_fraction: f64,
    /// Cycle type (default W).
    pub cycle: CycleType,
    /// Relaxation sweeps before the coarse-grid correction (default 2).
    pub pre_sweeps: usize,
    /// Relaxation sweeps after the coarse-grid correction (default 1).
    pub post_sweeps: usize,
    /// Relaxation sweeps on the coarsest grid per visit, each followed by an h0 update (default 10).
    pub coarse_sweeps: usize,
    /// Under-relaxation of Gauss–Seidel line changes (default 0.4).
    pub omega_gs: f64,
    /// Under-relaxation of Jacobi-distributive changes (default 0.3).
    pub omega_jd: f64,
    /// Gain of the h0 update on the coarsest grid, ΔH0 = −gain·(2π/3 − ∬P), dimensionless (default 0.05).
    pub h0_gain: f64,
    /// Switch to Jacobi-distributive relaxation where the Poiseuille diagonal is below this times
    /// the wedge-term diagonal (default 0.3).
    pub jd_threshold: f64,
    /// FAS cycles on each intermediate level of the full-multigrid start (default 2).
    pub fmg_cycles: usize,
}

/// Default of [`EhlSettings::discretization_fraction`].
pub const DISCRETIZATION_FRACTION: f64 = 0.25;
/// Smallest discretization-error estimate (relative) the stopping rule of
/// [`EhlSettings::discretization_fraction`] uses, so that a coarse-grid value that happens to
/// agree with the fine one does not demand an exact solution: 1e-4.
pub const DISCRETIZATION_FLOOR: f64 = 1e-4;
/// Largest discretization-error estimate (relative) the stopping rule of
/// [`EhlSettings::discretization_fraction`] uses: 4e-3, so that with the default fraction the
/// estimated algebraic error never exceeds 0.1 % however coarse the grid (an unconverged
/// coarse-grid value can also inflate the estimate).
pub const DISCRETIZATION_CAP: f64 = 4e-3;
/// The relative Reynolds residual below which the discretization-following rule may stop a
/// solve (a guard against stopping on a lucky pair of H_c and H0 values while the pressure
/// field is still far off): 1e-2.
pub const DISCRETIZATION_RESIDUAL_GUARD: f64 = 1e-2;

fn default_discretization_fraction() -> f64 {
    DISCRETIZATION_FRACTION
}

impl Default for EhlSettings {
    /// Defaults: 257 × 257 points, automatic inlet (4.5 a_x circular, 6 to 10.5 a_x elongated),
    /// outlet 1.5 a_x, automatic half-width (3 a_y circular to 2 a_y elongated) (see docs/ehl.md for the domain- and grid-convergence
    /// study behind them).
    fn default() -> Self {
        EhlSettings {
            grid: 257,
            coarsest: 33,
            inlet: None,
            outlet: 1.5,
            half_width: None,
            max_cycles: 40,
            tol_residual: 1e-4,
            tol_force: 1e-5,
            tol_film: 1e-4,
            discretization_fraction: DISCRETIZATION_FRACTION,
            cycle: CycleType::W,
            pre_sweeps: 2,
            post_sweeps: 1,
            coarse_sweeps: 10,
            omega_gs: 0.4,
            omega_jd: 0.3,
            h0_gain: 0.05,
            jd_threshold: 0.3,
            fmg_cycles: 2,
        }
    }
}

impl EhlSettings {
    /// A cheaper preset for loops over many contacts: 129 × 129 points, otherwise the defaults.
    /// About 3–4× faster than the default; H_c within 1–1.5 % of the 257² value at moderate load
    /// (M ≲ 300) but 5–10 % low at M ≳ 1000 on elongated contacts (docs/ehl.md §5.2).
    pub fn fast() -> Self {
        EhlSettings {
            grid: 129,
            ..Default::default()
        }
    }

    /// Checks every setting against its valid range (the check every solve makes first), so a
    /// caller can refuse invalid settings before any work; the error names the setting, its
    /// value and the range.
    pub fn validate(&self) -> Result<(), EhlError> {
        validate_settings(self)
    }
}

/// One lubricated elliptical point contact, SI units. x is the rolling (entrainment) direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EhlContact {
    /// Normal load w, N (> 0).
    pub load: f64,
    /// Reduced curvature radius in the rolling direction Rx, m (> 0, Rx ≤ Ry).
    pub rx: f64,
    /// Reduced curvature radius transverse to rolling Ry, m (1 ≤ Ry/Rx ≤ 1000).
    pub ry: f64,
    /// Sum velocity u_s = u1 + u2, m/s (> 0).
    pub sum_velocity: f64,
    /// Reduced modulus E′, Pa: 2/E′ = (1−ν1²)/E1 + (1−ν2²)/E2.
    pub e_reduced: f64,
    /// Lubricant and its rheology models.
    pub lubricant: crate::material::Lubricant,
}

/// A dimensionless case in Moes' parameters, for benchmarks and comparisons with the
/// literature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MoesCase {
    /// Moes load parameter M = W·U^(−3/4) (> 0).
    pub m: f64,
    /// Moes material parameter L = G·U^(1/4) (≥ 0).
    pub l: f64,
    /// Radius ratio Ry/Rx, in [1, 1000].
    pub ry_over_rx: f64,
    /// Viscosity model.
    pub viscosity: ViscosityModel,
    /// Density model.
    pub density: DensityModel,
    /// α·p0 with Roelands' p0 = 1.96e8 Pa (dimensionless; default 4.312 = 2.2e-8 1/Pa × 1.96e8 Pa,
    /// the project's default oil). With L it fixes the Hertz pressure in Pa, which Roelands and
    /// Dowson–Higginson need.
    pub alpha_p0: f64,
    /// ln(η0/η∞) = ln η0 + 9.67 with η0 in Pa·s (dimensionless; default 6.451 = ln 0.04 + 9.67).
    pub ln_eta0_ratio: f64,
}

impl MoesCase {
    /// A case with the project's default oil constants (α p0 = 4.312, ln η0 + 9.67 = 6.451).
    pub fn new(m: f64, l: f64, ry_over_rx: f64, v: ViscosityModel, d: DensityModel) -> Self {
        MoesCase {
            m,
            l,
            ry_over_rx,
            viscosity: v,
            density: d,
            alpha_p0: 2.2e-8 * crate::material::ROELANDS_P0,
            ln_eta0_ratio: 0.04_f64.ln() + crate::material::ROELANDS_LN_ETA_INF,
        }
    }
}

/// Pressure and film fields on the finest grid, SI units. Arrays are row-major with x fastest:
/// value at (x\[i\], y\[j\]) is at index i + nx·j.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct EhlFields {
    /// Rolling-direction coordinates of the grid nodes, m (contact centre at 0).
    pub x: Vec<f64>,
    /// Transverse coordinates of the grid nodes, m.
    pub y: Vec<f64>,
    /// Pressure, Pa.
    pub p: Vec<f64>,
    /// Film thickness, m.
    pub h: Vec<f64>,
    /// Dimensionless pressure P = p/p_h.
    pub p_dimensionless: Vec<f64>,
    /// Dimensionless film H = h·Rx/a_x².
    pub h_dimensionless: Vec<f64>,
    /// Hertz semi-axis along x, m.
    pub a_x: f64,
    /// Hertz semi-axis along y, m.
    pub a_y: f64,
}

/// Result of a steady EHL solution. Dimensional values in SI; Moes-scaled values dimensionless.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EhlSolution {
    /// True when all convergence criteria of [`EhlSettings`] were met.
    pub converged: bool,
    /// Moes load parameter M.
    pub moes_m: f64,
    /// Moes material parameter L.
    pub moes_l: f64,
    /// Ry/Rx.
    pub ry_over_rx: f64,
    /// Central film thickness at the geometric contact centre x = y = 0, m.
    pub h_central: f64,
    /// Minimum film thickness over the grid, m.
    pub h_min: f64,
    /// Maximum pressure, Pa.
    pub p_max: f64,
    /// Hertz maximum pressure of the same load, Pa.
    pub p_hertz: f64,
    /// Approach of distant points δ = −h0, m (tends to the Hertz deflection at high load).
    pub approach: f64,
    /// Hertz deflection of the same load, m.
    pub approach_hertz: f64,
    /// Central film in Moes scaling, (h_c/Rx)·U^(−1/2).
    pub h_central_moes: f64,
    /// Minimum film in Moes scaling, (h_min/Rx)·U^(−1/2).
    pub h_min_moes: f64,
    /// Relative force-balance error |∬p dA − w|/w.
    pub force_balance_residual: f64,
    /// Final relative residual of the Reynolds equation, Σ|r|/Σ|∂(ρ̄H)/∂X|.
    pub residual: f64,
    /// Grid [nx, ny] of the finest level.
    pub grid: [usize; 2],
    /// Multigrid cycles on the finest grid (all continuation steps included).
    pub cycles: usize,
    /// Wall-clock time, s.
    pub seconds: f64,
    /// Relative residual after each finest-grid cycle.
    pub residual_history: Vec<f64>,
    /// Estimated relative discretization error of [H_c, H0] on this grid, |q_h − q_2h|/(3·|q_h|)
    /// with q_2h the value on the next coarser grid at the end of the full-multigrid start
    /// (H0 scaled by max(|H0|, H_c)); for a warm start, the estimate of the solution it started
    /// from; `None` when there was none (single level, continuation steps, or a warm start from
    /// a solution without one). It is what [`EhlSettings::discretization_fraction`] compares with.
    #[serde(default)]
    pub discretization_estimate: Option<[f64; 2]>,
    /// True when the discretization-following rule stopped the iteration (false: the fixed
    /// tolerances, or not converged).
    #[serde(default)]
    pub stopped_by_discretization: bool,
    /// Continuation steps used, in load (`attempts` = 7) or in α (`attempts` = 8, and 9 with the
    /// final single-grid relaxation counted as one step); 0 when a direct start converged.
    pub continuation_steps: usize,
    /// Starts tried: 1 = the given settings; 2–5 = more conservative relaxation after a
    /// divergence or stagnation; 6 = the given settings with strongly under-relaxed
    /// Gauss–Seidel lines (ω_GS ≤ 0.1); 7 = load continuation with the settings of start 5;
    /// 8 = continuation in the pressure–viscosity coefficient α from α/4; 9 = the best iterate
    /// of a failed α-continuation relaxed on the finest grid alone (docs/ehl.md §2, §5.8). For
    /// an unconverged result: the start whose iterate is returned (the one with the lowest
    /// residual), not the number of starts tried.
    pub attempts: usize,
    /// Every start tried, in order, with its outcome (the last one produced this result, or,
    /// for an unconverged result, none converged). Empty in results written before it existed.
    #[serde(default)]
    pub attempt_log: Vec<EhlAttempt>,
    /// Fields on the finest grid (not serialized with the solution: reports add them where asked
    /// for, `report::EhlReport`).
    #[serde(skip)]
    pub fields: EhlFields,
}

impl EhlSolution {
    /// The (relative Reynolds residual, relative force-balance error) bounds a converged solution
    /// solved with settings `s` was held to: [`DISCRETIZATION_RESIDUAL_GUARD`] and
    /// `s.discretization_fraction` × its clamped discretization estimate when the
    /// discretization-following rule stopped it, else `s.tol_residual` and `s.tol_force`.
    pub fn tolerances(&self, s: &EhlSettings) -> (f64, f64) {
        match (self.stopped_by_discretization, self.discretization_estimate) {
            (true, Some(d)) => (
                DISCRETIZATION_RESIDUAL_GUARD,
                s.discretization_fraction
                    * d[0]
                        .max(d[1])
                        .clamp(DISCRETIZATION_FLOOR, DISCRETIZATION_CAP),
            ),
            _ => (s.tol_residual, s.tol_force),
        }
    }
}

/// A start strategy of the steady solver (docs/ehl.md §2). [`StartStrategy::number`] is the
/// value [`EhlSolution::attempts`] reports when that start produced the result.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StartStrategy {
    /// 0: from a previous solution (`solve_steady_from`), the given settings (a converged warm
    /// start reports `attempts` = 1, the given settings).
    Warm,
    /// 1: Hertzian full-multigrid start, the given settings.
    Given,
    /// 2: H0 gain × 0.4.
    SmallH0Gain,
    /// 3: Jacobi-distributive zone widened (threshold ≥ 1).
    WideJacobi,
    /// 4: 2 and 3, ω_JD ≤ 0.15.
    WideJacobiSmallSteps,
    /// 5: H0 gain × 0.2, wide Jacobi-distributive zone, ω_JD ≤ 0.15, ω_GS ≤ 0.3.
    Conservative,
    /// 6: the given settings with ω_GS ≤ 0.1 (strongly under-relaxed Gauss–Seidel lines).
    DampedLines,
    /// 7: load continuation with the settings of start 5.
    LoadContinuation,
    /// 8: continuation in the pressure–viscosity coefficient from α/4.
    AlphaContinuation,
    /// 9: the best iterate of a failed α-continuation relaxed on the finest grid alone.
    SingleGrid,
}

impl StartStrategy {
    /// The classic fallback order, starts 1 to 9.
    pub const LADDER: [StartStrategy; 9] = [
        StartStrategy::Given,
        StartStrategy::SmallH0Gain,
        StartStrategy::WideJacobi,
        StartStrategy::WideJacobiSmallSteps,
        StartStrategy::Conservative,
        StartStrategy::DampedLines,
        StartStrategy::LoadContinuation,
        StartStrategy::AlphaContinuation,
        StartStrategy::SingleGrid,
    ];

    /// Start number: 0 (warm) or 1–9, as in [`EhlSolution::attempts`].
    pub fn number(self) -> usize {
        match self {
            StartStrategy::Warm => 0,
            s => {
                1 + StartStrategy::LADDER
                    .iter()
                    .position(|x| *x == s)
                    .expect("every cold strategy is in the ladder")
            }
        }
    }
}

/// How one start ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttemptOutcome {
    /// All convergence criteria met.
    Converged,
    /// Stopped at the cycle limit without meeting the criteria.
    CycleLimit,
    /// Stopped because the residual gained less than a factor 2 in 6 cycles.
    Stagnated,
    /// Non-finite iterate, residual 100× above its best, or an absurd film.
    Diverged,
    /// Not run: its precondition was missing (start 9 needs an iterate of start 8).
    Skipped,
}

/// One start of the steady solver and its outcome.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EhlAttempt {
    /// The start strategy.
    pub strategy: StartStrategy,
    /// How it ended.
    pub outcome: AttemptOutcome,
    /// Multigrid cycles on the finest grid spent in it (continuation steps included).
    pub cycles: usize,
    /// Lowest (diverged) or last relative Reynolds residual (dimensionless; NaN if none).
    pub residual: f64,
    /// Wall time spent in it, s.
    pub seconds: f64,
}
