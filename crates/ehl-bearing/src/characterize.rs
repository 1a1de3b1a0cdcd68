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
use crate::budget::Deadline;
use crate::case::Case;
use crate::contact_law::ContactLaw;
use crate::fit::{FittedLaw, RangeStatus};
use crate::method::Method;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

// The method data and adapters live in `crate::method`; re-exported here for the callers that
// knew them from this module.
pub use crate::method::{
    predict_steady, CharacterizedContact, ContactCharacterizer, ContactConditions,
    HarmonicCharacterizer, HertzCharacterizer, LoadPredictor, MoesParameters, PredictedLaw,
    QuasiStaticCharacterizer, SyntheticCharacterizer, PREDICTOR_TOLERANCE,
};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
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
    #[error("characterization of ball {ball} {race:?} contact at load {load:.6e} N failed in iteration {iteration}: {cause}{hint}")]
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
        /// What the loop's settings can do about it ("" when nothing): for a contact in the
        /// hydrodynamic regime, the load floor `min_load_fraction` with its value.
        hint: String,
    },
    /// The wall-time budget (the `deadline` argument of [`characterize_bearing_with_control`])
    /// ran out.
    #[error(
        "characterization stopped at its time limit of {limit_s} s after {seconds:.1} s and \
         {iterations} finished iterations (largest relative load change after each: {})",
        crate::ehl::format_history(load_change_history)
    )]
    TimeLimit {
        /// The budget, s.
        limit_s: f64,
        /// Time spent, s.
        seconds: f64,
        /// Finished iterations.
        iterations: usize,
        /// Largest relative load change after each finished iteration.
        load_change_history: Vec<f64>,
    },
    /// The progress callback of [`characterize_bearing_with_control`] asked to stop.
    #[error(
        "characterization cancelled by its caller in iteration {iteration} after {seconds:.1} s \
         ({iterations} finished iterations)"
    )]
    Cancelled {
        /// The iteration running when the stop was seen (0: the load prediction).
        iteration: usize,
        /// Finished iterations.
        iterations: usize,
        /// Time spent, s.
        seconds: f64,
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
    Trend(#[from] crate::trends::TrendError),
    /// A law rescaled to another contact's conditions does not reach the load it carries there.
    #[error("rescaled law does not reach {load_n} N")]
    RescaledLawShort {
        /// The load the rescaled law must carry, N.
        load_n: f64,
    },
    /// A broken invariant of the loop: a contact planned for characterization has no result.
    #[error("contact {contact} was planned but not characterized")]
    NotCharacterized {
        /// Index of the contact.
        contact: usize,
    },
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

/// Settings of [`characterize_bearing`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
    /// Wall-clock time of the iteration, s (not serialized: files that are compared between
    /// runs hold no timings; [`IterationSummary`] adds it where wanted).
    #[serde(skip)]
    pub seconds: f64,
}

/// The load prediction that started the loop ([`CharacterizeSettings::predict_loads`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    /// Wall-clock time of the prediction, s (not serialized; [`PredictionSummary`] adds it
    /// where wanted).
    #[serde(skip)]
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
    /// The method and its settings.
    pub method: Method,
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
    /// Film, Λ, κ and thermal-reduction estimates at the final equilibrium (crate::lubrication);
    /// present when the case describes its oil or gives roughness.
    pub lubrication: Option<crate::lubrication::LubricationReport>,
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
        .ok_or(CharacterizeError::RescaledLawShort { load_n: load })?;
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
        c_std_error: src.c_std_error,
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
                    lubricant: case.lubricant_of(race),
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
    characterize_bearing_with_progress(case, ch, settings, None, &|_| {})
}

/// Progress of [`characterize_bearing_with_progress`] (for progress bars; no effect on results);
/// as a record: [`crate::report::ProgressEvent`].
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

/// As [`characterize_bearing`], within the wall-time budget `deadline` (None: none; see
/// [`characterize_bearing_with_control`]), calling `progress` as contacts and iterations finish.
pub fn characterize_bearing_with_progress(
    case: &Case,
    ch: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
    deadline: Option<Deadline>,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<BearingCharacterization, CharacterizeError> {
    characterize_bearing_with_control(case, ch, settings, deadline, &|p| {
        progress(p);
        ControlFlow::Continue(())
    })
}

/// As [`characterize_bearing_with_progress`], with a callback that can stop the run: once it
/// returns [`ControlFlow::Break`], no further contact characterization (or load prediction)
/// starts and the call
/// returns [`CharacterizeError::Cancelled`] as soon as those already running finish (a contact
/// takes up to seconds by the quasi-static method, tens of seconds by the harmonic one; bound
/// them with `deadline`). Callers use it for a cancel button, Ctrl-C, or an exception raised in a
/// Python or C callback.
///
/// `deadline` is the run's wall-time budget (None: none): the loop checks it before every
/// iteration and ends with [`CharacterizeError::TimeLimit`] once it has passed; the contacts'
/// characterizations and load predictions get it too (their EHL solves stop at it).
pub fn characterize_bearing_with_control(
    case: &Case,
    ch: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
    deadline: Option<Deadline>,
    control: &(dyn Fn(Progress) -> ControlFlow<()> + Sync),
) -> Result<BearingCharacterization, CharacterizeError> {
    let stop = AtomicBool::new(false);
    let progress = &|p: Progress| {
        if control(p).is_break() {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let cancelled = Cancel { stop: &stop };
    settings.validate()?;
    let t0 = Instant::now();
    let dry_laws = ContactLaws::hertz(&case.bearing).map_err(CharacterizeError::DryEquilibrium)?;
    let dry = solve_equilibrium(&case.bearing, &dry_laws, &case.operating, &case.settings)
        .map_err(CharacterizeError::DryEquilibrium)?;
    let (start, prediction) = if settings.predict_loads {
        predicted_start(
            case,
            ch,
            settings,
            &dry_laws,
            &dry,
            (progress, &stop),
            deadline,
        )
    } else {
        (None, None)
    };
    cancelled.check(0, 0, t0)?;
    let run = LoopRun {
        case,
        ch,
        settings,
        deadline,
        progress,
        cancelled,
        t0,
    };
    let mut state = LoopState {
        cache: Vec::new(),
        eq: start.unwrap_or_else(|| dry.clone()),
        history: Vec::new(),
        contacts: Vec::new(),
        change: f64::INFINITY,
    };
    let mut converged = false;
    for iteration in 1..=settings.max_iterations {
        run.cancelled.check(iteration, state.history.len(), t0)?;
        check_deadline(deadline, &state.history)?;
        run.iterate(iteration, &mut state)?;
        if state.change < settings.tolerance {
            converged = true;
            break;
        }
    }
    if !converged && settings.error_if_not_converged {
        return Err(CharacterizeError::NotConverged {
            iterations: state.history.len(),
            change: state.change,
            tolerance: settings.tolerance,
        });
    }
    Ok(run.result(state, converged, dry, prediction))
}

/// The wall-time budget's check before an iteration: past `deadline`, the error that carries
/// the iterations done and their load changes.
fn check_deadline(
    deadline: Option<Deadline>,
    history: &[IterationRecord],
) -> Result<(), CharacterizeError> {
    if let Some(d) = deadline.filter(|d| d.expired()) {
        return Err(CharacterizeError::TimeLimit {
            limit_s: d.limit_seconds(),
            seconds: d.elapsed_seconds(),
            iterations: history.len(),
            load_change_history: history.iter().map(|h| h.max_load_change).collect(),
        });
    }
    Ok(())
}

/// The fixed inputs of one run of the coupled loop: the case, the characterization method and
/// the loop settings, the wall-time budget, the caller's progress callback and stop flag, and
/// the run's start time.
struct LoopRun<'a> {
    case: &'a Case,
    ch: &'a dyn ContactCharacterizer,
    settings: &'a CharacterizeSettings,
    deadline: Option<Deadline>,
    progress: &'a (dyn Fn(Progress) + Sync),
    cancelled: Cancel<'a>,
    t0: Instant,
}

/// What the coupled loop carries from one iteration to the next.
struct LoopState {
    /// The laws characterized so far in this call. The cache lives for one call: method,
    /// settings, E′ and ball mass (the exact part of the key) are the same for every entry, so
    /// (M, L, Ry/Rx) are compared, and the lubricant (one per raceway with ring temperatures)
    /// must be equal.
    cache: Vec<CacheEntry>,
    /// The latest equilibrium (before the first iteration: the predicted or dry start).
    eq: Equilibrium,
    /// One record per iteration done.
    history: Vec<IterationRecord>,
    /// The contacts' laws of the latest iteration.
    contacts: Vec<LoopContact>,
    /// The latest iteration's largest relative load change (∞ before the first).
    change: f64,
}

impl LoopRun<'_> {
    /// Iteration `iteration`: characterize every contact at the loads of `state.eq` (reusing
    /// the cache), solve the equilibrium with the laws, record the iteration; `state` moves on
    /// to the new equilibrium, its contacts and load change, the cache grows by the contacts
    /// characterized.
    fn iterate(&self, iteration: usize, state: &mut LoopState) -> Result<(), CharacterizeError> {
        let settings = self.settings;
        let ti = Instant::now();
        let conds = conditions_of(self.case, &state.eq, settings.min_load_fraction);
        let keys: Vec<[f64; 3]> = conds.iter().map(|(c, _)| contact_key(c)).collect();
        let (plan, runs) = plan_iteration(&conds, &keys, &state.cache, settings);
        (self.progress)(Progress::IterationStarted {
            iteration,
            contacts: runs.len(),
        });
        let floor = LoadFloor {
            fraction: settings.min_load_fraction,
            largest: contact_loads(&state.eq).into_iter().fold(0.0_f64, f64::max),
        };
        let fresh = characterize_runs(
            self.ch,
            &conds,
            &runs,
            (iteration, floor),
            self.progress,
            self.cancelled.stop,
            self.deadline,
        );
        self.cancelled
            .check(iteration, state.history.len(), self.t0)?;
        let mut fresh = fresh.into_iter().collect::<Result<Vec<_>, _>>()?;
        let assembled =
            assemble_laws(&plan, &fresh, &state.cache, &conds, &keys, iteration, floor)?;
        for &i in &runs {
            let result = fresh[i]
                .take()
                .ok_or(CharacterizeError::NotCharacterized { contact: i })?;
            state
                .cache
                .push(CacheEntry::new(keys[i], conds[i].0, result));
        }
        let laws = laws_of(&assembled.contacts);
        let next = solve_equilibrium(
            &self.case.bearing,
            &laws,
            &self.case.operating,
            &self.case.settings,
        )
        .map_err(|cause| CharacterizeError::Equilibrium { iteration, cause })?;
        state.change = max_relative_load_change(
            &contact_loads(&state.eq),
            &contact_loads(&next),
            settings.min_load_fraction,
        );
        let record = IterationRecord {
            iteration,
            max_load_change: state.change,
            characterized: runs.len(),
            reused: conds.len() - runs.len(),
            max_key_distance: assembled.max_key_distance,
            max_load_offset: assembled.max_load_offset,
            max_relative_residual: assembled.max_relative_residual,
            equilibrium_iterations: next.iterations,
            seconds: ti.elapsed().as_secs_f64(),
        };
        state.history.push(record);
        (self.progress)(Progress::IterationDone(record));
        state.eq = next;
        state.contacts = assembled.contacts;
        Ok(())
    }

    /// The run's result from the loop's final `state`: the contacts at the last equilibrium,
    /// the lubrication figures when the case asks for them, the records.
    fn result(
        &self,
        state: LoopState,
        converged: bool,
        dry: Equilibrium,
        prediction: Option<PredictionRecord>,
    ) -> BearingCharacterization {
        let LoopState {
            eq,
            history,
            contacts,
            change,
            ..
        } = state;
        let max_key_distance = history.last().map_or(0.0, |h| h.max_key_distance);
        let (results, max_load_offset, max_relative_residual) = final_contacts(&eq, contacts);
        let lubrication = crate::lubrication::wanted(self.case).then(|| {
            let states: Vec<_> = results.iter().map(|r| (r.ball, r.race, r.state)).collect();
            crate::lubrication::assess(self.case, &states)
        });
        BearingCharacterization {
            converged,
            iterations: history.len(),
            max_load_change: change,
            history,
            dry,
            equilibrium: eq,
            contacts: results,
            method: self.ch.method(),
            settings: *self.settings,
            max_key_distance,
            max_load_offset,
            max_relative_residual,
            prediction,
            lubrication,
            seconds: self.t0.elapsed().as_secs_f64(),
        }
    }
}

/// A contact's law in an iteration: the characterized contact, whether its load was floored,
/// where the law came from and the key distance it was reused over.
type LoopContact = (CharacterizedContact, bool, LawSource, f64);

/// How a contact gets its law in an iteration.
enum Plan {
    /// From cache entry `.0`, at key distance `.1`.
    Cached(usize, f64),
    /// From the contact `.0` characterized in this iteration (lower index), at distance `.1`.
    Duplicate(usize, f64),
    /// Characterized.
    Run,
}

/// Plan an iteration: for every contact, a law of an earlier iteration (L and Ry/Rx within the
/// key tolerance, and M within the key tolerance or — the load reuse — within the load tolerance
/// with the load inside the law's fitted range; closest key first, earliest entry on ties), a
/// duplicate of a lower-index contact characterized now, or a characterization. Returns the plan
/// and the indices to characterize. The cache is frozen here, so the plan does not depend on
/// the number of threads.
fn plan_iteration(
    conds: &[(ContactConditions, bool)],
    keys: &[[f64; 3]],
    cache: &[CacheEntry],
    settings: &CharacterizeSettings,
) -> (Vec<Plan>, Vec<usize>) {
    let tol = settings.cache_tolerance;
    let load_tol = settings.load_reuse_tolerance;
    let mut plan = Vec::with_capacity(conds.len());
    let mut runs: Vec<usize> = Vec::new();
    for (i, key) in keys.iter().enumerate() {
        let w = load_parameter(&conds[i].0);
        let mut best: Option<(usize, f64)> = None;
        for (e, entry) in cache.iter().enumerate() {
            // (M, L, Ry/Rx) fix the law only for one lubricant (its α·p0 and ln(η0/η∞) are
            // further groups, docs/law_map.md): with ring temperatures the raceways differ.
            if entry.conditions.lubricant != conds[i].0.lubricant {
                continue;
            }
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
            if conds[r].0.lubricant != conds[i].0.lubricant {
                continue;
            }
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
    (plan, runs)
}

/// A stop asked for by the caller's progress callback.
struct Cancel<'a> {
    stop: &'a AtomicBool,
}

impl Cancel<'_> {
    fn check(
        &self,
        iteration: usize,
        iterations: usize,
        t0: Instant,
    ) -> Result<(), CharacterizeError> {
        if self.stop.load(Ordering::Relaxed) {
            return Err(CharacterizeError::Cancelled {
                iteration,
                iterations,
                seconds: t0.elapsed().as_secs_f64(),
            });
        }
        Ok(())
    }
}

/// Characterize the contacts `runs` in parallel, collected in index order (None elsewhere);
/// contacts not yet started when `stop` is set are skipped (None: the caller checks `stop`).
fn characterize_runs(
    ch: &dyn ContactCharacterizer,
    conds: &[(ContactConditions, bool)],
    runs: &[usize],
    (iteration, floor): (usize, LoadFloor),
    progress: &(dyn Fn(Progress) + Sync),
    stop: &AtomicBool,
    deadline: Option<Deadline>,
) -> Vec<Result<Option<CharacterizedContact>, CharacterizeError>> {
    let results: Vec<Option<Result<CharacterizedContact, crate::Error>>> = runs
        .par_iter()
        .map(|&i| {
            if stop.load(Ordering::Relaxed) {
                return None;
            }
            let r = ch.characterize(&conds[i].0, deadline);
            progress(Progress::ContactDone { iteration });
            Some(r)
        })
        .collect();
    let mut fresh: Vec<Result<Option<CharacterizedContact>, CharacterizeError>> =
        (0..conds.len()).map(|_| Ok(None)).collect();
    for (&i, r) in runs.iter().zip(results) {
        fresh[i] = match r {
            Some(Ok(c)) => Ok(Some(c)),
            Some(Err(e)) => Err(contact_error(conds, i, iteration, floor, e)),
            None => Ok(None),
        };
    }
    fresh
}

/// The load floor of an iteration: contacts lighter than `fraction` × `largest` (the largest
/// contact load, N) are characterized at that floor.
#[derive(Debug, Clone, Copy)]
struct LoadFloor {
    fraction: f64,
    largest: f64,
}

fn contact_error(
    conds: &[(ContactConditions, bool)],
    i: usize,
    iteration: usize,
    floor: LoadFloor,
    e: crate::Error,
) -> CharacterizeError {
    let (c, floored) = &conds[i];
    let hint = match &e {
        crate::Error::Fit(crate::fit::FitError::HydrodynamicRegime {
            load, amplitude, ..
        }) => {
            let f = floor.fraction;
            format!(
                ". Contacts lighter than min_load_fraction × the largest contact load (now {f} \
                 × {:.4} N = {:.4} N) are characterized at that floor{}: raise min_load_fraction \
                 (0 < f < 1) until the lowest load of each contact's range, w0·(1 − ε) with \
                 ε = {amplitude}, stays above the hydrodynamic regime (here it reached {load:.4} \
                 N), or lower the amplitude",
                floor.largest,
                f * floor.largest,
                if *floored { ", as this one is" } else { "" }
            )
        }
        _ => String::new(),
    };
    CharacterizeError::Contact {
        ball: i / 2,
        race: c.race,
        load: c.load,
        iteration,
        cause: Box::new(e),
        hint,
    }
}

/// The laws of an iteration and its reuse figures.
struct Assembled {
    contacts: Vec<LoopContact>,
    max_key_distance: f64,
    max_load_offset: f64,
    max_relative_residual: f64,
}

/// Every contact's law by its plan: characterized, or rescaled from the cache or from a
/// duplicate.
fn assemble_laws(
    plan: &[Plan],
    fresh: &[Option<CharacterizedContact>],
    cache: &[CacheEntry],
    conds: &[(ContactConditions, bool)],
    keys: &[[f64; 3]],
    iteration: usize,
    floor: LoadFloor,
) -> Result<Assembled, CharacterizeError> {
    let missing = |i: usize| CharacterizeError::NotCharacterized { contact: i };
    let mut out = Assembled {
        contacts: Vec::with_capacity(conds.len()),
        max_key_distance: 0.0,
        max_load_offset: 0.0,
        max_relative_residual: 0.0,
    };
    for (i, p) in plan.iter().enumerate() {
        let wrap = |e: crate::Error| contact_error(conds, i, iteration, floor, e);
        let (cc, source, dist) = match *p {
            Plan::Run => (
                fresh[i].clone().ok_or_else(|| missing(i))?,
                LawSource::Characterized,
                0.0,
            ),
            Plan::Cached(e, d) => (
                rescale(&cache[e], &conds[i].0).map_err(wrap)?,
                LawSource::Cached,
                d,
            ),
            Plan::Duplicate(r, d) => {
                let entry = CacheEntry::new(
                    keys[r],
                    conds[r].0,
                    fresh[r].clone().ok_or_else(|| missing(r))?,
                );
                (
                    rescale(&entry, &conds[i].0).map_err(wrap)?,
                    LawSource::Deduplicated,
                    d,
                )
            }
        };
        out.max_key_distance = out.max_key_distance.max(dist);
        if source != LawSource::Characterized {
            out.max_load_offset = out
                .max_load_offset
                .max((conds[i].0.load / cc.load - 1.0).abs());
        }
        out.max_relative_residual = out.max_relative_residual.max(cc.max_residual / cc.load);
        out.contacts.push((cc, conds[i].1, source, dist));
    }
    Ok(out)
}

/// The final contacts at equilibrium `eq`, with the largest load offset of the contacts that
/// were not floored and the largest relative fit residual.
fn final_contacts(eq: &Equilibrium, contacts: Vec<LoopContact>) -> (Vec<ContactResult>, f64, f64) {
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
    (results, max_load_offset, max_relative_residual)
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
    (progress, stop): (&(dyn Fn(Progress) + Sync), &AtomicBool),
    deadline: Option<Deadline>,
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
            if stop.load(Ordering::Relaxed) {
                // The caller stopped the run: the loop returns Cancelled after the prediction.
                return Err(crate::method::MethodError::Cancelled.into());
            }
            let r = predictor.predict(c, deadline);
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

fn laws_of(contacts: &[LoopContact]) -> ContactLaws {
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
    /// Damping coefficient c of the law's c·δ̇ term, N·s/m (null for laws without one: the
    /// quasi-static and dry methods).
    pub damping_n_s_m: Option<f64>,
    /// Standard error of K from the fit, N/m^d (null if undefined).
    pub k_std_error: Option<f64>,
    /// Standard error of d (null if undefined).
    pub d_std_error: Option<f64>,
    /// Standard error of ΔF, N (null if undefined).
    pub delta_f_std_error_n: Option<f64>,
    /// Standard error of the damping coefficient c, N·s/m (the harmonic map: its error estimate
    /// of c; null for laws without damping, or in rows written before this column existed).
    #[serde(default)]
    pub damping_std_error_n_s_m: Option<f64>,
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
    /// The method that characterized the law ([`method_label`]): `quasi-static`, `harmonic`,
    /// `hertz`, `map`, `map (harmonic)`, or with the map's fallback e.g. `quasi-static (outside the
    /// map)` (empty in rows written before this column existed).
    #[serde(default)]
    pub method: String,
}

/// The label of a characterized contact's method for reports and CSV cells: its `method` without
/// the reason a map's fallback gives after "(outside the map: " (the row's M, L and Ry/Rx say
/// where the contact lies), so it holds no comma.
pub fn method_label(method: &str) -> String {
    match method.find("(outside the map: ") {
        Some(i) => format!("{}(outside the map)", &method[..i]),
        None => method.replace(',', ";"),
    }
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
            damping_n_s_m: cc.law.c(),
            k_std_error: finite_or_none(cc.std_errors[0]),
            d_std_error: finite_or_none(cc.std_errors[1]),
            delta_f_std_error_n: finite_or_none(cc.std_errors[2]),
            damping_std_error_n_s_m: cc.c_std_error.and_then(finite_or_none),
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
            method: method_label(&cc.method),
        }
    }
}

/// Ring displacements (x, y, z in m; θy, θz in rad) as a named record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Displacements {
    /// Axial displacement x, m.
    pub x: f64,
    /// Radial displacement y, m.
    pub y: f64,
    /// Radial displacement z, m.
    pub z: f64,
    /// Tilt θy about +y, rad.
    pub theta_y: f64,
    /// Tilt θz about +z, rad.
    pub theta_z: f64,
}

impl From<[f64; 5]> for Displacements {
    fn from(q: [f64; 5]) -> Self {
        Displacements {
            x: q[0],
            y: q[1],
            z: q[2],
            theta_y: q[3],
            theta_z: q[4],
        }
    }
}

impl Displacements {
    /// As an array in the order x, y, z, θy, θz.
    pub fn to_array(&self) -> [f64; 5] {
        [self.x, self.y, self.z, self.theta_y, self.theta_z]
    }
}

/// Reactions on the inner ring (F_x, F_y, F_z in N; M_y, M_z in N·m) as a named record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Reactions {
    /// Axial force F_x, N.
    pub force_x: f64,
    /// Radial force F_y, N.
    pub force_y: f64,
    /// Radial force F_z, N.
    pub force_z: f64,
    /// Moment M_y, N·m.
    pub moment_y: f64,
    /// Moment M_z, N·m.
    pub moment_z: f64,
}

impl From<[f64; 5]> for Reactions {
    fn from(f: [f64; 5]) -> Self {
        Reactions {
            force_x: f[0],
            force_y: f[1],
            force_z: f[2],
            moment_y: f[3],
            moment_z: f[4],
        }
    }
}

impl Reactions {
    /// As an array in the order F_x, F_y, F_z, M_y, M_z.
    pub fn to_array(&self) -> [f64; 5] {
        [
            self.force_x,
            self.force_y,
            self.force_z,
            self.moment_y,
            self.moment_z,
        ]
    }
}

fn no_time(s: &Option<f64>) -> bool {
    s.is_none()
}

/// One iteration of the loop as written to files: the record, and its time only where timings
/// are wanted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IterationSummary {
    /// The iteration (its `seconds` field is not written; see `seconds` here).
    #[serde(flatten)]
    pub record: IterationRecord,
    /// Wall-clock time, s (absent in reproducible files).
    #[serde(default, skip_serializing_if = "no_time")]
    pub seconds: Option<f64>,
}

/// The load prediction as written to files: the record, and its time only where timings are
/// wanted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PredictionSummary {
    /// The prediction (its `seconds` field is not written; see `seconds` here).
    #[serde(flatten)]
    pub record: PredictionRecord,
    /// Wall-clock time, s (absent in reproducible files).
    #[serde(default, skip_serializing_if = "no_time")]
    pub seconds: Option<f64>,
}

/// A characterization as a typed record in SI units: what `characterize --json` prints,
/// `characterization.json` holds and every study point file carries. Reads back into the same
/// value (`serde_json::from_str`). Without timing it is reproducible bit for bit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CharacterizationReport {
    /// Whether the loop converged.
    pub converged: bool,
    /// Iterations performed.
    pub iterations: usize,
    /// Last largest relative load change (dimensionless).
    pub max_load_change: f64,
    /// Largest relative key distance of a reused law in the final iteration.
    pub max_key_distance: f64,
    /// Largest |Q/w0 − 1| of the final contacts that were not floored.
    pub max_load_offset: f64,
    /// Largest max_residual/w0 of the final laws.
    pub max_relative_residual: f64,
    /// The method and its settings.
    pub method: Method,
    /// Loop settings.
    pub settings: CharacterizeSettings,
    /// The load prediction the loop started from (null: started from the dry loads).
    pub prediction: Option<PredictionSummary>,
    /// Per-iteration history.
    pub history: Vec<IterationSummary>,
    /// Displacements of the final equilibrium (m, rad).
    pub displacement: Displacements,
    /// Displacements of the dry Hertz equilibrium (m, rad).
    pub dry_displacement: Displacements,
    /// Reactions of the final equilibrium (N, N·m).
    pub reaction: Reactions,
    /// Dry stiffness matrix, order x, y, z, θy, θz (N/m, N, N·m/rad).
    pub stiffness_dry: [[f64; 5]; 5],
    /// Stiffness matrix with the fitted laws.
    pub stiffness_ehl: [[f64; 5]; 5],
    /// Per-contact rows, ball 0 inner, ball 0 outer, ball 1 inner, …
    pub contacts: Vec<ContactRow>,
    /// Film, Λ, κ and thermal-reduction estimates (crate::lubrication); absent unless the case
    /// describes its oil or gives roughness.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lubrication: Option<crate::lubrication::LubricationReport>,
    /// Total wall-clock time, s (absent in reproducible files).
    #[serde(default, skip_serializing_if = "no_time")]
    pub seconds: Option<f64>,
}

impl BearingCharacterization {
    /// The typed record of this characterization; with `timing` false every time is left out, so
    /// the record is reproducible bit for bit.
    pub fn report(&self, timing: bool) -> CharacterizationReport {
        let t = |s: f64| timing.then_some(s);
        CharacterizationReport {
            converged: self.converged,
            iterations: self.iterations,
            max_load_change: self.max_load_change,
            max_key_distance: self.max_key_distance,
            max_load_offset: self.max_load_offset,
            max_relative_residual: self.max_relative_residual,
            method: self.method,
            settings: self.settings,
            // The records' own time is not serialized; it travels in `seconds` (0 inside, so a
            // report reads back into the same value).
            prediction: self.prediction.as_ref().map(|p| PredictionSummary {
                record: PredictionRecord {
                    seconds: 0.0,
                    ..p.clone()
                },
                seconds: t(p.seconds),
            }),
            history: self
                .history
                .iter()
                .map(|h| IterationSummary {
                    record: IterationRecord { seconds: 0.0, ..*h },
                    seconds: t(h.seconds),
                })
                .collect(),
            displacement: self.equilibrium.displacement.into(),
            dry_displacement: self.dry.displacement.into(),
            reaction: self.equilibrium.reaction.into(),
            stiffness_dry: self.dry.stiffness,
            stiffness_ehl: self.equilibrium.stiffness,
            contacts: self.contacts.iter().map(ContactRow::from_result).collect(),
            lubrication: self.lubrication.clone(),
            seconds: t(self.seconds),
        }
    }
}
