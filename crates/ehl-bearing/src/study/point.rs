//! Typed records of a study's points: what a point depends on ([`PointSpec`]), what a point file
//! holds ([`PointRecord`]), and the tables built from them (`results.csv`: [`ResultRow`],
//! [`results_csv`]; `points.csv`: [`points_csv`]).

use crate::bearing::{Bearing, EquilibriumSettings, OperatingPoint};
use crate::characterize::{CharacterizationReport, CharacterizeSettings, ContactRow};
use crate::lubrication::{LubricationReport, RingOils, Roughness};
use crate::material::Lubricant;
use crate::method::Method;
use crate::oil::OilProperties;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Everything a point's result depends on (SI). Written into the point file and compared on
/// resume: a point file with a different spec is recomputed, never reused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PointSpec {
    /// Inner-ring speed, rpm.
    pub inner_speed_rpm: f64,
    /// Load scale (dimensionless).
    pub load_scale: f64,
    /// The method and its full settings.
    pub method: Method,
    /// Loop settings.
    pub settings: CharacterizeSettings,
    /// Bearing geometry and materials.
    pub bearing: Bearing,
    /// Lubricant.
    pub lubricant: Lubricant,
    /// Operating point of the point (speeds in rad/s, scaled loads).
    pub operating: OperatingPoint,
    /// Equilibrium solver settings.
    pub equilibrium: EquilibriumSettings,
    /// The described oil's derived constants (absent when the lubricant is given by its
    /// constants): its temperature–viscosity coefficient and thermal conductivity enter the
    /// lubrication figures.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oil: Option<OilProperties>,
    /// Surface roughness (absent when not given): enters Λ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Roughness>,
    /// The oil at the ring temperatures (absent when not given): enters each raceway's figures.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring_oils: Option<RingOils>,
    /// The oil supply: distance from each contact's centre to the upstream meniscus, m (absent:
    /// fully flooded): enters the starvation estimate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inlet_meniscus_distance_m: Option<f64>,
}

impl PointSpec {
    /// Whether the point's outputs carry the lubrication figures (a described oil, roughness or
    /// an oil supply, as [`crate::lubrication::wanted`]).
    pub fn has_lubrication(&self) -> bool {
        self.oil.is_some() || self.roughness.is_some() || self.has_oil_supply()
    }

    /// Whether the point's outputs carry the starvation figures (an oil supply is described).
    pub fn has_oil_supply(&self) -> bool {
        self.inlet_meniscus_distance_m.is_some()
    }
}

/// One point file (`points/<stem>.json`): the spec and either the characterization (without
/// timings, so reproducible bit for bit) or the error that stopped it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointRecord {
    /// What the point depends on.
    pub spec: PointSpec,
    /// The characterization, if it ran to the end (converged or not).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub result: Option<CharacterizationReport>,
    /// Why the point failed (a load the bearing cannot carry, a diverged EHL solve, …).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl PointRecord {
    /// The point file's text: pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default() + "\n"
    }

    /// Parse a point file.
    pub fn from_json(text: &str) -> Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// Whether the point's loop converged (false for a failed point).
    pub fn converged(&self) -> bool {
        self.result.as_ref().is_some_and(|r| r.converged)
    }

    /// The point's rows of `results.csv` (none for a failed point).
    pub fn rows(&self) -> Vec<ResultRow> {
        let Some(r) = &self.result else {
            return Vec::new();
        };
        let rpm = self.spec.inner_speed_rpm;
        let lubricated = self.spec.has_lubrication();
        let supplied = self.spec.has_oil_supply();
        r.contacts
            .iter()
            .map(|c| ResultRow {
                speed_rpm: rpm,
                inner_speed_rad_s: rpm * PI / 30.0,
                load_scale: self.spec.load_scale,
                point_converged: r.converged,
                contact: c.clone(),
                lubrication: lubricated
                    .then(|| ContactLubrication::of(r.lubrication.as_ref(), c.ball, &c.race)),
                starvation: supplied
                    .then(|| ContactStarvation::of(r.lubrication.as_ref(), c.ball, &c.race)),
            })
            .collect()
    }
}

/// A contact's lubrication figures in `results.csv` (crate::lubrication; SI; None where not
/// computed: Λ without roughness, the thermal reduction without a described oil, films of an
/// unloaded contact).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactLubrication {
    /// Isothermal central film (Hamrock–Dowson 1977 at the equilibrium contact state), m.
    pub central_film_m: Option<f64>,
    /// Isothermal minimum film, m.
    pub min_film_m: Option<f64>,
    /// Film parameter Λ = h_min/σ.
    pub lambda: Option<f64>,
    /// Estimated film reduction by inlet shear heating (fraction).
    pub thermal_reduction: Option<f64>,
    /// Minimum film with the thermal reduction applied, m.
    pub min_film_thermal_m: Option<f64>,
}

impl ContactLubrication {
    /// The figures of contact (`ball`, `race`) in `report` (all None if absent).
    pub fn of(report: Option<&LubricationReport>, ball: usize, race: &str) -> Self {
        report
            .and_then(|l| l.contact(ball, race))
            .map(|c| ContactLubrication {
                central_film_m: c.central_film_m,
                min_film_m: c.min_film_m,
                lambda: c.lambda,
                thermal_reduction: c.thermal_reduction,
                min_film_thermal_m: c.min_film_thermal_m,
            })
            .unwrap_or_default()
    }
}

/// A contact's starvation figures in `results.csv` (crate::lubrication::Starvation; None where
/// not computed: an unloaded contact).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactStarvation {
    /// Dimensionless inlet distance m = x_meniscus/b.
    pub inlet_distance_ratio: Option<f64>,
    /// Estimated starvation reduction of the minimum film (fraction).
    pub starvation_reduction: Option<f64>,
    /// Starved minimum film, m.
    pub min_film_starved_m: Option<f64>,
}

impl ContactStarvation {
    /// The figures of contact (`ball`, `race`) in `report` (all None if absent).
    pub fn of(report: Option<&LubricationReport>, ball: usize, race: &str) -> Self {
        report
            .and_then(|l| l.contact(ball, race))
            .and_then(|c| c.starvation)
            .map(|s| ContactStarvation {
                inlet_distance_ratio: Some(s.inlet_distance_ratio),
                starvation_reduction: Some(s.reduction),
                min_film_starved_m: Some(s.min_film_m),
            })
            .unwrap_or_default()
    }
}

/// A row of `results.csv`: the point and one contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultRow {
    /// Inner-ring speed, rpm.
    pub speed_rpm: f64,
    /// Inner-ring speed, rad/s.
    pub inner_speed_rad_s: f64,
    /// Load scale.
    pub load_scale: f64,
    /// Whether the point's loop converged.
    pub point_converged: bool,
    /// The contact.
    #[serde(flatten)]
    pub contact: ContactRow,
    /// The contact's lubrication figures, appended as columns when the study's case describes
    /// its oil or gives roughness (None otherwise: no columns, the file as without them).
    #[serde(flatten, default, skip_serializing_if = "Option::is_none")]
    pub lubrication: Option<ContactLubrication>,
    /// The contact's starvation figures, appended as columns when the study's case describes an
    /// oil supply (`operating.inlet_meniscus_distance_mm`; None otherwise: no columns).
    #[serde(flatten, default, skip_serializing_if = "Option::is_none")]
    pub starvation: Option<ContactStarvation>,
}

/// Long-format CSV of `rows` (one line per point and contact; SI units in the column names;
/// empty cell for an undefined value).
pub fn results_csv(rows: &[ResultRow]) -> String {
    crate::csv::csv(rows)
}

/// Columns of `points.csv` (SI units in the names).
pub const POINTS_CSV_HEADER: &str = "speed_rpm,load_scale,converged,iterations,max_load_change,max_key_distance,max_load_offset,max_relative_residual,characterizations,x_m,y_m,z_m,theta_y_rad,theta_z_rad,dry_x_m,dry_y_m,dry_z_m,k_xx_n_m,k_yy_n_m,k_zz_n_m,dry_k_xx_n_m,dry_k_yy_n_m,dry_k_zz_n_m,trend_reaction_error";

/// Columns appended to `points.csv` when the study's case describes its oil or gives roughness
/// (crate::lubrication, at each point's final equilibrium; SI except ν): the operating kinematic
/// viscosity, ISO 281's κ, the smallest minimum film over the contacts, the smallest Λ and the
/// contact where it occurs, the largest thermal film reduction, and the number of warnings.
pub const POINTS_CSV_LUBRICATION_HEADER: &str = "kinematic_viscosity_mm2_s,kappa,min_film_m,min_lambda,min_lambda_ball,min_lambda_race,max_thermal_reduction,lubrication_warnings";

/// Column appended to `points.csv` after [`POINTS_CSV_LUBRICATION_HEADER`] when the study's case
/// describes an oil supply: the largest starvation reduction of the minimum film.
pub const POINTS_CSV_STARVATION_HEADER: &str = "max_starvation_reduction";

/// The cells of [`POINTS_CSV_LUBRICATION_HEADER`] for a point's report (empty cells where a
/// figure is not computed or the report is absent).
fn lubrication_cells(report: Option<&LubricationReport>) -> Vec<String> {
    let n = POINTS_CSV_LUBRICATION_HEADER.split(',').count();
    let Some(l) = report else {
        return vec![String::new(); n];
    };
    let num = |x: Option<f64>| x.map(number).unwrap_or_default();
    let min_film = l
        .contacts
        .iter()
        .filter_map(|c| c.min_film_m)
        .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.min(v))));
    // The first contact with the smallest Λ (the report's order: the characterization's).
    let worst = l
        .contacts
        .iter()
        .filter_map(|c| c.lambda.map(|x| (x, c)))
        .fold(
            None,
            |m: Option<(f64, &crate::lubrication::ContactFilm)>, (x, c)| match m {
                Some((y, _)) if y <= x => m,
                _ => Some((x, c)),
            },
        );
    vec![
        num(Some(l.kinematic_viscosity_mm2_s)),
        num(l.kappa),
        num(min_film),
        num(worst.map(|w| w.0)),
        worst.map(|w| w.1.ball.to_string()).unwrap_or_default(),
        worst.map(|w| w.1.race.clone()).unwrap_or_default(),
        num(l.max_thermal_reduction),
        l.warnings.len().to_string(),
    ]
}

/// `points.csv`: one row per point (`error` in the converged column and empty cells for a failed
/// point), with the trend force element's largest relative reaction error at that point in the
/// last column of [`POINTS_CSV_HEADER`] (`trend_errors[i]`, empty where None), followed by the
/// columns of [`POINTS_CSV_LUBRICATION_HEADER`] when the study's case describes its oil or gives
/// roughness (without them the file is as before).
pub fn points_csv(records: &[PointRecord], trend_errors: &[Option<f64>]) -> String {
    let lubricated = records.iter().any(|r| r.spec.has_lubrication());
    let supplied = records.iter().any(|r| r.spec.has_oil_supply());
    let mut out = String::from(POINTS_CSV_HEADER);
    if lubricated {
        out.push(',');
        out.push_str(POINTS_CSV_LUBRICATION_HEADER);
    }
    if supplied {
        out.push(',');
        out.push_str(POINTS_CSV_STARVATION_HEADER);
    }
    out.push('\n');
    let num = number;
    for (i, p) in records.iter().enumerate() {
        let mut cells = vec![num(p.spec.inner_speed_rpm), num(p.spec.load_scale)];
        match &p.result {
            None => {
                cells.push("error".into());
                cells.resize(24, String::new());
            }
            Some(r) => {
                let q = r.displacement.to_array();
                let dry = r.dry_displacement.to_array();
                let characterizations: usize =
                    r.history.iter().map(|h| h.record.characterized).sum();
                cells.extend([
                    r.converged.to_string(),
                    r.iterations.to_string(),
                    num(r.max_load_change),
                    num(r.max_key_distance),
                    num(r.max_load_offset),
                    num(r.max_relative_residual),
                    characterizations.to_string(),
                ]);
                cells.extend(q.iter().map(|&x| num(x)));
                cells.extend(dry[..3].iter().map(|&x| num(x)));
                cells.extend((0..3).map(|k| num(r.stiffness_ehl[k][k])));
                cells.extend((0..3).map(|k| num(r.stiffness_dry[k][k])));
                cells.push(
                    trend_errors
                        .get(i)
                        .copied()
                        .flatten()
                        .map(num)
                        .unwrap_or_default(),
                );
            }
        }
        let report = p.result.as_ref().and_then(|r| r.lubrication.as_ref());
        if lubricated {
            cells.extend(lubrication_cells(report));
        }
        if supplied {
            cells.push(
                report
                    .and_then(|l| l.max_starvation_reduction)
                    .map(number)
                    .unwrap_or_default(),
            );
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// A number as JSON writes it (shortest round-trip form; `null` if not finite).
fn number(x: f64) -> String {
    serde_json::to_string(&x).unwrap_or_default()
}
