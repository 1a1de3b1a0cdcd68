//! The trend model: curves, the raceways' trends with their validity range, the bearing, and
//! their JSON.

use super::{race_name, TrendError};
use crate::bearing::{Bearing, BearingGeometry, Race, RaceControl};
use crate::material::{Lubricant, Solid};
use crate::method::Method;
use serde::{Deserialize, Serialize};

/// A fitted trend curve y(Q[, n]).
///
/// Forms (Q: contact load in N, n: inner-ring speed relative to the outer ring in rad/s):
/// - `power`: y = p0·Q^p1 (K(Q));
/// - `hertz_limit`: y = 1.5 − p0·Q^(−p1) (d(Q), tends to the Hertz 1.5 as the load grows);
/// - `hertz_limit_speed`: y = 1.5 − p0·Q^(−p1)·n^p2 (d(Q, n), where the data separate by speed:
///   at light load the film's share of the approach, and with it 1.5 − d, grows with speed);
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
            "hertz_limit_speed" => 1.5 - at(0) * q.powf(-at(1)) * n.powf(at(2)),
            "log_linear" => at(0) + at(1) * q.ln(),
            "power_speed" | "power_elastic" => at(0) * q.powf(at(1)) * n.powf(at(2)),
            "hertz_minus_film" => at(0) * q.powf(at(1)) - at(2) * q.powf(at(3)) * n.powf(at(4)),
            "linear_speed" => at(0) + at(1) * q + at(2) * n,
            _ => f64::NAN,
        }
    }

    /// Value and derivative ∂y/∂Q at load `q` (N) and speed `n` (rad/s).
    pub fn eval_dq(&self, q: f64, n: f64) -> (f64, f64) {
        let p = &self.params;
        let at = |i: usize| p.get(i).copied().unwrap_or(0.0);
        let y = self.eval(q, n);
        let dy = match self.form.as_str() {
            "power" => at(0) * at(1) * q.powf(at(1) - 1.0),
            "hertz_limit" => at(0) * at(1) * q.powf(-at(1) - 1.0),
            "hertz_limit_speed" => at(0) * at(1) * q.powf(-at(1) - 1.0) * n.powf(at(2)),
            "log_linear" => at(1) / q,
            "power_speed" | "power_elastic" => at(0) * at(1) * q.powf(at(1) - 1.0) * n.powf(at(2)),
            "hertz_minus_film" => {
                at(0) * at(1) * q.powf(at(1) - 1.0)
                    - at(2) * at(3) * q.powf(at(3) - 1.0) * n.powf(at(4))
            }
            "linear_speed" => at(1),
            _ => f64::NAN,
        };
        (y, dy)
    }

    fn check(&self, curve: String) -> Result<(), TrendError> {
        let needed = match self.form.as_str() {
            "power" | "hertz_limit" | "log_linear" => 2,
            "power_speed" | "linear_speed" | "power_elastic" | "hertz_limit_speed" => 3,
            "hertz_minus_film" => 5,
            f => {
                return Err(TrendError::UnknownForm {
                    curve,
                    form: f.to_string(),
                })
            }
        };
        if self.params.len() != needed || self.params.iter().any(|v| !v.is_finite()) {
            return Err(TrendError::Parameters {
                curve,
                form: self.form.clone(),
                needed,
                params: self.params.clone(),
            });
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

    /// The approach trend δ(Q, n) (m) and its derivative ∂δ/∂Q (m/N) at load `q` (N) and speed
    /// `n` (rad/s).
    pub fn approach_dq(&self, q: f64, n: f64) -> (f64, f64) {
        if self.approach.form == "power_elastic" {
            let (df, ddf) = self.delta_f.eval_dq(q, n);
            let (a, da) = self.approach.eval_dq(q - df, n);
            (a, da * (1.0 - ddf))
        } else {
            self.approach.eval_dq(q, n)
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

/// Format version of trend JSON written by this library.
pub const TREND_VERSION: u32 = 2;

/// Trend curves of a study: what a rotor model needs to use the bearing without an EHL run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrendModel {
    /// Format version (2: the method as a typed [`Method`]; version 1 had a name and a JSON
    /// options table).
    pub version: u32,
    /// Characterization method of the study, with its settings.
    pub method: Method,
    /// The bearing.
    pub bearing: TrendBearing,
    /// The study case's lubricant at `operating.temperature_c` (a record: with ring temperatures
    /// each raceway's curves were fitted to laws of its ring's oil, `Case::lubricant_of`).
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
    pub fn from_json(text: &str) -> Result<Self, TrendError> {
        let m: TrendModel = serde_json::from_str(text).map_err(|e| TrendError::Json {
            message: e.to_string(),
        })?;
        if m.version != TREND_VERSION {
            return Err(TrendError::Version {
                found: m.version,
                supported: TREND_VERSION,
            });
        }
        for race in [Race::Inner, Race::Outer] {
            let (name, r) = (race_name(race), m.race(race));
            r.k.check(format!("{name}.k"))?;
            r.d.check(format!("{name}.d"))?;
            r.delta_f.check(format!("{name}.delta_f"))?;
            r.approach.check(format!("{name}.approach"))?;
            for (field, [lo, hi]) in [
                ("load_range_n", r.load_range_n),
                ("speed_range_rad_s", r.speed_range_rad_s),
            ] {
                if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi >= lo) {
                    return Err(TrendError::Range {
                        race,
                        field,
                        lo,
                        hi,
                    });
                }
            }
        }
        m.bearing_model()?;
        Ok(m)
    }

    /// The bearing (geometry and materials).
    pub fn bearing_model(&self) -> Result<Bearing, TrendError> {
        let b = &self.bearing;
        let geometry = BearingGeometry::new(
            b.ball_count,
            b.ball_diameter_m,
            b.pitch_diameter_m,
            b.inner_conformity,
            b.outer_conformity,
            b.free_contact_angle_rad,
        )
        .map_err(TrendError::Bearing)?;
        let bearing = Bearing {
            geometry,
            ball_material: b.ball_material,
            ring_material: b.ring_material,
        };
        bearing.validate().map_err(TrendError::Bearing)?;
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
