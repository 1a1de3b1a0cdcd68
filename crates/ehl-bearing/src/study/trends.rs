//! Trend curves K(Q), d(Q), ΔF(Q, n) and the approach δ(Q, n) per raceway, fitted over a study's
//! points ([`fit_trends`]), as a [`TrendModel`] a rotor model can evaluate without any EHL run
//! (as a force element: [`crate::force_element::TrendForceElement`]).

use super::point::ResultRow;
use super::spec::Study;
use crate::bearing::{Bearing, BearingGeometry, Race, RaceControl};
use crate::characterize::CharacterizeError;
use crate::fit::{levenberg_marquardt, LeastSquaresProblem, LmConvergence};
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

    fn check(&self, what: &str) -> Result<(), CharacterizeError> {
        let need = match self.form.as_str() {
            "power" | "hertz_limit" | "log_linear" => 2,
            "power_speed" | "linear_speed" | "power_elastic" | "hertz_limit_speed" => 3,
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
        if m.version != TREND_VERSION {
            return Err(CharacterizeError::Trend(format!(
                "trend JSON version {} (this library reads version {TREND_VERSION})",
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

/// d = 1.5 − a·Q^(−b)[·n^c] by Levenberg–Marquardt on the residuals of d, in (ln a, b[, c]);
/// the speed term only when `lnn` is given.
struct HertzLimit<'a> {
    lnq: &'a [f64],
    lnn: Option<&'a [f64]>,
    y: &'a [f64],
}

impl HertzLimit<'_> {
    fn exponent(&self, x: &[f64], i: usize) -> f64 {
        x[0] - x[1] * self.lnq[i] + self.lnn.map_or(0.0, |ln| x[2] * ln[i])
    }
}

impl LeastSquaresProblem for HertzLimit<'_> {
    fn n_params(&self) -> usize {
        if self.lnn.is_some() {
            3
        } else {
            2
        }
    }
    fn n_residuals(&self) -> usize {
        self.y.len()
    }
    fn residuals(&self, x: &[f64], r: &mut [f64]) {
        for (i, (ri, y)) in r.iter_mut().zip(self.y).enumerate() {
            *ri = 1.5 - self.exponent(x, i).exp() - y;
        }
    }
    fn jacobian(&self, x: &[f64], jac: &mut [f64]) {
        let p = self.n_params();
        for i in 0..self.y.len() {
            let e = self.exponent(x, i).exp();
            jac[p * i] = -e;
            jac[p * i + 1] = e * self.lnq[i];
            if let Some(ln) = self.lnn {
                jac[p * i + 2] = -e * ln[i];
            }
        }
    }
}

/// Fit d = 1.5 − a·Q^(−b)[·n^c] (all d < 1.5): a log-space start, then Levenberg–Marquardt
/// (its result kept when it converged or halved the cost). None when the start is singular.
fn fit_hertz_limit(lnq: &[f64], lnn: Option<&[f64]>, d: &[f64]) -> Option<Vec<f64>> {
    let y: Vec<f64> = d.iter().map(|v| (1.5 - v).ln()).collect();
    let (c0, s) = match lnn {
        Some(ln) => fit_affine(&[lnq, ln], &y)?,
        None => fit_affine(&[lnq], &y)?,
    };
    let mut x0 = vec![c0, -s[0]];
    if lnn.is_some() {
        x0.push(s[1]);
    }
    let problem = HertzLimit { lnq, lnn, y: d };
    let x = match levenberg_marquardt(&problem, &x0, &LmConvergence::default()) {
        Ok(rep) if rep.converged || rep.cost < 0.5 * rep.initial_cost => rep.params,
        _ => x0,
    };
    let mut p = x;
    p[0] = p[0].exp();
    Some(p)
}

/// Whether the speed term of d(Q, n) is supported by the data: an F test of the one extra
/// parameter, F = (SSR₁ − SSR₂)/(SSR₂/(N − 3)) > 10 (well past the 0.5 % point of F(1, N − 3)
/// for N ≥ 10), and an rms residual at least 20 % lower and above 1e-8. Data without a speed effect (or with
/// too few points) keep the speed-independent form.
fn speed_term_supported(one: &TrendCurve, two: &TrendCurve) -> bool {
    let n = one.points as f64;
    // Residuals below 1e-8 in d are the laws' own fit tolerance and rounding, not a trend.
    if one.points < 6 || one.rms_residual < 1e-8 {
        return false;
    }
    let (ssr1, ssr2) = (n * one.rms_residual.powi(2), n * two.rms_residual.powi(2));
    if ssr2 <= 0.0 {
        return ssr1 > 0.0;
    }
    let f = (ssr1 - ssr2) / (ssr2 / (n - 3.0));
    f > 10.0 && two.rms_residual < 0.8 * one.rms_residual
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
        let p = fit_hertz_limit(&lnq, None, d).ok_or_else(|| trend_err(race, "d"))?;
        let one = quality("hertz_limit", "d = 1.5 − p0·Q^(−p1) (Q in N)", p, qc, n, d);
        // The speed term where the data separate by speed (at light load d is 1.19 at
        // 3000 rpm and 1.05 at 5000 rpm on the seed's inner race).
        let lnn: Vec<f64> = n.iter().map(|v| v.ln()).collect();
        let two = (distinct(n) >= 2 && lnn.iter().all(|v| v.is_finite()))
            .then(|| fit_hertz_limit(&lnq, Some(&lnn), d))
            .flatten()
            .map(|p| {
                quality(
                    "hertz_limit_speed",
                    "d = 1.5 − p0·Q^(−p1)·n^p2 (Q in N, n in rad/s)",
                    p,
                    qc,
                    n,
                    d,
                )
            });
        match two {
            Some(two) if speed_term_supported(&one, &two) => two,
            _ => one,
        }
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
        version: TREND_VERSION,
        method: study.method,
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
