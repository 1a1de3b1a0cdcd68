//! Smoothness of the fitted contact laws over a load sweep: the quasi-static fits of
//! neighbouring loads must not scatter more than their reported standard errors admit, and d and
//! ΔF must grow with the load at a fixed speed (d → 1.5 as the load grows; the lift ΔF grows with
//! the film-carrying load). `docs/gallery.md` ("Smoothness of the fitted parameters") has the
//! measurements behind the bounds.
//!
//! - `family_fits_are_smooth_across_the_inlet_kink` (default run, ≈ 10–20 s): the seed's outer
//!   contact at 5000 rpm, families centred at 300…420 N — across Moes M = 1000, where the
//!   automatic inlet stops shrinking; before the family shared one domain, d fell from 1.451 to
//!   1.438 and ΔF from 28.6 to 25.7 N there.
//! - `seed_study_fits_are_smooth_in_load` (`#[ignore]`, 412 s at load average 2–3.6 on 2 cores, 15 min on a
//!   loaded machine): the whole seed study, `cargo test -p ehl-bearing --test study_smoothness
//!   -- --ignored` (the test profile is optimized).

use ehl_bearing::contact::{characterize_quasi_static, QuasiStaticSettings};
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::io::read_study;
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};
use ehl_bearing::study::{run_point, PointStore};
use std::path::Path;

/// One fitted point: characterization load (N), d and ΔF (N) with their standard errors.
#[derive(Debug, Clone, Copy)]
struct Fitted {
    load: f64,
    d: f64,
    d_se: f64,
    delta_f: f64,
    delta_f_se: f64,
}

/// Normalized scatter of a load-sorted series: for every interior point, its deviation from the
/// interpolation (in ln Q) between its neighbours, divided by the standard error of that
/// difference (z); and for every neighbouring pair, by how many joint standard errors the value
/// falls where it should rise. Returns (largest |z|, rms of z, largest fall), in standard errors.
fn scatter(pts: &[Fitted], get: fn(&Fitted) -> (f64, f64)) -> (f64, f64, f64) {
    let mut z = Vec::new();
    for w in pts.windows(3) {
        let (q0, q1, q2) = (w[0].load.ln(), w[1].load.ln(), w[2].load.ln());
        if q2 - q0 <= 0.0 {
            continue;
        }
        let t = (q1 - q0) / (q2 - q0);
        let ((y0, s0), (y1, s1), (y2, s2)) = (get(&w[0]), get(&w[1]), get(&w[2]));
        let se = (s1 * s1 + ((1.0 - t) * s0).powi(2) + (t * s2).powi(2)).sqrt();
        z.push((y1 - (y0 + t * (y2 - y0))) / se);
    }
    let max = z.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let rms = (z.iter().map(|v| v * v).sum::<f64>() / z.len().max(1) as f64).sqrt();
    let mut fall: f64 = 0.0;
    for w in pts.windows(2) {
        let ((y0, s0), (y1, s1)) = (get(&w[0]), get(&w[1]));
        fall = fall.max((y0 - y1) / s0.hypot(s1));
    }
    (max, rms, fall)
}

/// Bounds of a series' scatter, in standard errors.
struct Bounds {
    /// Largest |z| of one point.
    max_dev: f64,
    /// Largest rms of z over the series (None: too few points for it to mean anything).
    max_rms: Option<f64>,
}

fn check(what: &str, pts: &mut [Fitted], bounds: &Bounds) {
    pts.sort_by(|a, b| a.load.total_cmp(&b.load));
    for (name, get) in [
        (
            "d",
            (|f: &Fitted| (f.d, f.d_se)) as fn(&Fitted) -> (f64, f64),
        ),
        ("ΔF", |f: &Fitted| (f.delta_f, f.delta_f_se)),
    ] {
        let (dev, rms, fall) = scatter(pts, get);
        let values: Vec<String> = pts
            .iter()
            .map(|p| format!("{:.1} N: {:.4}", p.load, get(p).0))
            .collect();
        println!(
            "{what}, {name}: largest deviation {dev:.2} SE, rms {rms:.2} SE, fall {fall:.2} SE: {values:?}"
        );
        assert!(
            dev <= bounds.max_dev,
            "{what}, {name}: a point deviates by {dev:.2} standard errors from its neighbours' \
             interpolation: {values:?}"
        );
        if let Some(max_rms) = bounds.max_rms {
            assert!(
                rms <= max_rms,
                "{what}, {name}: the deviations' rms is {rms:.2} standard errors — the reported \
                 uncertainty does not cover the point-to-point scatter: {values:?}"
            );
        }
        // A fall of more than 2 joint standard errors with rising load is not noise.
        assert!(
            fall <= 2.0,
            "{what}, {name}: falls by {fall:.2} joint standard errors with rising load: {values:?}"
        );
    }
}

/// The seed's outer contact at 5000 rpm (Rx, Ry and u_s of the seed study's equilibrium).
fn outer_contact(load: f64) -> EhlContact {
    EhlContact {
        load,
        rx: 4.049e-3,
        ry: 47.25e-3,
        sum_velocity: 10.853,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

#[test]
fn family_fits_are_smooth_across_the_inlet_kink() {
    let mut s = QuasiStaticSettings::default();
    s.ehl.grid = 65;
    let mut pts: Vec<Fitted> = (0..7)
        .map(|i| {
            let w0 = 300.0 + 20.0 * i as f64;
            let f = characterize_quasi_static(&outer_contact(w0), &s).unwrap();
            assert!(f.converged, "family at {w0} N did not converge");
            Fitted {
                load: w0,
                d: f.d,
                d_se: f.std_errors.d,
                delta_f: f.delta_f,
                delta_f_se: f.std_errors.delta_f,
            }
        })
        .collect();
    // 3 standard errors: the fit's standard errors come from 7 samples (4 degrees of freedom);
    // measured 1.53 (d) and 1.18 (ΔF); without the one-domain family d falls by 0.06 here.
    check(
        "outer contact, 5000 rpm, 65² grid",
        &mut pts,
        &Bounds {
            max_dev: 3.0,
            max_rms: None,
        },
    );
}

#[test]
#[ignore = "the whole seed study, ≈ 6–15 min: cargo test -p ehl-bearing --test study_smoothness -- --ignored"]
fn seed_study_fits_are_smooth_in_load() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/study_7006.toml");
    let study = read_study(&path).unwrap();
    assert_eq!(study.method.name(), "quasi-static");
    let mut rows = Vec::new();
    // STUDY_DIR=<a finished `ehl-bearing study examples/study_7006.toml -o DIR`> checks that
    // folder's point files instead of recomputing the study.
    if let Some(dir) = std::env::var_os("STUDY_DIR") {
        let store = ehl_bearing::io::FsStore::open(Path::new(&dir)).unwrap();
        for p in study.points() {
            let text = store
                .load_point(&p.file_stem())
                .unwrap()
                .expect("point file");
            let v = ehl_bearing::study::PointRecord::from_json(&text).unwrap();
            assert!(v.error.is_none(), "{:?}", v.error);
            rows.extend(v.rows());
        }
    } else {
        for p in study.points() {
            let v = run_point(&study, &p, &|_| {});
            assert!(v.error.is_none(), "{:?}", v.error);
            rows.extend(v.rows());
        }
    }
    for race in ["inner", "outer"] {
        for &n in &study.inner_speeds_rpm {
            let mut pts: Vec<Fitted> = rows
                .iter()
                .filter(|r| r.speed_rpm == n && r.contact.race == race && !r.contact.load_floored)
                .map(|r| Fitted {
                    load: r.contact.characterized_load_n,
                    d: r.contact.d,
                    d_se: r.contact.d_std_error.unwrap_or(f64::NAN),
                    delta_f: r.contact.delta_f_n,
                    delta_f_se: r.contact.delta_f_std_error_n.unwrap_or(f64::NAN),
                })
                .collect();
            assert!(
                pts.len() >= 20,
                "{race} {n} rpm: only {} contacts",
                pts.len()
            );
            // If the reported standard errors cover the scatter, z is about standard normal:
            // its rms over the ≈ 42 interior points of a series stays near 1 (1.5 is past the
            // 99 % point of sqrt(χ²₄₂/42) = 1.25, left wider because neighbouring z share
            // points), and the largest |z| of 42 stays below 4 (P(|z| > 4) = 6e-5 per point,
            // 0.3 % per series). Measured with this session's code (docs/gallery.md): rms
            // 0.25–0.99, largest 3.07 (d) and 3.14 (ΔF) on the outer race at 4000 rpm; each
            // family's domain still follows its centre's Moes M, which leaves small
            // family-to-family steps that the rms shows to be within the reported uncertainty.
            check(
                &format!("{race} race, {n} rpm"),
                &mut pts,
                &Bounds {
                    max_dev: 4.0,
                    max_rms: Some(1.5),
                },
            );
        }
    }
}
