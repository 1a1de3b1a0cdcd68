//! Trend curves K(Q), d(Q), ΔF(Q, n) and the approach δ(Q, n) per raceway: the model and its
//! JSON ([`TrendModel`]), the fit over characterized contacts ([`fit_model`]; a study builds the
//! samples from its rows: [`crate::study::fit_trends`]), and the evaluation as contact laws
//! ([`TrendModel::law_at`], [`SpeedLaws`]; the force element built on them is
//! [`crate::force_element::TrendForceElement`]). Errors: [`TrendError`], with the numbers.
//!
//! This module sits below the characterization loop, the force element and the study
//! (`docs/architecture.md`): it imports the bearing, the fit, the materials and the method
//! settings, nothing above them. Its errors reach the crate [`Error`](crate::Error) as
//! [`CharacterizeError::Trend`](crate::characterize::CharacterizeError::Trend).

mod fit;
mod law;
mod model;

pub use fit::{fit_model, RaceSamples, TrendFitInput};
pub use law::{RaceLaw, SpeedLaws};
pub use model::{RaceTrends, TrendBearing, TrendCurve, TrendModel, TREND_VERSION};

use crate::bearing::{BearingError, Race};
use crate::fit::FitError;
use thiserror::Error;

/// "inner" or "outer".
pub(crate) fn race_name(race: Race) -> &'static str {
    match race {
        Race::Inner => "inner",
        Race::Outer => "outer",
    }
}

/// Errors of the trend curves: their fit, their JSON and their evaluation. Every variant carries
/// the raceway, curve and numbers concerned.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TrendError {
    /// A curve of trend JSON has a form this library does not know.
    #[error("{curve}: unknown form {form:?}")]
    UnknownForm {
        /// The curve, e.g. `inner.d`.
        curve: String,
        /// The form given.
        form: String,
    },
    /// A curve's parameters do not fit its form.
    #[error("{curve}: form {form} needs {needed} finite parameters, got {params:?}")]
    Parameters {
        /// The curve, e.g. `inner.d`.
        curve: String,
        /// Its form.
        form: String,
        /// Number of finite parameters the form needs.
        needed: usize,
        /// The parameters given.
        params: Vec<f64>,
    },
    /// Trend JSON that does not parse (the parser's message, with line and column).
    #[error("trend JSON: {message}")]
    Json {
        /// The JSON parser's message.
        message: String,
    },
    /// Trend JSON of another format version.
    #[error("trend JSON version {found} (this library reads version {supported})")]
    Version {
        /// The version of the JSON.
        found: u32,
        /// The version this library reads ([`TREND_VERSION`]).
        supported: u32,
    },
    /// A validity range that is not 0 < min ≤ max.
    #[error("{}.{field} = [{lo}, {hi}]: expected 0 < min ≤ max", race_name(*.race))]
    Range {
        /// The raceway.
        race: Race,
        /// `load_range_n` or `speed_range_rad_s`.
        field: &'static str,
        /// The minimum given.
        lo: f64,
        /// The maximum given.
        hi: f64,
    },
    /// The model's bearing is invalid.
    #[error("bearing: {0}")]
    Bearing(BearingError),
    /// The approach trend does not increase with the load, so it cannot be inverted for a
    /// contact's load.
    #[error("{} approach trend δ(Q, n) does not increase with the load at Q = {load_n:.4e} N, n = {speed_rad_s:.4e} rad/s: it cannot serve as a contact law", race_name(*.race))]
    NotIncreasing {
        /// The raceway.
        race: Race,
        /// Contact load, N.
        load_n: f64,
        /// Speed of the inner ring relative to the outer, rad/s.
        speed_rad_s: f64,
    },
    /// The law the trends give at a load and speed is not a valid fitted law.
    #[error("law from the trends at Q = {load_n} N, n = {speed_rad_s} rad/s ({race:?}): {source}")]
    Law {
        /// The raceway.
        race: Race,
        /// Contact load (clamped into the validity range), N.
        load_n: f64,
        /// Speed (clamped into the validity range), rad/s.
        speed_rad_s: f64,
        /// Why the law is invalid.
        source: FitError,
    },
    /// Too few usable contacts, or too few distinct loads among them, to fit a raceway's trends.
    #[error("{}: {contacts} usable contacts with {distinct_loads} distinct loads; at least 3 are needed", race_name(*.race))]
    TooFewContacts {
        /// The raceway.
        race: Race,
        /// Usable contacts (load not floored, fit converged, positive load).
        contacts: usize,
        /// Distinct equilibrium loads among them.
        distinct_loads: usize,
    },
    /// A characterized stiffness K that is not positive (its power law cannot be fitted).
    #[error("{} K (non-positive stiffness): the data cannot determine the trend (too few distinct loads?)", race_name(*.race))]
    NonPositiveStiffness {
        /// The raceway.
        race: Race,
    },
    /// A curve's least-squares problem is singular.
    #[error("{} {curve}: the data cannot determine the trend (too few distinct loads?)", race_name(*.race))]
    Singular {
        /// The raceway.
        race: Race,
        /// The curve: `K`, `d`, `ΔF` or `δ`.
        curve: &'static str,
    },
    /// A point without an equilibrium (it failed) to compare the trends with.
    #[error("the point failed: no equilibrium to compare")]
    NoEquilibrium,
}
