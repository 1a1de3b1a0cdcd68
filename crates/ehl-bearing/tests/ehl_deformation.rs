//! Closed-form and round-off checks of the DC-FFT deformation.

use ehl_bearing::ehl::deformation::Deformation;
use std::f64::consts::PI;

/// FFT convolution equals the direct double sum to round-off, on a small anisotropic grid with
/// an arbitrary (deterministic pseudo-random) pressure. The circular buffers have 2n − 2 slots
/// where that length is smooth (17 → 32, 9 → 16, 5 → 8: the offsets ±(n − 1) share a slot, exact
/// because the kernel is even), more otherwise (12 → 24, 10 → 18).
#[test]
fn fft_matches_direct_summation() {
    // odd and even row counts (rows are packed in pairs for the x transforms)
    for (nx, ny) in [(13, 9), (12, 10), (17, 17), (9, 5)] {
        check_fft(nx, ny);
    }
}

fn check_fft(nx: usize, ny: usize) {
    let mut d = Deformation::new(nx, ny, 0.37, 1.9, 0.7);
    let mut seed = 12345u64;
    let p: Vec<f64> = (0..nx * ny)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let mut a = vec![0.0; nx * ny];
    let mut b = vec![0.0; nx * ny];
    d.apply(&p, &mut a);
    d.apply_direct(&p, &mut b);
    let scale = b.iter().cloned().fold(0.0, f64::max);
    let err = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        err < 1e-13 * scale,
        "{nx}x{ny}: max difference {err}, scale {scale}"
    );
}

/// Maximum error of (2/π²)∬P/r for P = √(1 − r²) against 1 − r²/2 at the nodes with r ≤ 1,
/// on an n × n grid over [−1.5, 1.5]²; returns (max over r ≤ 1, RMS over r ≤ 1).
fn hertz_error(n: usize) -> (f64, f64) {
    let h = 3.0 / (n - 1) as f64;
    let c: Vec<f64> = (0..n).map(|i| -1.5 + i as f64 * h).collect();
    let mut p = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let r2 = c[i] * c[i] + c[j] * c[j];
            p[j * n + i] = if r2 < 1.0 { (1.0 - r2).sqrt() } else { 0.0 };
        }
    }
    let mut d = Deformation::new(n, n, h, h, 2.0 / (PI * PI));
    let mut w = vec![0.0; n * n];
    d.apply(&p, &mut w);
    let mut err: f64 = 0.0;
    let (mut s2, mut cnt) = (0.0, 0.0);
    for j in 0..n {
        for i in 0..n {
            let r2 = c[i] * c[i] + c[j] * c[j];
            if r2 <= 1.0 {
                let e = (w[j * n + i] - (1.0 - 0.5 * r2)).abs();
                err = err.max(e);
                s2 += e * e;
                cnt += 1.0;
            }
        }
    }
    (err, (s2 / cnt).sqrt())
}

/// Hertz check (Johnson, Contact Mechanics ch. 3–4; docs/design.md §2):
/// (2/π²)∬√(1 − r'²)/|r − r'| dA' = 1 − r²/2 for r ≤ 1. With piecewise-constant cells the
/// error is set by the square-root edge of the pressure. Measured (max, RMS over r ≤ 1):
/// 33 points (1.8e-3, 6.2e-4), 65 (1.5e-3, 2.2e-4), 129 (4.8e-4, 7.4e-5), 257 (2.4e-4, 1.7e-5):
/// the RMS error falls 2.8–4.4× per grid doubling (order 1.5–2), the maximum (at nodes next to
/// the edge r = 1, where the exact pressure has an infinite slope) irregularly.
/// Asserted: max error < 2e-3 on every grid and < 3e-4 at 257, RMS falling > 2.5× per doubling.
#[test]
fn hertz_pressure_gives_hertz_deformation() {
    let e: Vec<(f64, f64)> = [33, 65, 129, 257].iter().map(|&n| hertz_error(n)).collect();
    println!("Hertz deformation max error: {e:?}");
    assert!(e.iter().all(|v| v.0 < 2e-3), "{e:?}");
    assert!(e[3].0 < 3e-4, "{e:?}");
    for k in 0..3 {
        assert!(e[k].1 / e[k + 1].1 > 2.5, "{e:?}");
    }
}
