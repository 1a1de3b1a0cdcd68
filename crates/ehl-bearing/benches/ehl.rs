//! EHL benchmarks: `cargo bench -p ehl-bearing --bench ehl -- --warm-up-time 1 --measurement-time 5`.
//!
//! - circular contact M = 20, L = 10, Roelands + Dowson–Higginson, 257 × 257, default tolerances
//!   (converged below the discretization error);
//! - the seed's most loaded 7006 inner-race contact (600 N, 5000 rpm, Ry/Rx = 60.5);
//! - the circular case on 65, 129, 257 and 513 points per side (cost versus grid size).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl_bearing::ehl::{
    solve_moes, solve_steady, DensityModel, EhlContact, EhlSettings, MoesCase, ViscosityModel,
};
use ehl_bearing::material::Lubricant;
use std::hint::black_box;

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
    for grid in [65, 129, 257, 513] {
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

criterion_group!(benches, bench_circular, bench_seed, bench_grid);
criterion_main!(benches);
