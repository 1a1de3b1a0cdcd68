//! Quasi-static characterization of a seed contact: the fitted law reproduces its data, and the
//! paper's trends hold (d grows toward 1.5 with load, ΔF grows with speed).
//! Grid 65 keeps the test fast; the trends are the same on 129 (see docs/contact.md).

use ehl_bearing::contact::{characterize_quasi_static, ContactFit, QuasiStaticSettings};
use ehl_bearing::ehl::{EhlContact, EhlSettings};
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};
use ehl_bearing::ContactLaw;

/// The seed's inner-race contact (7006, docs/paper.md): Rx = 2.9487 mm, Ry = 178.5 mm; sum
/// velocity 10.85 m/s at 5000 rpm and 6.5 m/s at 3000 rpm.
fn inner(load: f64, us: f64) -> EhlContact {
    EhlContact {
        load,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: us,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn settings() -> QuasiStaticSettings {
    QuasiStaticSettings {
        ehl: EhlSettings {
            grid: 65,
            ..EhlSettings::default()
        },
        ..QuasiStaticSettings::default()
    }
}

fn run(load: f64, us: f64) -> ContactFit {
    let f = characterize_quasi_static(&inner(load, us), &settings()).unwrap();
    assert!(f.converged, "{load} N, {us} m/s");
    f
}

#[test]
fn fitted_law_reproduces_the_ehl_family() {
    let f = run(300.0, 10.85);
    assert_eq!(f.samples.len(), 7);
    // Every EHL sample within 4 RMS residuals of the law, and the RMS itself small against the
    // load (the EHL solutions are converged to 1e-5 in film and force).
    for s in &f.samples {
        let (q, _) = f.law.force(s.approach);
        assert!(
            (q - s.load).abs() <= 4.0 * f.rms_residual + 1e-9,
            "{q} vs {}",
            s.load
        );
    }
    assert!(f.rms_residual < 1e-3 * f.load, "{}", f.rms_residual);
    assert!(f.r_squared > 0.99999);
    // The law inverts to the approach of the operating point.
    let d0 = f.law.approach_at(f.load).unwrap();
    assert!((d0 - f.approach).abs() < 1e-3 * f.approach);
    // Lubricated: positive lift at zero approach, index between 1 and the dry 1.5.
    assert!(f.delta_f > 0.0 && f.d > 1.0 && f.d < 1.5, "{f:?}");
}

#[test]
fn paper_trends_d_grows_with_load_and_lift_grows_with_speed() {
    // d toward 1.5 (Hertz) as the load grows, at 5000 rpm.
    let d: Vec<f64> = [100.0, 300.0, 600.0]
        .iter()
        .map(|&w| run(w, 10.85).d)
        .collect();
    assert!(d[0] < d[1] && d[1] < d[2] && d[2] < 1.5, "{d:?}");
    // ΔF grows with speed at fixed load (3000 → 5000 rpm); the rise is many standard errors
    // (docs/contact.md: 19.4 ± 0.5 → 28.0 ± 0.2 N at 100 N on this grid).
    let slow = run(100.0, 6.5);
    let fast = run(100.0, 10.85);
    let se = slow.std_errors.delta_f.hypot(fast.std_errors.delta_f);
    assert!(
        fast.delta_f - slow.delta_f > 5.0 * se,
        "{} {} ± {se}",
        slow.delta_f,
        fast.delta_f
    );
}

#[test]
fn invalid_settings_are_errors() {
    let mut s = settings();
    s.amplitude = 1.5;
    let e = characterize_quasi_static(&inner(300.0, 10.85), &s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("amplitude"), "{e}");
    let mut s = settings();
    s.points = 3;
    let e = characterize_quasi_static(&inner(300.0, 10.85), &s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("points"), "{e}");
    let e = characterize_quasi_static(&inner(-1.0, 10.85), &settings())
        .unwrap_err()
        .to_string();
    assert!(e.contains("load"), "{e}");
}

/// The family's members share the DC-FFT kernels and plans (per-thread cache): a
/// characterization on a fresh thread builds few kernels and reuses them for the other members
/// (the seed contact at 600 N has the same domain at every load of the family, inlet 6 a_x and
/// half-width 2 a_y; the cache key is the exact cell size, and a_y/a_x differs in its last bits
/// between some loads: measured 4 built, 10 reused for 7 members × 2 levels). A second,
/// identical call builds nothing and gives identical results, and so does a call with the cache
/// off.
#[test]
fn family_reuses_kernels_and_plans() {
    use ehl_bearing::ehl::deformation::{kernel_cache_stats, set_kernel_cache};
    std::thread::spawn(|| {
        let a = run(600.0, 10.85);
        let (hits, misses) = kernel_cache_stats();
        println!("first call: {hits} kernels reused, {misses} built");
        // 65² has levels 33 and 65: 14 deformation operators in the family.
        assert_eq!(hits + misses, 14);
        assert!(hits > misses, "{hits} kernels reused, {misses} built");
        let b = run(600.0, 10.85);
        let (hits2, misses2) = kernel_cache_stats();
        println!(
            "second call: {} reused, {} built",
            hits2 - hits,
            misses2 - misses
        );
        assert_eq!(misses2, misses, "the second call builds no kernel");
        assert_eq!(a.k, b.k);
        assert_eq!(a.delta_f, b.delta_f);
        assert_eq!(a.samples, b.samples);
        // The cache is a memo, not a state: without it every kernel is built afresh and the
        // results are the same to the bit.
        set_kernel_cache(false);
        let c = run(600.0, 10.85);
        let (hits3, misses3) = kernel_cache_stats();
        assert_eq!((hits3, misses3), (0, 14), "cache off: every kernel built");
        set_kernel_cache(true);
        assert_eq!(a.k, c.k);
        assert_eq!(a.delta_f, c.delta_f);
        assert_eq!(a.samples, c.samples);
    })
    .join()
    .expect("thread");
}

/// Default accuracy of the film at w0: the Richardson estimate of the `contact`
/// command (129² family + one 257² solution at w0) brings the central film and the approach of
/// the most loaded seed inner contact (600 N, 5000 rpm) within 0.5 % of the grid-converged
/// values — reference: the Richardson extrapolation of the 257² and 513² families, H_c 0.56588 µm,
/// δ 6.56238 µm (docs/contact.md, "Default accuracy", measured 2026-11-25 with `ehl-bearing
/// contact examples/contact_7006_inner.toml --grid G --json`; the differences fall by 3.6–3.9
/// per halving from 129² on, so the extrapolation is second order). The 129² values alone are
/// 5.6 % and 0.44 % off, and the estimate's correction is the size of the 257² value's error.
#[test]
fn film_extrapolation_meets_the_default_accuracy_goal() {
    let s = QuasiStaticSettings {
        film_extrapolation: true,
        ..QuasiStaticSettings::default()
    };
    let f = characterize_quasi_static(&inner(600.0, 10.85), &s).unwrap();
    let x = f.film.expect("film estimate requested");
    assert!(f.converged && x.converged);
    assert_eq!(x.grid_fine, 257);
    let (h_ref, d_ref) = (0.56588e-6, 6.56238e-6);
    let rel = |a: f64, b: f64| (a - b).abs() / b;
    println!(
        "H_c {:.5e} ({:.2e}), δ {:.5e} ({:.2e}); 129²: {:.2e} {:.2e}; 257²: {:.2e} {:.2e}",
        x.h_central,
        rel(x.h_central, h_ref),
        x.approach,
        rel(x.approach, d_ref),
        rel(f.samples[3].h_central, h_ref),
        rel(f.approach, d_ref),
        rel(x.h_central_fine, h_ref),
        rel(x.approach_fine, d_ref)
    );
    assert!(rel(x.h_central, h_ref) < 5e-3);
    assert!(rel(x.approach, d_ref) < 5e-3);
    // The 129² centre alone misses the film goal; the extrapolation is closer than 257².
    assert!(rel(f.samples[3].h_central, h_ref) > 5e-3);
    assert!(rel(x.h_central, h_ref) < rel(x.h_central_fine, h_ref));
    // The correction estimates the 257² value's error within a factor 1.5.
    let err = (x.h_central_fine - h_ref).abs();
    assert!(err <= 1.5 * x.h_central_correction && x.h_central_correction <= 1.5 * err);
    // Off by default (the bearing loop), and refused where no finer grid exists.
    assert!(characterize_quasi_static(&inner(600.0, 10.85), &settings())
        .unwrap()
        .film
        .is_none());
    let e = characterize_quasi_static(
        &inner(600.0, 10.85),
        &QuasiStaticSettings {
            ehl: EhlSettings {
                grid: 1025,
                ..EhlSettings::default()
            },
            ..s
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("grid = 1025") && e.contains("≤ 513"), "{e}");
}

/// A light contact whose ±ε range reaches into the hydrodynamic regime (approach ≤ 0) is an error
/// that says what helps: a smaller amplitude when the approach at the centre of the range is
/// positive, only a larger load when it is not. Grid 33 keeps it fast (the regime is the same
/// on 129²: docs/study.md).
#[test]
fn a_hydrodynamic_range_says_what_helps() {
    use ehl_bearing::fit::FitError;
    let coarse = |amplitude: f64| QuasiStaticSettings {
        amplitude,
        points: 5,
        film_extrapolation: false,
        ehl: EhlSettings {
            grid: 33,
            ..EhlSettings::default()
        },
    };
    // 30 N ± 90 %: the centre is in the EHL regime, the lightest sample (3 N) is not.
    let e = characterize_quasi_static(&inner(30.0, 10.85), &coarse(0.9)).unwrap_err();
    let ehl_bearing::Error::Fit(FitError::HydrodynamicRegime {
        approach,
        load,
        time,
        centre_load,
        centre_approach,
        amplitude,
    }) = &e
    else {
        panic!("{e}");
    };
    assert!(*approach <= 0.0 && *centre_approach > 0.0, "{e}");
    assert!((load - 3.0).abs() < 1e-9, "{e}");
    assert!((centre_load - 30.0).abs() < 1e-9 && *amplitude == 0.9 && time.is_none());
    let msg = e.to_string();
    assert!(
        msg.contains("lower the relative load amplitude method_options.amplitude (now 0.9;")
            && msg.contains("0 < ε ≤ 0.9")
            && msg.contains("or raise the load"),
        "{msg}"
    );
    // 8 N ± 20 %: hydrodynamic even at the centre; a smaller amplitude cannot help.
    let msg = characterize_quasi_static(&inner(8.0, 10.85), &coarse(0.2))
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("even at the centre of the range, 8.0000 N")
            && msg.contains(
                "raise the load (a smaller method_options.amplitude, now 0.2, cannot help)"
            ),
        "{msg}"
    );
}
