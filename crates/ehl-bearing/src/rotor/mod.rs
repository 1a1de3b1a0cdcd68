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
    /// An input outside its valid range: names the field, its value and the range.
    #[error("invalid rotor input: {0}")]
    Invalid(String),
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
