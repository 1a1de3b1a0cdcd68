//! Fit of the lubricated contact force law Q = K·δ^d + ΔF (optionally + c·δ̇) to (δ, Q) samples
//! from EHL simulations, and the fitted law as a [`ContactLaw`](crate::contact_law::ContactLaw).
//!
//! - [`levenberg_marquardt`]: a small general Levenberg–Marquardt solver (scaled Marquardt step by
//!   QR, Nielsen damping update) with a [`LmConvergence`] settings struct and an [`LmReport`];
//!   [`covariance`] gives s²·(JᵀJ)⁻¹ at a solution.
//! - [`fit_power_law`] / [`fit_power_law_damped`]: the contact-law fit, reparametrized for
//!   conditioning, started by variable projection over d and polished by Levenberg–Marquardt,
//!   returning a [`PowerLawFit`] with standard errors and goodness of fit.
//! - [`FittedLaw`]: the fitted law with a C¹, positive, increasing exponential extension below a
//!   joint approach δ_j (a fraction of the smallest fitted approach), so that it is defined for
//!   every δ including negative approaches (film thicker than at zero approach).
//!
//! The method, the extension and the test figures are described in `docs/fit.md`.

use thiserror::Error;

mod law;
mod linalg;
mod lm;
mod power_law;

pub use law::{FittedLaw, RangeStatus, DEFAULT_JOINT_FRACTION};
pub use lm::{
    covariance, levenberg_marquardt, LeastSquaresProblem, LmConvergence, LmReport, LmStop,
};
pub use power_law::{
    fit_power_law, fit_power_law_damped, FitOptions, PowerLawFit, PowerLawStdErrors,
};

/// Errors of the fit. Every variant names the offending input and carries its numbers.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    /// A setting of a characterization outside its range (the value with its unit).
    #[error("invalid fit input: {name} = {value}: expected {expected}")]
    Setting {
        /// The setting, e.g. `amplitude`.
        name: &'static str,
        /// The value given, with its unit where it has one.
        value: String,
        /// The valid range.
        expected: &'static str,
    },
    /// Film extrapolation asked for on a grid that has no twice finer grid.
    #[error(
        "invalid fit input: film_extrapolation needs the twice finer grid: grid = {grid}, \
         expected grid ≤ 513 (the finest grid is 1025)"
    )]
    ExtrapolationGrid {
        /// The grid given.
        grid: usize,
    },
    /// A ball mass that is not finite and positive.
    #[error("invalid fit input: ball mass = {mass_kg} kg: expected finite and > 0")]
    BallMass {
        /// The mass, kg.
        mass_kg: f64,
    },
    /// The EHL approach does not grow with the load (hydrodynamic regime): no harmonic law.
    #[error(
        "invalid fit input: the EHL approach does not grow with the load around w0 = {load_n} N \
         (secant stiffness {secant_stiffness_n_m:e} N/m): the contact runs in the hydrodynamic \
         regime"
    )]
    NoElasticApproach {
        /// Load w0, N.
        load_n: f64,
        /// Secant stiffness between 0.95·w0 and 1.05·w0, N/m.
        secant_stiffness_n_m: f64,
    },
    /// Levenberg–Marquardt settings that are not finite and non-negative.
    #[error(
        "invalid fit input: Levenberg–Marquardt settings must be finite and non-negative with a \
         positive initial damping: {settings:?}"
    )]
    LmSettings {
        /// The settings given.
        settings: crate::fit::lm::LmConvergence,
    },
    /// The start grid of the exponent d is empty or not finite.
    #[error(
        "invalid fit input: d_start_range must be finite with 0 < min ≤ max and d_grid_points ≥ \
         2, got {d_start_range:?} and {d_grid_points}"
    )]
    DStartGrid {
        /// The range given.
        d_start_range: [f64; 2],
        /// Grid points given.
        d_grid_points: usize,
    },
    /// Two input arrays that must have the same length do not.
    #[error("length mismatch in {what}: expected {expected}, found {found}")]
    LengthMismatch {
        /// Which input.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
    /// Too few samples for the number of parameters.
    #[error("too few points: {points} given, at least {required} needed")]
    TooFewPoints {
        /// Samples given.
        points: usize,
        /// Samples needed (parameters + 1, so that the residual variance is defined).
        required: usize,
    },
    /// A NaN or infinite value.
    #[error("non-finite value in {what} at index {index}: {value}")]
    NonFinite {
        /// Which input.
        what: &'static str,
        /// Index of the first offending value.
        index: usize,
        /// The value.
        value: f64,
    },
    /// An approach δ ≤ 0, where δ^d is undefined: the fit needs δ > 0 (samples with a negative
    /// approach must be left out; the [`FittedLaw`] extension covers δ ≤ 0 afterwards).
    #[error("approach at index {index} is {value} m: the power law needs δ > 0")]
    NonPositiveApproach {
        /// Index of the first offending sample.
        index: usize,
        /// The approach, m.
        value: f64,
    },
    /// The contact runs in the hydrodynamic regime: an EHL approach ≤ 0 at a load of the
    /// characterization's range w0·(1 ± ε), where δ^d (and so Q = K·δ^d + ΔF) is not defined.
    /// The message says what helps: a smaller relative load amplitude ε when the approach at w0
    /// is positive, a larger load in any case.
    #[error("{}", hydrodynamic_message(*.approach, *.load, *.time, *.centre_load, *.centre_approach, *.amplitude))]
    HydrodynamicRegime {
        /// The first approach ≤ 0, m.
        approach: f64,
        /// The load at which it occurred, N.
        load: f64,
        /// The time at which it occurred (harmonic method), s.
        time: Option<f64>,
        /// The load at the centre of the range (w0, or the sample next to it), N.
        centre_load: f64,
        /// The (steady) approach at `centre_load`, m.
        centre_approach: f64,
        /// The relative load amplitude ε of the characterization (`method_options.amplitude`).
        amplitude: f64,
    },
    /// The approaches do not span enough distinct values to determine K, d and ΔF.
    #[error("the approaches take only {distinct} distinct value(s) (from {min} m to {max} m); at least 3 are needed")]
    DegenerateApproach {
        /// Number of distinct approaches.
        distinct: usize,
        /// Smallest approach, m.
        min: f64,
        /// Largest approach, m.
        max: f64,
    },
    /// The approach rates do not vary, so c cannot be separated from ΔF.
    #[error(
        "the approach rates are all equal ({value} m/s): the damping c cannot be separated from ΔF"
    )]
    DegenerateRate {
        /// The common rate, m/s.
        value: f64,
    },
    /// The least-squares problem is singular: some parameter is not identifiable.
    #[error("singular fit: {detail}")]
    Singular {
        /// What was singular.
        detail: String,
    },
    /// The iteration did not converge (returned only by [`PowerLawFit::require_converged`]).
    #[error("fit did not converge after {iterations} iterations ({reason}); rms residual {rms_residual} N")]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// Why the iteration stopped.
        reason: LmStop,
        /// Root-mean-square residual at the last iterate, N.
        rms_residual: f64,
    },
    /// A law parameter that is not finite.
    #[error(
        "invalid contact law: non-finite parameter: K = {k}, d = {d}, ΔF = {delta_f}, δ range \
         [{delta_min}, {delta_max}] m, joint fraction {fraction}"
    )]
    LawNotFinite {
        /// K, N/m^d.
        k: f64,
        /// d.
        d: f64,
        /// ΔF, N.
        delta_f: f64,
        /// δ_min, m.
        delta_min: f64,
        /// δ_max, m.
        delta_max: f64,
        /// Joint fraction.
        fraction: f64,
    },
    /// K or d not positive.
    #[error(
        "invalid contact law: K = {k} N/m^d and d = {d} must be positive for an increasing law"
    )]
    LawNotIncreasing {
        /// K, N/m^d.
        k: f64,
        /// d.
        d: f64,
    },
    /// A fitted range that is not 0 < δ_min ≤ δ_max.
    #[error(
        "invalid contact law: fitted range [{delta_min}, {delta_max}] m must satisfy 0 < δ_min ≤ \
         δ_max"
    )]
    LawRange {
        /// δ_min, m.
        delta_min: f64,
        /// δ_max, m.
        delta_max: f64,
    },
    /// A joint fraction outside (0, 1].
    #[error("invalid contact law: joint fraction {fraction} must lie in (0, 1]")]
    LawJointFraction {
        /// The fraction given.
        fraction: f64,
    },
    /// A law whose force at the smallest fitted approach is not positive.
    #[error(
        "invalid contact law: the law gives Q = {q_min} N ≤ 0 at the smallest fitted approach \
         {delta_min} m (ΔF = {delta_f} N)"
    )]
    LawForceNotPositive {
        /// Q(δ_min), N.
        q_min: f64,
        /// δ_min, m.
        delta_min: f64,
        /// ΔF, N.
        delta_f: f64,
    },
    /// A degenerate exponential extension below the joint.
    #[error(
        "invalid contact law: degenerate extension at δ_j = {delta_joint} m: Q_j = {force_joint} \
         N, s = {tail_rate} 1/m"
    )]
    LawExtension {
        /// δ_j, m.
        delta_joint: f64,
        /// Q_j, N.
        force_joint: f64,
        /// Tail rate s, 1/m.
        tail_rate: f64,
    },
    /// A damping coefficient that is not finite.
    #[error("invalid contact law: damping c = {c} N·s/m is not finite")]
    LawDamping {
        /// c, N·s/m.
        c: f64,
    },
}

/// The message of [`FitError::HydrodynamicRegime`]. It names the method option as a case or
/// study file writes it (`method_options.amplitude`); front ends map it to their own names.
fn hydrodynamic_message(
    approach: f64,
    load: f64,
    time: Option<f64>,
    centre_load: f64,
    centre_approach: f64,
    amplitude: f64,
) -> String {
    let at = time.map_or(String::new(), |t| format!(" at t = {t:.3e} s"));
    let remedy = if centre_approach > 0.0 {
        format!(
            "at the centre of the range, {centre_load:.4} N, the approach is \
             {centre_approach:.3e} m > 0: lower the relative load amplitude \
             method_options.amplitude (now {amplitude}; the load spans w0·(1 ± ε), 0 < ε ≤ 0.9) or \
             raise the load"
        )
    } else {
        format!(
            "even at the centre of the range, {centre_load:.4} N, the approach is \
             {centre_approach:.3e} m ≤ 0: raise the load (a smaller method_options.amplitude, now \
             {amplitude}, cannot help)"
        )
    };
    format!(
        "the EHL approach is {approach:.3e} m (≤ 0) at load {load:.4} N{at}: the contact runs in \
         the hydrodynamic regime, where Q = K·δ^d + ΔF is not defined; {remedy}"
    )
}
