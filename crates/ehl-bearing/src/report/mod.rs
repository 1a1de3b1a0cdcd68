//! Results as typed reports: the one place where the library's results become the records that
//! the command line prints and writes (JSON, CSV, tables), that Python returns as dicts and that C
//! returns as JSON text. One key set for every consumer; the schema is `docs/results.md`.
//!
//! Where a result type of a lower floor already serializes with the schema's keys it IS its report
//! (one owner, no copy): [`ContactReport`] is [`crate::contact::ContactFit`],
//! [`CharacterizationReport`] is the loop's record, a study point is
//! [`crate::study::PointRecord`], the coefficients are
//! [`crate::coefficients::SpeedCoefficients`]. The reports defined here are those whose result
//! type carries more than the record (the EHL solution's fields, the equilibrium's Newton
//! history) or lays it out differently (the equilibrium's displacements as named components).
//!
//! Every value is SI (m, N, Pa, s, rad, rad/s, kg); keys without a unit suffix are SI quantities
//! whose unit the schema names, keys with one (`load_n`, `frequency_rad_s`) carry it.

use crate::bearing::{BallState, ContactState, Equilibrium};
use crate::ehl::{EhlFields, EhlSolution};
use crate::lubrication::LubricationReport;
use serde::Serialize;
mod events;
pub use events::{ProgressEvent, SpeedProgressEvent, StudyEventReport};

pub use crate::characterize::{CharacterizationReport, ContactRow, Displacements, Reactions};
pub use crate::coefficients::SpeedCoefficients as CoefficientsReport;
pub use crate::contact::ContactFit as ContactReport;
pub use crate::csv::csv;
pub use crate::rotor::{StaticSolution as RotorStaticReport, TimeResponse as RotorRunReport};
pub use crate::study::PointRecord as StudyPointReport;

/// A report as pretty-printed JSON (two-space indent, keys in the report's field order).
pub fn to_json_pretty<T: Serialize + ?Sized>(report: &T) -> String {
    serde_json::to_string_pretty(report).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// A report as one line of JSON.
pub fn to_json_line<T: Serialize + ?Sized>(report: &T) -> String {
    serde_json::to_string(report).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// The steady EHL solution of one point contact (`ehl --json`, Python `ehl()`): every figure of
/// [`EhlSolution`] (its own serialization, one owner of the keys); the pressure and film fields on
/// the grid only where asked for (Python's `fields=True`; the command line writes them as CSV files
/// instead).
#[derive(Debug, Clone, Serialize)]
pub struct EhlReport<'a> {
    /// The solution's figures.
    #[serde(flatten)]
    pub solution: &'a EhlSolution,
    /// Pressure and film on the grid (only where asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fields: Option<&'a EhlFields>,
}

impl<'a> EhlReport<'a> {
    /// The report of `s`, with the fields on the grid where `fields`.
    pub fn new(s: &'a EhlSolution, fields: bool) -> Self {
        EhlReport {
            solution: s,
            fields: fields.then_some(&s.fields),
        }
    }
}

impl<'a> From<&'a EhlSolution> for EhlReport<'a> {
    fn from(s: &'a EhlSolution) -> Self {
        EhlReport::new(s, false)
    }
}

/// The film of one contact of an equilibrium, solved as a steady EHL point contact at the
/// contact's load, radii and sum velocity (`equilibrium --film`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "state", rename_all = "kebab-case")]
pub enum FilmReport {
    /// Load below the unloaded fraction of the largest: no solution.
    Unloaded,
    /// No entrainment (e.g. co-rotating rings): a dry contact, no film.
    NoEntrainment,
    /// The steady solution's figures.
    Solved(FilmSummary),
    /// The solver's error.
    Failed {
        /// Always false.
        converged: bool,
        /// The solver's message.
        error: String,
    },
}

/// The figures of a solved film (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FilmSummary {
    /// Whether the solution met its tolerances.
    pub converged: bool,
    /// Central film thickness h_c, m.
    pub h_central: f64,
    /// Minimum film thickness h_min, m.
    pub h_min: f64,
    /// Largest pressure, Pa.
    pub p_max: f64,
    /// Approach of distant points δ = −h0, m.
    pub approach: f64,
    /// Moes M.
    pub moes_m: f64,
    /// Moes L.
    pub moes_l: f64,
    /// Ry/Rx.
    pub ry_over_rx: f64,
    /// Relative force-balance residual.
    pub force_balance_residual: f64,
    /// Final relative residual of the Reynolds equation.
    pub residual: f64,
}

impl From<&EhlSolution> for FilmSummary {
    fn from(s: &EhlSolution) -> Self {
        FilmSummary {
            converged: s.converged,
            h_central: s.h_central,
            h_min: s.h_min,
            p_max: s.p_max,
            approach: s.approach,
            moes_m: s.moes_m,
            moes_l: s.moes_l,
            ry_over_rx: s.ry_over_rx,
            force_balance_residual: s.force_balance_residual,
            residual: s.residual,
        }
    }
}

/// One ball/raceway contact of an equilibrium: its [`ContactState`] (load, contact angle,
/// deflection, Hertz semi-axes and pressure, radii, sum velocity, spin-to-roll ratio, friction
/// needed and available) and, where solved, its film.
#[derive(Debug, Clone, Serialize)]
pub struct ContactStateReport {
    /// The contact's state.
    #[serde(flatten)]
    pub state: ContactState,
    /// The film, where solved (`equilibrium --film`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film: Option<FilmReport>,
}

/// One ball of an equilibrium: its [`BallState`]'s speeds, angles and forces, and its two
/// contacts.
#[derive(Debug, Clone, Serialize)]
pub struct BallReport {
    /// Azimuth ψ, rad.
    pub azimuth: f64,
    /// Orbital (cage) speed ω_m, rad/s.
    pub orbital_speed: f64,
    /// Signed roll speed ω_R about the rolling axis, relative to the cage, rad/s.
    pub spin_speed: f64,
    /// Pitch angle β, rad.
    pub pitch_angle: f64,
    /// Angle of the line of groove-curvature centres, rad.
    pub kinematic_angle: f64,
    /// Centrifugal force, N.
    pub centrifugal_force: f64,
    /// Gyroscopic moment, N·m.
    pub gyroscopic_moment: f64,
    /// Friction force of the inner race on the ball, N.
    pub inner_friction: f64,
    /// Friction force of the outer race on the ball, N.
    pub outer_friction: f64,
    /// Inner contact.
    pub inner: ContactStateReport,
    /// Outer contact.
    pub outer: ContactStateReport,
}

impl From<&BallState> for BallReport {
    fn from(b: &BallState) -> Self {
        BallReport {
            azimuth: b.azimuth,
            orbital_speed: b.orbital_speed,
            spin_speed: b.spin_speed,
            pitch_angle: b.pitch_angle,
            kinematic_angle: b.kinematic_angle,
            centrifugal_force: b.centrifugal_force,
            gyroscopic_moment: b.gyroscopic_moment,
            inner_friction: b.inner_friction,
            outer_friction: b.outer_friction,
            inner: ContactStateReport {
                state: b.inner,
                film: None,
            },
            outer: ContactStateReport {
                state: b.outer,
                film: None,
            },
        }
    }
}

/// A quasi-static equilibrium of the bearing (`equilibrium --json`, Python `equilibrium()`, C
/// `ehl_case_equilibrium_json`), SI: m, rad, N, N·m, Pa, rad/s, m/s.
#[derive(Debug, Clone, Serialize)]
pub struct EquilibriumReport {
    /// Whether the residual met the tolerance.
    pub converged: bool,
    /// Newton iterations used.
    pub iterations: usize,
    /// Final largest load-controlled residual, N.
    pub residual: f64,
    /// Inner-ring displacements x, y, z (m) and tilts θy, θz (rad).
    pub displacement: Displacements,
    /// Load on the inner ring in equilibrium with the balls (N, N·m).
    pub reaction: Reactions,
    /// Stiffness ∂reaction/∂displacement, order x, y, z, θy, θz (N/m, N, N·m/rad).
    pub stiffness: [[f64; 5]; 5],
    /// Conditions under which the result is approximate, in words.
    pub warnings: Vec<String>,
    /// Per-ball states, ball 0 on +y.
    pub balls: Vec<BallReport>,
    /// Film, Λ, κ and thermal-reduction estimates, where assessed (the case describes its oil
    /// or gives roughness).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lubrication: Option<LubricationReport>,
}

impl From<&Equilibrium> for EquilibriumReport {
    fn from(e: &Equilibrium) -> Self {
        EquilibriumReport {
            converged: e.converged,
            iterations: e.iterations,
            residual: e.residual,
            displacement: e.displacement.into(),
            reaction: e.reaction.into(),
            stiffness: e.stiffness,
            warnings: e.warnings.clone(),
            balls: e.balls.iter().map(BallReport::from).collect(),
            lubrication: None,
        }
    }
}

impl EquilibriumReport {
    /// The same report with each contact's film: `films[2j]` the inner and `films[2j + 1]` the
    /// outer contact of ball j.
    pub fn with_films(mut self, films: impl IntoIterator<Item = FilmReport>) -> Self {
        let mut f = films.into_iter();
        for b in &mut self.balls {
            b.inner.film = f.next();
            b.outer.film = f.next();
        }
        self
    }
}

/// The top-level keys of `record`'s serialized form, in order: the key set a result's consumers
/// (Python dicts of numpy arrays, which are built field by field) must give. Empty if the record
/// does not serialize to a map.
pub fn record_keys<T: Serialize + ?Sized>(record: &T) -> Vec<String> {
    match serde_json::to_value(record) {
        Ok(serde_json::Value::Object(m)) => m.keys().cloned().collect(),
        _ => Vec::new(),
    }
}
