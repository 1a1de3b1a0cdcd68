//! Seed-case equilibrium (7006, 1000 N in x, y, z, 0.001° tilts, 5000 rpm, outer-race control)
//! and one force-element evaluation (reactions + 5×5 Jacobian at given displacements).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ehl_bearing::bearing::{solve_equilibrium, BearingModel, ContactLaws};
use ehl_bearing::io::parse_case;

const SEED: &str = include_str!("../../../examples/7006.toml");

fn equilibrium(c: &mut Criterion) {
    let case = parse_case(SEED, "7006.toml").unwrap();
    let laws = ContactLaws::hertz(&case.bearing).unwrap();
    c.bench_function("equilibrium_7006_5000rpm", |b| {
        b.iter(|| {
            solve_equilibrium(
                black_box(&case.bearing),
                &laws,
                black_box(&case.operating),
                &case.settings,
            )
            .unwrap()
        })
    });
    let eq = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings).unwrap();
    let model = BearingModel::new(
        &case.bearing,
        &laws,
        case.operating.inner_speed,
        case.operating.outer_speed,
        case.operating.race_control,
    )
    .unwrap();
    c.bench_function("force_element_7006_5000rpm", |b| {
        b.iter(|| model.evaluate(black_box(&eq.displacement)).unwrap())
    });
}

criterion_group!(benches, equilibrium);
criterion_main!(benches);
