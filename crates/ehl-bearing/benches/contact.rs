//! One seed contact characterized by the quasi-static method at the default settings
//! (7 steady EHL solutions over w0·(1 ± 0.2) on 129 × 129, LM fit): the 7006's most loaded inner
//! contact at 5000 rpm (600 N, Rx = 2.9487 mm, Ry = 178.5 mm, u_s = 10.85 m/s; M ≈ 2360, L ≈ 25).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ehl_bearing::contact::{characterize_quasi_static, QuasiStaticSettings};
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

fn quasi_static(c: &mut Criterion) {
    let contact = EhlContact {
        load: 600.0,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    };
    let s = QuasiStaticSettings::default();
    let mut g = c.benchmark_group("contact");
    g.sample_size(10);
    g.bench_function("quasi_static_7006_inner_600N_5000rpm", |b| {
        b.iter(|| characterize_quasi_static(black_box(&contact), &s).unwrap())
    });
    g.finish();
}

criterion_group!(benches, quasi_static);
criterion_main!(benches);
