//! The bearing force element for rotor use, one call with a warm state (the rotor integrator's
//! case): the seed bearing (7006, 5000 rpm) with fitted laws (with damping terms) and with the
//! trend model of a synthetic study, each at a displaced position with rates and a turning cage.
//! Goals (issue 11): ≤ 20 µs fitted laws, ≤ 50 µs trend model.

mod common;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::force_element::{
    ElementInput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::parse_case;
use ehl_bearing::io::parse_study;
use ehl_bearing::study::{fit_trends, run_point};
use std::path::Path;

const SEED: &str = include_str!("../../../examples/7006.toml");

fn elements(c: &mut Criterion) {
    let case = parse_case(SEED, "7006.toml").unwrap();
    let b = &case.bearing;
    let laws = common::seed_fitted_laws(b);
    let fitted = LawElement::from_fitted(b, case.operating.race_control, &laws).unwrap();
    let hertz = ContactLaws::hertz(b).unwrap();
    let q0 = solve_equilibrium(b, &hertz, &case.operating, &case.settings)
        .unwrap()
        .displacement;
    let mut input = ElementInput::at(q0, case.operating.inner_speed, 0.0);
    input.velocity = [1e-4, -2e-4, 1e-4, 1e-3, -1e-3];
    let w_cage = fitted.cage_speed(input.inner_speed, 0.0);
    let dt = 1e-5;
    for (name, element) in [
        (
            "force_element_fitted_7006_warm",
            &fitted as &dyn ForceElement,
        ),
        (
            "force_element_trend_7006_warm",
            &trend_element() as &dyn ForceElement,
        ),
    ] {
        let mut state = ElementState::default();
        let mut step = 0u64;
        c.bench_function(name, |bench| {
            bench.iter(|| {
                // A rotor time step: the position moves a little and the cage turns.
                step += 1;
                let mut i = input;
                let t = step as f64 * dt;
                i.displacement[1] += 1e-8 * (1e3 * t).sin();
                i.cage_angle = w_cage * t;
                element.evaluate(black_box(&i), &mut state).unwrap()
            })
        });
    }
}

/// The trend model of the synthetic seed study (3 speeds × 3 load scales).
fn trend_element() -> TrendForceElement {
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let s = parse_study(
        "case = \"7006.toml\"\nmethod = \"synthetic\"\ninner_speeds_rpm = [3000, 4000, 5000]\nload_scales = [0.5, 1.0, 2.0]\n",
        "bench",
        examples,
    )
    .unwrap();
    let rows: Vec<_> = s
        .points()
        .iter()
        .flat_map(|p| run_point(&s, p, &|_| {}).rows())
        .collect();
    TrendForceElement::new(fit_trends(&s, &rows).unwrap()).unwrap()
}

criterion_group!(benches, elements);
criterion_main!(benches);
