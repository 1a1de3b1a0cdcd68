//! One seed contact characterized at the default settings: the 7006's most loaded inner contact
//! at 5000 rpm (600 N, Rx = 2.9487 mm, Ry = 178.5 mm, u_s = 10.85 m/s; M ≈ 2360, L ≈ 25; 7 mm
//! steel ball).
//! - quasi-static: 7 steady EHL solutions over w0·(1 ± 0.2) on 129 × 129, LM fit;
//! - quasi-static at 257² with the DC-FFT kernel/plan cache off and on (before/after keeping
//!   plans);
//! - harmonic: steady start and ±5 % solutions (ω_n), the start at the load maximum, then the
//!   settling (quarter periods until the periodicity is ≤ 1e-3: 32 steps on this contact) and
//!   1 recorded period of 64 transient steps at the default Ω (0.005·ω_n; 0.1·ω_n until
//!   2026-11-26: the steps are per period, so the cost does not depend on Ω) on 129 × 129, LM fit
//!   with the damping term; `harmonic_two_settled_periods`: the same with the settling of
//!   before (two whole periods, `periodicity_tol` = 0), for the comparison;
//!   `harmonic_65`: the default settings on 65².

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ehl_bearing::contact::{
    ball_mass, characterize_harmonic, characterize_quasi_static, HarmonicSettings,
    QuasiStaticSettings,
};
use ehl_bearing::ehl::deformation::set_kernel_cache;
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

fn seed_contact() -> EhlContact {
    EhlContact {
        load: 600.0,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn quasi_static(c: &mut Criterion) {
    let contact = seed_contact();
    let s = QuasiStaticSettings::default();
    let mut g = c.benchmark_group("contact");
    g.sample_size(10);
    g.bench_function("quasi_static_7006_inner_600N_5000rpm", |b| {
        b.iter(|| characterize_quasi_static(black_box(&contact), &s).unwrap())
    });
    g.finish();
}

/// The quasi-static family at 257² with the kernel cache off (kernels rebuilt as before) and on.
fn quasi_static_cache(c: &mut Criterion) {
    let contact = seed_contact();
    let mut s = QuasiStaticSettings::default();
    s.ehl.grid = 257;
    let mut g = c.benchmark_group("contact_kernel_cache");
    g.sample_size(10);
    for on in [false, true] {
        set_kernel_cache(on);
        let name = if on { "on" } else { "off" };
        g.bench_function(format!("quasi_static_257_{name}"), |b| {
            b.iter(|| characterize_quasi_static(black_box(&contact), &s).unwrap())
        });
    }
    set_kernel_cache(true);
    g.finish();
}

fn harmonic(c: &mut Criterion) {
    let contact = seed_contact();
    let s = HarmonicSettings::default();
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    let mut g = c.benchmark_group("contact");
    g.sample_size(10);
    g.measurement_time(std::time::Duration::from_secs(80));
    g.bench_function("harmonic_7006_inner_600N_5000rpm", |b| {
        b.iter(|| characterize_harmonic(black_box(&contact), m, &s).unwrap())
    });
    let two = HarmonicSettings {
        periodicity_tol: 0.0,
        ..s
    };
    g.bench_function("harmonic_two_settled_periods", |b| {
        b.iter(|| characterize_harmonic(black_box(&contact), m, &two).unwrap())
    });
    let mut small = s;
    small.ehl.grid = 65;
    g.bench_function("harmonic_65", |b| {
        b.iter(|| characterize_harmonic(black_box(&contact), m, &small).unwrap())
    });
    g.finish();
}

criterion_group!(benches, quasi_static, quasi_static_cache, harmonic);
criterion_main!(benches);
