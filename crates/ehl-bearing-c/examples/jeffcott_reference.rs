//! The Jeffcott rotor of `matlab/examples/jeffcott.json` on two ehl-bearing elements, integrated
//! by the library's rotor model (`ehl_bearing::rotor::RotorModel`: Newmark average acceleration,
//! bearing forces implicit): prints the steady unbalance amplitudes as JSON, the reference the
//! MATLAB/Octave example `matlab/examples/jeffcott_rotor.m` is checked against.
//!
//! `cargo run --release -p ehl-bearing-c --example jeffcott_reference [-- PARAMS.json]`

use ehl_bearing::force_element::{ForceElement, LawElement};
use ehl_bearing::io::read_case;
use ehl_bearing::rotor::{
    BearingSite, CageMotion, RotorMatrices, RotorModel, SpeedProfile, TimeOptions, Unbalance,
};
use ehl_bearing_c::reference::{at_rpm, CASE, REPORT};
use std::f64::consts::PI;
use std::sync::Arc;

/// The 1× amplitude of `x` sampled at times `t` over whole revolutions at speed `w`:
/// |(2/N)·Σ (x − x̄)·e^{−iωt}|.
fn amplitude(x: &[f64], t: &[f64], w: f64) -> f64 {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let (mut re, mut im) = (0.0, 0.0);
    for (xi, ti) in x.iter().zip(t) {
        re += (xi - mean) * (w * ti).cos();
        im -= (xi - mean) * (w * ti).sin();
    }
    2.0 / n * (re * re + im * im).sqrt()
}

fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = dir.join("../..");
    let params_path = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| dir.join("matlab/examples/jeffcott.json"));
    let p: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&params_path).unwrap()).unwrap();
    let g = |k: &str| {
        p[k].as_f64()
            .unwrap_or_else(|| panic!("{}: {k} missing", params_path.display()))
    };
    let (md, mj, ks) = (
        g("disk_mass_kg"),
        g("journal_mass_kg"),
        g("shaft_stiffness_n_m"),
    );
    let rpm = g("speed_rpm");
    let case = at_rpm(&read_case(&root.join(CASE)).unwrap(), rpm);
    let report =
        serde_json::from_str(&std::fs::read_to_string(root.join(REPORT)).unwrap()).unwrap();
    let e: Arc<dyn ForceElement> = Arc::new(
        LawElement::from_report(&case.bearing, case.operating.race_control, &report)
            .unwrap()
            .with_kinematics(case.settings.kinematics),
    );
    let n = 7;
    let mut m = vec![0.0; n * n];
    let mut c = vec![0.0; n * n];
    let mut k = vec![0.0; n * n];
    let masses = [md + 2.0 * mj, md, md, mj, mj, mj, mj];
    let (cd, cj, cx) = (
        g("disk_damping_n_s_m"),
        g("journal_damping_n_s_m"),
        g("axial_damping_n_s_m"),
    );
    let damping = [cx, cd, cd, cj, cj, cj, cj];
    for i in 0..n {
        m[i * n + i] = masses[i];
        c[i * n + i] = damping[i];
    }
    for (d, j) in [(1, 3), (2, 4), (1, 5), (2, 6)] {
        k[d * n + d] += ks;
        k[j * n + j] += ks;
        k[d * n + j] -= ks;
        k[j * n + d] -= ks;
    }
    let matrices = RotorMatrices::new(n, m, c, vec![0.0; n * n], k).unwrap();
    let offset = [g("preload_approach_m"), 0.0, 0.0, 0.0, 0.0];
    let a =
        BearingSite::new(e.clone(), [Some(0), Some(3), Some(4), None, None]).with_offset(offset);
    let b = BearingSite::new(e, [Some(0), Some(5), Some(6), None, None])
        .mirrored()
        .with_offset(offset);
    let mut force = vec![0.0; n];
    force[1] = g("disk_force_y_n");
    let ub = Unbalance {
        dofs: [1, 2],
        mass_eccentricity_kg_m: g("unbalance_kg_m"),
        phase_rad: 0.0,
    };
    let model = RotorModel::new(matrices, vec![a, b], vec![ub], force).unwrap();
    let w = rpm * PI / 30.0;
    let options = TimeOptions {
        step_s: g("step_s"),
        duration_s: g("duration_s"),
        cage: CageMotion::Fixed { angle_rad: 0.0 },
        ..TimeOptions::default()
    };
    let t0 = std::time::Instant::now();
    let r = model
        .simulate(&SpeedProfile::Constant { speed_rad_s: w }, &options, None)
        .unwrap();
    let seconds = t0.elapsed().as_secs_f64();
    let per_rev = (2.0 * PI / w / options.step_s).round() as usize;
    let count = per_rev * g("revolutions_measured") as usize;
    let first = r.time_s.len() - count;
    let t = &r.time_s[first..];
    let col = |i: usize| -> Vec<f64> { r.displacement[first..].iter().map(|q| q[i]).collect() };
    let out = serde_json::json!({
        "source": "ehl_bearing::rotor::RotorModel (Rust), examples/jeffcott_reference.rs",
        "steps": r.steps,
        "newton_iterations": r.newton_iterations,
        "static_disk_y_m": r.displacement[0][1],
        "static_axial_x_m": r.displacement[0][0],
        "amplitude_disk_y_m": amplitude(&col(1), t, w),
        "amplitude_disk_z_m": amplitude(&col(2), t, w),
        "amplitude_journal_a_y_m": amplitude(&col(3), t, w),
        "amplitude_journal_b_z_m": amplitude(&col(6), t, w),
        "seconds": seconds,
    });
    println!("{}", serde_json::to_string_pretty(&out).unwrap());
}
