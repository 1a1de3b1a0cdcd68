//! Reference numbers of the Rust library for the C and MATLAB/Octave tests (not part of the C
//! interface): the same elements built and evaluated through the Rust API, written as text that
//! `tests/c/test_ehl.c` and `matlab/tests/test_ehl_mex.m` read and compare to round-off.
//!
//! The elements, by name (paths relative to the repository root):
//! - `dry`: dry Hertz laws of `examples/7006.toml`;
//! - `fitted`: the harmonic method's fitted laws (with damping) of
//!   `crates/ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json`, for the case at
//!   3000 rpm;
//! - `trend`: the trend curves `docs/figures/study_7006_quasi_static_trends.json`;
//! - `synthetic`: the fitted laws of the characterization of `examples/7006.toml` by the
//!   `synthetic` method (instant).
//!
//! Lines (numbers in Rust's shortest round-trip form, read exactly by `strtod`):
//! - `eval NAME q[5] v[5] inner_speed outer_speed cage_angle reaction[5] K[25] C[25] cage_speed`: one
//!   evaluation; each element's evaluations use one state, in file order;
//! - `cage NAME inner_speed outer_speed cage_speed`;
//! - `equilibrium NAME q[5] K[25]`: the element's equilibrium under the case's loads
//!   (`fitted`: the case at 3000 rpm);
//! - `summary synthetic converged iterations q[5] K[25]`: the characterization's summary.

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::case::Case;
use ehl_bearing::characterize::{characterize_bearing, CharacterizeSettings};
use ehl_bearing::force_element::{
    ElementInput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::read_case;
use std::fmt::Write;
use std::path::Path;

/// The seed case, relative to the repository root.
pub const CASE: &str = "examples/7006.toml";
/// The fitted-law report (harmonic method, 3000 rpm), relative to the repository root.
pub const REPORT: &str = "crates/ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json";
/// The fitted-law report's inner-ring speed, rpm.
pub const REPORT_RPM: f64 = 3000.0;
/// The trend curves, relative to the repository root.
pub const TRENDS: &str = "docs/figures/study_7006_quasi_static_trends.json";

fn nums(out: &mut String, v: &[f64]) {
    for x in v {
        write!(out, " {x:e}").expect("write to String");
    }
}

fn flat(m: &[[f64; 5]; 5]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

/// The case at `rpm`.
pub fn at_rpm(case: &Case, rpm: f64) -> Case {
    let mut c = case.clone();
    c.operating.inner_speed = rpm * std::f64::consts::PI / 30.0;
    c
}

/// The reference text for the repository at `root`.
pub fn reference_text(root: &Path) -> Result<String, String> {
    reference(root).map_err(|e| e.to_string())
}

fn reference(root: &Path) -> Result<String, Box<dyn std::error::Error>> {
    let case = read_case(&root.join(CASE))?;
    let case3000 = at_rpm(&case, REPORT_RPM);
    let report_text =
        std::fs::read_to_string(root.join(REPORT)).map_err(|e| format!("{REPORT}: {e}"))?;
    let report: ehl_bearing::characterize::CharacterizationReport =
        serde_json::from_str(&report_text).map_err(|e| format!("{REPORT}: {e}"))?;
    let fitted =
        LawElement::from_report(&case3000.bearing, case3000.operating.race_control, &report)?
            .with_kinematics(case3000.settings.kinematics);
    let trend_text =
        std::fs::read_to_string(root.join(TRENDS)).map_err(|e| format!("{TRENDS}: {e}"))?;
    let trend = TrendForceElement::from_json(&trend_text)?;
    let dry = LawElement::hertz_case(&case)?;
    let synthetic_method = case.method_or(Some("synthetic"))?;
    let ch = characterize_bearing(&case, &synthetic_method, &CharacterizeSettings::default())?;
    let synthetic = LawElement::from_characterization(&case, &ch)?;

    let laws = ContactLaws::hertz(&case.bearing)?;
    let q0 = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)?.displacement;
    let mut out = String::from(
        "# Reference numbers of the Rust library (crates/ehl-bearing-c/src/reference.rs)\n",
    );
    let elements: [(&str, &dyn ForceElement, f64); 4] = [
        ("dry", &dry, case.operating.inner_speed),
        ("fitted", &fitted, case3000.operating.inner_speed),
        ("trend", &trend, case.operating.inner_speed),
        ("synthetic", &synthetic, case.operating.inner_speed),
    ];
    for (name, e, speed) in elements {
        let mut state = ElementState::default();
        for k in 0..4 {
            let s = k as f64;
            let mut q = q0;
            for (qi, dq) in q.iter_mut().zip([1e-7, 2e-7, -1.5e-7, 1e-5, -1e-5]) {
                *qi += s * dq;
            }
            let v = [1e-4 * s, -2e-4 * s, 1e-4 * s, 1e-3 * s, -1e-3 * s];
            let input = ElementInput {
                displacement: q,
                velocity: v,
                inner_speed: speed,
                outer_speed: 0.0,
                cage_angle: 0.1 * s,
            };
            let r = e.evaluate(&input, &mut state)?;
            out.push_str("eval ");
            out.push_str(name);
            nums(&mut out, &q);
            nums(&mut out, &v);
            nums(&mut out, &[speed, 0.0, input.cage_angle]);
            nums(&mut out, &r.reaction);
            nums(&mut out, &flat(&r.stiffness));
            nums(&mut out, &flat(&r.damping));
            nums(&mut out, &[r.cage_speed]);
            out.push('\n');
        }
        write!(out, "cage {name}").expect("write to String");
        nums(&mut out, &[speed, 10.0, e.cage_speed(speed, 10.0)]);
        out.push('\n');
    }
    for (name, e, c) in [
        ("dry", &dry as &dyn ForceElement, &case),
        ("fitted", &fitted, &case3000),
    ] {
        let laws = ContactLaws::hertz(&c.bearing)?;
        let start = solve_equilibrium(&c.bearing, &laws, &c.operating, &c.settings)?.displacement;
        let (q, lin) = ehl_bearing::coefficients::element_equilibrium(e, c, start)?;
        write!(out, "equilibrium {name}").expect("write to String");
        nums(&mut out, &q);
        nums(&mut out, &flat(&lin.stiffness));
        out.push('\n');
    }
    write!(
        out,
        "summary synthetic {} {}",
        ch.converged as i32, ch.iterations
    )
    .expect("write to String");
    nums(&mut out, &ch.equilibrium.displacement);
    nums(&mut out, &flat(&ch.ehl_stiffness()));
    out.push('\n');
    Ok(out)
}
