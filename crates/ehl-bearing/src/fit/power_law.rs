//! The contact-law fit Q = K·δ^d + ΔF (+ c·δ̇).
//!
//! Internally the model is written in scaled, well-conditioned parameters
//!
//! ```text
//! Q/q_ref = a·(δ/δ_ref)^d + b + e·(δ̇/v_ref)
//! ```
//!
//! with δ_ref the geometric mean of the approaches (so ln(δ/δ_ref) has zero mean and a and d are
//! nearly uncorrelated), q_ref the root-mean-square force and v_ref the root-mean-square rate.
//! Then K = q_ref·a/δ_ref^d, ΔF = q_ref·b, c = q_ref·e/v_ref. For fixed d the model is linear in
//! (a, b, e): the start is the best d on a grid with (a, b, e) by linear least squares (variable
//! projection), and Levenberg–Marquardt polishes all parameters together.

use super::law::FittedLaw;
use super::linalg::least_squares;
use super::lm::{
    check_finite, covariance, levenberg_marquardt, LeastSquaresProblem, LmConvergence, LmStop,
};
use super::FitError;
use serde::Serialize;

/// Settings of [`fit_power_law`] and [`fit_power_law_damped`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitOptions {
    /// Levenberg–Marquardt settings for the final polish.
    pub convergence: LmConvergence,
    /// Range [min, max] of the nonlinear index d scanned for the starting point (dimensionless).
    /// The final d is not restricted to it.
    pub d_start_range: [f64; 2],
    /// Number of grid points in `d_start_range` (≥ 2).
    pub d_grid_points: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            convergence: LmConvergence::default(),
            d_start_range: [0.3, 3.0],
            d_grid_points: 55,
        }
    }
}

/// Standard errors (one standard deviation, from the linearized covariance s²·(JᵀJ)⁻¹) of the
/// fitted parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PowerLawStdErrors {
    /// Standard error of K, N/m^d. Large relative to K because K and d are strongly correlated
    /// (δ ≪ 1 m); prefer `force_at_ref` for the uncertainty of the force scale.
    pub k: f64,
    /// Standard error of d (dimensionless).
    pub d: f64,
    /// Standard error of ΔF, N.
    pub delta_f: f64,
    /// Standard error of c, N·s/m (damped fit only).
    pub c: Option<f64>,
    /// Standard error of `force_at_ref` = K·δ_ref^d, N.
    pub force_at_ref: f64,
}

/// Result of [`fit_power_law`] / [`fit_power_law_damped`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PowerLawFit {
    /// Stiffness K, N/m^d.
    pub k: f64,
    /// Nonlinear index d (dimensionless).
    pub d: f64,
    /// Hydrodynamic lift at zero approach ΔF, N.
    pub delta_f: f64,
    /// Damping coefficient c, N·s/m (damped fit only).
    pub c: Option<f64>,
    /// Reference approach δ_ref (geometric mean of the samples), m.
    pub delta_ref: f64,
    /// Elastic force at the reference approach, K·δ_ref^d, N (the well-determined scale of K).
    pub force_at_ref: f64,
    /// Standard errors of the parameters.
    pub std_errors: PowerLawStdErrors,
    /// Covariance of (K, d, ΔF[, c]), row-major p × p, in products of the units N/m^d, 1, N, N·s/m.
    pub covariance: Vec<f64>,
    /// Coefficient of determination 1 − SSR/SST (dimensionless; NaN if all Q are equal).
    pub r_squared: f64,
    /// Root-mean-square residual √(SSR/n), N.
    pub rms_residual: f64,
    /// Residual standard deviation s = √(SSR/(n − p)), N.
    pub residual_std: f64,
    /// Largest absolute residual, N.
    pub max_abs_residual: f64,
    /// Smallest and largest approach of the samples [δ_min, δ_max], m.
    pub delta_range: [f64; 2],
    /// Number of samples n.
    pub n_points: usize,
    /// Number of fitted parameters p (3, or 4 with damping).
    pub n_params: usize,
    /// Levenberg–Marquardt iterations.
    pub iterations: usize,
    /// Whether Levenberg–Marquardt met a convergence test. `false` is reported, never hidden:
    /// see `stop` and `rms_residual`, or use [`PowerLawFit::require_converged`]. Also false when
    /// K, d, ΔF or c is not finite (e.g. K overflowing for an extreme d), whatever `stop` says.
    pub converged: bool,
    /// Why Levenberg–Marquardt stopped.
    pub stop: LmStop,
}

impl PowerLawFit {
    /// The fitted force K·δ^d + ΔF (+ c·δ̇ when damped and `delta_dot` is given), N, at approach
    /// `delta` (m, > 0) and rate `delta_dot` (m/s). No extension: see [`FittedLaw`] for δ ≤ 0.
    pub fn predict(&self, delta: f64, delta_dot: Option<f64>) -> f64 {
        let damping = match (self.c, delta_dot) {
            (Some(c), Some(v)) => c * v,
            _ => 0.0,
        };
        self.k * delta.powf(self.d) + self.delta_f + damping
    }

    /// This fit, or [`FitError::NotConverged`] if Levenberg–Marquardt did not converge.
    pub fn require_converged(self) -> Result<Self, FitError> {
        if self.converged {
            Ok(self)
        } else {
            Err(FitError::NotConverged {
                iterations: self.iterations,
                reason: self.stop,
                rms_residual: self.rms_residual,
            })
        }
    }

    /// The fitted law with its extension below the fitted range (joint at
    /// [`DEFAULT_JOINT_FRACTION`](super::DEFAULT_JOINT_FRACTION)·δ_min), carrying c if fitted.
    pub fn law(&self) -> Result<FittedLaw, FitError> {
        let law = FittedLaw::new(
            self.k,
            self.d,
            self.delta_f,
            self.delta_range[0],
            self.delta_range[1],
        )?;
        match self.c {
            Some(c) => law.with_damping(c),
            None => Ok(law),
        }
    }
}

/// Fit Q = K·δ^d + ΔF to samples (δ_i, Q_i): `delta` in m (all > 0), `q` in N.
///
/// Needs at least 4 samples with at least 3 distinct approaches, all values finite and all δ > 0
/// (samples with δ ≤ 0 are rejected with [`FitError::NonPositiveApproach`], not dropped: leave
/// them out explicitly). Non-convergence is reported in the result (`converged`, `stop`).
pub fn fit_power_law(delta: &[f64], q: &[f64], opts: &FitOptions) -> Result<PowerLawFit, FitError> {
    fit_impl(delta, None, q, opts)
}

/// Fit Q = K·δ^d + ΔF + c·δ̇ to samples (δ_i, δ̇_i, Q_i): `delta` in m (all > 0), `delta_dot` in
/// m/s, `q` in N. Needs at least 5 samples, 3 distinct approaches and varying rates; otherwise as
/// [`fit_power_law`].
pub fn fit_power_law_damped(
    delta: &[f64],
    delta_dot: &[f64],
    q: &[f64],
    opts: &FitOptions,
) -> Result<PowerLawFit, FitError> {
    fit_impl(delta, Some(delta_dot), q, opts)
}

/// Scaled problem: residual_i = a·exp(d·l_i) + b + e·w_i − y_i.
struct ScaledPowerLaw {
    ln_u: Vec<f64>,
    w: Option<Vec<f64>>,
    y: Vec<f64>,
}

impl LeastSquaresProblem for ScaledPowerLaw {
    fn n_params(&self) -> usize {
        if self.w.is_some() {
            4
        } else {
            3
        }
    }
    fn n_residuals(&self) -> usize {
        self.y.len()
    }
    fn residuals(&self, x: &[f64], r: &mut [f64]) {
        for (i, ri) in r.iter_mut().enumerate() {
            let mut m = x[0] * (x[1] * self.ln_u[i]).exp() + x[2];
            if let Some(w) = &self.w {
                m += x[3] * w[i];
            }
            *ri = m - self.y[i];
        }
    }
    fn jacobian(&self, x: &[f64], jac: &mut [f64]) {
        let n = self.n_params();
        for i in 0..self.y.len() {
            let p = (x[1] * self.ln_u[i]).exp();
            jac[i * n] = p;
            jac[i * n + 1] = x[0] * p * self.ln_u[i];
            jac[i * n + 2] = 1.0;
            if let Some(w) = &self.w {
                jac[i * n + 3] = w[i];
            }
        }
    }
}

fn validate_options(opts: &FitOptions) -> Result<(), FitError> {
    let [lo, hi] = opts.d_start_range;
    if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi >= lo) || opts.d_grid_points < 2 {
        return Err(FitError::DStartGrid {
            d_start_range: opts.d_start_range,
            d_grid_points: opts.d_grid_points,
        });
    }
    Ok(())
}

fn fit_impl(
    delta: &[f64],
    delta_dot: Option<&[f64]>,
    q: &[f64],
    opts: &FitOptions,
) -> Result<PowerLawFit, FitError> {
    validate_options(opts)?;
    let p = check_samples(delta, delta_dot, q)?;
    let n = q.len();
    let [dmin, dmax] = approach_range(delta)?;
    let v_ref = match delta_dot {
        Some(v) => rate_scale(v)?,
        None => 1.0,
    };

    // Scales.
    let mean_ln = delta.iter().map(|x| x.ln()).sum::<f64>() / n as f64;
    let delta_ref = mean_ln.exp();
    let q_rms = (q.iter().map(|a| a * a).sum::<f64>() / n as f64).sqrt();
    let q_ref = if q_rms > 0.0 { q_rms } else { 1.0 };
    let problem = ScaledPowerLaw {
        ln_u: delta.iter().map(|x| x.ln() - mean_ln).collect(),
        w: delta_dot.map(|v| v.iter().map(|a| a / v_ref).collect()),
        y: q.iter().map(|a| a / q_ref).collect(),
    };

    let x0 = projected_start(&problem, opts, p)?;
    let report = levenberg_marquardt(&problem, &x0, &opts.convergence)?;
    let x = &report.params;
    // With a negligible power-law term d has no influence on the model: not identifiable.
    if x[0].is_nan() || x[0].abs() <= 1e-9 {
        return Err(FitError::Singular {
            detail: format!(
                "the fitted elastic force K·δ_ref^d = {:.3e} N is negligible against the forces (rms {q_ref:.3e} N): d is not identifiable (are all Q equal?)",
                x[0] * q_ref
            ),
        });
    }
    let cov_int = covariance(&problem, x)?;

    // Back to physical parameters: θ = (K, d, ΔF[, c]).
    let (a, d, b) = (x[0], x[1], x[2]);
    let k = q_ref * a * (-d * mean_ln).exp();
    let delta_f = q_ref * b;
    let c = (p == 4).then(|| q_ref * x[3] / v_ref);
    let cov = physical_covariance(&cov_int, p, [k, d], mean_ln, q_ref, v_ref);
    let force_at_ref = q_ref * a;

    // Goodness of fit in N.
    let mut r = vec![0.0; n];
    problem.residuals(x, &mut r);
    let ssr: f64 = r.iter().map(|v| (v * q_ref).powi(2)).sum();
    let q_mean = q.iter().sum::<f64>() / n as f64;
    let sst: f64 = q.iter().map(|v| (v - q_mean).powi(2)).sum();
    let r_squared = if sst > 0.0 { 1.0 - ssr / sst } else { f64::NAN };

    Ok(PowerLawFit {
        k,
        d,
        delta_f,
        c,
        delta_ref,
        force_at_ref,
        std_errors: PowerLawStdErrors {
            k: cov[0].sqrt(),
            d: cov[p + 1].sqrt(),
            delta_f: cov[2 * p + 2].sqrt(),
            c: (p == 4).then(|| cov[3 * p + 3].sqrt()),
            force_at_ref: q_ref * cov_int[0].sqrt(),
        },
        covariance: cov,
        r_squared,
        rms_residual: (ssr / n as f64).sqrt(),
        residual_std: (ssr / (n - p) as f64).sqrt(),
        max_abs_residual: r.iter().map(|v| (v * q_ref).abs()).fold(0.0, f64::max),
        delta_range: [dmin, dmax],
        n_points: n,
        n_params: p,
        iterations: report.iterations,
        // The optimizer works on scaled parameters; K = K̃/δ_ref^d can still overflow for the
        // extreme d that data unlike a contact law produce. Such a fit is not a usable law.
        converged: report.converged
            && k.is_finite()
            && d.is_finite()
            && delta_f.is_finite()
            && c.map_or(true, f64::is_finite),
        stop: report.stop,
    })
}

/// The sample checks of the fit: equal lengths of δ, δ̇ (if given) and Q, at least p + 1
/// samples, all finite, all δ > 0. Returns p, the number of fitted parameters (3, or 4 with
/// the rates).
fn check_samples(delta: &[f64], delta_dot: Option<&[f64]>, q: &[f64]) -> Result<usize, FitError> {
    let n = q.len();
    if delta.len() != n {
        return Err(FitError::LengthMismatch {
            what: "approach δ vs force Q",
            expected: n,
            found: delta.len(),
        });
    }
    if let Some(v) = delta_dot {
        if v.len() != n {
            return Err(FitError::LengthMismatch {
                what: "approach rate δ̇ vs force Q",
                expected: n,
                found: v.len(),
            });
        }
    }
    let p = if delta_dot.is_some() { 4 } else { 3 };
    if n < p + 1 {
        return Err(FitError::TooFewPoints {
            points: n,
            required: p + 1,
        });
    }
    check_finite("approach δ", delta)?;
    check_finite("force Q", q)?;
    if let Some(v) = delta_dot {
        check_finite("approach rate δ̇", v)?;
    }
    if let Some(index) = delta.iter().position(|&x| x <= 0.0) {
        return Err(FitError::NonPositiveApproach {
            index,
            value: delta[index],
        });
    }
    Ok(p)
}

/// Smallest and largest approach [δ_min, δ_max] (m) of the samples (non-empty); an error unless
/// at least 3 of them are distinct (relative spacing > 1e-9).
fn approach_range(delta: &[f64]) -> Result<[f64; 2], FitError> {
    let mut sorted = delta.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (dmin, dmax) = (sorted[0], sorted[sorted.len() - 1]);
    let distinct = 1 + sorted
        .windows(2)
        .filter(|w| w[1] - w[0] > 1e-9 * w[1])
        .count();
    if distinct < 3 {
        return Err(FitError::DegenerateApproach {
            distinct,
            min: dmin,
            max: dmax,
        });
    }
    Ok([dmin, dmax])
}

/// Rate scale v_ref, the root-mean-square of the rates δ̇ (m/s); an error when the rates do
/// not vary (relative spread ≤ 1e-9).
fn rate_scale(v: &[f64]) -> Result<f64, FitError> {
    let vmin = v.iter().copied().fold(f64::INFINITY, f64::min);
    let vmax = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if vmax - vmin <= 1e-9 * vmax.abs().max(vmin.abs()) {
        return Err(FitError::DegenerateRate { value: v[0] });
    }
    Ok((v.iter().map(|a| a * a).sum::<f64>() / v.len() as f64).sqrt())
}

/// Start of the Levenberg–Marquardt polish by variable projection: for each d of the start grid
/// the linear parameters (a, b[, e]) by linear least squares, and the (a, d, b[, e]) of the
/// smallest sum of squared residuals. An error when no d of the grid gives a solution.
fn projected_start(
    problem: &ScaledPowerLaw,
    opts: &FitOptions,
    p: usize,
) -> Result<Vec<f64>, FitError> {
    let n = problem.y.len();
    let mut best: Option<(f64, Vec<f64>)> = None;
    let lin_p = p - 1;
    for g in 0..opts.d_grid_points {
        let [lo, hi] = opts.d_start_range;
        let d = lo + (hi - lo) * g as f64 / (opts.d_grid_points - 1) as f64;
        let mut a = vec![0.0; n * lin_p];
        for i in 0..n {
            a[i * lin_p] = (d * problem.ln_u[i]).exp();
            a[i * lin_p + 1] = 1.0;
            if let Some(w) = &problem.w {
                a[i * lin_p + 2] = w[i];
            }
        }
        let Some(sol) = least_squares(&a, n, lin_p, &problem.y, 1e-10) else {
            continue;
        };
        let ssr: f64 = (0..n)
            .map(|i| {
                let m: f64 = (0..lin_p).map(|j| a[i * lin_p + j] * sol[j]).sum();
                (m - problem.y[i]).powi(2)
            })
            .sum();
        let better = match &best {
            Some((s, _)) => ssr < *s,
            None => true,
        };
        if ssr.is_finite() && better {
            let mut x = vec![sol[0], d, sol[1]];
            if p == 4 {
                x.push(sol[2]);
            }
            best = Some((ssr, x));
        }
    }
    match best {
        Some((_, x0)) => Ok(x0),
        None => Err(FitError::Singular {
            detail: "the linear parameters (K, ΔF[, c]) are not identifiable for any d on the start grid".to_string(),
        }),
    }
}

/// Covariance of the physical parameters θ = (K, d, ΔF[, c]) (row-major p × p) from that of the
/// scaled ones, G·C·Gᵀ with G = ∂θ/∂x; `kd` holds the fitted K (N/m^d) and d, `mean_ln` is
/// ln δ_ref, `q_ref` (N) and `v_ref` (m/s) the force and rate scales.
fn physical_covariance(
    cov_int: &[f64],
    p: usize,
    kd: [f64; 2],
    mean_ln: f64,
    q_ref: f64,
    v_ref: f64,
) -> Vec<f64> {
    let [k, d] = kd;
    // G = ∂θ/∂x (p × p).
    let mut g = vec![0.0; p * p];
    g[0] = q_ref * (-d * mean_ln).exp(); // ∂K/∂a
    g[1] = -k * mean_ln; // ∂K/∂d
    g[p + 1] = 1.0; // ∂d/∂d
    g[2 * p + 2] = q_ref; // ∂ΔF/∂b
    if p == 4 {
        g[3 * p + 3] = q_ref / v_ref; // ∂c/∂e
    }
    let mut cov = vec![0.0; p * p];
    for i in 0..p {
        for j in 0..p {
            let mut s = 0.0;
            for u in 0..p {
                for v in 0..p {
                    s += g[i * p + u] * cov_int[u * p + v] * g[j * p + v];
                }
            }
            cov[i * p + j] = s;
        }
    }
    cov
}
