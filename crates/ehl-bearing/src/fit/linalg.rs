//! Small dense linear algebra for the fit: Householder QR least squares and the inverse of an
//! upper-triangular factor. Matrices are row-major `Vec<f64>`; sizes are tiny (n ≤ ~6 columns).

/// Householder QR of the `m × n` row-major matrix `a` (m ≥ n), applied in place to the right-hand
/// side `b` (length m) when given. Returns the `n × n` upper-triangular factor R (row-major).
///
/// After the call, `b[..n]` holds the first n components of Qᵀb and `b[n..]` the rest, whose norm
/// is the least-squares residual norm.
pub(crate) fn householder_qr(
    a: &mut [f64],
    m: usize,
    n: usize,
    mut b: Option<&mut [f64]>,
) -> Vec<f64> {
    debug_assert!(m >= n && a.len() == m * n);
    for k in 0..n {
        // Norm of column k from row k down, computed with scaling against overflow.
        let scale = (k..m).fold(0.0_f64, |s, i| s.max(a[i * n + k].abs()));
        if scale == 0.0 {
            continue;
        }
        let mut norm2 = 0.0;
        for i in k..m {
            let v = a[i * n + k] / scale;
            norm2 += v * v;
        }
        let norm = scale * norm2.sqrt();
        let alpha = if a[k * n + k] > 0.0 { -norm } else { norm };
        // v = x − alpha·e1, stored in column k (rows k..m); H = I − 2vvᵀ/(vᵀv).
        a[k * n + k] -= alpha;
        let vtv: f64 = (k..m).map(|i| a[i * n + k] * a[i * n + k]).sum();
        if vtv > 0.0 {
            for j in (k + 1)..n {
                let dot: f64 = (k..m).map(|i| a[i * n + k] * a[i * n + j]).sum();
                let f = 2.0 * dot / vtv;
                for i in k..m {
                    a[i * n + j] -= f * a[i * n + k];
                }
            }
            if let Some(b) = b.as_deref_mut() {
                let dot: f64 = (k..m).map(|i| a[i * n + k] * b[i]).sum();
                let f = 2.0 * dot / vtv;
                for (i, bi) in b.iter_mut().enumerate().take(m).skip(k) {
                    *bi -= f * a[i * n + k];
                }
            }
        }
        a[k * n + k] = alpha;
    }
    let mut r = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            r[i * n + j] = a[i * n + j];
        }
    }
    r
}

/// Whether the upper-triangular `r` (n × n) is numerically rank deficient: some |R_kk| not above
/// `rel_tol` times the largest |R_jj|, or not finite.
pub(crate) fn rank_deficient(r: &[f64], n: usize, rel_tol: f64) -> bool {
    let max = (0..n).fold(0.0_f64, |s, k| s.max(r[k * n + k].abs()));
    if !(max.is_finite() && max > 0.0) {
        return true;
    }
    (0..n).any(|k| {
        let v = r[k * n + k].abs();
        v.is_nan() || v <= rel_tol * max
    })
}

/// Solve R x = y by back substitution (R upper-triangular n × n).
pub(crate) fn solve_upper(r: &[f64], n: usize, y: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let mut s = y[i];
        for j in (i + 1)..n {
            s -= r[i * n + j] * x[j];
        }
        x[i] = s / r[i * n + i];
    }
    x
}

/// (RᵀR)⁻¹ = R⁻¹R⁻ᵀ for an upper-triangular, non-singular R (n × n), row-major n × n.
pub(crate) fn inverse_gram_of_upper(r: &[f64], n: usize) -> Vec<f64> {
    // Columns of R⁻¹ by back substitution on the unit vectors.
    let mut rinv = vec![0.0; n * n];
    for c in 0..n {
        let mut e = vec![0.0; n];
        e[c] = 1.0;
        let col = solve_upper(r, n, &e);
        for i in 0..n {
            rinv[i * n + c] = col[i];
        }
    }
    let mut out = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            out[i * n + j] = (0..n).map(|k| rinv[i * n + k] * rinv[j * n + k]).sum();
        }
    }
    out
}

/// Least-squares solution of A x ≈ b for the `m × n` row-major `a`, with the columns scaled to
/// unit norm first (so the rank test is scale-free). Returns `None` when A is numerically rank
/// deficient (relative tolerance `rel_tol` on the diagonal of R of the scaled matrix).
pub(crate) fn least_squares(
    a: &[f64],
    m: usize,
    n: usize,
    b: &[f64],
    rel_tol: f64,
) -> Option<Vec<f64>> {
    if m < n {
        return None;
    }
    let mut scale = vec![1.0; n];
    for (j, s) in scale.iter_mut().enumerate() {
        let norm = (0..m)
            .map(|i| a[i * n + j] * a[i * n + j])
            .sum::<f64>()
            .sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        *s = 1.0 / norm;
    }
    let mut work: Vec<f64> = (0..m * n).map(|k| a[k] * scale[k % n]).collect();
    let mut rhs = b.to_vec();
    let r = householder_qr(&mut work, m, n, Some(&mut rhs));
    if rank_deficient(&r, n, rel_tol) {
        return None;
    }
    let y = solve_upper(&r, n, &rhs[..n]);
    let x: Vec<f64> = y.iter().zip(&scale).map(|(yi, si)| yi * si).collect();
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_squares_recovers_an_exact_linear_model() {
        // y = 2 + 3x sampled at 5 points.
        let xs = [0.0, 1.0, 2.0, 3.0, 4.0];
        let a: Vec<f64> = xs.iter().flat_map(|&x| [1.0, x]).collect();
        let b: Vec<f64> = xs.iter().map(|&x| 2.0 + 3.0 * x).collect();
        let sol = least_squares(&a, 5, 2, &b, 1e-12).unwrap();
        assert!((sol[0] - 2.0).abs() < 1e-12 && (sol[1] - 3.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_columns_are_detected() {
        let a = vec![1.0, 2.0, 2.0, 4.0, 3.0, 6.0];
        assert!(least_squares(&a, 3, 2, &[1.0, 2.0, 3.0], 1e-12).is_none());
    }

    #[test]
    fn inverse_gram_matches_direct_inverse() {
        let a = vec![2.0, 1.0, 0.5, 3.0, 1.0, 1.0];
        let mut w = a.clone();
        let r = householder_qr(&mut w, 3, 2, None);
        let inv = inverse_gram_of_upper(&r, 2);
        // AᵀA = [[5.25, 4.5], [4.5, 11]]
        let g = [5.25, 4.5, 4.5, 11.0];
        let prod00 = g[0] * inv[0] + g[1] * inv[2];
        let prod01 = g[0] * inv[1] + g[1] * inv[3];
        assert!((prod00 - 1.0).abs() < 1e-12 && prod01.abs() < 1e-12);
    }
}
