//! The fit of the trend curves over characterized contacts: log-space and linear least squares,
//! Levenberg–Marquardt where a form is nonlinear in its parameters, the forms chosen by the data
//! (`docs/study.md`).

use super::{RaceTrends, TrendBearing, TrendCurve, TrendError, TrendModel, TREND_VERSION};
use crate::bearing::{Bearing, Race, RaceControl};
use crate::fit::{levenberg_marquardt, LeastSquaresProblem, LmConvergence};
use crate::material::Lubricant;
use crate::method::Method;

/// The characterized contacts of one raceway, one entry per contact in every field (contacts
/// whose load was floored or whose fit did not converge left out by the caller).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RaceSamples {
    /// The load each law was characterized at, N (abscissa of K, d and ΔF).
    pub characterized_load_n: Vec<f64>,
    /// The equilibrium load, N (abscissa of δ and of the validity range).
    pub load_n: Vec<f64>,
    /// Speed of the inner ring relative to the outer, rad/s.
    pub speed_rad_s: Vec<f64>,
    /// Fitted stiffness K, N/m^d.
    pub k: Vec<f64>,
    /// Fitted exponent d.
    pub d: Vec<f64>,
    /// Fitted lift ΔF, N.
    pub delta_f_n: Vec<f64>,
    /// Equilibrium approach δ, m.
    pub approach_m: Vec<f64>,
}

/// What the trend fit needs: the bearing and its setting, and the contacts of each raceway.
#[derive(Debug, Clone)]
pub struct TrendFitInput<'a> {
    /// Characterization method of the contacts, with its settings.
    pub method: Method,
    /// The bearing.
    pub bearing: &'a Bearing,
    /// The lubricant.
    pub lubricant: Lubricant,
    /// Race-control hypothesis.
    pub race_control: RaceControl,
    /// Contacts of the inner raceway.
    pub inner: RaceSamples,
    /// Contacts of the outer raceway.
    pub outer: RaceSamples,
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

fn trend_err(race: Race, curve: &'static str) -> TrendError {
    TrendError::Singular { race, curve }
}

/// y(Q, n) = p0·Q^p1·n^p2 (log-space least squares) when all y > 0, else p0 + p1·Q + p2·n.
fn power_or_linear(
    race: Race,
    what: &'static str,
    unit: &str,
    q: &[f64],
    n: &[f64],
    y: &[f64],
) -> Result<TrendCurve, TrendError> {
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
fn fit_race(race: Race, samples: &RaceSamples) -> Result<RaceTrends, TrendError> {
    let RaceSamples {
        characterized_load_n: qc,
        load_n: q,
        speed_rad_s: n,
        k,
        d,
        delta_f_n: df,
        approach_m: delta,
    } = samples;
    if q.len() < 3 || distinct(q) < 3 || distinct(qc) < 3 {
        return Err(TrendError::TooFewContacts {
            race,
            contacts: q.len(),
            distinct_loads: distinct(q),
        });
    }
    // K, d and ΔF are functions of the load the law was characterized at.
    let lnq: Vec<f64> = qc.iter().map(|v| v.ln()).collect();
    // K(Q) = a·Q^b by least squares on ln K (relative errors).
    if k.iter().any(|v| v.is_nan() || *v <= 0.0) {
        return Err(TrendError::NonPositiveStiffness { race });
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

/// Fit the trend curves of both raceways. K, d and ΔF are fitted against the load each law was
/// characterized at, the approach δ against the equilibrium load; the two differ by at most the
/// loop's load reuse tolerance.
pub fn fit_model(input: &TrendFitInput) -> Result<TrendModel, TrendError> {
    let g = &input.bearing.geometry;
    Ok(TrendModel {
        version: TREND_VERSION,
        method: input.method,
        bearing: TrendBearing {
            ball_count: g.ball_count,
            ball_diameter_m: g.ball_diameter,
            pitch_diameter_m: g.pitch_diameter,
            inner_conformity: g.inner_conformity,
            outer_conformity: g.outer_conformity,
            free_contact_angle_rad: g.free_contact_angle,
            ball_material: input.bearing.ball_material,
            ring_material: input.bearing.ring_material,
        },
        lubricant: input.lubricant,
        race_control: input.race_control,
        inner: fit_race(Race::Inner, &input.inner)?,
        outer: fit_race(Race::Outer, &input.outer)?,
    })
}
