//! Load × speed studies of a bearing's fitted contact laws, and trend curves a rotor model can
//! evaluate without any EHL run.
//!
//! - [`Study`]: a study file (TOML; see [`parse_study`]) — a case, inner-ring speeds, load scales,
//!   the characterization method and the loop settings.
//! - [`run_point`]: the characterization of one (speed, load scale) point as reproducible JSON
//!   (no timings), [`point_rows`] its rows of `results.csv`, [`results_csv`] the long-format table.
//! - [`fit_trends`]: trend curves K(Q), d(Q), ΔF(Q, n) per raceway with fit quality and validity
//!   range, as a [`TrendModel`] (JSON with [`TrendModel::to_json`] / [`TrendModel::from_json`]).
//! - [`TrendForceElement`]: the bearing as a force element with contact laws from the trend
//!   curves (displacements and speeds in, reactions and Jacobian out).
//!
//! Files are written by the command line (atomically, one per point); everything here is pure.
//! Forms, fits and measured figures: `docs/study.md`.

use crate::bearing::{
    solve_equilibrium, Bearing, BearingGeometry, ContactLaws, Control, EquilibriumSettings,
    ForceResult, OperatingPoint, Race, RaceControl,
};
use crate::characterize::{
    characterization_json, characterize_bearing_with_progress, max_relative_load_change,
    CharacterizeError, CharacterizeSettings, ContactCharacterizer, ContactRow, Progress,
};
use crate::contact_law::ContactLaw;
use crate::fit::{levenberg_marquardt, FittedLaw, LeastSquaresProblem, LmConvergence};
use crate::io::{parse_case, read_case, Case, InputError};
use crate::material::{Lubricant, Solid};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;

/// A validated study.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The base case (its speeds and loads are replaced per point).
    pub case: Case,
    /// Where the case came from (file path as given, or `inline`).
    pub case_origin: String,
    /// Characterization method: `quasi-static` (default), `harmonic`, `hertz`, `synthetic`.
    pub method: String,
    /// Method options (the `[method_options]` table as JSON; the method validates its keys).
    pub method_options: Value,
    /// Inner-ring speeds, rpm (the outer ring speed is the case's).
    pub inner_speeds_rpm: Vec<f64>,
    /// Factors applied to the case's load-controlled DOFs (forces and moments); imposed
    /// displacements and tilts are kept.
    pub load_scales: Vec<f64>,
    /// Loop settings.
    pub settings: CharacterizeSettings,
}

/// One point of a study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudyPoint {
    /// Index in the study (speeds outer, load scales inner).
    pub index: usize,
    /// Inner-ring speed, rpm.
    pub inner_speed_rpm: f64,
    /// Load scale (dimensionless).
    pub load_scale: f64,
}

impl StudyPoint {
    /// File stem of the point, e.g. `n3000rpm_s1.5`: Rust's shortest round-trip formatting, so
    /// a value always maps to the same name.
    pub fn file_stem(&self) -> String {
        format!("n{}rpm_s{}", self.inner_speed_rpm, self.load_scale)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    case: Option<toml::Value>,
    method: Option<String>,
    method_options: Option<toml::Table>,
    inner_speeds_rpm: Option<Vec<f64>>,
    load_scales: Option<Vec<f64>>,
    characterize: Option<RawCharacterize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCharacterize {
    tolerance: Option<f64>,
    max_iterations: Option<i64>,
    cache_tolerance: Option<f64>,
    min_load_fraction: Option<f64>,
    load_reuse_tolerance: Option<f64>,
    predict_loads: Option<bool>,
}

/// Methods a study file may name.
pub const METHODS: [&str; 4] = ["quasi-static", "harmonic", "hertz", "synthetic"];

/// Read a study file; a relative `case` path is resolved against the study file's folder.
pub fn read_study(path: &Path) -> Result<Study, InputError> {
    let text = std::fs::read_to_string(path).map_err(|e| InputError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse_study(&text, &path.display().to_string(), base)
}

/// Parse and validate study-file text (`origin` names it in messages, `base_dir` resolves a
/// relative case path).
///
/// ```toml
/// case = "7006.toml"                    # path relative to the study file, or an inline [case]
/// method = "quasi-static"               # "harmonic", "hertz", "synthetic"; default quasi-static
/// inner_speeds_rpm = [3000, 4000, 5000] # each > 0 and ≤ 1e6, distinct, 1 to 1000 values
/// load_scales = [0.5, 1.0, 1.5, 2.0]    # each > 0 and ≤ 100, distinct, 1 to 1000 values
///
/// [characterize]                        # optional, defaults of CharacterizeSettings
/// tolerance = 1e-3                      # 0 < tol < 1
/// max_iterations = 20                   # 1 to 1000
/// cache_tolerance = 1e-3                # 0 to 0.1
/// min_load_fraction = 0.01              # 0 < f < 1
/// load_reuse_tolerance = 0.01           # 0 to 0.5; reuse a law while the load moved less than this
/// predict_loads = true                  # start from predicted lubricated loads (quasi-static)
///
/// [method_options]                      # optional, passed to the method (e.g. hertz: samples, amplitude)
/// ```
pub fn parse_study(text: &str, origin: &str, base_dir: &Path) -> Result<Study, InputError> {
    let raw: RawStudy = toml::from_str(text).map_err(|e| InputError::Syntax {
        path: origin.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    let (case, case_origin) = match raw.case {
        None => {
            return Err(InputError::Missing {
                field: "case".into(),
                hint: "a case file path relative to the study file, or an inline [case] table"
                    .into(),
            })
        }
        Some(toml::Value::String(p)) => {
            let path = base_dir.join(&p);
            (read_case(&path)?, p)
        }
        Some(toml::Value::Table(t)) => {
            let text = toml::to_string(&t).map_err(|e| InputError::Syntax {
                path: format!("{origin} [case]"),
                message: e.to_string(),
            })?;
            (
                parse_case(&text, &format!("{origin} [case]"))?,
                "inline".into(),
            )
        }
        Some(other) => {
            return Err(InputError::field(
                "case",
                other.to_string(),
                "a file path (string) or an inline [case] table",
            ))
        }
    };
    let method = raw.method.unwrap_or_else(|| "quasi-static".into());
    if !METHODS.contains(&method.as_str()) {
        return Err(InputError::field(
            "method",
            &method,
            format!("one of {}", METHODS.join(", ")),
        ));
    }
    let method_options = serde_json::to_value(raw.method_options.unwrap_or_default())
        .map_err(|e| InputError::field("method_options", "", e.to_string()))?;
    let list = |v: Option<Vec<f64>>,
                key: &str,
                default: Vec<f64>,
                max: f64,
                what: &str|
     -> Result<Vec<f64>, InputError> {
        let v = v.unwrap_or(default);
        if v.is_empty() || v.len() > 1000 {
            return Err(InputError::field(
                key,
                format!("{} values", v.len()),
                "a list of 1 to 1000 values",
            ));
        }
        for (i, &x) in v.iter().enumerate() {
            if !(x.is_finite() && x > 0.0 && x <= max) {
                return Err(InputError::field(
                    &format!("{key}[{i}]"),
                    x,
                    format!("{what} greater than 0 and at most {max}"),
                ));
            }
            if v[..i].contains(&x) {
                return Err(InputError::field(
                    &format!("{key}[{i}]"),
                    x,
                    "distinct values (this one is repeated)",
                ));
            }
        }
        Ok(v)
    };
    let inner_speeds_rpm = list(
        raw.inner_speeds_rpm,
        "inner_speeds_rpm",
        vec![case.operating.inner_speed * 30.0 / PI],
        1e6,
        "a speed in rpm",
    )?;
    let load_scales = list(
        raw.load_scales,
        "load_scales",
        vec![1.0],
        100.0,
        "a load factor",
    )?;
    let mut settings = CharacterizeSettings::default();
    if let Some(c) = raw.characterize {
        if let Some(v) = c.tolerance {
            settings.tolerance = v;
        }
        if let Some(v) = c.max_iterations {
            if !(1..=1000).contains(&v) {
                return Err(InputError::field(
                    "characterize.max_iterations",
                    v,
                    "an integer from 1 to 1000",
                ));
            }
            settings.max_iterations = v as usize;
        }
        if let Some(v) = c.cache_tolerance {
            settings.cache_tolerance = v;
        }
        if let Some(v) = c.min_load_fraction {
            settings.min_load_fraction = v;
        }
        if let Some(v) = c.load_reuse_tolerance {
            settings.load_reuse_tolerance = v;
        }
        if let Some(v) = c.predict_loads {
            settings.predict_loads = v;
        }
    }
    if let Err(CharacterizeError::Setting {
        field,
        value,
        expected,
    }) = settings.validate()
    {
        return Err(InputError::Field {
            field: format!("characterize.{field}"),
            value,
            expected,
        });
    }
    Ok(Study {
        case,
        case_origin,
        method,
        method_options,
        inner_speeds_rpm,
        load_scales,
        settings,
    })
}

impl Study {
    /// All points, speeds outer, load scales inner.
    pub fn points(&self) -> Vec<StudyPoint> {
        let mut out = Vec::new();
        for &n in &self.inner_speeds_rpm {
            for &s in &self.load_scales {
                out.push(StudyPoint {
                    index: out.len(),
                    inner_speed_rpm: n,
                    load_scale: s,
                });
            }
        }
        out
    }

    /// The case of a point: inner speed replaced, load-controlled DOFs scaled.
    pub fn point_case(&self, p: &StudyPoint) -> Case {
        let mut c = self.case.clone();
        c.operating.inner_speed = p.inner_speed_rpm * PI / 30.0;
        for dof in c.operating.dofs.iter_mut() {
            if let Control::Load(f) = dof {
                *f *= p.load_scale;
            }
        }
        c
    }

    /// Everything a point's result depends on, as JSON: written into the point file and compared
    /// on resume (a point file with a different spec is recomputed).
    pub fn point_spec(&self, p: &StudyPoint, ch: &dyn ContactCharacterizer) -> Value {
        let c = self.point_case(p);
        json!({
            "inner_speed_rpm": p.inner_speed_rpm,
            "load_scale": p.load_scale,
            "method": ch.name(),
            "method_settings": ch.settings_json(),
            "settings": self.settings,
            "bearing": c.bearing,
            "lubricant": c.lubricant,
            "operating": c.operating,
            "equilibrium": c.settings,
        })
    }
}

/// Characterize one point: JSON `{"spec": …, ...characterization_json(…, timing = false)}`,
/// reproducible bit for bit (no timings).
pub fn run_point(
    study: &Study,
    p: &StudyPoint,
    ch: &dyn ContactCharacterizer,
) -> Result<Value, CharacterizeError> {
    run_point_with_progress(study, p, ch, &|_| {})
}

/// As [`run_point`], reporting the loop's [`Progress`].
pub fn run_point_with_progress(
    study: &Study,
    p: &StudyPoint,
    ch: &dyn ContactCharacterizer,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Value, CharacterizeError> {
    let c =
        characterize_bearing_with_progress(&study.point_case(p), ch, &study.settings, progress)?;
    let mut v = json!({"spec": study.point_spec(p, ch)});
    if let (Value::Object(dst), Value::Object(src)) = (&mut v, characterization_json(&c, false)) {
        dst.extend(src);
    }
    Ok(v)
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
}

fn bad_point(msg: impl Into<String>) -> CharacterizeError {
    CharacterizeError::Trend(format!("malformed point result: {}", msg.into()))
}

/// The rows of a point JSON (as written by [`run_point`]).
pub fn point_rows(point: &Value) -> Result<Vec<ResultRow>, CharacterizeError> {
    let rpm = point["spec"]["inner_speed_rpm"]
        .as_f64()
        .ok_or_else(|| bad_point("spec.inner_speed_rpm"))?;
    let scale = point["spec"]["load_scale"]
        .as_f64()
        .ok_or_else(|| bad_point("spec.load_scale"))?;
    let converged = point["converged"]
        .as_bool()
        .ok_or_else(|| bad_point("converged"))?;
    let contacts = point["contacts"]
        .as_array()
        .ok_or_else(|| bad_point("contacts"))?;
    contacts
        .iter()
        .map(|c| {
            let contact: ContactRow =
                serde_json::from_value(c.clone()).map_err(|e| bad_point(e.to_string()))?;
            Ok(ResultRow {
                speed_rpm: rpm,
                inner_speed_rad_s: rpm * PI / 30.0,
                load_scale: scale,
                point_converged: converged,
                contact,
            })
        })
        .collect()
}

fn csv_cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Long-format CSV of `rows` (one line per point and contact; SI units in the column names;
/// empty cell for an undefined value).
pub fn results_csv(rows: &[ResultRow]) -> String {
    let mut out = String::new();
    let mut header = false;
    for r in rows {
        let Ok(Value::Object(m)) = serde_json::to_value(r) else {
            continue;
        };
        if !header {
            out.push_str(&m.keys().cloned().collect::<Vec<_>>().join(","));
            out.push('\n');
            header = true;
        }
        out.push_str(&m.values().map(csv_cell).collect::<Vec<_>>().join(","));
        out.push('\n');
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Trend curves
// ---------------------------------------------------------------------------------------------

/// A fitted trend curve y(Q[, n]).
///
/// Forms (Q: contact load in N, n: inner-ring speed relative to the outer ring in rad/s):
/// - `power`: y = p0·Q^p1 (K(Q));
/// - `hertz_limit`: y = 1.5 − p0·Q^(−p1) (d(Q), tends to the Hertz 1.5 as the load grows);
/// - `log_linear`: y = p0 + p1·ln Q (d(Q) when some d ≥ 1.5);
/// - `power_speed`: y = p0·Q^p1·n^p2 (ΔF(Q, n));
/// - `linear_speed`: y = p0 + p1·Q + p2·n (ΔF when some ΔF ≤ 0);
/// - `hertz_minus_film`: y = p0·Q^p1 − p2·Q^p3·n^p4 (the approach δ: a Hertz-like approach minus
///   a film term, started from the Hertz exponent 2/3 and the Hamrock–Dowson central-film
///   exponents −0.067 (load) and 0.67 (speed));
/// - `power_elastic`: y = p0·(Q − ΔF(Q, n))^p1·n^p2 (the approach δ, driven by the load the
///   solids carry beyond the lift; evaluated through [`RaceTrends::approach_at`], while
///   [`TrendCurve::eval`] takes the elastic load Q − ΔF as its first argument).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrendCurve {
    /// The form (see above).
    pub form: String,
    /// The formula in words, e.g. `K = p0·Q^p1 (Q in N)`.
    pub formula: String,
    /// Parameters p0, p1[, p2] (units follow from the formula with Q in N, n in rad/s).
    pub params: Vec<f64>,
    /// Coefficient of determination of y (null when y does not vary).
    pub r_squared: Option<f64>,
    /// Root-mean-square residual of y, in y's unit.
    pub rms_residual: f64,
    /// Largest relative residual |y_fit − y|/|y| (null when some y = 0).
    pub max_relative_residual: Option<f64>,
    /// Number of contacts fitted.
    pub points: usize,
}

impl TrendCurve {
    /// Evaluate at load `q` (N) and speed `n` (rad/s).
    pub fn eval(&self, q: f64, n: f64) -> f64 {
        let p = &self.params;
        let at = |i: usize| p.get(i).copied().unwrap_or(0.0);
        match self.form.as_str() {
            "power" => at(0) * q.powf(at(1)),
            "hertz_limit" => 1.5 - at(0) * q.powf(-at(1)),
            "log_linear" => at(0) + at(1) * q.ln(),
            "power_speed" | "power_elastic" => at(0) * q.powf(at(1)) * n.powf(at(2)),
            "hertz_minus_film" => at(0) * q.powf(at(1)) - at(2) * q.powf(at(3)) * n.powf(at(4)),
            "linear_speed" => at(0) + at(1) * q + at(2) * n,
            _ => f64::NAN,
        }
    }

    fn check(&self, what: &str) -> Result<(), CharacterizeError> {
        let need = match self.form.as_str() {
            "power" | "hertz_limit" | "log_linear" => 2,
            "power_speed" | "linear_speed" | "power_elastic" => 3,
            "hertz_minus_film" => 5,
            f => {
                return Err(CharacterizeError::Trend(format!(
                    "{what}: unknown form {f:?}"
                )))
            }
        };
        if self.params.len() != need || self.params.iter().any(|v| !v.is_finite()) {
            return Err(CharacterizeError::Trend(format!(
                "{what}: form {} needs {need} finite parameters, got {:?}",
                self.form, self.params
            )));
        }
        Ok(())
    }
}

/// Trend curves and validity range of one raceway.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RaceTrends {
    /// K(Q), N/m^d.
    pub k: TrendCurve,
    /// d(Q).
    pub d: TrendCurve,
    /// ΔF(Q, n), N.
    pub delta_f: TrendCurve,
    /// Equilibrium approach δ(Q, n), m: the law at load Q is anchored at (δ(Q, n), Q), which
    /// fixes K = (Q − ΔF)/δ^d consistently with d(Q) and ΔF(Q, n) (K and d are strongly
    /// correlated, so K(Q) fitted on its own is a poor predictor; see `docs/study.md`).
    pub approach: TrendCurve,
    /// Range of contact loads fitted [Q_min, Q_max], N.
    pub load_range_n: [f64; 2],
    /// Range of speeds fitted [n_min, n_max], rad/s.
    pub speed_range_rad_s: [f64; 2],
}

impl RaceTrends {
    /// The stiffness K (N/m^d) the force element uses at load `q` (N) and speed `n` (rad/s):
    /// K = (Q − ΔF)/δ^d with d, ΔF and δ from their trends, so that the law passes through
    /// (δ(Q, n), Q); the K(Q) power fit only where that anchor is not positive.
    pub fn k_at(&self, q: f64, n: f64) -> f64 {
        let d = self.d.eval(q, n);
        let df = self.delta_f.eval(q, n);
        let anchor = self.approach_at(q, n);
        if anchor > 0.0 && q > df && d > 0.0 {
            (q - df) / anchor.powf(d)
        } else {
            self.k.eval(q, n)
        }
    }

    /// The approach trend δ(Q, n), m, at load `q` (N) and speed `n` (rad/s).
    pub fn approach_at(&self, q: f64, n: f64) -> f64 {
        if self.approach.form == "power_elastic" {
            self.approach.eval(q - self.delta_f.eval(q, n), n)
        } else {
            self.approach.eval(q, n)
        }
    }
}

/// The bearing a trend model belongs to (SI).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrendBearing {
    /// Number of balls.
    pub ball_count: usize,
    /// Ball diameter, m.
    pub ball_diameter_m: f64,
    /// Pitch diameter, m.
    pub pitch_diameter_m: f64,
    /// Inner conformity r_i/D.
    pub inner_conformity: f64,
    /// Outer conformity r_o/D.
    pub outer_conformity: f64,
    /// Free contact angle, rad.
    pub free_contact_angle_rad: f64,
    /// Ball material.
    pub ball_material: Solid,
    /// Ring material.
    pub ring_material: Solid,
}

/// Trend curves of a study: what a rotor model needs to use the bearing without an EHL run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrendModel {
    /// Format version (1).
    pub version: u32,
    /// Characterization method of the study.
    pub method: String,
    /// Its settings.
    pub method_settings: Value,
    /// The bearing.
    pub bearing: TrendBearing,
    /// The lubricant.
    pub lubricant: Lubricant,
    /// Race-control hypothesis of the study's case.
    pub race_control: RaceControl,
    /// Inner raceway.
    pub inner: RaceTrends,
    /// Outer raceway.
    pub outer: RaceTrends,
}

impl TrendModel {
    /// Pretty JSON (SI).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Parse and validate JSON written by [`TrendModel::to_json`].
    pub fn from_json(text: &str) -> Result<Self, CharacterizeError> {
        let m: TrendModel = serde_json::from_str(text)
            .map_err(|e| CharacterizeError::Trend(format!("trend JSON: {e}")))?;
        if m.version != 1 {
            return Err(CharacterizeError::Trend(format!(
                "trend JSON version {} (this library reads version 1)",
                m.version
            )));
        }
        for (name, r) in [("inner", &m.inner), ("outer", &m.outer)] {
            r.k.check(&format!("{name}.k"))?;
            r.d.check(&format!("{name}.d"))?;
            r.delta_f.check(&format!("{name}.delta_f"))?;
            r.approach.check(&format!("{name}.approach"))?;
            for (what, [lo, hi]) in [
                ("load_range_n", r.load_range_n),
                ("speed_range_rad_s", r.speed_range_rad_s),
            ] {
                if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi >= lo) {
                    return Err(CharacterizeError::Trend(format!(
                        "{name}.{what} = [{lo}, {hi}]: expected 0 < min ≤ max"
                    )));
                }
            }
        }
        m.bearing_model()?;
        Ok(m)
    }

    /// The bearing (geometry and materials).
    pub fn bearing_model(&self) -> Result<Bearing, CharacterizeError> {
        let b = &self.bearing;
        let geometry = BearingGeometry::new(
            b.ball_count,
            b.ball_diameter_m,
            b.pitch_diameter_m,
            b.inner_conformity,
            b.outer_conformity,
            b.free_contact_angle_rad,
        )
        .map_err(|e| CharacterizeError::Trend(format!("bearing: {e}")))?;
        let bearing = Bearing {
            geometry,
            ball_material: b.ball_material,
            ring_material: b.ring_material,
        };
        bearing
            .validate()
            .map_err(|e| CharacterizeError::Trend(format!("bearing: {e}")))?;
        Ok(bearing)
    }

    /// The trends of a raceway.
    pub fn race(&self, race: Race) -> &RaceTrends {
        match race {
            Race::Inner => &self.inner,
            Race::Outer => &self.outer,
        }
    }
}

/// Least squares by normal equations on (already centred) columns; tiny problems only.
fn linear_lsq(cols: &[Vec<f64>], y: &[f64]) -> Option<Vec<f64>> {
    let p = cols.len();
    let mut a = vec![vec![0.0; p + 1]; p];
    for i in 0..p {
        for j in 0..p {
            a[i][j] = cols[i].iter().zip(&cols[j]).map(|(x, z)| x * z).sum();
        }
        a[i][p] = cols[i].iter().zip(y).map(|(x, z)| x * z).sum();
    }
    // Gaussian elimination with partial pivoting.
    for c in 0..p {
        let piv = (c..p).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        a.swap(c, piv);
        let scale = a[c][c];
        let norm = (0..p).map(|j| a[j][j].abs()).fold(0.0_f64, f64::max);
        if scale.abs() <= 1e-13 * norm.max(1e-300) {
            return None;
        }
        for r in 0..p {
            if r != c {
                let f = a[r][c] / scale;
                let pivot_row = a[c].clone();
                for (x, pv) in a[r].iter_mut().zip(&pivot_row).skip(c) {
                    *x -= f * pv;
                }
            }
        }
    }
    Some((0..p).map(|i| a[i][p] / a[i][i]).collect())
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

fn distinct(v: &[f64]) -> usize {
    let mut s: Vec<f64> = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs().max(1e-300));
    s.len()
}

/// Fit y = Σ c_k·x_k with an intercept column, the x_k centred; returns (intercept, slopes) for
/// the uncentred variables. Columns with fewer than 2 distinct values get slope 0.
fn fit_affine(xs: &[&[f64]], y: &[f64]) -> Option<(f64, Vec<f64>)> {
    let n = y.len();
    let active: Vec<usize> = (0..xs.len()).filter(|&k| distinct(xs[k]) >= 2).collect();
    let means: Vec<f64> = xs.iter().map(|x| mean(x)).collect();
    let mut cols = vec![vec![1.0; n]];
    for &k in &active {
        cols.push(xs[k].iter().map(|v| v - means[k]).collect());
    }
    let c = linear_lsq(&cols, y)?;
    let mut slopes = vec![0.0; xs.len()];
    let mut intercept = c[0];
    for (j, &k) in active.iter().enumerate() {
        slopes[k] = c[j + 1];
        intercept -= c[j + 1] * means[k];
    }
    Some((intercept, slopes))
}

fn quality(
    form: &str,
    formula: &str,
    params: Vec<f64>,
    q: &[f64],
    n: &[f64],
    y: &[f64],
) -> TrendCurve {
    let mut c = TrendCurve {
        form: form.into(),
        formula: formula.into(),
        params,
        r_squared: None,
        rms_residual: 0.0,
        max_relative_residual: None,
        points: y.len(),
    };
    let ym = mean(y);
    let mut ssr = 0.0;
    let mut sst = 0.0;
    let mut rel = 0.0_f64;
    let mut rel_ok = true;
    for i in 0..y.len() {
        let r = c.eval(q[i], n[i]) - y[i];
        ssr += r * r;
        sst += (y[i] - ym).powi(2);
        if y[i] != 0.0 {
            rel = rel.max((r / y[i]).abs());
        } else {
            rel_ok = false;
        }
    }
    c.rms_residual = (ssr / y.len() as f64).sqrt();
    // R² is meaningless when y varies only at rounding level.
    if sst > 1e-24 * (ym * ym * y.len() as f64).max(1e-300) {
        c.r_squared = Some(1.0 - ssr / sst);
    }
    if rel_ok {
        c.max_relative_residual = Some(rel);
    }
    c
}

/// d = 1.5 − a·Q^(−b) by Levenberg–Marquardt on the residuals of d, in (ln a, b) around a
/// reference load.
struct HertzLimit<'a> {
    lnq: &'a [f64],
    y: &'a [f64],
}

impl LeastSquaresProblem for HertzLimit<'_> {
    fn n_params(&self) -> usize {
        2
    }
    fn n_residuals(&self) -> usize {
        self.y.len()
    }
    fn residuals(&self, x: &[f64], r: &mut [f64]) {
        for ((ri, lq), y) in r.iter_mut().zip(self.lnq).zip(self.y) {
            *ri = 1.5 - (x[0] - x[1] * lq).exp() - y;
        }
    }
    fn jacobian(&self, x: &[f64], jac: &mut [f64]) {
        for i in 0..self.y.len() {
            let e = (x[0] - x[1] * self.lnq[i]).exp();
            jac[2 * i] = -e;
            jac[2 * i + 1] = e * self.lnq[i];
        }
    }
}

fn trend_err(race: &str, what: &str) -> CharacterizeError {
    CharacterizeError::Trend(format!(
        "{race} {what}: the data cannot determine the trend (too few distinct loads?)"
    ))
}

/// y(Q, n) = p0·Q^p1·n^p2 (log-space least squares) when all y > 0, else p0 + p1·Q + p2·n.
fn power_or_linear(
    race: &str,
    what: &str,
    unit: &str,
    q: &[f64],
    n: &[f64],
    y: &[f64],
) -> Result<TrendCurve, CharacterizeError> {
    let lnq: Vec<f64> = q.iter().map(|v| v.ln()).collect();
    let lnn: Vec<f64> = n.iter().map(|v| v.ln()).collect();
    Ok(if y.iter().all(|v| *v > 0.0) {
        let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
        let (c0, s) = fit_affine(&[&lnq, &lnn], &ly).ok_or_else(|| trend_err(race, what))?;
        quality(
            "power_speed",
            &format!("{what} = p0·Q^p1·n^p2 ({what} in {unit}, Q in N, n in rad/s)"),
            vec![c0.exp(), s[0], s[1]],
            q,
            n,
            y,
        )
    } else {
        let (c0, s) = fit_affine(&[q, n], y).ok_or_else(|| trend_err(race, what))?;
        quality(
            "linear_speed",
            &format!("{what} = p0 + p1·Q + p2·n ({what} in {unit}, Q in N, n in rad/s)"),
            vec![c0, s[0], s[1]],
            q,
            n,
            y,
        )
    })
}

/// δ = p0·Q^p1 − p2·Q^p3·n^p4: linear least squares for (p0, p2) at the exponents (2/3, −0.067,
/// 0.67), then Levenberg–Marquardt on all five (in ln p0, ln p2) when p0, p2 > 0 and the speeds
/// vary. None when the linear problem is singular.
fn hertz_minus_film(q: &[f64], n: &[f64], delta: &[f64]) -> Option<TrendCurve> {
    let a: Vec<f64> = q.iter().map(|v| v.powf(2.0 / 3.0)).collect();
    let b: Vec<f64> = q
        .iter()
        .zip(n)
        .map(|(qi, ni)| -qi.powf(-0.067) * ni.powf(0.67))
        .collect();
    // Scale the columns to O(1) for the normal equations.
    let sa = a.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(1e-300);
    let sb = b.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(1e-300);
    let sy = delta
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(1e-300);
    let cols = vec![
        a.iter().map(|v| v / sa).collect::<Vec<_>>(),
        b.iter().map(|v| v / sb).collect::<Vec<_>>(),
    ];
    let y: Vec<f64> = delta.iter().map(|v| v / sy).collect();
    let c = linear_lsq(&cols, &y)?;
    let mut params = vec![c[0] * sy / sa, 2.0 / 3.0, c[1] * sy / sb, -0.067, 0.67];
    let formula = "δ = p0·Q^p1 − p2·Q^p3·n^p4 (δ in m, Q in N, n in rad/s)";
    if params[0] > 0.0 && params[2] > 0.0 && distinct(n) >= 2 {
        let problem = HertzFilm {
            q,
            n,
            y: delta,
            scale: sy,
        };
        let x0 = [
            params[0].ln(),
            params[1],
            params[2].ln(),
            params[3],
            params[4],
        ];
        if let Ok(rep) = levenberg_marquardt(&problem, &x0, &LmConvergence::default()) {
            if rep.cost < rep.initial_cost && rep.params.iter().all(|v| v.is_finite()) {
                let x = &rep.params;
                params = vec![x[0].exp(), x[1], x[2].exp(), x[3], x[4]];
            }
        }
    }
    Some(quality("hertz_minus_film", formula, params, q, n, delta))
}

/// Residuals (δ_fit − δ)/scale of δ = e^x0·Q^x1 − e^x2·Q^x3·n^x4.
struct HertzFilm<'a> {
    q: &'a [f64],
    n: &'a [f64],
    y: &'a [f64],
    scale: f64,
}

impl LeastSquaresProblem for HertzFilm<'_> {
    fn n_params(&self) -> usize {
        5
    }
    fn n_residuals(&self) -> usize {
        self.y.len()
    }
    fn residuals(&self, x: &[f64], r: &mut [f64]) {
        for (i, ri) in r.iter_mut().enumerate() {
            let (lq, ln) = (self.q[i].ln(), self.n[i].ln());
            let h = (x[0] + x[1] * lq).exp();
            let f = (x[2] + x[3] * lq + x[4] * ln).exp();
            *ri = (h - f - self.y[i]) / self.scale;
        }
    }
    fn jacobian(&self, x: &[f64], jac: &mut [f64]) {
        for i in 0..self.y.len() {
            let (lq, ln) = (self.q[i].ln(), self.n[i].ln());
            let h = (x[0] + x[1] * lq).exp() / self.scale;
            let f = (x[2] + x[3] * lq + x[4] * ln).exp() / self.scale;
            let row = &mut jac[5 * i..5 * i + 5];
            row.copy_from_slice(&[h, h * lq, -f, -f * lq, -f * ln]);
        }
    }
}

/// The trends of one raceway. `qc`: the loads the laws were characterized at (abscissa of K, d,
/// ΔF); `q`: the equilibrium loads (abscissa of δ and of the validity range); they differ by at
/// most the loop's load reuse tolerance.
#[allow(clippy::too_many_arguments)]
fn fit_race(
    race: &str,
    qc: &[f64],
    q: &[f64],
    n: &[f64],
    k: &[f64],
    d: &[f64],
    df: &[f64],
    delta: &[f64],
) -> Result<RaceTrends, CharacterizeError> {
    if q.len() < 3 || distinct(q) < 3 || distinct(qc) < 3 {
        return Err(CharacterizeError::Trend(format!(
            "{race}: {} usable contacts with {} distinct loads; at least 3 are needed",
            q.len(),
            distinct(q)
        )));
    }
    // K, d and ΔF are functions of the load the law was characterized at.
    let lnq: Vec<f64> = qc.iter().map(|v| v.ln()).collect();
    // K(Q) = a·Q^b by least squares on ln K (relative errors).
    if k.iter().any(|v| v.is_nan() || *v <= 0.0) {
        return Err(trend_err(race, "K (non-positive stiffness)"));
    }
    let lnk: Vec<f64> = k.iter().map(|v| v.ln()).collect();
    let (c0, s) = fit_affine(&[&lnq], &lnk).ok_or_else(|| trend_err(race, "K"))?;
    let k_curve = quality(
        "power",
        "K = p0·Q^p1 (K in N/m^d, Q in N)",
        vec![c0.exp(), s[0]],
        qc,
        n,
        k,
    );
    // d(Q).
    let d_curve = if d.iter().all(|v| *v < 1.5 - 1e-9) {
        let y: Vec<f64> = d.iter().map(|v| (1.5 - v).ln()).collect();
        let (c0, s) = fit_affine(&[&lnq], &y).ok_or_else(|| trend_err(race, "d"))?;
        let problem = HertzLimit { lnq: &lnq, y: d };
        let x0 = [c0, -s[0]];
        let rep = levenberg_marquardt(&problem, &x0, &LmConvergence::default())
            .map_err(|e| CharacterizeError::Trend(format!("{race} d: {e}")))?;
        let (la, b) = if rep.converged || rep.cost < 0.5 * rep.initial_cost {
            (rep.params[0], rep.params[1])
        } else {
            (x0[0], x0[1])
        };
        quality(
            "hertz_limit",
            "d = 1.5 − p0·Q^(−p1) (Q in N)",
            vec![la.exp(), b],
            qc,
            n,
            d,
        )
    } else {
        let (c0, s) = fit_affine(&[&lnq], d).ok_or_else(|| trend_err(race, "d"))?;
        quality(
            "log_linear",
            "d = p0 + p1·ln Q (Q in N)",
            vec![c0, s[0]],
            qc,
            n,
            d,
        )
    };
    // ΔF(Q, n) and δ(Q, n): δ as a power law of the elastic load Q − ΔF when that is positive
    // everywhere and fits better than a power law of Q. δ is the equilibrium approach at the
    // equilibrium load.
    let df_curve = power_or_linear(race, "ΔF", "N", qc, n, df)?;
    let mut approach = power_or_linear(race, "δ", "m", q, n, delta)?;
    let qe: Vec<f64> = q
        .iter()
        .zip(n)
        .map(|(&qi, &ni)| qi - df_curve.eval(qi, ni))
        .collect();
    if approach.form == "power_speed" && qe.iter().all(|v| *v > 0.0) {
        let alt = power_or_linear(race, "δ", "m", &qe, n, delta)?;
        if alt.rms_residual < approach.rms_residual {
            approach = TrendCurve {
                form: "power_elastic".into(),
                formula: "δ = p0·(Q − ΔF(Q, n))^p1·n^p2 (δ in m, Q and ΔF in N, n in rad/s)".into(),
                ..alt
            };
        }
    }
    if let Some(alt) = hertz_minus_film(q, n, delta) {
        if alt.rms_residual < approach.rms_residual {
            approach = alt;
        }
    }
    let range = |v: &[f64]| {
        [
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ]
    };
    Ok(RaceTrends {
        k: k_curve,
        d: d_curve,
        delta_f: df_curve,
        approach,
        load_range_n: range(q),
        speed_range_rad_s: range(n),
    })
}

/// Fit the trend curves of a study to its rows. Contacts whose load was floored (lightly loaded)
/// or whose fit did not converge are left out. K, d and ΔF are fitted against the load each law
/// was characterized at (`characterized_load_n`), the approach δ against the equilibrium load
/// (`load_n`); the two differ by at most the loop's load reuse tolerance. The speed n is the inner-ring speed relative to
/// the outer ring, rad/s.
pub fn fit_trends(study: &Study, rows: &[ResultRow]) -> Result<TrendModel, CharacterizeError> {
    let outer_speed = study.case.operating.outer_speed;
    let pick = |race: &str| {
        let mut qc = Vec::new();
        let mut q = Vec::new();
        let mut n = Vec::new();
        let mut k = Vec::new();
        let mut d = Vec::new();
        let mut df = Vec::new();
        let mut delta = Vec::new();
        for r in rows {
            let c = &r.contact;
            if c.race == race && !c.load_floored && c.fit_converged && c.load_n > 0.0 {
                qc.push(c.characterized_load_n);
                q.push(c.load_n);
                n.push((r.inner_speed_rad_s - outer_speed).abs());
                k.push(c.k);
                d.push(c.d);
                df.push(c.delta_f_n);
                delta.push(c.approach_m);
            }
        }
        (qc, q, n, k, d, df, delta)
    };
    let (qci, qi, ni, ki, di, dfi, ai) = pick("inner");
    let (qco, qo, no, ko, d_o, dfo, ao) = pick("outer");
    let g = &study.case.bearing.geometry;
    Ok(TrendModel {
        version: 1,
        method: study.method.clone(),
        method_settings: study.method_options.clone(),
        bearing: TrendBearing {
            ball_count: g.ball_count,
            ball_diameter_m: g.ball_diameter,
            pitch_diameter_m: g.pitch_diameter,
            inner_conformity: g.inner_conformity,
            outer_conformity: g.outer_conformity,
            free_contact_angle_rad: g.free_contact_angle,
            ball_material: study.case.bearing.ball_material,
            ring_material: study.case.bearing.ring_material,
        },
        lubricant: study.case.lubricant,
        race_control: study.case.operating.race_control,
        inner: fit_race("inner", &qci, &qi, &ni, &ki, &di, &dfi, &ai)?,
        outer: fit_race("outer", &qco, &qo, &no, &ko, &d_o, &dfo, &ao)?,
    })
}

// ---------------------------------------------------------------------------------------------
// Force element
// ---------------------------------------------------------------------------------------------

/// Settings of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrendEvalOptions {
    /// Fixed point on the contact loads converged when their largest relative change is below
    /// this (dimensionless).
    pub tolerance: f64,
    /// Iteration limit of the fixed point.
    pub max_iterations: usize,
    /// How the Jacobian is computed.
    pub jacobian: JacobianMode,
}

/// Jacobian of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum JacobianMode {
    /// Exact derivative of the final laws with their parameters frozen (free; omits
    /// ∂(K, d, ΔF)/∂Q: measured 5 % off the total derivative on a strongly load-dependent
    /// synthetic d(Q), see `docs/study.md`). Enough for the Newton iterations of an implicit
    /// integrator.
    Frozen,
    /// Central differences of the full evaluation (10 more evaluations) with steps `step_m` (m)
    /// for x, y, z and `step_rad` (rad) for θy, θz: the total derivative.
    CentralDifference {
        /// Step of the translations, m.
        step_m: f64,
        /// Step of the tilts, rad.
        step_rad: f64,
    },
}

impl Default for TrendEvalOptions {
    fn default() -> Self {
        TrendEvalOptions {
            tolerance: 1e-8,
            max_iterations: 50,
            jacobian: JacobianMode::Frozen,
        }
    }
}

/// Result of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrendForce {
    /// Reactions on the inner ring (N, N·m) and their Jacobian with respect to the displacements,
    /// at frozen law parameters (N/m, N, N·m/rad).
    pub force: ForceResult,
    /// Contact loads [inner, outer] per ball, N.
    pub contact_loads: Vec<[f64; 2]>,
    /// Fixed-point iterations used.
    pub iterations: usize,
    /// Whether the fixed point on the contact loads converged.
    pub converged: bool,
    /// Last largest relative load change of the fixed point.
    pub load_change: f64,
    /// Whether any contact load or the speed lies outside the trend curves' validity range
    /// (parameters are then evaluated at the nearest end of the range).
    pub outside_validity: bool,
    /// The contacts outside the load range: (ball, race).
    pub contacts_outside: Vec<(usize, Race)>,
    /// Whether the speed lies outside the speed range of either raceway.
    pub speed_outside: bool,
}

/// The bearing as a force element with contact laws from trend curves: no EHL run.
///
/// The law of each contact depends on the contact's own load (K(Q), d(Q), ΔF(Q, n)), which
/// depends on the laws. [`TrendForceElement::evaluate`] resolves this implicit dependence by a
/// fixed point on the contact loads: start from the dry Hertz loads at the given displacement,
/// build each contact's law from the trends at its current load (clamped into the validity
/// range), solve every ball's equilibrium at the imposed ring displacement, and repeat until the
/// loads change by less than `options.tolerance`. The Jacobian is that of the final laws with
/// their parameters frozen by default, or the total derivative by central differences
/// ([`JacobianMode`]).
#[derive(Debug, Clone)]
pub struct TrendForceElement {
    model: TrendModel,
    bearing: Bearing,
    /// Fixed-point settings.
    pub options: TrendEvalOptions,
}

impl TrendForceElement {
    /// A force element from a trend model.
    pub fn new(model: TrendModel) -> Result<Self, CharacterizeError> {
        let bearing = model.bearing_model()?;
        Ok(TrendForceElement {
            model,
            bearing,
            options: TrendEvalOptions::default(),
        })
    }

    /// A force element from trend JSON ([`TrendModel::to_json`]).
    pub fn from_json(text: &str) -> Result<Self, CharacterizeError> {
        Self::new(TrendModel::from_json(text)?)
    }

    /// Largest relative difference between the reactions F_x, F_y, F_z this element gives at a
    /// characterized point's displacement and speed and the point's own equilibrium reactions
    /// (each relative to max(|F|, 1 N)): how well the trends reproduce the characterization.
    /// `point` is a point JSON as written by [`run_point`].
    pub fn reaction_error(&self, point: &Value) -> Result<f64, crate::Error> {
        let num = |v: &Value, what: &str| {
            v.as_f64()
                .ok_or_else(|| CharacterizeError::Trend(format!("point JSON: {what} missing")))
        };
        let mut q = [0.0; 5];
        for (k, key) in ["x", "y", "z", "theta_y", "theta_z"].iter().enumerate() {
            q[k] = num(&point["displacement"][key], key)?;
        }
        let rpm = num(&point["spec"]["inner_speed_rpm"], "spec.inner_speed_rpm")?;
        let outer = num(
            &point["spec"]["operating"]["outer_speed"],
            "spec.operating.outer_speed",
        )?;
        let r = self.evaluate(&q, rpm * PI / 30.0, outer)?;
        let mut worst = 0.0_f64;
        for (k, key) in ["force_x", "force_y", "force_z"].iter().enumerate() {
            let want = num(&point["reaction"][key], key)?;
            worst = worst.max((r.force.reaction[k] - want).abs() / want.abs().max(1.0));
        }
        Ok(worst)
    }

    /// The trend model.
    pub fn model(&self) -> &TrendModel {
        &self.model
    }

    /// The law of a contact on `race` at load `load` (N) and speed `n` (rad/s): d and ΔF from
    /// their trends at the load and speed clamped into the validity range, K = (Q − ΔF)/δ(Q, n)^d
    /// so that the law passes through the approach trend (K(Q) from its own trend only if that
    /// anchor is not positive), fitted range δ at 0.8·Q and 1.2·Q (or just above ΔF). Returns the
    /// law and whether the load was clamped.
    pub fn law_at(
        &self,
        race: Race,
        load: f64,
        n: f64,
    ) -> Result<(FittedLaw, bool), CharacterizeError> {
        let t = self.model.race(race);
        let [lo, hi] = t.load_range_n;
        let qc = if load.is_nan() {
            lo
        } else {
            load.clamp(lo, hi)
        };
        let clamped = !(load >= lo && load <= hi);
        let [nlo, nhi] = t.speed_range_rad_s;
        let nc = n.clamp(nlo, nhi);
        let d = t.d.eval(qc, nc);
        let df = t.delta_f.eval(qc, nc);
        let k = t.k_at(qc, nc);
        let q_lo = (0.8 * qc).max(df + 0.05 * qc);
        let q_hi = (1.2 * qc).max(1.5 * q_lo);
        let delta = |q: f64| ((q - df) / k).powf(1.0 / d);
        let law = FittedLaw::new(k, d, df, delta(q_lo), delta(q_hi)).map_err(|e| {
            CharacterizeError::Trend(format!(
                "law from the trends at Q = {qc} N, n = {nc} rad/s ({race:?}): {e}"
            ))
        })?;
        Ok((law, clamped))
    }

    /// Reactions and Jacobian at ring displacement `displacement` (x, y, z in m; θy, θz in rad)
    /// and ring speeds (rad/s), with the flags of the validity range. See the type's
    /// documentation for how the load dependence of the laws is resolved.
    pub fn evaluate(
        &self,
        displacement: &[f64; 5],
        inner_speed: f64,
        outer_speed: f64,
    ) -> Result<TrendForce, crate::Error> {
        self.evaluate_from(displacement, inner_speed, outer_speed, None)
    }

    /// As [`TrendForceElement::evaluate`], starting the fixed point from `start_loads` (N,
    /// [inner, outer] per ball, e.g. the `contact_loads` of the previous time step) instead of the
    /// dry Hertz loads: the result is the same to the fixed-point tolerance, in fewer iterations.
    pub fn evaluate_from(
        &self,
        displacement: &[f64; 5],
        inner_speed: f64,
        outer_speed: f64,
        start_loads: Option<&[[f64; 2]]>,
    ) -> Result<TrendForce, crate::Error> {
        let op = OperatingPoint {
            inner_speed,
            outer_speed,
            dofs: displacement.map(Control::Displacement),
            race_control: self.model.race_control,
        };
        let settings = EquilibriumSettings::default();
        let n = (inner_speed - outer_speed).abs();
        let loads_of = |e: &crate::bearing::Equilibrium| -> Vec<f64> {
            e.balls
                .iter()
                .flat_map(|b| [b.inner.load, b.outer.load])
                .collect()
        };
        let z = self.bearing.geometry.ball_count;
        let mut loads = match start_loads {
            Some(l) if l.len() == z => l.iter().flatten().copied().collect(),
            Some(l) => {
                return Err(CharacterizeError::Trend(format!(
                    "start loads given for {} balls, the bearing has {z}",
                    l.len()
                ))
                .into())
            }
            None => {
                let hertz = ContactLaws::hertz(&self.bearing)?;
                loads_of(&solve_equilibrium(&self.bearing, &hertz, &op, &settings)?)
            }
        };
        let mut iterations = 0;
        let (eq, change) = loop {
            iterations += 1;
            let mut inner: Vec<Arc<dyn ContactLaw>> = Vec::new();
            let mut outer: Vec<Arc<dyn ContactLaw>> = Vec::new();
            for (i, &q) in loads.iter().enumerate() {
                let race = if i % 2 == 0 { Race::Inner } else { Race::Outer };
                let (law, _) = self.law_at(race, q, n)?;
                if i % 2 == 0 {
                    inner.push(Arc::new(law));
                } else {
                    outer.push(Arc::new(law));
                }
            }
            let laws = ContactLaws { inner, outer };
            let eq = solve_equilibrium(&self.bearing, &laws, &op, &settings)?;
            let next = loads_of(&eq);
            let change = max_relative_load_change(&loads, &next, 0.01);
            loads = next;
            if change < self.options.tolerance || iterations >= self.options.max_iterations {
                break (eq, change);
            }
        };
        // Flags at the final loads.
        let mut contacts_outside = Vec::new();
        for (i, &q) in loads.iter().enumerate() {
            let race = if i % 2 == 0 { Race::Inner } else { Race::Outer };
            let [lo, hi] = self.model.race(race).load_range_n;
            if !(q >= lo && q <= hi) {
                contacts_outside.push((i / 2, race));
            }
        }
        let speed_outside = [&self.model.inner, &self.model.outer].iter().any(|t| {
            let [lo, hi] = t.speed_range_rad_s;
            !(n >= lo * (1.0 - 1e-12) && n <= hi * (1.0 + 1e-12))
        });
        let mut jacobian = eq.stiffness;
        if let JacobianMode::CentralDifference { step_m, step_rad } = self.options.jacobian {
            let frozen = TrendForceElement {
                options: TrendEvalOptions {
                    jacobian: JacobianMode::Frozen,
                    ..self.options
                },
                ..self.clone()
            };
            for k in 0..5 {
                let h = if k < 3 { step_m } else { step_rad };
                let mut qp = *displacement;
                let mut qm = *displacement;
                qp[k] += h;
                qm[k] -= h;
                let fp = frozen
                    .evaluate(&qp, inner_speed, outer_speed)?
                    .force
                    .reaction;
                let fm = frozen
                    .evaluate(&qm, inner_speed, outer_speed)?
                    .force
                    .reaction;
                for r in 0..5 {
                    jacobian[r][k] = (fp[r] - fm[r]) / (2.0 * h);
                }
            }
        }
        Ok(TrendForce {
            force: ForceResult {
                reaction: eq.reaction,
                jacobian,
            },
            contact_loads: loads.chunks(2).map(|c| [c[0], c[1]]).collect(),
            iterations,
            converged: change < self.options.tolerance,
            load_change: change,
            outside_validity: !contacts_outside.is_empty() || speed_outside,
            contacts_outside,
            speed_outside,
        })
    }
}
