//! Characterization methods: how one ball/raceway contact is turned into a fitted law
//! Q = K·δ^d + ΔF (+ c·δ̇).
//!
//! - [`ContactConditions`] (what a contact is characterized at) and [`CharacterizedContact`]
//!   (the fitted law and what a user needs to judge it): the data between the methods and the
//!   coupled loop ([`crate::characterize`]).
//! - [`ContactCharacterizer`]: the plug-in point of a method; [`LoadPredictor`]: its optional
//!   cheap load predictor.
//! - The methods: [`HertzCharacterizer`] (dry reference), [`QuasiStaticCharacterizer`] (a family
//!   of steady EHL solutions, [`crate::contact::characterize_quasi_static`]),
//!   [`HarmonicCharacterizer`] (transient EHL with the ball's equation of motion,
//!   [`crate::contact::characterize_harmonic`]) and [`SyntheticCharacterizer`] (a test fixture
//!   with known parameters).
//! - [`Method`]: the methods as one typed value with their settings, which case files, study
//!   files, the command line and the bindings all parse into ([`Method::parse`]), with one
//!   validation ([`Method::validate`]) and one list of names ([`Method::NAMES`]).
//!
//! This module sits below the loop: it uses the single-contact methods of [`crate::contact`] and
//! is used by [`crate::characterize`] and [`crate::study`], never the other way round.

use crate::bearing::Race;
use crate::budget::Deadline;
use crate::contact::{characterize_harmonic_within, HarmonicSettings, QuasiStaticSettings};
use crate::contact_law::ContactLaw;
use crate::ehl::{solve_steady_within, EhlContact, EhlSettings};
use crate::fit::{fit_power_law, FitOptions, FittedLaw};
use crate::hertz::HertzGeometry;
use crate::material::Lubricant;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use thiserror::Error;

mod map;
pub use map::{fallback_settings, harmonic_fallback_settings, MapCharacterizer};

/// Errors of the method settings and of the method adapters.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MethodError {
    /// A setting or an input has an invalid value.
    #[error("{field} = {value}: expected {expected}")]
    Setting {
        /// The setting, e.g. `method_options.grid`.
        field: String,
        /// The value given.
        value: String,
        /// The valid range.
        expected: String,
    },
    /// An unknown method name.
    #[error("unknown method {name:?}: expected one of {}", Method::NAMES.join(", "))]
    UnknownMethod {
        /// The name given.
        name: String,
    },
    /// A fitted law that does not reach the load of its contact.
    #[error("the fitted law does not reach the load {load_n} N")]
    LawShortOfLoad {
        /// The contact's load, N.
        load_n: f64,
    },
    /// A load prediction asked of a method that has none.
    #[error("method {method} has no load predictor")]
    NoPredictor {
        /// The method's name.
        method: &'static str,
    },
    /// The caller stopped the run.
    #[error("cancelled")]
    Cancelled,
}

impl MethodError {
    pub(crate) fn setting(
        field: impl Into<String>,
        value: impl ToString,
        expected: impl Into<String>,
    ) -> Self {
        MethodError::Setting {
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

/// Dimensionless groups of an EHL point contact (Moes; the definitions are below and in
/// docs/paper.md — the seed paper's eq. (7) is wrong).
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
            c_std_error: fit.std_errors.c,
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
                return Err(MethodError::setting(field, v, expected).into());
            }
        }
        if !(self.sum_velocity.is_finite() && self.sum_velocity >= 0.0) {
            return Err(MethodError::setting(
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
    /// Standard error of the damping coefficient c, N·s/m, for a law with one (the damped fit's;
    /// for the harmonic map its error estimate of c, as `std_errors` for the other terms); None
    /// for laws without damping.
    pub c_std_error: Option<f64>,
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
    /// Characterize the contact `c` within the wall-time budget `deadline` (None: no budget;
    /// the EHL methods end with a time-limit error once it has passed, the dry ones ignore it).
    fn characterize(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error>;
    /// The method and its full settings, written into every result (typed; serializes to the
    /// `method` object of result files).
    fn method(&self) -> Method;
    /// Name of the method, e.g. `hertz`.
    fn name(&self) -> &str {
        self.method().name()
    }
    /// The method's load predictor, if it has one (default: none, the loop starts from the dry
    /// Hertz loads).
    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        None
    }
}

/// A cheap approximate law of a contact near a load, used by the loop (with
/// [`crate::characterize::CharacterizeSettings::predict_loads`]) to predict the lubricated loads before the first
/// characterization. It only moves the point where the first characterization is centred; the
/// result is still the loop's fixed point with the characterized laws. Must be deterministic.
pub trait LoadPredictor: Sync + Send {
    /// The predictor law of contact `c` near `c.load`, within the wall-time budget `deadline`
    /// (None: no budget).
    fn predict(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<PredictedLaw, crate::Error>;
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
    pub fn new(stiffness: f64, film: f64, converged: bool) -> Result<Self, MethodError> {
        if !(stiffness.is_finite() && stiffness > 0.0 && film.is_finite()) {
            return Err(MethodError::setting(
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
        return Err(MethodError::setting("samples", samples, "an integer from 4 to 10000").into());
    }
    if !(amplitude.is_finite() && amplitude > 0.0 && amplitude < 1.0) {
        return Err(MethodError::setting(
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
    let approach = law
        .approach_at(c.load)
        .ok_or(MethodError::LawShortOfLoad { load_n: c.load })?;
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
        c_std_error: fit.std_errors.c,
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
    fn characterize(
        &self,
        c: &ContactConditions,
        _deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        let start = Instant::now();
        c.validate()?;
        check_sampling(self.samples, self.amplitude)?;
        let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
        let q = sample_loads(c.load, self.samples, self.amplitude);
        let delta: Vec<f64> = q.iter().map(|&w| h.contact(w).deflection).collect();
        fit_samples(c, &delta, &q, self.name(), start)
    }

    fn method(&self) -> Method {
        Method::Hertz(*self)
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
    fn characterize(
        &self,
        c: &ContactConditions,
        _deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        let start = Instant::now();
        c.validate()?;
        check_sampling(self.samples, self.amplitude)?;
        let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
        let (k, d, lift) = self.parameters(c.load, c.sum_velocity, h.stiffness);
        if !(k.is_finite() && k > 0.0 && d > 0.0 && lift < 0.5 * c.load) {
            return Err(MethodError::setting(
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

    fn method(&self) -> Method {
        Method::Synthetic(*self)
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
    fn characterize(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        c.validate()?;
        let fit = crate::contact::characterize_quasi_static_within(
            &c.ehl_contact(),
            &self.settings,
            deadline,
        )?;
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

    fn method(&self) -> Method {
        Method::QuasiStatic(self.settings)
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
    fn predict(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<PredictedLaw, crate::Error> {
        predict_steady(c, &self.settings.ehl, deadline)
    }
}

/// The load predictor shared by the EHL methods: one steady EHL solution at `c.load` with the
/// grid and domain of `ehl` but its tolerances loosened to [`PREDICTOR_TOLERANCE`], turned into a
/// [`PredictedLaw`] (dry Hertz shifted by h = δ_Hertz(w0) − δ_EHL(w0), m).
pub fn predict_steady(
    c: &ContactConditions,
    ehl: &EhlSettings,
    deadline: Option<Deadline>,
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
    let sol = solve_steady_within(&c.ehl_contact(), &settings, deadline)?;
    let film = h.contact(c.load).deflection - sol.approach;
    Ok(PredictedLaw::new(h.stiffness, film, sol.converged)?)
}

/// Convergence tolerance of the predictor's steady EHL solution (relative Reynolds residual,
/// force balance and film change; dimensionless).
pub const PREDICTOR_TOLERANCE: f64 = 1e-2;

/// The harmonic method ([`crate::contact::characterize_harmonic`]) as a
/// [`ContactCharacterizer`] for the coupled loop: each
/// contact is excited with its own ball mass ([`ContactConditions::ball_mass`](ContactConditions)).
/// The fitted law's damping term (if any) is kept in the law but plays no part in the quasi-static
/// bearing equilibrium (δ̇ = 0 there).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HarmonicCharacterizer {
    /// Settings of the method.
    pub settings: HarmonicSettings,
}

impl ContactCharacterizer for HarmonicCharacterizer {
    fn characterize(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        use crate::ContactLaw;
        // The contact and the mass are validated by characterize_harmonic (EHL input checks).
        let fit =
            characterize_harmonic_within(&c.ehl_contact(), c.ball_mass, &self.settings, deadline)?;
        // Largest force residual of the fit over the recorded steps, damping term included (N).
        let damping = fit.c.unwrap_or(0.0);
        let max_residual = fit.history[fit.settling_steps..]
            .iter()
            .map(|x| (fit.law.force(x.approach).0 + damping * x.velocity - x.film_force).abs())
            .fold(0.0_f64, f64::max);
        let samples = fit.history.len() - fit.settling_steps;
        Ok(CharacterizedContact::from_fit(
            fit,
            c.load,
            max_residual,
            samples,
        ))
    }

    fn method(&self) -> Method {
        Method::Harmonic(self.settings)
    }

    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        Some(self)
    }
}

impl LoadPredictor for HarmonicCharacterizer {
    /// The steady predictor of the quasi-static method
    /// ([`predict_steady`]) with this method's grid and domain.
    fn predict(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<PredictedLaw, crate::Error> {
        predict_steady(c, &self.settings.ehl, deadline)
    }
}

// ---------------------------------------------------------------------------------------------
// The methods as one typed value
// ---------------------------------------------------------------------------------------------

/// A characterization method with its full settings: what case files, study files
/// (`method = "…"` and `[method_options]`), the command line (`--method`) and the bindings parse
/// into ([`Method::parse`]), validated in one place ([`Method::validate`]). It is itself a
/// [`ContactCharacterizer`].
///
/// Serialized (in result and point files) as `{"name": "quasi-static", "settings": {…}}` with
/// every setting written out, so a result records exactly what produced it and reads back into
/// the same value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "name", content = "settings", rename_all = "kebab-case")]
pub enum Method {
    /// Dry Hertz reference ([`HertzCharacterizer`]): K = K_Hertz, d = 1.5, ΔF = 0.
    Hertz(HertzCharacterizer),
    /// The quasi-static EHL method ([`crate::contact::characterize_quasi_static`]).
    QuasiStatic(QuasiStaticSettings),
    /// The harmonic EHL method ([`crate::contact::characterize_harmonic`]).
    Harmonic(HarmonicSettings),
    /// Test fixture with known parameters ([`SyntheticCharacterizer`]); accepted by name but not
    /// listed in [`Method::NAMES`] or in the command line's help.
    Synthetic(SyntheticCharacterizer),
    /// The quasi-static law from the embedded map of the dimensionless law
    /// ([`MapCharacterizer`], docs/law_map.md).
    Map(MapSettings),
}

/// Settings of the `map` method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct MapSettings {
    /// Outside the map's envelope, characterize the contact by the quasi-static method with the
    /// map's settings (true, the default; the contact's `method` then says so) or fail with an
    /// error naming the group, its value and the envelope (false). For the harmonic law the
    /// fallback is the harmonic method at the harmonic map's settings.
    pub fallback: bool,
    /// The law the maps give: the quasi-static law (the default, not written in results) or
    /// the harmonic method's, with the damping c (`[method_options] law = "harmonic"`).
    #[serde(
        default,
        skip_serializing_if = "crate::law_map::LawKind::is_quasi_static"
    )]
    pub law: crate::law_map::LawKind,
}

impl Default for MapSettings {
    /// With the quasi-static fallback: every case gets its laws, from the map where it holds
    /// the contacts (milliseconds) and by EHL solutions elsewhere, each contact naming its
    /// method.
    fn default() -> Self {
        MapSettings {
            fallback: true,
            law: crate::law_map::LawKind::QuasiStatic,
        }
    }
}

/// Options of `map` as a user gives them.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MapOptions {
    fallback: Option<bool>,
    law: Option<crate::law_map::LawKind>,
    /// Refused with a message: only relative frequencies map.
    frequency_rad_s: Option<f64>,
}

impl Default for Method {
    /// The quasi-static method at its defaults.
    fn default() -> Self {
        Method::QuasiStatic(QuasiStaticSettings::default())
    }
}

/// Options of `hertz` as a user gives them (all optional; defaults of [`HertzCharacterizer`]).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct HertzOptions {
    samples: Option<usize>,
    amplitude: Option<f64>,
}

/// Options of `quasi-static` as a user gives them.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuasiStaticOptions {
    amplitude: Option<f64>,
    points: Option<usize>,
    grid: Option<usize>,
}

/// Options of `harmonic` as a user gives them.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct HarmonicOptions {
    amplitude: Option<f64>,
    grid: Option<usize>,
    frequency_fraction: Option<f64>,
    frequency_rad_s: Option<f64>,
    settling_periods: Option<usize>,
    periodicity_tol: Option<f64>,
    recorded_periods: Option<usize>,
    steps_per_period: Option<usize>,
    step_tol_film: Option<f64>,
    mass_kg: Option<f64>,
    damping_term: Option<bool>,
}

/// Options of `synthetic` (test fixture).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SyntheticOptions {
    samples: Option<usize>,
    amplitude: Option<f64>,
    d_amplitude: Option<f64>,
    d_exponent: Option<f64>,
    load_ref: Option<f64>,
    lift_ref: Option<f64>,
    lift_load_exponent: Option<f64>,
    lift_speed_exponent: Option<f64>,
    speed_ref: Option<f64>,
}

/// Deserialize a user's option table into `T`, naming the key of a wrong type or an unknown key.
fn options<T: serde::de::DeserializeOwned + Default>(
    method: &str,
    table: Option<&toml::Table>,
) -> Result<T, MethodError> {
    let Some(table) = table else {
        return Ok(T::default());
    };
    let value = toml::Value::Table(table.clone());
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner().to_string();
        let (field, value) = if path == "." {
            ("method_options".to_string(), String::new())
        } else {
            let v = table
                .get(path.split('.').next().unwrap_or(""))
                .map(|v| v.to_string())
                .unwrap_or_default();
            (format!("method_options.{path}"), v)
        };
        MethodError::Setting {
            field,
            value,
            expected: format!("{inner} (method {method})"),
        }
    })
}

fn is_grid(n: usize) -> bool {
    n >= 2 && (n - 1).is_power_of_two() && (GRID_RANGE.0..=GRID_RANGE.1).contains(&n)
}

/// Smallest and largest EHL grid (nodes per side, 2^k + 1).
pub const GRID_RANGE: (usize, usize) = (17, 1025);

impl Method {
    /// The names a user may give (`--method`, `method = "…"`), default first.
    pub const NAMES: [&'static str; 4] = ["quasi-static", "harmonic", "hertz", "map"];

    /// The method's name.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Hertz(_) => "hertz",
            Method::QuasiStatic(_) => "quasi-static",
            Method::Harmonic(_) => "harmonic",
            Method::Synthetic(_) => "synthetic",
            Method::Map(_) => "map",
        }
    }

    /// The method `name` with the user's options `table` (the `[method_options]` table of a study
    /// or case file, or the command line's options; None: defaults), validated. Unknown keys,
    /// values of the wrong type and values out of range are errors naming the key, the value and
    /// the valid range.
    pub fn parse(name: &str, table: Option<&toml::Table>) -> Result<Method, MethodError> {
        let m = match name {
            "hertz" => {
                let o: HertzOptions = options(name, table)?;
                let d = HertzCharacterizer::default();
                Method::Hertz(HertzCharacterizer {
                    samples: o.samples.unwrap_or(d.samples),
                    amplitude: o.amplitude.unwrap_or(d.amplitude),
                })
            }
            "quasi-static" => {
                let o: QuasiStaticOptions = options(name, table)?;
                let mut s = QuasiStaticSettings::default();
                s.amplitude = o.amplitude.unwrap_or(s.amplitude);
                s.points = o.points.unwrap_or(s.points);
                s.ehl.grid = o.grid.unwrap_or(s.ehl.grid);
                Method::QuasiStatic(s)
            }
            "harmonic" => {
                let o: HarmonicOptions = options(name, table)?;
                let mut s = HarmonicSettings::default();
                s.amplitude = o.amplitude.unwrap_or(s.amplitude);
                s.ehl.grid = o.grid.unwrap_or(s.ehl.grid);
                match (o.frequency_fraction, o.frequency_rad_s) {
                    (Some(_), Some(_)) => {
                        return Err(MethodError::setting(
                            "method_options.frequency_rad_s",
                            o.frequency_rad_s.unwrap_or_default(),
                            "either frequency_fraction or frequency_rad_s, not both",
                        ))
                    }
                    (Some(f), None) => {
                        s.frequency = crate::contact::ExcitationFrequency::FractionOfNatural(f)
                    }
                    (None, Some(w)) => {
                        s.frequency = crate::contact::ExcitationFrequency::RadPerSecond(w)
                    }
                    (None, None) => {}
                }
                s.settling_periods = o.settling_periods.unwrap_or(s.settling_periods);
                s.periodicity_tol = o.periodicity_tol.unwrap_or(s.periodicity_tol);
                s.recorded_periods = o.recorded_periods.unwrap_or(s.recorded_periods);
                s.steps_per_period = o.steps_per_period.unwrap_or(s.steps_per_period);
                s.step_tol_film = o.step_tol_film.or(s.step_tol_film);
                if o.mass_kg.is_some() {
                    s.mass = o.mass_kg;
                }
                s.damping_term = o.damping_term.unwrap_or(s.damping_term);
                Method::Harmonic(s)
            }
            "synthetic" => {
                let o: SyntheticOptions = options(name, table)?;
                let d = SyntheticCharacterizer::default();
                Method::Synthetic(SyntheticCharacterizer {
                    d_amplitude: o.d_amplitude.unwrap_or(d.d_amplitude),
                    d_exponent: o.d_exponent.unwrap_or(d.d_exponent),
                    load_ref: o.load_ref.unwrap_or(d.load_ref),
                    lift_ref: o.lift_ref.unwrap_or(d.lift_ref),
                    lift_load_exponent: o.lift_load_exponent.unwrap_or(d.lift_load_exponent),
                    lift_speed_exponent: o.lift_speed_exponent.unwrap_or(d.lift_speed_exponent),
                    speed_ref: o.speed_ref.unwrap_or(d.speed_ref),
                    samples: o.samples.unwrap_or(d.samples),
                    amplitude: o.amplitude.unwrap_or(d.amplitude),
                })
            }
            "map" => {
                let o: MapOptions = options(name, table)?;
                if let Some(w) = o.frequency_rad_s {
                    return Err(MethodError::setting(
                        "method_options.frequency_rad_s",
                        w,
                        "none: the map method maps the harmonic law at a relative excitation \
                         frequency only (Ω/ω_n = 0.005, the harmonic map's); an absolute Ω needs \
                         method = \"harmonic\"",
                    ));
                }
                Method::Map(MapSettings {
                    fallback: o.fallback.unwrap_or(MapSettings::default().fallback),
                    law: o.law.unwrap_or_default(),
                })
            }
            other => {
                return Err(MethodError::UnknownMethod {
                    name: other.to_string(),
                })
            }
        };
        m.validate()?;
        Ok(m)
    }

    /// Check every setting against its valid range (the one set of ranges of the program); the
    /// error names the key as a user writes it in `[method_options]`, the value and the range.
    pub fn validate(&self) -> Result<(), MethodError> {
        let key = |k: &str| format!("method_options.{k}");
        let grid = |ehl: &EhlSettings| -> Result<(), MethodError> {
            if !is_grid(ehl.grid) {
                return Err(MethodError::setting(
                    key("grid"),
                    ehl.grid,
                    format!(
                        "a grid size 2^k + 1 from {} to {}",
                        GRID_RANGE.0, GRID_RANGE.1
                    ),
                ));
            }
            crate::ehl::validate_settings(ehl)
                .map_err(|e| MethodError::setting("method settings (ehl)", "", e.to_string()))
        };
        let amplitude = |a: f64, hi: f64, closed: bool| -> Result<(), MethodError> {
            let ok = a.is_finite() && a > 0.0 && if closed { a <= hi } else { a < hi };
            if ok {
                Ok(())
            } else {
                Err(MethodError::setting(
                    key("amplitude"),
                    a,
                    format!(
                        "a relative amplitude ε with 0 < ε {} {hi}",
                        if closed { "≤" } else { "<" }
                    ),
                ))
            }
        };
        let count = |k: &str, v: usize, lo: usize, hi: usize| -> Result<(), MethodError> {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(MethodError::setting(
                    key(k),
                    v,
                    format!("an integer from {lo} to {hi}"),
                ))
            }
        };
        let positive = |k: &str, v: f64| -> Result<(), MethodError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(MethodError::setting(key(k), v, "a finite number > 0"))
            }
        };
        match self {
            Method::Hertz(h) => {
                count("samples", h.samples, 4, 10_000)?;
                amplitude(h.amplitude, 1.0, false)
            }
            Method::Synthetic(s) => {
                count("samples", s.samples, 4, 10_000)?;
                amplitude(s.amplitude, 1.0, false)?;
                positive("load_ref", s.load_ref)?;
                positive("speed_ref", s.speed_ref)?;
                for (k, v) in [
                    ("d_amplitude", s.d_amplitude),
                    ("d_exponent", s.d_exponent),
                    ("lift_ref", s.lift_ref),
                    ("lift_load_exponent", s.lift_load_exponent),
                    ("lift_speed_exponent", s.lift_speed_exponent),
                ] {
                    if !v.is_finite() {
                        return Err(MethodError::setting(key(k), v, "a finite number"));
                    }
                }
                Ok(())
            }
            Method::QuasiStatic(s) => {
                amplitude(s.amplitude, 0.9, true)?;
                count("points", s.points, 4, 101)?;
                grid(&s.ehl)
            }
            Method::Harmonic(s) => {
                if let Some(v) = s.violation() {
                    return Err(MethodError::setting(key(v.key), v.value, v.range));
                }
                grid(&s.ehl)
            }
            Method::Map(_) => Ok(()),
        }
    }

    /// The EHL grid of an EHL method (None for hertz and synthetic).
    pub fn grid(&self) -> Option<usize> {
        match self {
            Method::QuasiStatic(s) => Some(s.ehl.grid),
            Method::Harmonic(s) => Some(s.ehl.grid),
            _ => None,
        }
    }
}

impl ContactCharacterizer for Method {
    fn characterize(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        match self {
            Method::Hertz(h) => h.characterize(c, deadline),
            Method::Synthetic(s) => s.characterize(c, deadline),
            Method::QuasiStatic(s) => {
                QuasiStaticCharacterizer { settings: *s }.characterize(c, deadline)
            }
            Method::Harmonic(s) => HarmonicCharacterizer { settings: *s }.characterize(c, deadline),
            Method::Map(s) => MapCharacterizer { settings: *s }.characterize(c, deadline),
        }
    }

    fn method(&self) -> Method {
        *self
    }

    fn name(&self) -> &str {
        Method::name(self)
    }

    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        match self {
            Method::QuasiStatic(_) | Method::Harmonic(_) | Method::Map(_) => Some(self),
            Method::Hertz(_) | Method::Synthetic(_) => None,
        }
    }
}

impl LoadPredictor for Method {
    /// The steady predictor of the EHL methods ([`predict_steady`] with the method's EHL grid
    /// and domain), the map's own for the map method ([`MapCharacterizer`]); an error for the
    /// dry methods, which have none.
    fn predict(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<PredictedLaw, crate::Error> {
        match self {
            Method::QuasiStatic(s) => predict_steady(c, &s.ehl, deadline),
            Method::Harmonic(s) => predict_steady(c, &s.ehl, deadline),
            Method::Map(s) => MapCharacterizer { settings: *s }.predict(c, deadline),
            other => Err(MethodError::NoPredictor {
                method: other.name(),
            }
            .into()),
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
