//! The rotor time response (`ehl_bearing::rotor`): a 48-DOF shaft (8 nodes × x, y, z, α, β, θ, the
//! layout of a ROSS rotor) on two seed bearings (7006) with fitted laws and damping terms,
//! back-to-back with an axial preload, gravity and an unbalance, at 5000 rpm, cages rolling,
//! h = 20 µs. One benchmark iteration simulates 0.01 s (500 steps); the goal of issue 12 is 1 s of
//! simulated time in under 5 s, i.e. ≤ 50 ms per iteration here (≤ 100 µs per step).

use criterion::{criterion_group, criterion_main, Criterion};
use ehl_bearing::bearing::Race;
use ehl_bearing::fit::FittedLaw;
use ehl_bearing::force_element::{ForceElement, LawElement};
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::io::parse_case;
use ehl_bearing::rotor::{
    BearingSite, RotorMatrices, RotorModel, SpeedProfile, TimeOptions, Unbalance,
};
use std::sync::Arc;

const SEED: &str = include_str!("../../../examples/7006.toml");

/// Fitted-looking laws with damping, magnitudes of the seed's (as benches/force_element.rs).
fn element() -> LawElement {
    let case = parse_case(SEED, "7006.toml").unwrap();
    let b = &case.bearing;
    let a0 = b.geometry.free_contact_angle;
    let mut laws = Vec::new();
    for _ in 0..b.geometry.ball_count {
        for race in [Race::Inner, Race::Outer] {
            let (rx, ry) = b.geometry.curvature_radii(race, a0);
            let kh = HertzGeometry::new(rx, ry, b.reduced_modulus())
                .unwrap()
                .stiffness;
            laws.push(
                FittedLaw::new(kh * 5e-6_f64.powf(0.05), 1.45, 20.0, 1e-6, 12e-6)
                    .unwrap()
                    .with_damping(150.0)
                    .unwrap(),
            );
        }
    }
    LawElement::from_fitted(b, case.operating.race_control, &laws).unwrap()
}

/// A chain of 8 nodes (6 DOFs each) joined by springs: 2e7 N/m laterally and axially, 2e4
/// N·m/rad in bending, 1e3 N·m/rad in torsion; node mass 0.4 kg, transverse inertia 3e-4
/// kg·m², polar 5e-4 kg·m² (gyroscopic coupling of α and β); light proportional damping.
fn shaft() -> RotorMatrices {
    let (nodes, per) = (8, 6);
    let n = nodes * per;
    let mut m = vec![0.0; n * n];
    let mut c = vec![0.0; n * n];
    let mut g = vec![0.0; n * n];
    let mut k = vec![0.0; n * n];
    let spring = [2e7, 2e7, 2e7, 2e4, 2e4, 1e3];
    let mass = [0.4, 0.4, 0.4, 3e-4, 3e-4, 5e-4];
    for node in 0..nodes {
        for d in 0..per {
            let i = node * per + d;
            m[i * n + i] = mass[d];
            c[i * n + i] = 1e-5 * spring[d];
            if node + 1 < nodes {
                let j = i + per;
                k[i * n + i] += spring[d];
                k[j * n + j] += spring[d];
                k[i * n + j] -= spring[d];
                k[j * n + i] -= spring[d];
            }
        }
        let (a, b) = (node * per + 3, node * per + 4);
        g[a * n + b] = 5e-4;
        g[b * n + a] = -5e-4;
    }
    RotorMatrices::new(n, m, c, g, k).unwrap()
}

fn model() -> RotorModel {
    let e: Arc<dyn ForceElement> = Arc::new(element());
    // ROSS x, y, z, α, β → bearing y, z, x, θy, θz.
    let site = |node: usize| {
        let o = node * 6;
        BearingSite::new(
            e.clone(),
            [Some(o + 2), Some(o), Some(o + 1), Some(o + 3), Some(o + 4)],
        )
        .with_offset([15e-6, 0.0, 0.0, 0.0, 0.0])
    };
    let mut gravity = vec![0.0; 48];
    for node in 0..8 {
        gravity[node * 6 + 1] = -0.4 * 9.81;
    }
    RotorModel::new(
        shaft(),
        vec![site(1), site(6).mirrored()],
        vec![Unbalance {
            dofs: [24, 25],
            mass_eccentricity_kg_m: 1e-5,
            phase_rad: 0.0,
        }],
        gravity,
    )
    .unwrap()
}

fn rotor(c: &mut Criterion) {
    let model = model();
    let profile = SpeedProfile::Constant {
        speed_rad_s: 5000.0 * std::f64::consts::PI / 30.0,
    };
    let options = TimeOptions {
        step_s: 2e-5,
        duration_s: 0.01,
        record_every: 10,
        ..TimeOptions::default()
    };
    let r = model.simulate(&profile, &options, None).unwrap();
    eprintln!(
        "rotor_48dof_two_fitted_7006: {} steps, {:.2} Newton iterations/step (max {}), \
         total {:.1} ms: bearings {:.1} ms, factorization {:.2} ms",
        r.steps,
        r.newton_iterations as f64 / r.steps as f64,
        r.max_newton_iterations,
        1e3 * r.breakdown.total_s,
        1e3 * r.breakdown.bearing_s,
        1e3 * r.breakdown.factorization_s
    );
    c.bench_function("rotor_48dof_two_fitted_7006_10ms_simulated", |b| {
        b.iter(|| model.simulate(&profile, &options, None).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = rotor
}
criterion_main!(benches);
