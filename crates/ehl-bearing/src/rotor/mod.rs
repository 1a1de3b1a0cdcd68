//! A linear rotor (finite-element matrices M, C, G, K, e.g. from ROSS) on nonlinear bearings
//! ([`crate::force_element::ForceElement`]s): static equilibrium, linearization, and time response at constant speed
//! or in a run-up, with the bearing forces treated implicitly.
//!
//! Equation of motion, rotor DOFs q (n), SI:
//!
//! M·q̈ + (C + Ω·G)·q̇ + K·q = f_const + f_unbalance(t) − Σ_b L_bᵀ·R_b(L_b·q + o_b, L_b·q̇)
//!
//! with Ω(t) the shaft speed (rad/s), G the gyroscopic matrix per unit speed (ROSS's
//! `rotor.G()`, used as `C + Ω·G` as ROSS does), `R_b` the reaction of bearing b
//! ([`crate::force_element::ElementOutput::reaction`]: the load on its inner ring, so the
//! bearing acts on the shaft with −R), `L_b` the signed selection of the rotor DOFs that carry
//! the bearing's x (axial), y, z, θy, θz ([`BearingSite`]), and `o_b` the bearing displacement
//! when those rotor DOFs are zero (e.g. the axial preload approach). The outer rings are fixed
//! to the ground and the inner rings turn with the shaft: inner speed Ω, outer speed 0.
//!
//! Time stepping ([`simulate`](RotorModel::simulate)) is Newmark's average-acceleration rule
//! (trapezoidal, second order, unconditionally stable for the linear part, no numerical
//! damping). With [`Coupling::Implicit`] (the default) each step solves the full nonlinear
//! equation at the new time by Newton's method on the bearing DOFs alone: the linear rotor is
//! condensed onto them through one factorization of the effective matrix S = M/(βh²) +
//! D·γ/(βh) + K per speed, so a Newton iteration costs one evaluation per bearing and a 5·B×5·B
//! solve. [`Coupling::Lagged`] instead applies the bearing forces of the previous step as an
//! explicit load — what ROSS's `add_to_RHS` hook does — and is kept to show why it is not the
//! default: with stiff, lightly damped contacts it diverges at time steps where the implicit
//! scheme is stable.

mod model;
mod time;

pub use model::{
    BearingSite, RotorMatrices, RotorModel, StaticDiagnosis, StaticSolution, Unbalance,
};
pub use time::{
    CageMotion, Coupling, ProgressCallback, RotorProgress, SpeedProfile, Start, TimeBreakdown,
    TimeOptions, TimeResponse,
};

use thiserror::Error;

/// Errors of the rotor model and its solvers; each carries the numbers that explain it.
#[derive(Debug, Error)]
pub enum RotorError {
    /// A number outside its valid range: names the field, its value (with `unit`) and the range.
    #[error("invalid rotor input: {field} = {value}{unit}; must be {expected}")]
    Range {
        /// The input, e.g. `step_s`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Its unit as written after the value (e.g. " rad/s"; empty when the field names it).
        unit: &'static str,
        /// The valid range.
        expected: &'static str,
    },
    /// The rotor has no degree of freedom.
    #[error("invalid rotor input: rotor dofs = 0; a rotor needs at least one DOF")]
    NoDofs,
    /// A matrix with the wrong number of entries.
    #[error("invalid rotor input: {name} matrix has {entries} entries; {n}×{n} = {} expected", n * n)]
    MatrixSize {
        /// The matrix, e.g. `mass`.
        name: &'static str,
        /// Entries given.
        entries: usize,
        /// Rotor DOFs.
        n: usize,
    },
    /// A matrix entry that is not finite.
    #[error("invalid rotor input: {name}[{row}, {col}] = {value}; entries must be finite")]
    MatrixEntry {
        /// The matrix.
        name: &'static str,
        /// Row.
        row: usize,
        /// Column.
        col: usize,
        /// The value given.
        value: f64,
    },
    /// A vector with the wrong number of entries.
    #[error("invalid rotor input: {name} has {entries} entries; {n} expected")]
    VectorSize {
        /// The vector, e.g. `constant_force`.
        name: &'static str,
        /// Entries given.
        entries: usize,
        /// Rotor DOFs.
        n: usize,
    },
    /// A vector entry that is not finite.
    #[error("invalid rotor input: {name}[{index}] = {value}; must be finite{unit}")]
    VectorEntry {
        /// The vector.
        name: &'static str,
        /// Entry.
        index: usize,
        /// The value given.
        value: f64,
        /// Its unit, e.g. " (N or N·m)".
        unit: &'static str,
    },
    /// A bearing site's DOF index outside the rotor's.
    #[error(
        "invalid rotor input: bearing {bearing}: dofs[{k}] = {dof}; rotor DOF indices run 0..{n}"
    )]
    SiteDof {
        /// Bearing site.
        bearing: usize,
        /// Bearing DOF (0 to 4).
        k: usize,
        /// Rotor DOF given.
        dof: usize,
        /// Rotor DOFs.
        n: usize,
    },
    /// A bearing site's sign other than ±1.
    #[error("invalid rotor input: bearing {bearing}: signs[{k}] = {value}; must be +1 or −1")]
    SiteSign {
        /// Bearing site.
        bearing: usize,
        /// Bearing DOF.
        k: usize,
        /// The sign given.
        value: f64,
    },
    /// A bearing site's offset that is not finite.
    #[error(
        "invalid rotor input: bearing {bearing}: offset[{k}] = {value}; must be finite (m or rad)"
    )]
    SiteOffset {
        /// Bearing site.
        bearing: usize,
        /// Bearing DOF.
        k: usize,
        /// The offset given.
        value: f64,
    },
    /// Two DOFs of one bearing site mapped to the same rotor DOF.
    #[error("invalid rotor input: bearing {bearing}: dofs {dofs:?} map two bearing DOFs to one rotor DOF")]
    SiteDofsRepeated {
        /// Bearing site.
        bearing: usize,
        /// Its rotor DOFs.
        dofs: [Option<usize>; 5],
    },
    /// An unbalance's DOF outside the rotor's.
    #[error("invalid rotor input: unbalance {unbalance}: dof {dof}; rotor DOF indices run 0..{n}")]
    UnbalanceDof {
        /// Unbalance.
        unbalance: usize,
        /// Rotor DOF given.
        dof: usize,
        /// Rotor DOFs.
        n: usize,
    },
    /// An unbalance acting twice on one DOF.
    #[error(
        "invalid rotor input: unbalance {unbalance}: dofs {dofs:?} must be two different DOFs"
    )]
    UnbalanceSameDofs {
        /// Unbalance.
        unbalance: usize,
        /// Its DOFs.
        dofs: [usize; 2],
    },
    /// An unbalance that is not finite.
    #[error(
        "invalid rotor input: unbalance {unbalance}: mass_eccentricity_kg_m = \
         {mass_eccentricity_kg_m}, phase_rad = {phase_rad}; must be finite"
    )]
    UnbalanceNotFinite {
        /// Unbalance.
        unbalance: usize,
        /// m·e, kg·m.
        mass_eccentricity_kg_m: f64,
        /// Phase, rad.
        phase_rad: f64,
    },
    /// A recorded DOF outside the rotor's.
    #[error("invalid rotor input: record_dofs contains {dof}; rotor DOF indices run 0..{n}")]
    RecordDof {
        /// Rotor DOF given.
        dof: usize,
        /// Rotor DOFs.
        n: usize,
    },
    /// A record too large to keep in memory.
    #[error(
        "invalid rotor input: duration_s / step_s / record_every = {rows:.3e} recorded samples \
         of {per_row} DOFs ({:.1} GB); at most {:.0} GB: raise record_every or narrow \
         record_dofs",
        bytes * 1e-9,
        max_bytes * 1e-9
    )]
    RecordTooLarge {
        /// Recorded samples.
        rows: f64,
        /// DOFs per sample.
        per_row: usize,
        /// Bytes the record needs.
        bytes: f64,
        /// The limit, bytes.
        max_bytes: f64,
    },
    /// A matrix that must be invertible is singular (e.g. the mass matrix, or the effective
    /// matrix of a step).
    #[error("singular {what} matrix at t = {time_s} s")]
    Singular {
        /// Which matrix.
        what: &'static str,
        /// Simulated time, s.
        time_s: f64,
    },
    /// The static equilibrium did not converge within its iteration budget; the message says
    /// why, from [`StaticDiagnosis`] (the direction the load pushes the rotor along).
    #[error(
        "static equilibrium not converged after {iterations} Newton iterations (largest force \
         residual {first:.4e} at the start, {last:.4e} at the end, N or N·m){why}",
        first = residual_history.first().copied().unwrap_or(f64::NAN),
        last = residual_history.last().copied().unwrap_or(f64::NAN),
        why = diagnosis.as_ref().map(|d| format!("; {d}")).unwrap_or_default()
    )]
    StaticNotConverged {
        /// Iterations done.
        iterations: usize,
        /// Largest force residual per iteration, N (or N·m).
        residual_history: Vec<f64>,
        /// Why: the rotor's softest loaded direction at the last iterate (None if the mass
        /// matrix is not positive definite).
        diagnosis: Option<StaticDiagnosis>,
    },
    /// The Newton iteration of one implicit step did not converge within its budget.
    #[error(
        "time step {step} (t = {time_s} s): Newton on the bearing DOFs not converged after \
         {iterations} iterations (update history, m or rad: {update_history:?}); \
         try a smaller time step"
    )]
    StepNotConverged {
        /// Step index.
        step: usize,
        /// Simulated time at the end of the step, s.
        time_s: f64,
        /// Iterations done.
        iterations: usize,
        /// Largest bearing-DOF update per iteration, m or rad.
        update_history: Vec<f64>,
    },
    /// The response grew without bound (non-finite, or a bearing displacement beyond
    /// `divergence_limit_m` or a tilt beyond `divergence_limit_rad`).
    #[error(
        "response diverged at step {step} (t = {time_s} s): bearing displacement \
         {displacement_m} (m or rad) beyond the limit {limit_m}"
    )]
    Diverged {
        /// Step index.
        step: usize,
        /// Simulated time, s.
        time_s: f64,
        /// The bearing displacement that crossed the limit, m (or rad), or NaN.
        displacement_m: f64,
        /// The limit, m.
        limit_m: f64,
    },
    /// The caller's progress callback asked to stop (e.g. a cancel button, a time limit).
    #[error("run stopped by the caller at step {step} of {steps} (t = {time_s} s)")]
    Cancelled {
        /// Steps done.
        step: usize,
        /// Steps in all.
        steps: usize,
        /// Simulated time reached, s.
        time_s: f64,
    },
    /// A bearing's force element failed (e.g. a ball equilibrium that did not converge).
    #[error("bearing {bearing} at t = {time_s} s: {source}")]
    Element {
        /// Bearing index.
        bearing: usize,
        /// Simulated time, s.
        time_s: f64,
        /// The element's error.
        source: Box<crate::Error>,
    },
}
