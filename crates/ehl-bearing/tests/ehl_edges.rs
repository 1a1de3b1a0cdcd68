//! Physics inputs at the edges (docs/robustness.md): the EHL solver over random
//! (M, L, Ry/Rx, rheology) beyond the documented range, and the bearing equilibrium over random
//! valid geometry, speeds and loads. Each either converges with finite numbers or reports that
//! it did not (an error or `converged: false`); never a panic, never NaN.
//!
//! Default run: a few cases each. Many:
//!
//! ```text
//! EDGE_CASES=400 cargo test -p ehl-bearing --test ehl_edges -- --ignored --nocapture
//! ```

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::budget::Deadline;
use ehl_bearing::ehl::{solve_moes_within, EhlError, EhlSettings, MoesCase};
use ehl_bearing::io::parse_case;
use ehl_bearing::material::{DensityModel, ViscosityModel};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Outcome counts for the table of docs/robustness.md: converged, returned not converged,
/// reported error (diverged, not converged, time limit), refused by validation, and (of the
/// converged) a film the grid does not resolve (h_min ≤ 0: very thin films on the 33² grid).
static COUNTS: [[AtomicUsize; 5]; 2] = [
    [const { AtomicUsize::new(0) }; 5],
    [const { AtomicUsize::new(0) }; 5],
];

fn count(which: usize, outcome: usize) {
    COUNTS[which][outcome].fetch_add(1, Ordering::Relaxed);
}

fn report(which: usize) {
    let c: Vec<usize> = COUNTS[which]
        .iter()
        .map(|a| a.load(Ordering::Relaxed))
        .collect();
    println!(
        "{}: converged {} (film not resolved, h_min <= 0: {}), returned not converged {}, \
         error reported {}, refused {}",
        ["EHL", "equilibrium"][which],
        c[0],
        c[4],
        c[1],
        c[2],
        c[3]
    );
}

/// A runner with a fixed seed (CI runs the same cases every time), or a random one with
/// `EHL_TEST_RANDOM=1` (as the property tests, `tests/seeded`).
fn runner(n: u32) -> TestRunner {
    let config = Config::with_cases(n);
    if std::env::var("EHL_TEST_RANDOM").is_ok_and(|v| v != "0") {
        TestRunner::new(config)
    } else {
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha))
    }
}

fn cases(default: u32) -> u32 {
    std::env::var("EDGE_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// One EHL case on a 33² grid; Err(text) on a panic-free but wrong outcome.
fn ehl_case(
    log_m: f64,
    l: f64,
    log_ratio: f64,
    barus: bool,
    incompressible: bool,
) -> Result<(), TestCaseError> {
    let case = MoesCase::new(
        10f64.powf(log_m),
        l,
        10f64.powf(log_ratio),
        if barus {
            ViscosityModel::Barus
        } else {
            ViscosityModel::Roelands
        },
        if incompressible {
            DensityModel::Incompressible
        } else {
            DensityModel::DowsonHigginson
        },
    );
    let s = EhlSettings {
        grid: 33,
        coarsest: 9,
        max_cycles: 20,
        ..Default::default()
    };
    match solve_moes_within(&case, &s, Deadline::after_seconds(60.0)) {
        Ok(sol) => {
            let nums = [
                sol.h_central,
                sol.h_min,
                sol.p_max,
                sol.approach,
                sol.residual,
                sol.force_balance_residual,
            ];
            prop_assert!(
                nums.iter().all(|x| x.is_finite()) && sol.fields.p.iter().all(|x| x.is_finite()),
                "NaN in a returned solution: {case:?} {nums:?}"
            );
            if sol.converged {
                prop_assert!(sol.residual < sol.tolerances(&s).0, "{case:?}");
                if sol.h_min <= 0.0 {
                    count(0, 4);
                }
            }
            count(0, if sol.converged { 0 } else { 1 });
        }
        Err(EhlError::Invalid { .. }) => {
            prop_assert!(false, "valid case refused: {case:?}");
        }
        Err(e) => {
            count(0, 2);
            prop_assert!(!e.to_string().is_empty())
        }
    }
    Ok(())
}

fn run_ehl(n: u32) {
    let mut runner = runner(n);
    // M 0.1 to 1e5 (documented: about 10 to 3000), L 0.5 to 40 (documented 20–25), Ry/Rx 1 to 1000.
    runner
        .run(
            &(
                -1.0f64..5.0,
                0.5f64..40.0,
                0.0f64..3.0,
                any::<bool>(),
                any::<bool>(),
            ),
            |(m, l, r, b, i)| ehl_case(m, l, r, b, i),
        )
        .unwrap();
    report(0);
}

/// A random bearing in the generator's terms: balls, ball diameter (mm), relative gap between
/// the balls, conformities, contact angle (deg), speed (rpm), loads x, y, z (N), race control.
struct RandomBearing {
    z: u32,
    d: f64,
    gap: f64,
    conformity: [f64; 2],
    alpha: f64,
    rpm: f64,
    force: [f64; 3],
    control: usize,
}

/// A random bearing case in case-file form (geometry valid by construction, loads and speeds
/// random).
fn bearing_text(b: &RandomBearing) -> String {
    let RandomBearing {
        z,
        d,
        gap,
        conformity: [fi, fo],
        alpha,
        rpm,
        force: [fx, fy, fz],
        control,
    } = *b;
    // Pitch diameter with the balls just fitting, times 1 + gap.
    let dm = d / (std::f64::consts::PI / z as f64).sin() * (1.0 + gap);
    let rc = ["outer", "inner", "none", "no-gyroscopic"][control];
    format!(
        "[bearing]\nball_count = {z}\nball_diameter_mm = {d}\npitch_diameter_mm = {dm}\n\
         inner_conformity = {fi}\nouter_conformity = {fo}\ncontact_angle_deg = {alpha}\n\
         [operating]\ninner_speed_rpm = {rpm}\nforce_axial_n = {fx}\nforce_y_n = {fy}\n\
         force_z_n = {fz}\nrace_control = \"{rc}\"\n"
    )
}

fn run_equilibrium(n: u32) {
    let mut runner = runner(n);
    runner
        .run(
            &(
                (
                    3u32..40,
                    1.0f64..50.0,
                    0.05f64..2.0,
                    0.505f64..0.6,
                    0.505f64..0.6,
                ),
                (
                    0.0f64..45.0,
                    0.0f64..40000.0,
                    -1.0f64..5.0,
                    -1.0f64..4.0,
                    -1.0f64..4.0,
                    0usize..4,
                ),
            ),
            |((z, d, gap, fi, fo), (alpha, rpm, lx, ly, lz, rc))| {
                let f = |e: f64| if e < 0.0 { 0.0 } else { 10f64.powf(e) };
                let text = bearing_text(&RandomBearing {
                    z,
                    d,
                    gap,
                    conformity: [fi, fo],
                    alpha,
                    rpm,
                    force: [f(lx), f(ly), f(lz)],
                    control: rc,
                });
                let Ok(case) = parse_case(&text, "edge") else {
                    count(1, 3);
                    return Ok(());
                };
                let Ok(laws) = ContactLaws::hertz(&case.bearing) else {
                    count(1, 3);
                    return Ok(());
                };
                match solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings) {
                    Ok(eq) => {
                        let mut nums: Vec<f64> = eq.displacement.to_vec();
                        nums.extend(eq.reaction);
                        nums.extend(eq.stiffness.iter().flatten());
                        for b in &eq.balls {
                            nums.extend([
                                b.inner.load,
                                b.outer.load,
                                b.inner.contact_angle,
                                b.outer.max_pressure,
                            ]);
                        }
                        prop_assert!(nums.iter().all(|x| x.is_finite()), "NaN:\n{text}");
                        prop_assert!(eq.converged);
                        count(1, 0);
                    }
                    Err(e) => {
                        count(1, 2);
                        prop_assert!(!e.to_string().is_empty())
                    }
                }
                Ok(())
            },
        )
        .unwrap();
    report(1);
}

#[test]
fn ehl_beyond_the_documented_range_converges_or_says_so() {
    run_ehl(cases(4));
}

#[test]
fn equilibrium_over_random_valid_bearings_converges_or_says_so() {
    run_equilibrium(cases(64));
}

/// Many cases: `EDGE_CASES=400 cargo test -p ehl-bearing --test ehl_edges -- --ignored`.
#[test]
#[ignore]
fn ehl_edges_many() {
    run_ehl(cases(400));
}

/// Many cases: `EDGE_CASES=20000 cargo test -p ehl-bearing --test ehl_edges -- --ignored`.
#[test]
#[ignore]
fn equilibrium_edges_many() {
    run_equilibrium(cases(20000));
}
