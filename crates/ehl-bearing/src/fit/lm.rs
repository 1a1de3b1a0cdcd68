//! A small Levenberg–Marquardt least-squares solver for a handful of parameters.
//!
//! Minimises F(x) = ½‖r(x)‖² with the scaled Marquardt step
//! (JᵀJ + μ·D²) h = −Jᵀr, D = diag(column norms of J, never decreasing — Moré 1978), solved as the
//! least-squares problem [J·D⁻¹; √μ·I] (D h) ≈ [−r; 0] by Householder QR (no normal equations).
//! The damping μ follows Nielsen's update (H. B. Nielsen, *Damping parameter in Marquardt's
//! method*, IMM-REP-1999-05; Madsen, Nielsen & Tingleff, *Methods for non-linear least squares
//! problems*, 2004, §3.2): with the gain ratio ρ = (F(x) − F(x+h)) / (L(0) − L(h)),
//! a step with ρ > 0 is accepted and μ ← μ·max(1/3, 1 − (2ρ − 1)³), ν ← 2; otherwise μ ← μ·ν,
//! ν ← 2ν.

use super::linalg::{householder_qr, inverse_gram_of_upper, rank_deficient, solve_upper};
use super::FitError;
use serde::Serialize;

/// A nonlinear least-squares problem with an analytic Jacobian.
pub trait LeastSquaresProblem {
    /// Number of parameters n.
    fn n_params(&self) -> usize;
    /// Number of residuals m (m ≥ n).
    fn n_residuals(&self) -> usize;
    /// Residuals r(x) (units of the data), written into `r` (length m).
    fn residuals(&self, x: &[f64], r: &mut [f64]);
    /// Jacobian ∂r_i/∂x_j, written row-major into `jac` (length m·n, entry `jac[i * n + j]`).
    fn jacobian(&self, x: &[f64], jac: &mut [f64]);
}

/// Convergence settings of [`levenberg_marquardt`]. All tolerances are dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LmConvergence {
    /// Relative step tolerance: stop when ‖D·h‖ ≤ x_tol·(‖D·x‖ + x_tol).
    pub x_tol: f64,
    /// Gradient tolerance: stop when max_j |(Jᵀr)_j| / (‖J_j‖·‖r‖) ≤ g_tol (the cosine of the
    /// angle between the residual and each Jacobian column; 0 at an exact minimum).
    pub g_tol: f64,
    /// Relative cost tolerance: stop when both the actual and the predicted relative reduction of
    /// F = ½‖r‖² in an accepted step are ≤ f_tol.
    pub f_tol: f64,
    /// Maximum number of iterations (trial steps, accepted or rejected).
    pub max_iterations: usize,
    /// Initial damping μ₀ relative to the scaling D² (dimensionless; 1e-3 for a fair start,
    /// 1e-6 for a start believed close to the solution).
    pub initial_damping: f64,
}

impl Default for LmConvergence {
    fn default() -> Self {
        Self {
            x_tol: 1e-10,
            g_tol: 1e-10,
            f_tol: 1e-12,
            max_iterations: 200,
            initial_damping: 1e-3,
        }
    }
}

/// Why [`levenberg_marquardt`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum LmStop {
    /// The residual is exactly zero (converged).
    ZeroResidual,
    /// Gradient test met (converged).
    Gradient,
    /// Relative step test met (converged): either an accepted step, or — after rejected steps —
    /// no step longer than the tolerance reduces the cost any more (as in MINPACK). With a wrong
    /// analytic Jacobian the latter can also happen away from a minimum: check
    /// `LmReport::gradient_measure`.
    Step,
    /// Relative cost-reduction test met (converged).
    Cost,
    /// Iteration limit reached before any test was met (not converged).
    MaxIterations,
    /// The damping grew without bound: no step reduces the cost, yet no convergence test is met
    /// (not converged).
    DampingOverflow,
}

impl LmStop {
    /// Whether this reason counts as convergence.
    pub fn is_converged(self) -> bool {
        matches!(
            self,
            LmStop::ZeroResidual | LmStop::Gradient | LmStop::Step | LmStop::Cost
        )
    }
}

impl std::fmt::Display for LmStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = match self {
            LmStop::ZeroResidual => "zero residual",
            LmStop::Gradient => "gradient tolerance met",
            LmStop::Step => "relative step tolerance met",
            LmStop::Cost => "relative cost-reduction tolerance met",
            LmStop::MaxIterations => "iteration limit reached",
            LmStop::DampingOverflow => "damping overflow (no descent step found)",
        };
        f.write_str(s)
    }
}

/// Outcome of [`levenberg_marquardt`]. Check `converged`: the solver never hides a failure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LmReport {
    /// Final parameters x (units of the problem's parameters).
    pub params: Vec<f64>,
    /// Iterations performed (trial steps, accepted or rejected).
    pub iterations: usize,
    /// Residual evaluations, including the initial one.
    pub evaluations: usize,
    /// Initial cost ½‖r(x₀)‖² (squared units of the residuals).
    pub initial_cost: f64,
    /// Final cost ½‖r(x)‖² (squared units of the residuals).
    pub cost: f64,
    /// Final gradient measure max_j |(Jᵀr)_j| / (‖J_j‖·‖r‖) (dimensionless, 0 at a minimum).
    pub gradient_measure: f64,
    /// Final damping μ (dimensionless, relative to D²).
    pub damping: f64,
    /// Cost after each iteration (squared units of the residuals).
    pub cost_history: Vec<f64>,
    /// Why the iteration stopped.
    pub stop: LmStop,
    /// Whether a convergence test was met (`stop.is_converged()`).
    pub converged: bool,
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// `FitError::NonFinite` naming `what` and the first non-finite entry of `v`.
pub(super) fn check_finite(what: &'static str, v: &[f64]) -> Result<(), FitError> {
    match v.iter().position(|a| !a.is_finite()) {
        Some(index) => Err(FitError::NonFinite {
            what,
            index,
            value: v[index],
        }),
        None => Ok(()),
    }
}

/// Minimise ½‖r(x)‖² from `x0` by Levenberg–Marquardt (see the module documentation).
///
/// Errors only for unusable input: fewer residuals than parameters, a wrong `x0` length, invalid
/// settings, or non-finite residuals/Jacobian at `x0`. Non-finite values at trial points are
/// treated as failed steps. Failure to converge is *not* an error: it is reported by
/// `LmReport::converged == false` together with the reason and the final cost.
pub fn levenberg_marquardt<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x0: &[f64],
    conv: &LmConvergence,
) -> Result<LmReport, FitError> {
    let n = problem.n_params();
    let m = problem.n_residuals();
    if n == 0 || x0.len() != n {
        return Err(FitError::LengthMismatch {
            what: "initial parameters",
            expected: n,
            found: x0.len(),
        });
    }
    if m < n {
        return Err(FitError::TooFewPoints {
            points: m,
            required: n,
        });
    }
    let tols = [conv.x_tol, conv.g_tol, conv.f_tol, conv.initial_damping];
    if tols.iter().any(|t| !(t.is_finite() && *t >= 0.0)) || conv.initial_damping <= 0.0 {
        return Err(FitError::LmSettings { settings: *conv });
    }
    check_finite("initial parameters", x0)?;

    let mut x = x0.to_vec();
    let mut r = vec![0.0; m];
    let mut jac = vec![0.0; m * n];
    problem.residuals(&x, &mut r);
    check_finite("residuals at the initial parameters", &r)?;
    problem.jacobian(&x, &mut jac);
    check_finite("Jacobian at the initial parameters", &jac)?;
    let mut evaluations = 1;

    let col_norms = |jac: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|j| {
                (0..m)
                    .map(|i| jac[i * n + j] * jac[i * n + j])
                    .sum::<f64>()
                    .sqrt()
            })
            .collect()
    };
    let mut cn = col_norms(&jac);
    // Scaling D: column norms, never decreased (Moré); a zero column gets scale 1.
    let mut diag: Vec<f64> = cn.iter().map(|&c| if c > 0.0 { c } else { 1.0 }).collect();

    let mut cost = 0.5 * norm2(&r).powi(2);
    let initial_cost = cost;
    let mut mu = conv.initial_damping;
    let mut nu = 2.0_f64;
    let mut iterations = 0;
    let mut history = Vec::new();
    let mut r_trial = vec![0.0; m];
    let mut x_trial = vec![0.0; n];

    let gradient = |jac: &[f64], r: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|j| (0..m).map(|i| jac[i * n + j] * r[i]).sum())
            .collect()
    };

    let stop = loop {
        let g = gradient(&jac, &r);
        let rnorm = norm2(&r);
        if rnorm == 0.0 {
            break LmStop::ZeroResidual;
        }
        let gm = gradient_measure(&g, &cn, rnorm);
        if gm <= conv.g_tol {
            break LmStop::Gradient;
        }
        if iterations >= conv.max_iterations {
            break LmStop::MaxIterations;
        }
        iterations += 1;

        // Step: minimise ‖J h + r‖² + μ‖D h‖² via QR of [J D⁻¹; √μ I] in the scaled variable z = D h.
        let rows = m + n;
        let mut a = vec![0.0; rows * n];
        for i in 0..m {
            for j in 0..n {
                a[i * n + j] = jac[i * n + j] / diag[j];
            }
        }
        let sq = mu.sqrt();
        for j in 0..n {
            a[(m + j) * n + j] = sq;
        }
        let mut rhs = vec![0.0; rows];
        for i in 0..m {
            rhs[i] = -r[i];
        }
        let rfac = householder_qr(&mut a, rows, n, Some(&mut rhs));
        let z = solve_upper(&rfac, n, &rhs[..n]);
        let h: Vec<f64> = z.iter().zip(&diag).map(|(zi, di)| zi / di).collect();
        let dh = norm2(&z);
        let dx = norm2(
            &x.iter()
                .zip(&diag)
                .map(|(xi, di)| xi * di)
                .collect::<Vec<_>>(),
        );
        let step_small = dh <= conv.x_tol * (dx + conv.x_tol);

        // Predicted reduction L(0) − L(h) = ½(μ‖D h‖² − hᵀg), a sum of non-negative terms.
        let htg: f64 = h.iter().zip(&g).map(|(a, b)| a * b).sum();
        let predicted = 0.5 * (mu * dh * dh - htg);

        let mut trial_cost = f64::INFINITY;
        if h.iter().all(|v| v.is_finite()) {
            for j in 0..n {
                x_trial[j] = x[j] + h[j];
            }
            problem.residuals(&x_trial, &mut r_trial);
            evaluations += 1;
            if r_trial.iter().all(|v| v.is_finite()) {
                trial_cost = 0.5 * norm2(&r_trial).powi(2);
            }
        }
        let rho = if predicted > 0.0 && trial_cost.is_finite() {
            (cost - trial_cost) / predicted
        } else {
            -1.0
        };

        if rho > 0.0 {
            let mut jac_trial = vec![0.0; m * n];
            problem.jacobian(&x_trial, &mut jac_trial);
            if jac_trial.iter().all(|v| v.is_finite()) {
                let actual_rel = (cost - trial_cost) / cost;
                let predicted_rel = predicted / cost;
                x.copy_from_slice(&x_trial);
                r.copy_from_slice(&r_trial);
                jac = jac_trial;
                cost = trial_cost;
                cn = col_norms(&jac);
                for j in 0..n {
                    diag[j] = diag[j].max(cn[j]);
                }
                mu *= (1.0 / 3.0_f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
                nu = 2.0;
                history.push(cost);
                if cost == 0.0 {
                    break LmStop::ZeroResidual;
                }
                if step_small {
                    break LmStop::Step;
                }
                if actual_rel <= conv.f_tol && predicted_rel <= conv.f_tol {
                    break LmStop::Cost;
                }
                continue;
            }
        }
        // Rejected step.
        history.push(cost);
        if step_small {
            // Even the damped step is below the resolution asked for: nothing left to gain.
            break LmStop::Step;
        }
        mu *= nu;
        nu *= 2.0;
        if !(mu.is_finite() && mu < 1e150) {
            break LmStop::DampingOverflow;
        }
    };

    let g = gradient(&jac, &r);
    let gm = gradient_measure(&g, &cn, norm2(&r));
    Ok(LmReport {
        params: x,
        iterations,
        evaluations,
        initial_cost,
        cost,
        gradient_measure: gm,
        damping: mu,
        cost_history: history,
        stop,
        converged: stop.is_converged(),
    })
}

fn gradient_measure(g: &[f64], col_norms: &[f64], rnorm: f64) -> f64 {
    if rnorm == 0.0 {
        return 0.0;
    }
    g.iter()
        .zip(col_norms)
        .filter(|(_, c)| **c > 0.0)
        .map(|(gj, c)| (gj / (c * rnorm)).abs())
        .fold(0.0, f64::max)
}

/// Parameter covariance s²·(JᵀJ)⁻¹ at `x`, with s² = ‖r‖²/(m − n), row-major n × n
/// (units: products of the parameters' units).
///
/// Computed from the QR factor of the column-scaled Jacobian (no normal equations). Errors when
/// m ≤ n (no degrees of freedom), when r or J is not finite, or when J is numerically rank
/// deficient (a parameter is not identifiable from the data).
pub fn covariance<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x: &[f64],
) -> Result<Vec<f64>, FitError> {
    let n = problem.n_params();
    let m = problem.n_residuals();
    if x.len() != n {
        return Err(FitError::LengthMismatch {
            what: "parameters",
            expected: n,
            found: x.len(),
        });
    }
    if m <= n {
        return Err(FitError::TooFewPoints {
            points: m,
            required: n + 1,
        });
    }
    let mut r = vec![0.0; m];
    let mut jac = vec![0.0; m * n];
    problem.residuals(x, &mut r);
    check_finite("residuals", &r)?;
    problem.jacobian(x, &mut jac);
    check_finite("Jacobian", &jac)?;
    let s2 = r.iter().map(|v| v * v).sum::<f64>() / (m - n) as f64;
    let mut scale = vec![1.0; n];
    for (j, s) in scale.iter_mut().enumerate() {
        let c = (0..m)
            .map(|i| jac[i * n + j] * jac[i * n + j])
            .sum::<f64>()
            .sqrt();
        if c.is_nan() || c <= 0.0 {
            return Err(FitError::Singular {
                detail: format!("Jacobian column {j} is zero"),
            });
        }
        *s = 1.0 / c;
    }
    let mut a: Vec<f64> = (0..m * n).map(|k| jac[k] * scale[k % n]).collect();
    let rf = householder_qr(&mut a, m, n, None);
    if rank_deficient(&rf, n, 1e-10) {
        return Err(FitError::Singular {
            detail: "Jacobian is numerically rank deficient: the parameters are not all identifiable from these data"
                .to_string(),
        });
    }
    let inv = inverse_gram_of_upper(&rf, n);
    let mut cov = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            cov[i * n + j] = s2 * inv[i * n + j] * scale[i] * scale[j];
        }
    }
    Ok(cov)
}
