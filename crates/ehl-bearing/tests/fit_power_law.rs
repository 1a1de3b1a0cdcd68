//! The contact-law fit Q = K·δ^d + ΔF (+ c·δ̇) on synthetic data with known parameters.

mod seeded;
use ehl_bearing::fit::{fit_power_law, fit_power_law_damped, FitError, FitOptions, PowerLawFit};
use proptest::prelude::*;

/// xorshift64* uniform generator with Box–Muller normals (seeded, reproducible).
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        // 53 random bits in (0, 1).
        ((v >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// A realistic case: K (N/m^d), d, ΔF (N).
#[derive(Clone, Copy, Debug)]
struct Case {
    k: f64,
    d: f64,
    delta_f: f64,
}

const CASES: [Case; 3] = [
    Case {
        k: 1.5e10,
        d: 1.45,
        delta_f: 40.0,
    },
    Case {
        k: 1.7e8,
        d: 1.1,
        delta_f: 200.0,
    },
    Case {
        k: 3.0e10,
        d: 1.5,
        delta_f: 0.0,
    },
];

fn approaches(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 2e-6 + 4e-6 * i as f64 / (n - 1) as f64)
        .collect()
}

fn forces(c: Case, delta: &[f64]) -> Vec<f64> {
    delta
        .iter()
        .map(|x| c.k * x.powf(c.d) + c.delta_f)
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

#[test]
fn noise_free_data_give_the_parameters_to_1e_8() {
    // The default start grid contains d = 1.45, 1.1 and 1.5 exactly; the coarse grid (0.5, 1.1,
    // 1.7, 2.3, 2.9 shifted by 0.037) makes Levenberg–Marquardt do the work.
    let coarse = FitOptions {
        d_start_range: [0.537, 2.937],
        d_grid_points: 5,
        ..FitOptions::default()
    };
    for (c, opts) in CASES
        .into_iter()
        .flat_map(|c| [(c, FitOptions::default()), (c, coarse)])
    {
        let delta = approaches(25);
        let q = forces(c, &delta);
        let f = fit_power_law(&delta, &q, &opts).unwrap();
        let q_max = q.iter().copied().fold(0.0, f64::max);
        let df_err = (f.delta_f - c.delta_f).abs() / c.delta_f.abs().max(q_max);
        println!(
            "{c:?}, start grid {:?}/{}: K rel err {:.1e}, d rel err {:.1e}, ΔF err {:.1e} (rel. to max(ΔF, Q_max)), {} iterations ({:?}), rms {:.1e} N",
            opts.d_start_range,
            opts.d_grid_points,
            rel(f.k, c.k),
            rel(f.d, c.d),
            df_err,
            f.iterations,
            f.stop,
            f.rms_residual
        );
        assert!(f.converged);
        assert!(
            rel(f.k, c.k) < 1e-8 && rel(f.d, c.d) < 1e-8 && df_err < 1e-8,
            "{f:?}"
        );
        assert!(f.r_squared > 1.0 - 1e-12);
        assert_eq!(f.delta_range, [2e-6, 6e-6]);
        assert_eq!(f.n_points, 25);
    }
}

fn noisy(c: Case, n: usize, sigma: f64, rng: &mut Rng) -> (Vec<f64>, Vec<f64>) {
    let delta = approaches(n);
    let q = forces(c, &delta)
        .into_iter()
        .map(|v| v + sigma * rng.normal())
        .collect();
    (delta, q)
}

/// With seeded Gaussian noise (σ = 1 N on forces of 80–450 N) the estimates scatter about the
/// truth as the reported standard errors say: over 20 seeds × 3 cases, z = (estimate − truth)/SE
/// for d, ΔF and the force scale K·δ_ref^d. (The standard error of K itself is a linearization of
/// a strongly skewed quantity — K ∝ δ_ref^(−d) with ln δ_ref ≈ −12.5 — so K is checked through
/// the force scale.) A fit counts as an outlier if any |z| > 3; at most 2 of 60 are allowed
/// (expected ≈ 0.3 for independent normals, more since the three z of one fit are correlated),
/// and no |z| may exceed 4.5.
#[test]
fn noisy_estimates_lie_within_three_standard_errors() {
    let sigma = 1.0; // N
    let mut outliers = 0;
    let mut max_z = 0.0_f64;
    let mut within_2 = 0;
    let mut count = 0;
    for (ci, c) in CASES.into_iter().enumerate() {
        for seed in 1..=20u64 {
            let mut rng = Rng::new(100 * ci as u64 + seed);
            let (delta, q) = noisy(c, 30, sigma, &mut rng);
            let f = fit_power_law(&delta, &q, &FitOptions::default()).unwrap();
            assert!(f.converged, "{:?}", f.stop);
            let scale_true = c.k * f.delta_ref.powf(c.d);
            let z = [
                (f.d - c.d) / f.std_errors.d,
                (f.delta_f - c.delta_f) / f.std_errors.delta_f,
                (f.force_at_ref - scale_true) / f.std_errors.force_at_ref,
            ];
            if z.iter().any(|v| v.abs() > 3.0) {
                outliers += 1;
                println!("{c:?} seed {seed}: z = {z:.2?}");
            }
            max_z = z.iter().fold(max_z, |m, v| m.max(v.abs()));
            within_2 += z.iter().filter(|v| v.abs() <= 2.0).count();
            count += 3;
            // The residual standard deviation estimates σ.
            assert!(
                (f.residual_std / sigma - 1.0).abs() < 0.4,
                "s = {}",
                f.residual_std
            );
        }
    }
    println!(
        "60 noisy fits: {outliers} with some |z| > 3, max |z| = {max_z:.2}, {:.1} % of z within ±2",
        100.0 * within_2 as f64 / count as f64
    );
    assert!(outliers <= 2 && max_z < 4.5);
}

fn std_dev(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
}

#[test]
fn monte_carlo_spread_matches_reported_standard_errors() {
    let sigma = 1.0; // N
    let reps = 200;
    for c in [CASES[0], CASES[1]] {
        let mut rng = Rng::new(2024);
        let mut d = Vec::new();
        let mut df = Vec::new();
        let mut se_d = Vec::new();
        let mut se_df = Vec::new();
        for _ in 0..reps {
            let (delta, q) = noisy(c, 30, sigma, &mut rng);
            let f = fit_power_law(&delta, &q, &FitOptions::default()).unwrap();
            assert!(f.converged);
            d.push(f.d);
            df.push(f.delta_f);
            se_d.push(f.std_errors.d);
            se_df.push(f.std_errors.delta_f);
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let ratio_d = std_dev(&d) / mean(&se_d);
        let ratio_df = std_dev(&df) / mean(&se_df);
        println!(
            "{c:?}: {reps} fits, sd(d) = {:.4e}, mean SE(d) = {:.4e}, ratio {ratio_d:.3}; sd(ΔF) = {:.3} N, mean SE(ΔF) = {:.3} N, ratio {ratio_df:.3}; mean d − d_true = {:.2e}",
            std_dev(&d),
            mean(&se_d),
            std_dev(&df),
            mean(&se_df),
            mean(&d) - c.d
        );
        assert!((ratio_d - 1.0).abs() < 0.25, "d spread ratio {ratio_d}");
        assert!((ratio_df - 1.0).abs() < 0.25, "ΔF spread ratio {ratio_df}");
    }
}

/// Harmonic approach history δ(t) = δ0 + A·sin(Ωt) over two periods (a transient EHL run).
fn harmonic(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (d0, amp, omega) = (4e-6, 2e-6, 2.0 * std::f64::consts::PI * 1000.0);
    let t: Vec<f64> = (0..n).map(|i| 2.0 / 1000.0 * i as f64 / n as f64).collect();
    let delta = t.iter().map(|t| d0 + amp * (omega * t).sin()).collect();
    let rate = t.iter().map(|t| amp * omega * (omega * t).cos()).collect();
    (delta, rate)
}

#[test]
fn damped_fit_recovers_c() {
    let (c_true, case) = (2000.0, CASES[0]); // N·s/m
    let (delta, rate) = harmonic(60);
    let q: Vec<f64> = forces(case, &delta)
        .iter()
        .zip(&rate)
        .map(|(q, v)| q + c_true * v)
        .collect();
    let f = fit_power_law_damped(&delta, &rate, &q, &FitOptions::default()).unwrap();
    let c = f.c.unwrap();
    println!(
        "damped, noise-free: c rel err {:.1e}, K {:.1e}, d {:.1e}, ΔF {:.1e}",
        rel(c, c_true),
        rel(f.k, case.k),
        rel(f.d, case.d),
        rel(f.delta_f, case.delta_f)
    );
    assert!(f.converged && f.n_params == 4);
    assert!(rel(c, c_true) < 1e-8 && rel(f.k, case.k) < 1e-8 && rel(f.d, case.d) < 1e-8);
    assert!(rel(f.delta_f, case.delta_f) < 1e-8);

    // With noise: within three standard errors.
    let mut rng = Rng::new(7);
    let qn: Vec<f64> = q.iter().map(|v| v + rng.normal()).collect();
    let f = fit_power_law_damped(&delta, &rate, &qn, &FitOptions::default()).unwrap();
    let z = (f.c.unwrap() - c_true) / f.std_errors.c.unwrap();
    println!(
        "damped, σ = 1 N: c = {:.1} ± {:.1} N·s/m (z = {z:.2})",
        f.c.unwrap(),
        f.std_errors.c.unwrap()
    );
    assert!(z.abs() < 3.0);
    // The undamped fit of the same data leaves a much larger residual.
    let u = fit_power_law(&delta, &qn, &FitOptions::default()).unwrap();
    assert!(u.rms_residual > 3.0 * f.rms_residual);

    // Monte Carlo: the spread of c over 100 noisy repetitions matches its reported standard error.
    let mut cs = Vec::new();
    let mut ses = Vec::new();
    for _ in 0..100 {
        let qn: Vec<f64> = q.iter().map(|v| v + rng.normal()).collect();
        let f = fit_power_law_damped(&delta, &rate, &qn, &FitOptions::default()).unwrap();
        assert!(f.converged);
        cs.push(f.c.unwrap());
        ses.push(f.std_errors.c.unwrap());
    }
    let ratio = std_dev(&cs) / (ses.iter().sum::<f64>() / ses.len() as f64);
    println!(
        "damped, 100 noisy fits: sd(c) = {:.2} N·s/m, sd/mean SE = {ratio:.3}",
        std_dev(&cs)
    );
    assert!((ratio - 1.0).abs() < 0.25);
}

#[test]
fn the_fit_serializes_and_its_law_reproduces_it() {
    let delta = approaches(10);
    let q = forces(CASES[0], &delta);
    let f: PowerLawFit = fit_power_law(&delta, &q, &FitOptions::default()).unwrap();
    let json = serde_json::to_string(&f).unwrap();
    assert!(json.contains("\"delta_f\"") && json.contains("\"std_errors\""));
    let law = f.law().unwrap();
    use ehl_bearing::ContactLaw;
    for &x in &delta {
        assert!(rel(law.force(x).0, f.predict(x, None)) < 1e-14);
    }
    assert!(f.clone().require_converged().is_ok());
}

#[test]
fn non_convergence_is_reported() {
    let delta = approaches(10);
    let q = forces(CASES[1], &delta);
    let mut opts = FitOptions::default();
    opts.convergence.max_iterations = 0;
    opts.d_start_range = [2.5, 3.0]; // start far from d = 1.1
    let f = fit_power_law(&delta, &q, &opts).unwrap();
    assert!(!f.converged);
    assert!(matches!(
        f.clone().require_converged(),
        Err(FitError::NotConverged { .. })
    ));
    assert!(f.rms_residual > 0.0);
}

#[test]
fn bad_input_names_the_problem() {
    let o = FitOptions::default();
    let delta = approaches(10);
    let q = forces(CASES[0], &delta);
    let e = fit_power_law(&delta[..3], &q[..3], &o).unwrap_err();
    assert!(
        matches!(
            e,
            FitError::TooFewPoints {
                points: 3,
                required: 4
            }
        ),
        "{e}"
    );
    let e = fit_power_law(&delta, &q[..9], &o).unwrap_err();
    assert!(matches!(e, FitError::LengthMismatch { .. }), "{e}");
    let e = fit_power_law_damped(&delta, &delta[..9], &q, &o).unwrap_err();
    assert!(matches!(e, FitError::LengthMismatch { .. }), "{e}");
    let mut qn = q.clone();
    qn[4] = f64::NAN;
    let e = fit_power_law(&delta, &qn, &o).unwrap_err();
    assert!(matches!(e, FitError::NonFinite { index: 4, .. }), "{e}");
    let mut dn = delta.clone();
    dn[2] = f64::INFINITY;
    assert!(matches!(
        fit_power_law(&dn, &q, &o).unwrap_err(),
        FitError::NonFinite { index: 2, .. }
    ));
    dn[2] = -1e-7;
    let e = fit_power_law(&dn, &q, &o).unwrap_err();
    assert!(
        matches!(e, FitError::NonPositiveApproach { index: 2, .. }),
        "{e}"
    );
    dn[2] = 0.0;
    assert!(matches!(
        fit_power_law(&dn, &q, &o).unwrap_err(),
        FitError::NonPositiveApproach { .. }
    ));
    let e = fit_power_law(&[3e-6; 10], &q, &o).unwrap_err();
    assert!(
        matches!(e, FitError::DegenerateApproach { distinct: 1, .. }),
        "{e}"
    );
    let two: Vec<f64> = (0..10)
        .map(|i| if i % 2 == 0 { 2e-6 } else { 5e-6 })
        .collect();
    assert!(matches!(
        fit_power_law(&two, &q, &o).unwrap_err(),
        FitError::DegenerateApproach { distinct: 2, .. }
    ));
    let e = fit_power_law_damped(&delta, &[1e-3; 10], &q, &o).unwrap_err();
    assert!(matches!(e, FitError::DegenerateRate { .. }), "{e}");
    // All forces equal: d is not identifiable.
    let e = fit_power_law(&delta, &[100.0; 10], &o).unwrap_err();
    assert!(matches!(e, FitError::Singular { .. }), "{e}");
    let bad = FitOptions {
        d_grid_points: 1,
        ..o
    };
    assert!(matches!(
        fit_power_law(&delta, &q, &bad).unwrap_err(),
        FitError::DStartGrid { .. }
    ));
    println!(
        "example message: {}",
        fit_power_law(&dn, &q, &o).unwrap_err()
    );
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 1e-7..1e-5f64,
        2 => -1e3..1e3f64,
        1 => Just(0.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => any::<f64>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, ..seeded::config(300) })]
    #[test]
    fn random_input_never_panics(
        delta in prop::collection::vec(any_f64(), 0..12),
        q in prop::collection::vec(any_f64(), 0..12),
        rate in prop::collection::vec(any_f64(), 0..12),
    ) {
        let o = FitOptions::default();
        let _ = fit_power_law(&delta, &q, &o);
        let _ = fit_power_law_damped(&delta, &rate, &q, &o);
        if let Ok(f) = fit_power_law(&delta, &q[..q.len().min(delta.len())], &o) {
            let _ = f.law();
        }
    }

    #[test]
    fn random_valid_shaped_input_never_panics(
        delta in prop::collection::vec(1e-8..1e-4f64, 4..20),
        q in prop::collection::vec(-1e4..1e4f64, 20),
    ) {
        let o = FitOptions::default();
        let q = &q[..delta.len()];
        if let Ok(f) = fit_power_law(&delta, q, &o) {
            // A successful fit reports finite numbers (or says it did not converge).
            prop_assert!(!f.converged || (f.k.is_finite() && f.d.is_finite() && f.delta_f.is_finite()));
            prop_assert!(f.rms_residual.is_finite());
            let _ = f.law();
        }
    }
}

/// Found by `random_valid_shaped_input_never_panics` (proptest, shrunk): data unlike a contact law
/// drive d so far that K = K̃/δ_ref^d overflows; the fit must then not claim convergence.
#[test]
fn overflowing_k_is_not_reported_as_converged() {
    let delta = [
        8.453005958585252e-5,
        9.652075826769571e-5,
        9.246593524745456e-5,
        7.808656675587289e-5,
    ];
    let q = [
        5714.513320382155,
        -9291.719919536019,
        4500.987944614861,
        3939.3151297079685,
    ];
    if let Ok(f) = fit_power_law(&delta, &q, &FitOptions::default()) {
        assert!(
            !f.converged || (f.k.is_finite() && f.d.is_finite() && f.delta_f.is_finite()),
            "{f:?}"
        );
    }
}
