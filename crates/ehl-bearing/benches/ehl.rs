//! EHL benchmarks: `cargo bench -p ehl-bearing --bench ehl -- --warm-up-time 1 --measurement-time 5`.
//!
//! - circular contact M = 20, L = 10, Roelands + Dowson–Higginson, 257 × 257, default tolerances
//!   (converged below the discretization error);
//! - the seed's most loaded 7006 inner-race contact (600 N, 5000 rpm, Ry/Rx = 60.5);
//! - the circular case on 129, 257, 513 and 1025 points per side (cost per grid point);
//! - the seed contact and the circular case at 257² with the kernel cache off (every level,
//!   start and call builds its DC-FFT kernel, as before the cache) and on;
//! - the 22 contacts of the seed bearing at 5000 rpm (`benches/seed_contacts.csv`), 257², one
//!   after the other (`seed_22`; about 25 s per sample).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl_bearing::ehl::deformation::set_kernel_cache;
use ehl_bearing::ehl::{
    solve_moes, solve_steady, DensityModel, EhlContact, EhlSettings, MoesCase, ViscosityModel,
};
use ehl_bearing::material::Lubricant;
use std::hint::black_box;

#[path = "common/seed_contacts.rs"]
mod seed_contacts;

fn circular() -> MoesCase {
    MoesCase::new(
        20.0,
        10.0,
        1.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    )
}

fn bench_circular(c: &mut Criterion) {
    let mut g = c.benchmark_group("ehl_circular_m20_l10");
    g.sample_size(10);
    let s = EhlSettings {
        grid: 257,
        ..Default::default()
    };
    g.bench_function("257", |b| {
        b.iter(|| {
            let r = solve_moes(black_box(&circular()), &s).expect("solves");
            assert!(r.converged);
            r.h_central
        })
    });
    // The same with the fixed tolerances alone (the stopping rule before issue 16's
    // discretization-following one).
    let fixed = EhlSettings {
        discretization_fraction: 0.0,
        ..s
    };
    g.bench_function("257_fixed_tolerances", |b| {
        b.iter(|| {
            let r = solve_moes(black_box(&circular()), &fixed).expect("solves");
            assert!(r.converged);
            r.h_central
        })
    });
    g.finish();
}

fn bench_seed(c: &mut Criterion) {
    let mut g = c.benchmark_group("ehl_7006_inner");
    g.sample_size(10);
    let contact = EhlContact {
        load: 600.0,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: 208e9 / 0.91,
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    };
    for grid in [129, 257] {
        let s = EhlSettings {
            grid,
            ..Default::default()
        };
        g.bench_with_input(BenchmarkId::from_parameter(grid), &s, |b, s| {
            b.iter(|| {
                let r = solve_steady(black_box(&contact), s).expect("solves");
                assert!(r.converged);
                r.h_central
            })
        });
    }
    g.finish();
}

fn bench_grid(c: &mut Criterion) {
    let mut g = c.benchmark_group("ehl_grid_size");
    g.sample_size(10);
    for grid in [129, 257, 513, 1025] {
        let s = EhlSettings {
            grid,
            ..Default::default()
        };
        g.bench_with_input(BenchmarkId::from_parameter(grid), &s, |b, s| {
            b.iter(|| {
                solve_moes(black_box(&circular()), s)
                    .expect("solves")
                    .h_central
            })
        });
    }
    g.finish();
}

fn seed_600n() -> EhlContact {
    EhlContact {
        load: 600.0,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: 208e9 / 0.91,
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn bench_cache(c: &mut Criterion) {
    let mut g = c.benchmark_group("ehl_kernel_cache");
    g.sample_size(10);
    let s = EhlSettings::default();
    for on in [false, true] {
        set_kernel_cache(on);
        let name = if on { "on" } else { "off" };
        g.bench_function(BenchmarkId::new("7006_inner_257", name), |b| {
            b.iter(|| {
                let r = solve_steady(black_box(&seed_600n()), &s).expect("solves");
                assert!(r.converged);
                r.h_central
            })
        });
        g.bench_function(BenchmarkId::new("circular_257", name), |b| {
            b.iter(|| {
                let r = solve_moes(black_box(&circular()), &s).expect("solves");
                assert!(r.converged);
                r.h_central
            })
        });
    }
    set_kernel_cache(true);
    g.finish();
}

/// The seed bearing's contacts at 5000 rpm (rows of `seed_contacts.csv`).
fn seed_contacts_5000() -> Vec<EhlContact> {
    seed_contacts::seed_contacts()
        .into_iter()
        .filter(|r| r.rpm == "5000")
        .map(|r| r.contact)
        .collect()
}

fn bench_seed_22(c: &mut Criterion) {
    let contacts = seed_contacts_5000();
    assert_eq!(contacts.len(), 22);
    let mut g = c.benchmark_group("ehl_seed_22");
    g.sample_size(10);
    let s = EhlSettings::default();
    g.bench_function("5000rpm_257", |b| {
        b.iter(|| {
            for ct in &contacts {
                let r = solve_steady(black_box(ct), &s).expect("solves");
                assert!(r.converged);
            }
        })
    });
    // The slowest of them alone (ball 4 inner, 263 N, M 1030: start 5 first, 9 cycles).
    g.bench_function("5000rpm_257_ball4_inner", |b| {
        b.iter(|| {
            let r = solve_steady(black_box(&contacts[8]), &s).expect("solves");
            assert!(r.converged);
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    bench_circular,
    bench_seed,
    bench_grid,
    bench_cache,
    bench_seed_22
);
criterion_main!(benches);
