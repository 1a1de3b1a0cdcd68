//! Characterization of a lubricated bearing: the coupled loop of the seed paper.
//!
//! dry Hertz equilibrium → for every ball and raceway, characterize the contact (EHL + fit of
//! Q = K·δ^d + ΔF) at that contact's load, sum velocity, Rx and Ry → equilibrium with the fitted
//! laws → repeat until the largest relative change of the contact loads is below a tolerance.
//!
//! - [`ContactCharacterizer`] is the plug-in point for a characterization method:
//!   [`QuasiStaticCharacterizer`] runs the EHL quasi-static method of `crate::contact`;
//!   [`HertzCharacterizer`] is the documented reference method used by the tests;
//!   [`SyntheticCharacterizer`] has known load- and speed-dependent parameters for testing trend
//!   curves.
//! - [`characterize_bearing`] runs the loop. Contacts of one iteration are characterized in
//!   parallel (rayon); the result does not depend on the number of threads (bitwise).
//! - Fitted laws are cached by their dimensionless inputs (Moes M, L, Ry/Rx; exact match of the
//!   method settings, E′, lubricant and ball mass) and reused, rescaled to the new contact's
//!   dimensions, within a relative key tolerance; the largest key distance used is reported. A law
//!   from an earlier iteration is also reused while the contact's load stays within
//!   [`CharacterizeSettings::load_reuse_tolerance`] of the load it was characterized at and
//!   inside its fitted load range (its force error there is the fit residual, reported).
//! - A method may offer a cheap load predictor ([`ContactCharacterizer::predictor`]; for the
//!   quasi-static method one loosely converged steady EHL solution per contact, [`PredictedLaw`])
//!   that moves the loop's start from the dry loads to near the lubricated ones, so that the
//!   first characterization is already centred within the reuse tolerance of the final loads.
//!
//! The loop, the cache and its error bounds are described in `docs/study.md`.

use crate::bearing::{
    solve_equilibrium, BearingError, ContactLaws, ContactState, Equilibrium, Race,
};
use crate::contact_law::ContactLaw;
use crate::ehl::{solve_steady, EhlContact, EhlSettings};
use crate::fit::{fit_power_law, FitOptions, FittedLaw, RangeStatus};
use crate::hertz::HertzGeometry;
use crate::io::Case;
use crate::material::Lubricant;
use rayon::prelude::*;
use serde::Serialize;
use serde_json::{json, Value};
use std::sync::Arc;
use std::time::Instant;
use thiserror::Error;

/// Errors of the characterization loop, the study and the trend curves.
#[derive(Debug, Error)]
pub enum CharacterizeError {
    /// A setting has an invalid value.
    #[error("{field} = {value}: expected {expected}")]
    Setting {
        /// The setting, e.g. `characterize.tolerance`.
        field: String,
        /// The value given.
        value: String,
        /// The valid range.
        expected: String,
    },
    /// The dry (Hertz) equilibrium that starts the loop failed.
    #[error("dry Hertz equilibrium failed: {0}")]
    DryEquilibrium(BearingError),
    /// Characterizing one contact failed.
    #[error("characterization of ball {ball} {race:?} contact at load {load:.6e} N failed in iteration {iteration}: {cause}")]
    Contact {
        /// Ball index.
        ball: usize,
        /// Raceway.
        race: Race,
        /// Load the contact was characterized at, N.
        load: f64,
        /// Loop iteration (1-based).
        iteration: usize,
        /// What went wrong.
        cause: Box<crate::Error>,
    },
    /// The equilibrium with the fitted laws failed.
    #[error("equilibrium with the fitted laws failed in iteration {iteration}: {cause}")]
    Equilibrium {
        /// Loop iteration (1-based).
        iteration: usize,
        /// The equilibrium error.
        cause: BearingError,
    },
    /// The loop hit its iteration limit (only when
    /// [`CharacterizeSettings::error_if_not_converged`] is set; otherwise the result says
    /// `converged: false`).
    #[error("characterization did not converge after {iterations} iterations: largest relative load change {change:.3e} (tolerance {tolerance:.1e})")]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// Last largest relative load change (dimensionless).
        change: f64,
        /// Tolerance (dimensionless).
        tolerance: f64,
    },
    /// A trend-curve fit or a trend model is invalid.
    #[error("trend curves: {0}")]
    Trend(String),
}

impl CharacterizeError {
    pub(crate) fn setting(
        field: impl Into<String>,
        value: impl ToString,
        expected: impl Into<String>,
    ) -> Self {
        CharacterizeError::Setting {
            field: field.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }
}

/// Operating conditions of one ball/raceway contact (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactConditions {
    /// Which raceway.
    pub race: Race,
    /// Normal load w0 the contact is characterized at, N (> 0).
    pub load: f64,
    /// Curvature radius in the rolling direction, m.
    pub rx: f64,
    /// Transverse curvature radius, m.
    pub ry: f64,
    /// Sum velocity u_s = u1 + u2 (entrainment velocity times two), m/s (≥ 0).
    pub sum_velocity: f64,
    /// Reduced modulus E′ (2/E′ = (1−ν1²)/E1 + (1−ν2²)/E2), Pa.
    pub e_reduced: f64,
    /// Lubricant.
    pub lubricant: Lubricant,
    /// Ball mass, kg (the moving mass of a dynamic characterization).
    pub ball_mass: f64,
}

/// Dimensionless groups of an EHL point contact (Moes; see DESIGN.md §2 for the definitions —
/// the seed paper's eq. (7) is wrong).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MoesParameters {
    /// Load parameter W = w/(E′Rx²).
    pub w: f64,
    /// Speed parameter U = η0·u_s/(E′Rx) (u_s: sum velocity).
    pub u: f64,
    /// Material parameter G = α·E′.
    pub g: f64,
    /// Moes load parameter M = W·U^(−3/4) (infinite when U = 0).
    pub m: f64,
    /// Moes lubricant parameter L = G·U^(1/4).
    pub l: f64,
}

impl CharacterizedContact {
    /// The characterized contact of an EHL method's fit (`contact::ContactFit`) at load `load`
    /// (N): the approach where the law gives `load` (the fit's centre approach if the law cannot
    /// reach it), the law's largest force residual `max_residual` (N) over the `samples` fitted
    /// samples; the method's name is the fit's.
    pub fn from_fit(
        fit: crate::contact::ContactFit,
        load: f64,
        max_residual: f64,
        samples: usize,
    ) -> Self {
        let approach = fit.law.approach_at(load).unwrap_or(fit.approach);
        CharacterizedContact {
            law: fit.law,
            k: fit.k,
            d: fit.d,
            delta_f: fit.delta_f,
            load,
            approach,
            moes_m: fit.moes_m,
            moes_l: fit.moes_l,
            ry_over_rx: fit.ry_over_rx,
            r_squared: fit.r_squared,
            rms_residual: fit.rms_residual,
            max_residual,
            std_errors: [fit.std_errors.k, fit.std_errors.d, fit.std_errors.delta_f],
            converged: fit.converged,
            method: fit.method,
            seconds: fit.seconds,
            samples,
        }
    }
}

impl ContactConditions {
    /// The steady EHL problem of this contact at its load `load` (N).
    pub fn ehl_contact(&self) -> EhlContact {
        EhlContact {
            load: self.load,
            rx: self.rx,
            ry: self.ry,
            sum_velocity: self.sum_velocity,
            e_reduced: self.e_reduced,
            lubricant: self.lubricant,
        }
    }

    /// Moes' dimensionless parameters of this contact.
    pub fn moes(&self) -> MoesParameters {
        let w = self.load / (self.e_reduced * self.rx * self.rx);
        let u = self.lubricant.viscosity * self.sum_velocity / (self.e_reduced * self.rx);
        let g = self.lubricant.pressure_viscosity * self.e_reduced;
        MoesParameters {
            w,
            u,
            g,
            m: w * u.powf(-0.75),
            l: g * u.powf(0.25),
        }
    }

    /// Ratio Ry/Rx (dimensionless).
    pub fn ry_over_rx(&self) -> f64 {
        self.ry / self.rx
    }

    fn validate(&self) -> Result<(), crate::Error> {
        let checks = [
            ("load", self.load, "a positive finite load in N"),
            ("rx", self.rx, "a positive curvature radius in m"),
            ("ry", self.ry, "a positive curvature radius in m"),
            ("e_reduced", self.e_reduced, "a positive modulus in Pa"),
        ];
        for (field, v, expected) in checks {
            if !(v.is_finite() && v > 0.0) {
                return Err(CharacterizeError::setting(field, v, expected).into());
            }
        }
        if !(self.sum_velocity.is_finite() && self.sum_velocity >= 0.0) {
            return Err(CharacterizeError::setting(
                "sum_velocity",
                self.sum_velocity,
                "a finite sum velocity ≥ 0 in m/s",
            )
            .into());
        }
        Ok(())
    }
}

/// A characterized contact: the fitted law and what a user needs to judge it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CharacterizedContact {
    /// The fitted law Q(δ) with its extension below the fitted range.
    pub law: FittedLaw,
    /// Stiffness K, N/m^d.
    pub k: f64,
    /// Nonlinear index d (dimensionless; 1.5 for dry Hertz).
    pub d: f64,
    /// Hydrodynamic lift at zero approach ΔF, N.
    pub delta_f: f64,
    /// Load the contact was characterized at, N.
    pub load: f64,
    /// Approach δ of the fitted law at `load`, m.
    pub approach: f64,
    /// Moes load parameter M (dimensionless).
    pub moes_m: f64,
    /// Moes lubricant parameter L (dimensionless).
    pub moes_l: f64,
    /// Ry/Rx (dimensionless).
    pub ry_over_rx: f64,
    /// Coefficient of determination of the fit (dimensionless).
    pub r_squared: f64,
    /// Root-mean-square residual of the fit, N.
    pub rms_residual: f64,
    /// Largest absolute residual |Q_law(δ_k) − Q_k| over the fitted samples, N: the estimate of
    /// the law's force error anywhere inside its fitted range (between the samples the EHL
    /// force–approach curve is smooth), whether the contact operates at the characterization load
    /// or elsewhere in the range (a reused law, `docs/study.md` §3.2).
    pub max_residual: f64,
    /// Standard errors of (K in N/m^d, d, ΔF in N) from the fit's linearized covariance (K's is
    /// large relative to K: K and d are strongly correlated).
    pub std_errors: [f64; 3],
    /// Whether the characterization (solver and fit) converged.
    pub converged: bool,
    /// Name of the method.
    pub method: String,
    /// Wall-clock time of the characterization, s (not reproducible; never written to files
    /// that are compared between runs).
    pub seconds: f64,
    /// Number of (δ, Q) samples fitted.
    pub samples: usize,
}

/// A method that characterizes one contact: computes (δ, Q) samples around the contact's load and
/// fits Q = K·δ^d + ΔF. Implementations must be deterministic (same input, same bits) for the
/// loop's results not to depend on the number of threads.
pub trait ContactCharacterizer: Sync + Send {
    /// Characterize the contact `c`.
    fn characterize(&self, c: &ContactConditions) -> Result<CharacterizedContact, crate::Error>;
    /// Settings that define the excitation/method, part of the cache key and written into results.
    fn settings_json(&self) -> Value;
    /// Name of the method, e.g. `hertz`.
    fn name(&self) -> &str;
    /// The method's load predictor, if it has one (default: none, the loop starts from the dry
    /// Hertz loads).
    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        None
    }
}

/// A cheap approximate law of a contact near a load, used by the loop (with
/// [`CharacterizeSettings::predict_loads`]) to predict the lubricated loads before the first
/// characterization. It only moves the point where the first characterization is centred; the
/// result is still the loop's fixed point with the characterized laws. Must be deterministic.
pub trait LoadPredictor: Sync + Send {
    /// The predictor law of contact `c` near `c.load`.
    fn predict(&self, c: &ContactConditions) -> Result<PredictedLaw, crate::Error>;
}

/// A load predictor law: dry Hertz shifted by an effective film h,
///
/// ```text
/// Q(δ) = K_H·(δ + h)^1.5   for δ > −h,   0 otherwise
/// ```
///
/// with K_H the contact's Hertz constant (N/m^1.5) and h = δ_H(w0) − δ_EHL(w0) (m) from one steady
/// EHL solution at the load w0, so Q(δ_EHL(w0)) = w0 exactly. The lubricated approach is the
/// Hertz approach minus a film term that varies only weakly with the load (≈ Q^−0.06,
/// `docs/study.md` §6), so this law predicts the contact's load near w0 closely: on the seed
/// case the loads of the predicted equilibrium are within 0.7 % of the converged lubricated
/// ones (dry Hertz: up to 26 %), `docs/study.md` §3.3. Never used for results.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PredictedLaw {
    /// Hertz load–deflection constant K_H, N/m^1.5.
    pub stiffness: f64,
    /// Effective film h, m (the shift of the approach against dry Hertz).
    pub film: f64,
    /// Whether the solution behind it met its (loosened) convergence criteria.
    pub converged: bool,
}

impl PredictedLaw {
    /// A predictor law; errors if K_H is not positive or h is not finite.
    pub fn new(stiffness: f64, film: f64, converged: bool) -> Result<Self, CharacterizeError> {
        if !(stiffness.is_finite() && stiffness > 0.0 && film.is_finite()) {
            return Err(CharacterizeError::setting(
                "predicted law",
                format!("K_H = {stiffness} N/m^1.5, h = {film} m"),
                "a positive Hertz constant and a finite film",
            ));
        }
        Ok(PredictedLaw {
            stiffness,
            film,
            converged,
        })
    }
}

impl ContactLaw for PredictedLaw {
    fn force(&self, approach: f64) -> (f64, f64) {
        let x = approach + self.film;
        if x > 0.0 {
            let s = x.sqrt();
            (self.stiffness * x * s, 1.5 * self.stiffness * s)
        } else {
            (0.0, 0.0)
        }
    }

    fn approach_at(&self, load: f64) -> Option<f64> {
        if load >= 0.0 && load.is_finite() {
            Some((load / self.stiffness).powf(2.0 / 3.0) - self.film)
        } else {
            None
        }
    }
}

/// Largest absolute residual of `law` over the samples (δ_k, Q_k), N.
fn max_abs_residual(law: &FittedLaw, delta: &[f64], q: &[f64]) -> f64 {
    delta
        .iter()
        .zip(q)
        .map(|(&d, &w)| (law.force(d).0 - w).abs())
        .fold(0.0_f64, f64::max)
}

/// Sample loads w0·(1 + ε·(2i/(n−1) − 1)), i = 0..n−1.
fn sample_loads(w0: f64, samples: usize, amplitude: f64) -> Vec<f64> {
    (0..samples)
        .map(|i| w0 * (1.0 + amplitude * (2.0 * i as f64 / (samples - 1) as f64 - 1.0)))
        .collect()
}

fn check_sampling(samples: usize, amplitude: f64) -> Result<(), crate::Error> {
    if !(4..=10_000).contains(&samples) {
        return Err(
            CharacterizeError::setting("samples", samples, "an integer from 4 to 10000").into(),
        );
    }
    if !(amplitude.is_finite() && amplitude > 0.0 && amplitude < 1.0) {
        return Err(CharacterizeError::setting(
            "amplitude",
            amplitude,
            "a relative amplitude ε with 0 < ε < 1",
        )
        .into());
    }
    Ok(())
}

/// Fit samples and assemble a [`CharacterizedContact`].
fn fit_samples(
    c: &ContactConditions,
    delta: &[f64],
    q: &[f64],
    method: &str,
    start: Instant,
) -> Result<CharacterizedContact, crate::Error> {
    let fit = fit_power_law(delta, q, &FitOptions::default())?;
    let law = fit.law()?;
    let approach = law.approach_at(c.load).ok_or_else(|| {
        CharacterizeError::Trend(format!(
            "the fitted law does not reach the load {} N",
            c.load
        ))
    })?;
    let moes = c.moes();
    Ok(CharacterizedContact {
        law,
        k: fit.k,
        d: fit.d,
        delta_f: fit.delta_f,
        load: c.load,
        approach,
        moes_m: moes.m,
        moes_l: moes.l,
        ry_over_rx: c.ry_over_rx(),
        r_squared: fit.r_squared,
        rms_residual: fit.rms_residual,
        max_residual: max_abs_residual(&law, delta, q),
        std_errors: [fit.std_errors.k, fit.std_errors.d, fit.std_errors.delta_f],
        converged: fit.converged,
        method: method.to_string(),
        seconds: start.elapsed().as_secs_f64(),
        samples: delta.len(),
    })
}

/// Reference method: samples the contact's dry Hertz law Q = K_H·δ^1.5 (exact elliptic integrals,
/// [`HertzGeometry`]) at loads w0·(1 ± ε) and fits Q = K·δ^d + ΔF to them, so it returns
/// K = K_H, d = 1.5, ΔF = 0 to fit precision. The coupled loop with it reproduces the dry
/// equilibrium (with K evaluated at each contact's operating contact angle): a test of the
/// plumbing, and the method of choice for a dry or very heavily loaded bearing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzCharacterizer {
    /// Number of samples n (≥ 4; default 9).
    pub samples: usize,
    /// Relative load amplitude ε of the samples (0 < ε < 1; default 0.2).
    pub amplitude: f64,
}

impl Default for HertzCharacterizer {
    fn default() -> Self {
        HertzCharacterizer {
            samples: 9,
            amplitude: 0.2,
        }
    }
}

impl ContactCharacterizer for HertzCharacterizer {
    fn characterize(&self, c: &ContactConditions) -> Result<CharacterizedContact, crate::Error> {
        let start = Instant::now();
        c.validate()?;
        check_sampling(self.samples, self.amplitude)?;
        let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
        let q = sample_loads(c.load, self.samples, self.amplitude);
        let delta: Vec<f64> = q.iter().map(|&w| h.contact(w).deflection).collect();
        fit_samples(c, &delta, &q, self.name(), start)
    }

    fn settings_json(&self) -> Value {
        json!({"samples": self.samples, "amplitude": self.amplitude})
    }

    fn name(&self) -> &str {
        "hertz"
    }
}

/// A synthetic characterizer with known, smooth load and speed dependence, for testing trend
/// curves and the loop. At load w and sum velocity u_s:
///
/// ```text
/// d(w)      = 1.5 − d_amplitude·(w/load_ref)^(−d_exponent)
/// ΔF(w,u_s) = lift_ref·(w/load_ref)^lift_load_exponent·(u_s/speed_ref)^lift_speed_exponent
/// K(w)      = (w − ΔF)/δ_H(w − ΔF)^d,   δ_H(x) = (x/K_H)^(2/3)  (Hertz approach)
/// ```
///
/// so that the law reaches w at the Hertz approach of w − ΔF (the lift carries ΔF: a smaller
/// approach than dry, as in EHL), sampled at w·(1 ± ε) from the law with the parameters frozen at
/// w and fitted like the other methods (so the fit returns these K, d, ΔF to fit precision). Not
/// physics: a test fixture.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SyntheticCharacterizer {
    /// Amplitude of the deviation of d from 1.5 at `load_ref` (dimensionless).
    pub d_amplitude: f64,
    /// Exponent of the decay of that deviation with load (dimensionless, > 0).
    pub d_exponent: f64,
    /// Reference load, N.
    pub load_ref: f64,
    /// Lift ΔF at `load_ref` and `speed_ref`, N.
    pub lift_ref: f64,
    /// Load exponent of ΔF (dimensionless).
    pub lift_load_exponent: f64,
    /// Speed exponent of ΔF (dimensionless).
    pub lift_speed_exponent: f64,
    /// Reference sum velocity, m/s.
    pub speed_ref: f64,
    /// Number of samples (≥ 4).
    pub samples: usize,
    /// Relative load amplitude of the samples.
    pub amplitude: f64,
}

impl Default for SyntheticCharacterizer {
    fn default() -> Self {
        SyntheticCharacterizer {
            d_amplitude: 0.1,
            d_exponent: 0.5,
            load_ref: 100.0,
            lift_ref: 2.0,
            lift_load_exponent: 0.3,
            lift_speed_exponent: 0.7,
            speed_ref: 10.0,
            samples: 9,
            amplitude: 0.2,
        }
    }
}

impl SyntheticCharacterizer {
    /// (K in N/m^d, d, ΔF in N) at load `w` (N) and sum velocity `us` (m/s) for a contact with
    /// Hertz constant `k_hertz` (N/m^1.5).
    pub fn parameters(&self, w: f64, us: f64, k_hertz: f64) -> (f64, f64, f64) {
        let d = 1.5 - self.d_amplitude * (w / self.load_ref).powf(-self.d_exponent);
        let lift = self.lift_ref
            * (w / self.load_ref).powf(self.lift_load_exponent)
            * (us / self.speed_ref).powf(self.lift_speed_exponent);
        let dh = ((w - lift).max(0.0) / k_hertz).powf(2.0 / 3.0);
        ((w - lift) / dh.powf(d), d, lift)
    }
}

impl ContactCharacterizer for SyntheticCharacterizer {
    fn characterize(&self, c: &ContactConditions) -> Result<CharacterizedContact, crate::Error> {
        let start = Instant::now();
        c.validate()?;
        check_sampling(self.samples, self.amplitude)?;
        let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
        let (k, d, lift) = self.parameters(c.load, c.sum_velocity, h.stiffness);
        if !(k.is_finite() && k > 0.0 && d > 0.0 && lift < 0.5 * c.load) {
            return Err(CharacterizeError::setting(
                "synthetic parameters",
                format!("K = {k}, d = {d}, ΔF = {lift} at w = {} N", c.load),
                "K > 0, d > 0 and ΔF < w/2",
            )
            .into());
        }
        let q = sample_loads(c.load, self.samples, self.amplitude);
        let delta: Vec<f64> = q.iter().map(|&w| ((w - lift) / k).powf(1.0 / d)).collect();
        fit_samples(c, &delta, &q, self.name(), start)
    }

    fn settings_json(&self) -> Value {
        serde_json::to_value(self).unwrap_or(Value::Null)
    }

    fn name(&self) -> &str {
        "synthetic"
    }
}

/// The EHL quasi-static method ([`crate::contact::characterize_quasi_static`]: a family of steady
/// EHL solutions at w0·(1 ± ε), fitted) as a [`ContactCharacterizer`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct QuasiStaticCharacterizer {
    /// Settings of the method (amplitude, number of solutions, EHL grid and solver).
    pub settings: crate::contact::QuasiStaticSettings,
}

impl ContactCharacterizer for QuasiStaticCharacterizer {
    fn characterize(&self, c: &ContactConditions) -> Result<CharacterizedContact, crate::Error> {
        c.validate()?;
        let fit = crate::contact::characterize_quasi_static(&c.ehl_contact(), &self.settings)?;
        let (delta, q): (Vec<f64>, Vec<f64>) =
            fit.samples.iter().map(|x| (x.approach, x.load)).unzip();
        let max_residual = max_abs_residual(&fit.law, &delta, &q);
        let samples = fit.samples.len();
        Ok(CharacterizedContact::from_fit(
            fit,
            c.load,
            max_residual,
            samples,
        ))
    }

    fn settings_json(&self) -> Value {
        serde_json::to_value(self.settings).unwrap_or(Value::Null)
    }

    fn name(&self) -> &str {
        "quasi-static"
    }

    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        Some(self)
    }
}

impl LoadPredictor for QuasiStaticCharacterizer {
    /// One steady EHL solution at `c.load` with the method's grid and domain, converged to
    /// [`PREDICTOR_TOLERANCE`] (100–1000× looser than the family's solutions: a third of the
    /// cycles, and the predicted loads hardly change — within 0.64 % of the converged ones at
    /// 5000 rpm on the seed case, 0.62 % with the family's tolerances), turned into a
    /// [`PredictedLaw`].
    fn predict(&self, c: &ContactConditions) -> Result<PredictedLaw, crate::Error> {
        predict_steady(c, &self.settings.ehl)
    }
}

/// The load predictor shared by the EHL methods: one steady EHL solution at `c.load` with the
/// grid and domain of `ehl` but its tolerances loosened to [`PREDICTOR_TOLERANCE`], turned into a
/// [`PredictedLaw`] (dry Hertz shifted by h = δ_Hertz(w0) − δ_EHL(w0), m).
pub fn predict_steady(
    c: &ContactConditions,
    ehl: &EhlSettings,
) -> Result<PredictedLaw, crate::Error> {
    c.validate()?;
    let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
    let e = ehl;
    let settings = EhlSettings {
        tol_residual: e.tol_residual.max(PREDICTOR_TOLERANCE),
        tol_force: e.tol_force.max(PREDICTOR_TOLERANCE),
        tol_film: e.tol_film.max(PREDICTOR_TOLERANCE),
        ..*e
    };
    let sol = solve_steady(&c.ehl_contact(), &settings)?;
    let film = h.contact(c.load).deflection - sol.approach;
    Ok(PredictedLaw::new(h.stiffness, film, sol.converged)?)
}

/// Convergence tolerance of the predictor's steady EHL solution (relative Reynolds residual,
/// force balance and film change; dimensionless).
pub const PREDICTOR_TOLERANCE: f64 = 1e-2;

/// Settings of [`characterize_bearing`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CharacterizeSettings {
    /// Converged when the largest relative change of the contact loads between two iterations is
    /// below this (dimensionless; default 1e-3).
    pub tolerance: f64,
    /// Iteration limit (default 20).
    pub max_iterations: usize,
    /// Relative key tolerance of the law cache: a law is reused for a contact whose (M, L, Ry/Rx)
    /// are all within this relative distance of a characterized contact's (dimensionless;
    /// default 1e-3; 0 reuses only exact matches).
    pub cache_tolerance: f64,
    /// Contacts with a load below this fraction of the largest contact load are characterized at
    /// that floor load instead (dimensionless, default 0.01); the floor is also the scale of the
    /// relative load change for such contacts.
    pub min_load_fraction: f64,
    /// Return [`CharacterizeError::NotConverged`] instead of a result with `converged: false`
    /// when the iteration limit is hit (default false).
    pub error_if_not_converged: bool,
    /// Load reuse: a law from an earlier iteration is reused for a contact whose L and Ry/Rx are
    /// within `cache_tolerance` of the law's and whose Moes M (at equal L: its load) differs by at
    /// most this relative (logarithmic) distance, provided the load lies inside the law's fitted
    /// load range (dimensionless, default 0.01; 0 disables it, then only `cache_tolerance`
    /// applies). The reused law's force error is its fit residual; its K, d, ΔF are those
    /// characterized at the other load: at 1 % they differ from a re-centred characterization by
    /// less than one standard error of the fit (measured, `docs/study.md` §3.2).
    pub load_reuse_tolerance: f64,
    /// Start the loop from loads predicted with the method's [`ContactCharacterizer::predictor`]
    /// laws instead of the dry Hertz loads, when the method offers a predictor (default true).
    pub predict_loads: bool,
}

impl Default for CharacterizeSettings {
    fn default() -> Self {
        CharacterizeSettings {
            tolerance: 1e-3,
            max_iterations: 20,
            cache_tolerance: 1e-3,
            min_load_fraction: 0.01,
            error_if_not_converged: false,
            load_reuse_tolerance: 0.01,
            predict_loads: true,
        }
    }
}

impl CharacterizeSettings {
    /// Check every setting; the error names the setting, its value and the valid range.
    pub fn validate(&self) -> Result<(), CharacterizeError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(CharacterizeError::setting(
                "tolerance",
                self.tolerance,
                "a relative load tolerance with 0 < tol < 1",
            ));
        }
        if !(1..=1000).contains(&self.max_iterations) {
            return Err(CharacterizeError::setting(
                "max_iterations",
                self.max_iterations,
                "an integer from 1 to 1000",
            ));
        }
        if !(self.cache_tolerance.is_finite()
            && self.cache_tolerance >= 0.0
            && self.cache_tolerance <= 0.1)
        {
            return Err(CharacterizeError::setting(
                "cache_tolerance",
                self.cache_tolerance,
                "a relative key tolerance from 0 to 0.1",
            ));
        }
        if !(self.min_load_fraction.is_finite()
            && self.min_load_fraction > 0.0
            && self.min_load_fraction < 1.0)
        {
            return Err(CharacterizeError::setting(
                "min_load_fraction",
                self.min_load_fraction,
                "a fraction with 0 < f < 1",
            ));
        }
        if !(self.load_reuse_tolerance.is_finite()
            && self.load_reuse_tolerance >= 0.0
            && self.load_reuse_tolerance <= 0.5)
        {
            return Err(CharacterizeError::setting(
                "load_reuse_tolerance",
                self.load_reuse_tolerance,
                "a relative load tolerance from 0 to 0.5",
            ));
        }
        Ok(())
    }
}

/// How a contact's law was obtained in an iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawSource {
    /// Characterized for this contact.
    Characterized,
    /// Reused from the cache of earlier iterations, rescaled to this contact.
    Cached,
    /// Reused from another contact characterized in the same iteration (lower index), rescaled.
    Deduplicated,
}

/// One ball/raceway contact in the final state of the loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactResult {
    /// Ball index (ball 0 on +y).
    pub ball: usize,
    /// Raceway.
    pub race: Race,
    /// The law used in the final equilibrium and what it was characterized at (its `load` is the
    /// characterization load w0, the equilibrium load of the previous iteration or the floor).
    pub characterized: CharacterizedContact,
    /// Whether the characterization load was raised to the floor (lightly loaded contact).
    pub load_floored: bool,
    /// Where the law came from in the last iteration.
    pub source: LawSource,
    /// Relative key distance to the characterized contact the law came from (0 if characterized
    /// for this contact), dimensionless.
    pub key_distance: f64,
    /// Equilibrium state of the contact (load, contact angle, approach, Rx, Ry, sum velocity).
    pub state: ContactState,
    /// The law evaluated at the equilibrium approach, N (equals `state.load` to the equilibrium
    /// tolerance: the consistency check).
    pub law_load_at_approach: f64,
    /// Relative offset of the equilibrium load from the load the law was characterized at,
    /// Q/w0 − 1 (dimensionless; for a floored contact, from the floor).
    pub load_offset: f64,
    /// Where the equilibrium approach lies relative to the law's fitted range.
    pub range_status: RangeStatus,
}

/// One iteration of the loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IterationRecord {
    /// Iteration number (1-based).
    pub iteration: usize,
    /// Largest relative change of the contact loads against the previous equilibrium.
    pub max_load_change: f64,
    /// Contacts characterized in this iteration.
    pub characterized: usize,
    /// Contacts whose law was reused (cache or same-iteration duplicate).
    pub reused: usize,
    /// Largest relative key distance of a reused law in this iteration (0 if none).
    pub max_key_distance: f64,
    /// Largest relative offset |w/w0 − 1| between a contact's load in this iteration and the
    /// load its reused law was characterized at (0 if none reused), dimensionless.
    pub max_load_offset: f64,
    /// Largest fit residual of the laws of this iteration relative to the load they were
    /// characterized at (max_residual/w0; the force error bound inside the fitted range),
    /// dimensionless.
    pub max_relative_residual: f64,
    /// Newton iterations of the equilibrium with the fitted laws.
    pub equilibrium_iterations: usize,
    /// Wall-clock time of the iteration, s.
    pub seconds: f64,
}

/// The load prediction that started the loop ([`CharacterizeSettings::predict_loads`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PredictionRecord {
    /// Contacts predicted.
    pub contacts: usize,
    /// Predictor solutions that stopped short of their tolerance (used all the same: the
    /// prediction only moves where the first characterization is centred).
    pub not_converged: usize,
    /// Contacts whose predictor failed and kept their dry Hertz law for the prediction.
    pub failed: usize,
    /// Largest relative change of the contact loads from the dry to the predicted equilibrium.
    pub max_load_change: f64,
    /// Newton iterations of the predicted equilibrium (0 if it failed).
    pub equilibrium_iterations: usize,
    /// Why the predicted equilibrium failed, if it did (the loop then starts from the dry one).
    pub error: Option<String>,
    /// Wall-clock time of the prediction, s.
    pub seconds: f64,
}

/// Result of [`characterize_bearing`].
#[derive(Debug, Clone, Serialize)]
pub struct BearingCharacterization {
    /// Whether the load change fell below the tolerance.
    pub converged: bool,
    /// Iterations performed.
    pub iterations: usize,
    /// Last largest relative load change (dimensionless).
    pub max_load_change: f64,
    /// Per-iteration history.
    pub history: Vec<IterationRecord>,
    /// The dry Hertz equilibrium the loop started from.
    pub dry: Equilibrium,
    /// The final equilibrium with the fitted laws.
    pub equilibrium: Equilibrium,
    /// Per-contact results, ordered ball 0 inner, ball 0 outer, ball 1 inner, …
    pub contacts: Vec<ContactResult>,
    /// Method name.
    pub method: String,
    /// Method settings.
    pub method_settings: Value,
    /// Loop settings.
    pub settings: CharacterizeSettings,
    /// Largest relative key distance of any reused law in the final iteration (dimensionless).
    pub max_key_distance: f64,
    /// Largest |load_offset| of the final contacts that were not floored: how far from its
    /// characterization load a final law is used (dimensionless).
    pub max_load_offset: f64,
    /// Largest max_residual/w0 of the final laws (dimensionless): the relative force error bound
    /// of the laws inside their fitted ranges.
    pub max_relative_residual: f64,
    /// The load prediction the loop started from (None: started from the dry loads).
    pub prediction: Option<PredictionRecord>,
    /// Total wall-clock time, s.
    pub seconds: f64,
}

impl BearingCharacterization {
    /// Dry stiffness matrix ∂reaction/∂displacement (N/m, N, N·m/rad), order x, y, z, θy, θz.
    pub fn dry_stiffness(&self) -> [[f64; 5]; 5] {
        self.dry.stiffness
    }
    /// Stiffness matrix of the final equilibrium with the fitted (EHL) laws.
    pub fn ehl_stiffness(&self) -> [[f64; 5]; 5] {
        self.equilibrium.stiffness
    }
    /// The fitted laws of the final equilibrium, as bearing contact laws.
    pub fn laws(&self) -> ContactLaws {
        let mut inner = Vec::new();
        let mut outer = Vec::new();
        for c in &self.contacts {
            let law: Arc<dyn ContactLaw> = Arc::new(c.characterized.law);
            match c.race {
                Race::Inner => inner.push(law),
                Race::Outer => outer.push(law),
            }
        }
        ContactLaws { inner, outer }
    }
}

/// Cache key: context (exact) + dimensionless inputs (within a relative tolerance).
#[derive(Debug, Clone)]
struct CacheEntry {
    key: [f64; 3],
    conditions: ContactConditions,
    result: CharacterizedContact,
    /// Fitted range of the law in the load parameter W = Q/(E′Rx²), [W(δ_min), W(δ_max)].
    w_range: [f64; 2],
}

impl CacheEntry {
    fn new(key: [f64; 3], conditions: ContactConditions, result: CharacterizedContact) -> Self {
        let [lo, hi] = result.law.fit_range();
        let scale = conditions.e_reduced * conditions.rx * conditions.rx;
        let w_range = [
            result.law.force(lo).0 / scale,
            result.law.force(hi).0 / scale,
        ];
        CacheEntry {
            key,
            conditions,
            result,
            w_range,
        }
    }
}

/// Load parameter W = Q/(E′Rx²) of a contact.
fn load_parameter(c: &ContactConditions) -> f64 {
    c.load / (c.e_reduced * c.rx * c.rx)
}

/// Componentwise relative distances |ln(a/b)| of two keys (∞ where a component is not finite
/// and positive).
fn key_components(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    let mut d = [0.0; 3];
    for k in 0..3 {
        d[k] = if a[k].is_finite() && b[k].is_finite() && a[k] > 0.0 && b[k] > 0.0 {
            (a[k] / b[k]).ln().abs()
        } else {
            f64::INFINITY
        };
    }
    d
}

/// Relative distance between two keys: max over components of |ln(a/b)| (∞ if a component is not
/// finite and positive).
fn key_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let [m, l, r] = key_components(a, b);
    m.max(l).max(r)
}

/// Rescale a characterized contact to new conditions with (nearly) the same L and Ry/Rx:
/// Q/(E′Rx²) as a function of δ/Rx is kept, so K′ = K·(E′′/E′)·(Rx′/Rx)^(2−d),
/// ΔF′ = ΔF·(E′′/E′)·(Rx′/Rx)², δ-range × Rx′/Rx, and the characterization load and the
/// residuals × (E′′/E′)·(Rx′/Rx)² (the result describes where the law was characterized, at the
/// new contact's scale; its load may differ from `to.load` by the load reuse tolerance).
fn rescale(
    from: &CacheEntry,
    to: &ContactConditions,
) -> Result<CharacterizedContact, crate::Error> {
    let r = to.rx / from.conditions.rx;
    let e = to.e_reduced / from.conditions.e_reduced;
    let src = &from.result;
    let k = src.k * e * r.powf(2.0 - src.d);
    let delta_f = src.delta_f * e * r * r;
    let [lo, hi] = src.law.fit_range();
    let mut law = FittedLaw::new(k, src.d, delta_f, lo * r, hi * r)?;
    if let Some(c) = src.law.c() {
        law = law.with_damping(c)?;
    }
    let load = src.load * e * r * r;
    let approach = law
        .approach_at(load)
        .ok_or_else(|| CharacterizeError::Trend(format!("rescaled law does not reach {load} N")))?;
    let moes = ContactConditions { load, ..*to }.moes();
    Ok(CharacterizedContact {
        law,
        k,
        d: src.d,
        delta_f,
        load,
        approach,
        moes_m: moes.m,
        moes_l: moes.l,
        ry_over_rx: to.ry_over_rx(),
        r_squared: src.r_squared,
        rms_residual: src.rms_residual * e * r * r,
        max_residual: src.max_residual * e * r * r,
        std_errors: [
            src.std_errors[0] * e * r.powf(2.0 - src.d),
            src.std_errors[1],
            src.std_errors[2] * e * r * r,
        ],
        converged: src.converged,
        method: src.method.clone(),
        seconds: 0.0,
        samples: src.samples,
    })
}

fn contact_key(c: &ContactConditions) -> [f64; 3] {
    let m = c.moes();
    [m.m, m.l, c.ry_over_rx()]
}

/// Conditions of every contact (ball-major, inner then outer) at an equilibrium, with the floor.
fn conditions_of(
    case: &Case,
    eq: &Equilibrium,
    floor_fraction: f64,
) -> Vec<(ContactConditions, bool)> {
    let qmax = eq
        .balls
        .iter()
        .flat_map(|b| [b.inner.load, b.outer.load])
        .fold(0.0_f64, f64::max);
    let floor = (floor_fraction * qmax).max(1e-6);
    let e_reduced = case.bearing.reduced_modulus();
    let mass = case.bearing.ball_mass();
    let mut out = Vec::with_capacity(2 * eq.balls.len());
    for b in &eq.balls {
        for (race, s) in [(Race::Inner, &b.inner), (Race::Outer, &b.outer)] {
            let floored = s.load.is_nan() || s.load < floor;
            out.push((
                ContactConditions {
                    race,
                    load: if floored { floor } else { s.load },
                    rx: s.rx,
                    ry: s.ry,
                    sum_velocity: s.sum_velocity,
                    e_reduced,
                    lubricant: case.lubricant,
                    ball_mass: mass,
                },
                floored,
            ));
        }
    }
    out
}

fn contact_loads(eq: &Equilibrium) -> Vec<f64> {
    eq.balls
        .iter()
        .flat_map(|b| [b.inner.load, b.outer.load])
        .collect()
}

/// Largest relative change of the contact loads, each relative to max(|Q_old|, floor) with
/// floor = `floor_fraction`·max|Q_old|.
pub fn max_relative_load_change(old: &[f64], new: &[f64], floor_fraction: f64) -> f64 {
    let qmax = old.iter().fold(0.0_f64, |m, q| m.max(q.abs()));
    let floor = (floor_fraction * qmax).max(1e-12);
    old.iter()
        .zip(new)
        .map(|(a, b)| (b - a).abs() / a.abs().max(floor))
        .fold(0.0_f64, f64::max)
}

/// Run the coupled loop on `case` with the characterization method `ch`.
///
/// Iteration i (1-based): characterize every contact at the loads of equilibrium i−1 (the dry
/// Hertz equilibrium for i = 1) — reusing cached laws within `settings.cache_tolerance` —, solve
/// the equilibrium with the fitted laws, and stop when the largest relative load change against
/// equilibrium i−1 is below `settings.tolerance`. At the iteration limit the result has
/// `converged: false` and the last change (or an error if `settings.error_if_not_converged`).
///
/// Determinism: the cache is frozen during an iteration; contacts not found in it are
/// deduplicated in index order (a contact within the key tolerance of a lower-index one reuses
/// it), the remaining ones are characterized in parallel and collected in index order, then added
/// to the cache in index order. The result therefore does not depend on the number of threads.
pub fn characterize_bearing(
    case: &Case,
    ch: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
) -> Result<BearingCharacterization, CharacterizeError> {
    characterize_bearing_with_progress(case, ch, settings, &|_| {})
}

/// Progress of [`characterize_bearing_with_progress`] (for progress bars; no effect on results).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Progress {
    /// An iteration starts and will characterize `contacts` contacts (the others are reused).
    /// Iteration 0 is the load prediction (`contacts` predictor solutions).
    IterationStarted {
        /// Iteration number (1-based).
        iteration: usize,
        /// Contacts to characterize.
        contacts: usize,
    },
    /// One contact was characterized (called from the worker threads, in any order).
    ContactDone {
        /// Iteration number.
        iteration: usize,
    },
    /// An iteration finished.
    IterationDone(IterationRecord),
}

/// As [`characterize_bearing`], calling `progress` as contacts and iterations finish.
pub fn characterize_bearing_with_progress(
    case: &Case,
    ch: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<BearingCharacterization, CharacterizeError> {
    settings.validate()?;
    let t0 = Instant::now();
    let dry_laws = ContactLaws::hertz(&case.bearing).map_err(CharacterizeError::DryEquilibrium)?;
    let dry = solve_equilibrium(&case.bearing, &dry_laws, &case.operating, &case.settings)
        .map_err(CharacterizeError::DryEquilibrium)?;
    let (start, prediction) = if settings.predict_loads {
        predicted_start(case, ch, settings, &dry_laws, &dry, progress)
    } else {
        (None, None)
    };
    // The cache lives for one call: method, settings, E′, lubricant and ball mass (the exact part
    // of the key) are the same for every entry, so only (M, L, Ry/Rx) are compared.
    let mut cache: Vec<CacheEntry> = Vec::new();
    let mut eq = start.unwrap_or_else(|| dry.clone());
    let mut history = Vec::new();
    let mut converged = false;
    let mut change = f64::INFINITY;
    let mut contacts: Vec<(CharacterizedContact, bool, LawSource, f64)> = Vec::new();
    let tol = settings.cache_tolerance;
    let load_tol = settings.load_reuse_tolerance;
    for iteration in 1..=settings.max_iterations {
        let ti = Instant::now();
        let conds = conditions_of(case, &eq, settings.min_load_fraction);
        let keys: Vec<[f64; 3]> = conds.iter().map(|(c, _)| contact_key(c)).collect();
        // Plan: cached (entry index), duplicate of a lower index, or to characterize.
        enum Plan {
            Cached(usize, f64),
            Duplicate(usize, f64),
            Run,
        }
        let mut plan = Vec::with_capacity(conds.len());
        let mut runs: Vec<usize> = Vec::new();
        for (i, key) in keys.iter().enumerate() {
            // A law of an earlier iteration: L and Ry/Rx within the key tolerance, and M within
            // the key tolerance or — the load reuse — within the load tolerance with the load
            // inside the law's fitted range. Closest key first, earliest entry on ties.
            let w = load_parameter(&conds[i].0);
            let mut best: Option<(usize, f64)> = None;
            for (e, entry) in cache.iter().enumerate() {
                let [dm, dl, dr] = key_components(key, &entry.key);
                let in_range = w >= entry.w_range[0] && w <= entry.w_range[1];
                let ok = dl <= tol && dr <= tol && (dm <= tol || (dm <= load_tol && in_range));
                let d = dm.max(dl).max(dr);
                if ok && best.map_or(true, |(_, bd)| d < bd) {
                    best = Some((e, d));
                }
            }
            if let Some((e, d)) = best {
                plan.push(Plan::Cached(e, d));
                continue;
            }
            let mut dup: Option<(usize, f64)> = None;
            for &r in &runs {
                let d = key_distance(key, &keys[r]);
                if d <= tol && dup.map_or(true, |(_, bd)| d < bd) {
                    dup = Some((r, d));
                }
            }
            match dup {
                Some((r, d)) => plan.push(Plan::Duplicate(r, d)),
                None => {
                    runs.push(i);
                    plan.push(Plan::Run);
                }
            }
        }
        progress(Progress::IterationStarted {
            iteration,
            contacts: runs.len(),
        });
        let results: Vec<Result<CharacterizedContact, crate::Error>> = runs
            .par_iter()
            .map(|&i| {
                let r = ch.characterize(&conds[i].0);
                progress(Progress::ContactDone { iteration });
                r
            })
            .collect();
        let mut fresh: Vec<Option<CharacterizedContact>> = vec![None; conds.len()];
        for (&i, r) in runs.iter().zip(results) {
            match r {
                Ok(c) => fresh[i] = Some(c),
                Err(e) => {
                    return Err(CharacterizeError::Contact {
                        ball: i / 2,
                        race: conds[i].0.race,
                        load: conds[i].0.load,
                        iteration,
                        cause: Box::new(e),
                    })
                }
            }
        }
        let mut new_contacts = Vec::with_capacity(conds.len());
        let mut max_dist = 0.0_f64;
        let mut max_offset = 0.0_f64;
        let mut max_residual = 0.0_f64;
        let wrap = |i: usize, e: crate::Error| CharacterizeError::Contact {
            ball: i / 2,
            race: conds[i].0.race,
            load: conds[i].0.load,
            iteration,
            cause: Box::new(e),
        };
        for (i, p) in plan.iter().enumerate() {
            let (cc, source, dist) = match *p {
                Plan::Run => (
                    fresh[i].clone().expect("characterized above"),
                    LawSource::Characterized,
                    0.0,
                ),
                Plan::Cached(e, d) => (
                    rescale(&cache[e], &conds[i].0).map_err(|e| wrap(i, e))?,
                    LawSource::Cached,
                    d,
                ),
                Plan::Duplicate(r, d) => {
                    let entry = CacheEntry::new(
                        keys[r],
                        conds[r].0,
                        fresh[r].clone().expect("characterized above"),
                    );
                    (
                        rescale(&entry, &conds[i].0).map_err(|e| wrap(i, e))?,
                        LawSource::Deduplicated,
                        d,
                    )
                }
            };
            max_dist = max_dist.max(dist);
            if source != LawSource::Characterized {
                max_offset = max_offset.max((conds[i].0.load / cc.load - 1.0).abs());
            }
            max_residual = max_residual.max(cc.max_residual / cc.load);
            new_contacts.push((cc, conds[i].1, source, dist));
        }
        for &i in &runs {
            cache.push(CacheEntry::new(
                keys[i],
                conds[i].0,
                fresh[i].take().expect("characterized above"),
            ));
        }
        let laws = laws_of(&new_contacts);
        let next = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
            .map_err(|cause| CharacterizeError::Equilibrium { iteration, cause })?;
        change = max_relative_load_change(
            &contact_loads(&eq),
            &contact_loads(&next),
            settings.min_load_fraction,
        );
        history.push(IterationRecord {
            iteration,
            max_load_change: change,
            characterized: runs.len(),
            reused: conds.len() - runs.len(),
            max_key_distance: max_dist,
            max_load_offset: max_offset,
            max_relative_residual: max_residual,
            equilibrium_iterations: next.iterations,
            seconds: ti.elapsed().as_secs_f64(),
        });
        if let Some(h) = history.last() {
            progress(Progress::IterationDone(*h));
        }
        eq = next;
        contacts = new_contacts;
        if change < settings.tolerance {
            converged = true;
            break;
        }
    }
    if !converged && settings.error_if_not_converged {
        return Err(CharacterizeError::NotConverged {
            iterations: history.len(),
            change,
            tolerance: settings.tolerance,
        });
    }
    let max_key_distance = history.last().map_or(0.0, |h| h.max_key_distance);
    let mut results = Vec::with_capacity(contacts.len());
    let (mut max_load_offset, mut max_relative_residual) = (0.0_f64, 0.0_f64);
    for (i, (cc, floored, source, dist)) in contacts.into_iter().enumerate() {
        let b = &eq.balls[i / 2];
        let (race, state) = if i % 2 == 0 {
            (Race::Inner, b.inner)
        } else {
            (Race::Outer, b.outer)
        };
        let load_offset = state.load / cc.load - 1.0;
        if !floored {
            max_load_offset = max_load_offset.max(load_offset.abs());
        }
        max_relative_residual = max_relative_residual.max(cc.max_residual / cc.load);
        results.push(ContactResult {
            ball: i / 2,
            race,
            law_load_at_approach: cc.law.force(state.deflection).0,
            range_status: cc.law.range_status(state.deflection),
            load_offset,
            characterized: cc,
            load_floored: floored,
            source,
            key_distance: dist,
            state,
        });
    }
    Ok(BearingCharacterization {
        converged,
        iterations: history.len(),
        max_load_change: change,
        history,
        dry,
        equilibrium: eq,
        contacts: results,
        method: ch.name().to_string(),
        method_settings: ch.settings_json(),
        settings: *settings,
        max_key_distance,
        max_load_offset,
        max_relative_residual,
        prediction,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// The equilibrium with the method's predictor laws at the dry loads, or None if the method has
/// no predictor. Progress is reported as iteration 0. A contact whose predictor fails keeps its
/// dry Hertz law; if the predicted equilibrium fails the loop starts from the dry one. Both are
/// counted in the record: they cost time (the first characterization is centred less well), not
/// accuracy.
fn predicted_start(
    case: &Case,
    ch: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
    dry_laws: &ContactLaws,
    dry: &Equilibrium,
    progress: &(dyn Fn(Progress) + Sync),
) -> (Option<Equilibrium>, Option<PredictionRecord>) {
    let t0 = Instant::now();
    let Some(predictor) = ch.predictor() else {
        return (None, None);
    };
    let conds = conditions_of(case, dry, settings.min_load_fraction);
    progress(Progress::IterationStarted {
        iteration: 0,
        contacts: conds.len(),
    });
    let predicted: Vec<Result<PredictedLaw, crate::Error>> = conds
        .par_iter()
        .map(|(c, _)| {
            let r = predictor.predict(c);
            progress(Progress::ContactDone { iteration: 0 });
            r
        })
        .collect();
    let mut laws = ContactLaws {
        inner: Vec::new(),
        outer: Vec::new(),
    };
    let (mut failed, mut not_converged) = (0, 0);
    for (i, p) in predicted.into_iter().enumerate() {
        let dry_law = if i % 2 == 0 {
            &dry_laws.inner[i / 2]
        } else {
            &dry_laws.outer[i / 2]
        };
        let law: Arc<dyn ContactLaw> = match p {
            Ok(l) => {
                if !l.converged {
                    not_converged += 1;
                }
                Arc::new(l)
            }
            Err(_) => {
                failed += 1;
                dry_law.clone()
            }
        };
        if i % 2 == 0 {
            laws.inner.push(law);
        } else {
            laws.outer.push(law);
        }
    }
    let mut record = PredictionRecord {
        contacts: conds.len(),
        not_converged,
        failed,
        max_load_change: 0.0,
        equilibrium_iterations: 0,
        error: None,
        seconds: 0.0,
    };
    let eq = match solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings) {
        Ok(eq) => {
            record.max_load_change = max_relative_load_change(
                &contact_loads(dry),
                &contact_loads(&eq),
                settings.min_load_fraction,
            );
            record.equilibrium_iterations = eq.iterations;
            Some(eq)
        }
        Err(e) => {
            record.error = Some(e.to_string());
            None
        }
    };
    record.seconds = t0.elapsed().as_secs_f64();
    (eq, Some(record))
}

fn laws_of(contacts: &[(CharacterizedContact, bool, LawSource, f64)]) -> ContactLaws {
    let mut inner: Vec<Arc<dyn ContactLaw>> = Vec::new();
    let mut outer: Vec<Arc<dyn ContactLaw>> = Vec::new();
    for (i, c) in contacts.iter().enumerate() {
        let law: Arc<dyn ContactLaw> = Arc::new(c.0.law);
        if i % 2 == 0 {
            inner.push(law);
        } else {
            outer.push(law);
        }
    }
    ContactLaws { inner, outer }
}

/// One contact as a flat record in SI units (a row of `results.csv`; the names carry the units).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct ContactRow {
    /// Ball index (ball 0 on +y).
    pub ball: usize,
    /// `inner` or `outer`.
    pub race: String,
    /// Equilibrium load Q, N.
    pub load_n: f64,
    /// Equilibrium approach δ, m.
    pub approach_m: f64,
    /// Equilibrium contact angle, rad.
    pub contact_angle_rad: f64,
    /// Stiffness K, N/m^d.
    pub k: f64,
    /// Nonlinear index d.
    pub d: f64,
    /// Lift at zero approach ΔF, N.
    pub delta_f_n: f64,
    /// Standard error of K from the fit, N/m^d (null if undefined).
    pub k_std_error: Option<f64>,
    /// Standard error of d (null if undefined).
    pub d_std_error: Option<f64>,
    /// Standard error of ΔF, N (null if undefined).
    pub delta_f_std_error_n: Option<f64>,
    /// Moes M at the characterization load.
    pub moes_m: f64,
    /// Moes L.
    pub moes_l: f64,
    /// Ry/Rx.
    pub ry_over_rx: f64,
    /// R² of the contact's fit (null if undefined).
    pub r_squared: Option<f64>,
    /// RMS residual of the contact's fit, N.
    pub rms_residual_n: f64,
    /// Largest absolute residual of the contact's fit, N (its force error bound inside the
    /// fitted range).
    pub fit_max_residual_n: f64,
    /// Whether the characterization converged.
    pub fit_converged: bool,
    /// Load the law was characterized at, N.
    pub characterized_load_n: f64,
    /// Whether that load was raised to the floor.
    pub load_floored: bool,
    /// `characterized`, `cached` or `deduplicated`.
    pub source: String,
    /// Relative key distance of a reused law.
    pub key_distance: f64,
    /// Relative offset of the equilibrium load from the characterization load, Q/w0 − 1.
    pub load_offset: f64,
    /// Sum velocity, m/s.
    pub sum_velocity_m_s: f64,
    /// Rx, m.
    pub rx_m: f64,
    /// Ry, m.
    pub ry_m: f64,
    /// Law evaluated at the equilibrium approach, N.
    pub law_load_at_approach_n: f64,
    /// Fitted approach range, lower end, m.
    pub fit_approach_min_m: f64,
    /// Fitted approach range, upper end, m.
    pub fit_approach_max_m: f64,
    /// Whether the equilibrium approach is outside the fitted range.
    pub outside_fit_range: bool,
}

fn finite_or_none(v: f64) -> Option<f64> {
    if v.is_finite() {
        Some(v)
    } else {
        None
    }
}

impl ContactRow {
    /// The row of a contact result.
    pub fn from_result(c: &ContactResult) -> Self {
        let cc = &c.characterized;
        let [lo, hi] = cc.law.fit_range();
        ContactRow {
            ball: c.ball,
            race: match c.race {
                Race::Inner => "inner".into(),
                Race::Outer => "outer".into(),
            },
            load_n: c.state.load,
            approach_m: c.state.deflection,
            contact_angle_rad: c.state.contact_angle,
            k: cc.k,
            d: cc.d,
            delta_f_n: cc.delta_f,
            k_std_error: finite_or_none(cc.std_errors[0]),
            d_std_error: finite_or_none(cc.std_errors[1]),
            delta_f_std_error_n: finite_or_none(cc.std_errors[2]),
            moes_m: cc.moes_m,
            moes_l: cc.moes_l,
            ry_over_rx: cc.ry_over_rx,
            r_squared: finite_or_none(cc.r_squared),
            rms_residual_n: cc.rms_residual,
            fit_max_residual_n: cc.max_residual,
            fit_converged: cc.converged,
            characterized_load_n: cc.load,
            load_floored: c.load_floored,
            source: match c.source {
                LawSource::Characterized => "characterized".into(),
                LawSource::Cached => "cached".into(),
                LawSource::Deduplicated => "deduplicated".into(),
            },
            key_distance: c.key_distance,
            load_offset: c.load_offset,
            sum_velocity_m_s: c.state.sum_velocity,
            rx_m: c.state.rx,
            ry_m: c.state.ry,
            law_load_at_approach_n: c.law_load_at_approach,
            fit_approach_min_m: lo,
            fit_approach_max_m: hi,
            outside_fit_range: cc.law.outside_fit_range(c.state.deflection),
        }
    }
}

/// The characterization as JSON in SI units: `converged`, `iterations`, `max_load_change`,
/// `max_key_distance`, `max_load_offset`, `max_relative_residual`, `method`, `method_settings`,
/// `settings`, `prediction` (null, or `contacts`, `not_converged`, `failed`, `max_load_change`,
/// `equilibrium_iterations`, `error`, and `seconds` if `timing`), `history` (per iteration:
/// `iteration`, `max_load_change`, `characterized`, `reused`, `max_key_distance`,
/// `max_load_offset`, `max_relative_residual`, `equilibrium_iterations`, and `seconds` if
/// `timing`), `displacement` and `dry_displacement`
/// (x, y, z in m; θy, θz in rad), `reaction` (N, N·m), `stiffness_dry` and `stiffness_ehl`
/// (5×5, N/m, N, N·m/rad), `contacts` ([`ContactRow`]s) and `seconds` if `timing`. Without
/// timing the output is reproducible bit for bit.
pub fn characterization_json(c: &BearingCharacterization, timing: bool) -> Value {
    let history: Vec<Value> = c
        .history
        .iter()
        .map(|h| {
            let mut v = json!({
                "iteration": h.iteration,
                "max_load_change": h.max_load_change,
                "characterized": h.characterized,
                "reused": h.reused,
                "max_key_distance": h.max_key_distance,
                "max_load_offset": h.max_load_offset,
                "max_relative_residual": h.max_relative_residual,
                "equilibrium_iterations": h.equilibrium_iterations,
            });
            if timing {
                v["seconds"] = json!(h.seconds);
            }
            v
        })
        .collect();
    let dof =
        |q: &[f64; 5]| json!({"x": q[0], "y": q[1], "z": q[2], "theta_y": q[3], "theta_z": q[4]});
    let prediction = c.prediction.as_ref().map(|p| {
        let mut v = json!({
            "contacts": p.contacts,
            "not_converged": p.not_converged,
            "failed": p.failed,
            "max_load_change": p.max_load_change,
            "equilibrium_iterations": p.equilibrium_iterations,
            "error": p.error,
        });
        if timing {
            v["seconds"] = json!(p.seconds);
        }
        v
    });
    let f = &c.equilibrium.reaction;
    let mut v = json!({
        "converged": c.converged,
        "iterations": c.iterations,
        "max_load_change": c.max_load_change,
        "max_key_distance": c.max_key_distance,
        "max_load_offset": c.max_load_offset,
        "max_relative_residual": c.max_relative_residual,
        "method": c.method,
        "method_settings": c.method_settings,
        "settings": c.settings,
        "prediction": prediction,
        "history": history,
        "displacement": dof(&c.equilibrium.displacement),
        "dry_displacement": dof(&c.dry.displacement),
        "reaction": {"force_x": f[0], "force_y": f[1], "force_z": f[2], "moment_y": f[3], "moment_z": f[4]},
        "stiffness_dry": c.dry.stiffness,
        "stiffness_ehl": c.equilibrium.stiffness,
        "contacts": c.contacts.iter().map(ContactRow::from_result).collect::<Vec<_>>(),
    });
    if timing {
        v["seconds"] = json!(c.seconds);
    }
    v
}
