//! The bearing case as domain data: [`Case`] (geometry, materials, lubricant, operating point,
//! solver settings, method) in SI units, its parts ([`Roughness`], [`RingOils`]), and
//! [`InputError`], the error of an invalid input naming the key, the value and the valid range.
//!
//! Reading and writing case files (TOML, engineering units in every key name) is [`crate::io`]'s.

use crate::bearing::{Bearing, EquilibriumSettings, OperatingPoint};
use crate::material::Lubricant;
use crate::oil::OilProperties;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A validated bearing case, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Optional bearing name.
    pub name: Option<String>,
    /// Geometry and materials.
    pub bearing: Bearing,
    /// Lubricant (the default mineral oil when the file has no `[lubricant]`).
    pub lubricant: Lubricant,
    /// Whether the lubricant was given in the file (false: the default was used).
    pub lubricant_given: bool,
    /// The described lubricant's derived constants at the operating temperature, with their
    /// sources (None: the lubricant is given by its constants or not at all).
    pub oil: Option<OilProperties>,
    /// Surface roughness of balls and rings (None: not given).
    pub roughness: Option<Roughness>,
    /// The described lubricant's constants at the inner and outer ring temperatures
    /// (`operating.inner_ring_temperature_c`, `operating.outer_ring_temperature_c`; None: not
    /// given). Each raceway's contacts are characterized with its ring's oil
    /// ([`Case::lubricant_of`]) and get their lubrication figures from it; κ and the report's
    /// η0, α are at `operating.temperature_c` (docs/lubricant.md §3.1).
    pub ring_oils: Option<RingOils>,
    /// Distance from each contact's centre to the upstream oil meniscus along the rolling
    /// direction, m (`operating.inlet_meniscus_distance_mm`; None: fully flooded, the default).
    /// Used by the starvation estimate of the lubrication figures only (docs/lubricant.md §3).
    pub inlet_meniscus_distance_m: Option<f64>,
    /// Speeds, loads and race control.
    pub operating: OperatingPoint,
    /// Equilibrium solver settings.
    pub settings: EquilibriumSettings,
    /// Characterization method given in the file (`method` with its `[method_options]`
    /// applied), if any.
    pub method: Option<crate::method::Method>,
}

impl Case {
    /// The lubricant at the contacts of raceway `race`: the described oil's constants at the
    /// ring's temperature when ring temperatures are given (`operating.inner_ring_temperature_c`,
    /// `outer_ring_temperature_c`), else [`Case::lubricant`]; the viscosity and density models
    /// are the case's.
    pub fn lubricant_of(&self, race: crate::bearing::Race) -> Lubricant {
        match &self.ring_oils {
            Some(r) => {
                let o = r.of(race);
                Lubricant {
                    viscosity: o.viscosity_pa_s,
                    pressure_viscosity: o.pressure_viscosity_1_pa,
                    density: o.density_kg_m3,
                    ..self.lubricant
                }
            }
            None => self.lubricant,
        }
    }

    /// The method to characterize this case with: `name` if given (with the file's
    /// `[method_options]` when `name` is the file's own method), else the file's method, else the
    /// default (quasi-static).
    pub fn method_or(
        &self,
        name: Option<&str>,
    ) -> Result<crate::method::Method, crate::method::MethodError> {
        match (name, &self.method) {
            (Some(n), Some(m)) if n == m.name() => Ok(*m),
            (Some(n), _) => crate::method::Method::parse(n, None),
            (None, Some(m)) => Ok(*m),
            (None, None) => Ok(crate::method::Method::default()),
        }
    }
}

/// A described oil's constants at the inner and outer ring temperatures
/// (`operating.inner_ring_temperature_c`, `operating.outer_ring_temperature_c`): each raceway's
/// figures, EHL solves and laws use its ring's; κ uses the oil at `operating.temperature_c`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RingOils {
    /// At the inner ring's temperature.
    pub inner: crate::oil::OilProperties,
    /// At the outer ring's temperature.
    pub outer: crate::oil::OilProperties,
}

impl RingOils {
    /// The oil of raceway `race`.
    pub fn of(&self, race: crate::bearing::Race) -> &crate::oil::OilProperties {
        match race {
            crate::bearing::Race::Inner => &self.inner,
            crate::bearing::Race::Outer => &self.outer,
        }
    }
}

/// Surface roughness of balls and rings, m (RMS, Rq).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Roughness {
    /// Ball roughness Rq, m.
    pub ball_rq_m: f64,
    /// Raceway roughness Rq, m.
    pub ring_rq_m: f64,
}

impl Roughness {
    /// Composite roughness σ = √(Rq_ball² + Rq_race²), m.
    pub fn composite(&self) -> f64 {
        (self.ball_rq_m * self.ball_rq_m + self.ring_rq_m * self.ring_rq_m).sqrt()
    }
}

/// Errors reading user input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum InputError {
    /// A field has an invalid value.
    #[error("{field} = {value}: expected {expected}")]
    Field {
        /// The key, with its table, e.g. `bearing.ball_diameter_mm`.
        field: String,
        /// The value given.
        value: String,
        /// The valid range.
        expected: String,
    },
    /// Two keys that exclude each other were both given.
    #[error("{first} and {second} are both given: give one or the other")]
    Conflict {
        /// One key.
        first: String,
        /// The other key.
        second: String,
    },
    /// A required key is missing.
    #[error("{field} is missing: {hint}")]
    Missing {
        /// The key.
        field: String,
        /// What to give.
        hint: String,
    },
    /// The file is not valid TOML for a case (syntax, wrong type, unknown key).
    #[error("{path}: {message}")]
    Syntax {
        /// File name (or `<input>`).
        path: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// The file could not be read.
    #[error("cannot read {path}: {message}")]
    Io {
        /// File name.
        path: String,
        /// The OS error.
        message: String,
    },
}

/// Shortest round-trip text of `v` for names and messages: positional (`3000`, `0.5`) when at
/// most 20 characters, else exponent form (`1e-300`, `1e300`, where positional text runs to
/// 300 digits). Distinct values give distinct texts (only the exponent form has an `e`).
pub fn number_text(v: f64) -> String {
    let positional = format!("{v}");
    if positional.len() <= 20 {
        positional
    } else {
        format!("{v:e}")
    }
}

impl InputError {
    pub(crate) fn field(field: &str, value: impl ToString, expected: impl Into<String>) -> Self {
        InputError::Field {
            field: field.to_string(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }
}
