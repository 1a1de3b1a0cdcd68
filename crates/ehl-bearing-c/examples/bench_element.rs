//! The timed loop of `tests/c/test_ehl.c` and `matlab/tests/bench_ehl_mex.m` in Rust, calling
//! the library directly: one force-element call with warm state (the harmonic method's fitted
//! laws with damping, 7006 at 3000 rpm, displaced, with rates and a turning cage), so the
//! per-call cost through C and MEX can be set beside the native one.
//!
//! `cargo run --release -p ehl-bearing-c --example bench_element -- [CALLS]`

use ehl_bearing::force_element::{ElementInput, ElementState, ForceElement, LawElement};
use ehl_bearing::io::read_case;
use ehl_bearing_c::reference::{at_rpm, CASE, REPORT, REPORT_RPM};
use std::time::Instant;

fn main() {
    let calls: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(200_000);
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let case = at_rpm(&read_case(&root.join(CASE)).unwrap(), REPORT_RPM);
    let report =
        serde_json::from_str(&std::fs::read_to_string(root.join(REPORT)).unwrap()).unwrap();
    let e = LawElement::from_report(&case.bearing, case.operating.race_control, &report)
        .unwrap()
        .with_kinematics(case.settings.kinematics);
    let laws = ehl_bearing::bearing::ContactLaws::hertz(&case.bearing).unwrap();
    let dry = ehl_bearing::bearing::solve_equilibrium(
        &case.bearing,
        &laws,
        &case.operating,
        &case.settings,
    )
    .unwrap();
    let (q, _) =
        ehl_bearing::coefficients::element_equilibrium(&e, &case, dry.displacement).unwrap();
    let ws = case.operating.inner_speed;
    let wc = e.cage_speed(ws, 0.0);
    let mut input = ElementInput::at(q, ws, 0.0);
    input.velocity = [1e-4, -2e-4, 1e-4, 1e-3, -1e-3];
    let mut state = ElementState::default();
    e.evaluate(&input, &mut state).unwrap();
    let t0 = Instant::now();
    let mut sum = 0.0;
    for i in 1..=calls {
        let t = i as f64 * 1e-5;
        input.displacement[1] = q[1] + 1e-8 * (1e3 * t).sin();
        input.cage_angle = wc * t;
        sum += e.evaluate(&input, &mut state).unwrap().reaction[1];
    }
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "force element in Rust (fitted laws with damping, warm state): {calls} calls, {:.2} us per call (checksum {sum:.6e})",
        1e6 * dt / calls as f64
    );
}
