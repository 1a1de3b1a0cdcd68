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
    check_input(problem, x0, conv)?;
    let mut st = LmState::start(problem, x0, conv.initial_damping)?;
    let initial_cost = st.cost;
    let mut iterations = 0;
    let mut history = Vec::new();
    let mut r_trial = vec![0.0; st.m];
    let mut x_trial = vec![0.0; st.n];

    let stop = loop {
        let g = gradient(&st.jac, &st.r, st.m, st.n);
        let rnorm = norm2(&st.r);
        if rnorm == 0.0 {
            break LmStop::ZeroResidual;
        }
        let gm = gradient_measure(&g, &st.cn, rnorm);
        if gm <= conv.g_tol {
            break LmStop::Gradient;
        }
        if iterations >= conv.max_iterations {
            break LmStop::MaxIterations;
        }
        iterations += 1;

        let step = st.step(&g, conv.x_tol);
        let trial_cost = st.trial_cost(problem, &step.h, &mut x_trial, &mut r_trial);
        let rho = if step.predicted > 0.0 && trial_cost.is_finite() {
            (st.cost - trial_cost) / step.predicted
        } else {
            -1.0
        };

        if rho > 0.0 {
            let mut jac_trial = vec![0.0; st.m * st.n];
            problem.jacobian(&x_trial, &mut jac_trial);
            if jac_trial.iter().all(|v| v.is_finite()) {
                let actual_rel = (st.cost - trial_cost) / st.cost;
                let predicted_rel = step.predicted / st.cost;
                st.accept(&x_trial, &r_trial, jac_trial, trial_cost, rho);
                history.push(st.cost);
                if st.cost == 0.0 {
                    break LmStop::ZeroResidual;
                }
                if step.small {
                    break LmStop::Step;
                }
                if actual_rel <= conv.f_tol && predicted_rel <= conv.f_tol {
                    break LmStop::Cost;
                }
                continue;
            }
        }
        // Rejected step.
        history.push(st.cost);
        if step.small {
            // Even the damped step is below the resolution asked for: nothing left to gain.
            break LmStop::Step;
        }
        if !st.reject() {
            break LmStop::DampingOverflow;
        }
    };

    let g = gradient(&st.jac, &st.r, st.m, st.n);
    let gm = gradient_measure(&g, &st.cn, norm2(&st.r));
    Ok(LmReport {
        params: st.x,
        iterations,
        evaluations: st.evaluations,
        initial_cost,
        cost: st.cost,
        gradient_measure: gm,
        damping: st.mu,
        cost_history: history,
        stop,
        converged: stop.is_converged(),
    })
}

/// The input checks of [`levenberg_marquardt`]: at least as many residuals as parameters, `x0`
/// of the problem's length and finite, tolerances finite and ≥ 0, initial damping > 0.
fn check_input<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x0: &[f64],
    conv: &LmConvergence,
) -> Result<(), FitError> {
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
    check_finite("initial parameters", x0)
}

/// Euclidean norms of the n columns of the row-major m × n Jacobian `jac`.
fn column_norms(jac: &[f64], m: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|j| {
            (0..m)
                .map(|i| jac[i * n + j] * jac[i * n + j])
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

/// Gradient Jᵀr of the cost ½‖r‖² (units of the residuals squared per unit of each parameter).
fn gradient(jac: &[f64], r: &[f64], m: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|j| (0..m).map(|i| jac[i * n + j] * r[i]).sum())
        .collect()
}

/// A trial step of [`levenberg_marquardt`] from the current iterate.
struct TrialStep {
    /// Step h in the parameters (units of the parameters).
    h: Vec<f64>,
    /// Predicted reduction L(0) − L(h) = ½(μ‖D h‖² − hᵀg) of the cost (squared units of the
    /// residuals).
    predicted: f64,
    /// Whether the step is below the relative step tolerance: ‖D·h‖ ≤ x_tol·(‖D·x‖ + x_tol).
    small: bool,
}

/// The iterate of [`levenberg_marquardt`]: parameters with their residuals and Jacobian, the
/// scaling D and the damping.
struct LmState {
    /// Number of parameters n and of residuals m.
    n: usize,
    m: usize,
    /// Parameters x, residuals r(x) and row-major Jacobian J(x).
    x: Vec<f64>,
    r: Vec<f64>,
    jac: Vec<f64>,
    /// Column norms of J.
    cn: Vec<f64>,
    /// Scaling D: column norms, never decreased (Moré); a zero column gets scale 1.
    diag: Vec<f64>,
    /// Cost ½‖r‖² (squared units of the residuals).
    cost: f64,
    /// Damping μ (relative to D²) and its growth factor ν after a rejected step.
    mu: f64,
    nu: f64,
    /// Residual evaluations, including the initial one.
    evaluations: usize,
}

impl LmState {
    /// The iterate at `x0` with damping `mu`; errors when r or J is not finite there.
    fn start<P: LeastSquaresProblem + ?Sized>(
        problem: &P,
        x0: &[f64],
        mu: f64,
    ) -> Result<Self, FitError> {
        let n = problem.n_params();
        let m = problem.n_residuals();
        let x = x0.to_vec();
        let mut r = vec![0.0; m];
        let mut jac = vec![0.0; m * n];
        problem.residuals(&x, &mut r);
        check_finite("residuals at the initial parameters", &r)?;
        problem.jacobian(&x, &mut jac);
        check_finite("Jacobian at the initial parameters", &jac)?;
        let cn = column_norms(&jac, m, n);
        let diag: Vec<f64> = cn.iter().map(|&c| if c > 0.0 { c } else { 1.0 }).collect();
        let cost = 0.5 * norm2(&r).powi(2);
        Ok(LmState {
            n,
            m,
            x,
            r,
            jac,
            cn,
            diag,
            cost,
            mu,
            nu: 2.0,
            evaluations: 1,
        })
    }

    /// The damped step: minimises ‖J h + r‖² + μ‖D h‖² via QR of [J D⁻¹; √μ I] in the scaled
    /// variable z = D h; `g` is the gradient Jᵀr, `x_tol` the relative step tolerance.
    fn step(&self, g: &[f64], x_tol: f64) -> TrialStep {
        let (m, n) = (self.m, self.n);
        let rows = m + n;
        let mut a = vec![0.0; rows * n];
        for i in 0..m {
            for j in 0..n {
                a[i * n + j] = self.jac[i * n + j] / self.diag[j];
            }
        }
        let sq = self.mu.sqrt();
        for j in 0..n {
            a[(m + j) * n + j] = sq;
        }
        let mut rhs = vec![0.0; rows];
        for (v, ri) in rhs.iter_mut().zip(&self.r) {
            *v = -ri;
        }
        let rfac = householder_qr(&mut a, rows, n, Some(&mut rhs));
        let z = solve_upper(&rfac, n, &rhs[..n]);
        let h: Vec<f64> = z.iter().zip(&self.diag).map(|(zi, di)| zi / di).collect();
        let dh = norm2(&z);
        let dx = norm2(
            &self
                .x
                .iter()
                .zip(&self.diag)
                .map(|(xi, di)| xi * di)
                .collect::<Vec<_>>(),
        );
        let small = dh <= x_tol * (dx + x_tol);

        // Predicted reduction L(0) − L(h) = ½(μ‖D h‖² − hᵀg), a sum of non-negative terms.
        let htg: f64 = h.iter().zip(g).map(|(a, b)| a * b).sum();
        let predicted = 0.5 * (self.mu * dh * dh - htg);
        TrialStep {
            h,
            predicted,
            small,
        }
    }

    /// Cost ½‖r‖² at x + h, with the point and its residuals left in `x_trial` and `r_trial`;
    /// infinite when h or the residuals there are not finite.
    fn trial_cost<P: LeastSquaresProblem + ?Sized>(
        &mut self,
        problem: &P,
        h: &[f64],
        x_trial: &mut [f64],
        r_trial: &mut [f64],
    ) -> f64 {
        let mut trial_cost = f64::INFINITY;
        if h.iter().all(|v| v.is_finite()) {
            for j in 0..self.n {
                x_trial[j] = self.x[j] + h[j];
            }
            problem.residuals(x_trial, r_trial);
            self.evaluations += 1;
            if r_trial.iter().all(|v| v.is_finite()) {
                trial_cost = 0.5 * norm2(r_trial).powi(2);
            }
        }
        trial_cost
    }

    /// Moves to the accepted trial point (its residuals, Jacobian and cost), widens the scaling
    /// and lowers the damping by Nielsen's rule for the gain ratio `rho`.
    fn accept(&mut self, x_trial: &[f64], r_trial: &[f64], jac: Vec<f64>, cost: f64, rho: f64) {
        self.x.copy_from_slice(x_trial);
        self.r.copy_from_slice(r_trial);
        self.jac = jac;
        self.cost = cost;
        self.cn = column_norms(&self.jac, self.m, self.n);
        for j in 0..self.n {
            self.diag[j] = self.diag[j].max(self.cn[j]);
        }
        self.mu *= (1.0 / 3.0_f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
        self.nu = 2.0;
    }

    /// Raises the damping after a rejected step (μ ← μ·ν, ν ← 2ν); false when μ overflows
    /// (not finite or ≥ 1e150).
    fn reject(&mut self) -> bool {
        self.mu *= self.nu;
        self.nu *= 2.0;
        self.mu.is_finite() && self.mu < 1e150
    }
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
