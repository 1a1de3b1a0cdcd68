//! Bearing equilibrium against closed forms and physical expectations.
// Index loops mirror the matrix formulas in these checks.
#![allow(clippy::needless_range_loop)]

mod bearing_common;
mod seeded;
use bearing_common::fd_jacobian;
use ehl_bearing::bearing::{
    solve_equilibrium, BallState, Bearing, BearingGeometry, BearingModel, ContactLaws, Control,
    Equilibrium, EquilibriumSettings, Kinematics, OperatingPoint, RaceControl,
};
use ehl_bearing::material::Solid;
use proptest::prelude::*;
use std::f64::consts::PI;

const RPM: f64 = PI / 30.0;

fn b7006() -> Bearing {
    Bearing {
        geometry: BearingGeometry::new(11, 7e-3, 42.5e-3, 0.51, 0.54, 15f64.to_radians()).unwrap(),
        ball_material: Solid::AISI_52100,
        ring_material: Solid::AISI_52100,
    }
}

fn loads(fx: f64, fy: f64, fz: f64, my: f64, mz: f64, rpm: f64, rc: RaceControl) -> OperatingPoint {
    OperatingPoint {
        inner_speed: rpm * RPM,
        outer_speed: 0.0,
        dofs: [
            Control::Load(fx),
            Control::Load(fy),
            Control::Load(fz),
            Control::Load(my),
            Control::Load(mz),
        ],
        race_control: rc,
    }
}

fn solve(b: &Bearing, op: &OperatingPoint) -> Equilibrium {
    solve_kin(b, op, Kinematics::OperatingAngles)
}

/// Solve with the given kinematics model (the default is the textbook model at the operating
/// contact angles; `GrooveLine` is the model before the textbook kinematics).
fn solve_kin(b: &Bearing, op: &OperatingPoint, kinematics: Kinematics) -> Equilibrium {
    let laws = ContactLaws::hertz(b).unwrap();
    let settings = EquilibriumSettings {
        kinematics,
        ..Default::default()
    };
    solve_equilibrium(b, &laws, op, &settings).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// Pure thrust at zero speed: Jones' relation (Jones 1960; Harris ch. 7):
/// F_a = Z·K_n·(A(cos α0/cos α − 1))^1.5·sin α, δ_a = A·sin(α − α0)/cos α, with
/// 1/K_n^(2/3) = 1/K_i^(2/3) + 1/K_o^(2/3). The relation is exact for the model, so the tolerance
/// is set by the solver's convergence (1e-11 relative force) and round-off. With the Hertz
/// constants at the free contact angle (groove-line model) K_n is a constant; in the textbook
/// model K_n = K_n(α) at the operating angle (Harris solves the relation iteratively for it), and
/// the same relation holds with it.
#[test]
fn pure_thrust_matches_jones_relation() {
    for kin in [Kinematics::GrooveLine, Kinematics::OperatingAngles] {
        pure_thrust_jones(kin);
    }
}

fn pure_thrust_jones(kin: Kinematics) {
    let b = b7006();
    let g = &b.geometry;
    let a0 = g.free_contact_angle;
    let kn = |alpha: f64| {
        let at = if kin == Kinematics::GrooveLine {
            a0
        } else {
            alpha
        };
        let ki = b
            .hertz(ehl_bearing::bearing::Race::Inner, at)
            .unwrap()
            .stiffness;
        let ko = b
            .hertz(ehl_bearing::bearing::Race::Outer, at)
            .unwrap()
            .stiffness;
        (ki.powf(-2.0 / 3.0) + ko.powf(-2.0 / 3.0)).powf(-1.5)
    };
    let a = g.center_distance();
    let z = g.ball_count as f64;
    let thrust =
        |alpha: f64| z * kn(alpha) * (a * (a0.cos() / alpha.cos() - 1.0)).powf(1.5) * alpha.sin();
    for fa in [100.0, 1000.0, 5000.0] {
        // Independent solution of Jones' equation for α by bisection.
        let (mut lo, mut hi) = (a0 + 1e-12, 80f64.to_radians());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if thrust(mid) < fa {
                lo = mid
            } else {
                hi = mid
            }
        }
        let alpha = 0.5 * (lo + hi);
        let e = solve_kin(
            &b,
            &loads(fa, 0.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer),
            kin,
        );
        for ball in &e.balls {
            assert!(
                rel(ball.inner.contact_angle, alpha) < 1e-9,
                "α {fa} {kin:?}"
            );
            assert!(rel(ball.outer.contact_angle, alpha) < 1e-9);
            assert!(rel(ball.inner.load, fa / (z * alpha.sin())) < 1e-9);
        }
        let da = a * (alpha - a0).sin() / alpha.cos();
        assert!(rel(e.displacement[0], da) < 1e-9, "δa {fa}");
        for k in 1..5 {
            assert!(e.displacement[k].abs() < 1e-15, "{:?}", e.displacement);
        }
    }
}

#[test]
fn pure_axial_load_loads_all_balls_equally_even_at_speed() {
    let b = b7006();
    for rc in [
        RaceControl::Outer,
        RaceControl::Inner,
        RaceControl::None,
        RaceControl::NoGyroscopic,
    ] {
        let e = solve(&b, &loads(800.0, 0.0, 0.0, 0.0, 0.0, 8000.0, rc));
        let q0 = e.balls[0].inner.load;
        for ball in &e.balls {
            assert!(rel(ball.inner.load, q0) < 1e-9);
            assert!(rel(ball.outer.load, e.balls[0].outer.load) < 1e-9);
        }
    }
}

#[test]
fn radial_load_distribution_is_symmetric_about_the_load_line() {
    // Load along +y with some thrust: ball j and ball Z−j mirror each other about the y axis.
    let b = b7006();
    let e = solve(
        &b,
        &loads(300.0, 2000.0, 0.0, 0.0, 0.0, 4000.0, RaceControl::Outer),
    );
    let z = e.balls.len();
    for j in 1..z {
        let (a, m) = (&e.balls[j], &e.balls[z - j]);
        assert!((a.inner.load - m.inner.load).abs() < 1e-8 * e.balls[0].inner.load);
        assert!((a.outer.contact_angle - m.outer.contact_angle).abs() < 1e-11);
    }
    // The most loaded ball is on the load line, and no displacement leaves the load plane.
    let qmax = e.balls.iter().map(|b| b.inner.load).fold(0.0, f64::max);
    assert_eq!(qmax, e.balls[0].inner.load);
    // Nothing moves out of the load plane (z, θy) beyond round-off; θz is free and non-zero: a
    // radial load on one angular-contact bearing has an offset load centre and tilts the ring.
    assert!(e.displacement[2].abs() < 1e-9 * e.displacement[1].abs());
    assert!(e.displacement[3].abs() < 1e-9 * e.displacement[1].abs() / 0.02);
    assert!(e.displacement[4].abs() > 1e-6);
}

#[test]
fn equilibrium_residual_is_at_round_off() {
    // Seed case at every speed: the reactions reproduce the applied loads to ~1e-12 relative
    // (sums of 11 terms of ~500 N: round-off ~1e-13 N per term).
    let b = b7006();
    for rpm in [0.0, 3000.0, 4000.0, 5000.0] {
        let mut op = loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, rpm, RaceControl::Outer);
        op.dofs[3] = Control::Displacement(0.001f64.to_radians());
        op.dofs[4] = Control::Displacement(0.001f64.to_radians());
        let e = solve(&b, &op);
        for k in 0..3 {
            assert!(
                (e.reaction[k] - 1000.0).abs() < 1e-8,
                "{rpm}: {:?}",
                e.reaction
            );
        }
        // Each ball in equilibrium too: check through the 3-D balance below.
        for ball in &e.balls {
            check_ball_newton_euler(&b, ball, RaceControl::Outer, op.inner_speed);
        }
        // The groove-line model too.
        let e = solve_kin(&b, &op, Kinematics::GrooveLine);
        for ball in &e.balls {
            check_ball_newton_euler_kin(
                &b,
                ball,
                RaceControl::Outer,
                op.inner_speed,
                Kinematics::GrooveLine,
            );
        }
    }
}

/// Rebuild the forces and moments on a ball in 3-D from its reported state and check Newton–Euler:
/// ΣF = 0 and ΣM about the centre = dH/dt = ω_m x̂ × (J·Ω_ball), with Ω_ball = ω_m x̂ + ω_R ê,
/// computed with plain cross products (independent of the 2-D equations in the solver).
fn check_ball_newton_euler(b: &Bearing, ball: &BallState, rc: RaceControl, inner_speed: f64) {
    check_ball_newton_euler_kin(b, ball, rc, inner_speed, Kinematics::OperatingAngles)
}

fn check_ball_newton_euler_kin(
    b: &Bearing,
    ball: &BallState,
    rc: RaceControl,
    inner_speed: f64,
    kin: Kinematics,
) {
    let cross = |a: [f64; 3], c: [f64; 3]| {
        [
            a[1] * c[2] - a[2] * c[1],
            a[2] * c[0] - a[0] * c[2],
            a[0] * c[1] - a[1] * c[0],
        ]
    };
    let add =
        |a: [f64; 3], c: [f64; 3], s: f64| [a[0] + s * c[0], a[1] + s * c[1], a[2] + s * c[2]];
    let psi = ball.azimuth;
    let x = [1.0, 0.0, 0.0];
    let r = [0.0, psi.cos(), psi.sin()];
    let dvec = |ax: f64, ra: f64| add([ax, 0.0, 0.0], r, ra);
    let d = b.geometry.ball_diameter;
    let (ai, ao, beta) = (
        ball.inner.contact_angle,
        ball.outer.contact_angle,
        ball.pitch_angle,
    );
    let j = b.ball_inertia();
    let e_axis = dvec(beta.cos(), -beta.sin());
    let omega = add([ball.orbital_speed, 0.0, 0.0], e_axis, ball.spin_speed);
    let hdot = cross(
        [ball.orbital_speed, 0.0, 0.0],
        [j * omega[0], j * omega[1], j * omega[2]],
    );
    // The reported gyroscopic moment is dH/dt along t̂ = x̂ × r̂, and dH/dt has no other component.
    let t = cross(x, r);
    let g_t = hdot[0] * t[0] + hdot[1] * t[1] + hdot[2] * t[2];
    if rc != RaceControl::NoGyroscopic {
        assert!(
            (g_t - ball.gyroscopic_moment).abs() <= 1e-12 * g_t.abs().max(1e-12),
            "{g_t} vs {}",
            ball.gyroscopic_moment
        );
    }
    // Friction forces as reported; unless limited by μ_max·Q they carry G with λ_i + λ_o = 2.
    let (li, lo) = match rc {
        RaceControl::Outer => (0.0, 2.0),
        RaceControl::Inner => (2.0, 0.0),
        RaceControl::None => (1.0, 1.0),
        RaceControl::NoGyroscopic => (0.0, 0.0),
    };
    let g = ball.gyroscopic_moment;
    let free = |f: f64, q: f64| f.abs() < ehl_bearing::bearing::equilibrium::MU_MAX * q / 6.0;
    let unsaturated =
        free(ball.inner_friction, ball.inner.load) && free(ball.outer_friction, ball.outer.load);
    if unsaturated {
        assert!((ball.inner_friction - li * g / d).abs() <= 1e-6 * (g / d).abs() + 1e-15);
        assert!((ball.outer_friction + lo * g / d).abs() <= 1e-6 * (g / d).abs() + 1e-15);
    }
    let ni = dvec(ai.sin(), ai.cos()); // inner race pushes along +n_i
    let no = dvec(ao.sin(), ao.cos()); // outer race pushes along −n_o
    let ti = dvec(ai.cos(), -ai.sin());
    let to = dvec(ao.cos(), -ao.sin());
    let fi = add(
        [
            ball.inner.load * ni[0],
            ball.inner.load * ni[1],
            ball.inner.load * ni[2],
        ],
        ti,
        ball.inner_friction,
    );
    let fo = add(
        [
            -ball.outer.load * no[0],
            -ball.outer.load * no[1],
            -ball.outer.load * no[2],
        ],
        to,
        ball.outer_friction,
    );
    let fc = [
        0.0,
        ball.centrifugal_force * r[1],
        ball.centrifugal_force * r[2],
    ];
    let sum = add(add(fi, fo, 1.0), fc, 1.0);
    let scale = ball.inner.load + ball.outer.load + 1e-9;
    for s in sum {
        assert!(s.abs() < 1e-9 * scale, "force balance {sum:?}");
    }
    // Moments about the ball centre: inner contact at −(D/2)n_i, outer at +(D/2)n_o.
    let pi = [-0.5 * d * ni[0], -0.5 * d * ni[1], -0.5 * d * ni[2]];
    let po = [0.5 * d * no[0], 0.5 * d * no[1], 0.5 * d * no[2]];
    let m = add(cross(pi, fi), cross(po, fo), 1.0);
    if rc != RaceControl::NoGyroscopic && unsaturated {
        for k in 0..3 {
            assert!(
                (m[k] - hdot[k]).abs() < 1e-9 * (scale * d),
                "moment {m:?} vs dH/dt {hdot:?}"
            );
        }
    }
    // Pure rolling (cage frame) at the contact points at which the solver evaluates the speeds:
    // the groove-line model at the angle α_k of the line of groove centres for both contacts; the
    // textbook model at each loaded contact's operating angle (a separated inner contact falls
    // back to α_k): surface speeds match.
    let (aki, ako) = match kin {
        Kinematics::GrooveLine => (ball.kinematic_angle, ball.kinematic_angle),
        Kinematics::OperatingAngles => (
            if ball.inner.deflection >= 0.0 {
                ai
            } else if ball.inner.deflection < -0.01 * (b.geometry.inner_conformity - 0.5) * d {
                ball.kinematic_angle
            } else {
                return; // inside the blend band: no single angle to check
            },
            ao,
        ),
    };
    let nki = dvec(aki.sin(), aki.cos());
    let nko = dvec(ako.sin(), ako.cos());
    let pi = [-0.5 * d * nki[0], -0.5 * d * nki[1], -0.5 * d * nki[2]];
    let po = [0.5 * d * nko[0], 0.5 * d * nko[1], 0.5 * d * nko[2]];
    let rpi = 0.5 * b.geometry.pitch_diameter - 0.5 * d * aki.cos();
    let rpo = 0.5 * b.geometry.pitch_diameter + 0.5 * d * ako.cos();
    let wb = [
        ball.spin_speed * e_axis[0],
        ball.spin_speed * e_axis[1],
        ball.spin_speed * e_axis[2],
    ];
    let vi = cross(wb, pi);
    let vo = cross(wb, po);
    let ui = (inner_speed - ball.orbital_speed) * rpi;
    let uo = (0.0 - ball.orbital_speed) * rpo;
    let dot = |a: [f64; 3], c: [f64; 3]| a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
    assert!((dot(vi, t) - ui).abs() < 1e-9 * ui.abs().max(1e-9));
    assert!((dot(vo, t) - uo).abs() < 1e-9 * uo.abs().max(1e-9));
}

#[test]
fn gyroscopic_moment_direction_and_sign() {
    // A rotating inner ring makes the ball roll backwards (ω_R < 0, Harris' signed roll speed) and
    // the races must supply a positive moment along t̂; every race-control option satisfies 3-D
    // Newton–Euler with that moment.
    let b = b7006();
    for rc in [
        RaceControl::Outer,
        RaceControl::Inner,
        RaceControl::None,
        RaceControl::NoGyroscopic,
    ] {
        let mut op = loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, 20000.0, rc);
        op.dofs[3] = Control::Displacement(0.0);
        op.dofs[4] = Control::Displacement(0.0);
        let e = solve(&b, &op);
        let checked = e
            .balls
            .iter()
            .filter(|b| {
                let lim = ehl_bearing::bearing::equilibrium::MU_MAX / 6.0;
                b.inner_friction.abs() < lim * b.inner.load
                    && b.outer_friction.abs() < lim * b.outer.load
            })
            .count();
        // The moment balance is checked on the balls whose friction is below the limit's knee.
        assert!(checked >= 4, "{rc:?}: only {checked} balls checked");
        for ball in &e.balls {
            assert!(ball.spin_speed < 0.0 && ball.orbital_speed > 0.0);
            if rc == RaceControl::NoGyroscopic {
                assert_eq!(ball.gyroscopic_moment, 0.0);
            } else {
                assert!(ball.gyroscopic_moment > 0.0);
            }
            check_ball_newton_euler(&b, ball, rc, op.inner_speed);
        }
    }
}

#[test]
fn speed_effects_have_the_expected_signs() {
    // Centrifugal force raises the outer loads; under outer-race control the inner contact angle
    // grows and the outer one shrinks with speed (Harris, Rolling Bearing Analysis, high-speed
    // ball bearings).
    let b = b7006();
    let slow = solve(
        &b,
        &loads(1000.0, 0.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer),
    );
    let fast = solve(
        &b,
        &loads(1000.0, 0.0, 0.0, 0.0, 0.0, 15000.0, RaceControl::Outer),
    );
    let (s, f) = (&slow.balls[0], &fast.balls[0]);
    // Radial balance of the ball: Q_o cos α_o − Q_i cos α_i = F_c (+ gyroscopic friction, small).
    let split =
        f.outer.load * f.outer.contact_angle.cos() - f.inner.load * f.inner.contact_angle.cos();
    assert!(
        rel(split, f.centrifugal_force) < 0.05,
        "{split} vs {}",
        f.centrifugal_force
    );
    assert!(f.centrifugal_force > 10.0);
    // Without the gyroscopic friction the outer load itself rises (under pure thrust Q_o·sin α_o is
    // fixed by the load, so the rise is only through the smaller α_o).
    let fast_ng = solve(
        &b,
        &loads(
            1000.0,
            0.0,
            0.0,
            0.0,
            0.0,
            15000.0,
            RaceControl::NoGyroscopic,
        ),
    );
    assert!(fast_ng.balls[0].outer.load > s.outer.load + 1.0);
    assert!(f.inner.contact_angle > s.inner.contact_angle + 1e-3);
    assert!(f.outer.contact_angle < s.outer.contact_angle - 1e-3);
    assert!((s.inner.contact_angle - s.outer.contact_angle).abs() < 1e-12);
    // Orbital speed near the epicyclic value ω_i(1 − γ cos α)/2.
    let g = &b.geometry;
    let gamma = g.ball_diameter / g.pitch_diameter;
    let wm = 0.5 * 15000.0 * RPM * (1.0 - gamma * f.inner.contact_angle.cos());
    assert!(rel(f.orbital_speed, wm) < 0.02);
}

#[test]
fn stiffness_predicts_the_response_to_a_small_load_change() {
    // Fully load-controlled seed loads; perturb F_y by 1 N: Δq ≈ K⁻¹ ΔF (to second order).
    let b = b7006();
    let op = loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, 5000.0, RaceControl::Outer);
    let e0 = solve(&b, &op);
    let mut op1 = op;
    op1.dofs[1] = Control::Load(1001.0);
    let e1 = solve(&b, &op1);
    // K·Δq should equal ΔF = (0, 1, 0, 0, 0) N.
    let dq: Vec<f64> = (0..5)
        .map(|k| e1.displacement[k] - e0.displacement[k])
        .collect();
    let df: Vec<f64> = (0..5)
        .map(|r| (0..5).map(|c| e0.stiffness[r][c] * dq[c]).sum())
        .collect();
    assert!((df[1] - 1.0).abs() < 2e-3, "{df:?}");
    for k in [0, 2] {
        assert!(df[k].abs() < 2e-3, "{df:?}");
    }
    for k in [3, 4] {
        assert!(df[k].abs() < 2e-3 * 0.02, "{df:?}");
    }
}

#[test]
fn unloaded_balls_do_not_break_the_solver() {
    // Heavy radial load with moderate thrust (F_a/F_r = 0.2 < 1.25·tan α): several balls lose
    // contact with the inner race.
    let b = b7006();
    for rpm in [0.0, 5000.0] {
        let mut op = loads(600.0, 3000.0, 0.0, 0.0, 0.0, rpm, RaceControl::Outer);
        op.dofs[3] = Control::Displacement(0.0);
        op.dofs[4] = Control::Displacement(0.0);
        let e = solve(&b, &op);
        // At rest the unloaded balls carry exactly nothing; at speed centrifugal force pushes them
        // along the outer groove until the close-conforming inner groove touches them lightly.
        let qmax = e.balls.iter().map(|b| b.inner.load).fold(0.0, f64::max);
        let unloaded = e
            .balls
            .iter()
            .filter(|b| b.inner.load < 0.01 * qmax)
            .count();
        if rpm == 0.0 {
            assert!(e.balls.iter().filter(|b| b.inner.load == 0.0).count() >= 3);
        }
        assert!(unloaded >= 3, "{rpm}: {unloaded}");
        assert!((e.reaction[1] - 3000.0).abs() < 1e-7);
    }
    // Zero load, zero speed: nothing to do.
    let e = solve(&b, &loads(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer));
    assert_eq!(e.displacement, [0.0; 5]);
}

#[test]
fn loads_the_bearing_cannot_carry_are_errors_with_residual_or_reason() {
    let b = b7006();
    let laws = ContactLaws::hertz(&b).unwrap();
    let error = |op: OperatingPoint, settings: EquilibriumSettings| {
        solve_equilibrium(&b, &laws, &op, &settings)
            .unwrap_err()
            .to_string()
    };
    for (what, op) in [
        // A reversed thrust on a single-row angular-contact bearing.
        (
            "reversed thrust",
            loads(-1000.0, 0.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer),
        ),
        // An absurd load: deflections beyond 2 % of the ball diameter.
        (
            "overload",
            loads(1e7, 0.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer),
        ),
    ] {
        let err = error(op, EquilibriumSettings::default());
        assert!(err.contains("cannot carry"), "{what}: {err}");
    }
    // Too few iterations: not converged, with the residual in the message.
    let settings = EquilibriumSettings {
        max_iterations: 1,
        ..Default::default()
    };
    let err = error(
        loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
        settings,
    );
    assert!(
        err.contains("did not converge") && err.contains("residual"),
        "{err}"
    );
    // Zero load at speed: centrifugal force holds every ball on the outer race and nothing
    // touches the inner ring, whose position is then undetermined.
    let err = error(
        loads(0.0, 0.0, 0.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
        EquilibriumSettings::default(),
    );
    assert!(err.contains("undetermined"), "{err}");
    // Kept below for the message check of the non-converged case.
    let err = error(
        loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
        EquilibriumSettings {
            max_iterations: 1,
            ..Default::default()
        },
    );
    assert!(
        err.contains("did not converge") && err.contains("residual"),
        "{err}"
    );
}

proptest! {
    #![proptest_config(seeded::config(24))]
    /// The analytic (dual-number + implicit-function) Jacobian equals central finite differences
    /// of the reactions, for random displacements, speeds and race controls. Tolerance: central
    /// differences with h = 0.1 nm have truncation error ~h²·f‴ and round-off ~ε·F/h ≈ 1e-4 N/m·…;
    /// 1e-5 of the largest entry in the column covers both.
    #[test]
    fn jacobian_matches_finite_differences(
        x in 15e-6..40e-6f64,
        y in -8e-6..8e-6f64,
        z in -8e-6..8e-6f64,
        ty in -2e-4..2e-4f64,
        tz in -2e-4..2e-4f64,
        rpm in 0.0..12000.0f64,
        rc in 0usize..4,
    ) {
        let b = b7006();
        let laws = ContactLaws::hertz(&b).unwrap();
        let rc = [RaceControl::Outer, RaceControl::Inner, RaceControl::None, RaceControl::NoGyroscopic][rc];
        let model = BearingModel::new(&b, &laws, rpm * RPM, 0.0, rc).unwrap();
        let q = [x, y, z, ty, tz];
        let an = model.evaluate(&q).unwrap().jacobian;
        let fd = fd_jacobian(&model, &q, 4e-9);
        for c in 0..5 {
            let colmax = (0..5).map(|r| an[r][c].abs()).fold(0.0, f64::max);
            for r in 0..5 {
                prop_assert!((an[r][c] - fd[r][c]).abs() <= 1e-5 * colmax,
                    "J[{}][{}] analytic {} fd {}", r, c, an[r][c], fd[r][c]);
            }
        }
    }
}

/// A knife edge of the per-ball Newton path (found by `jacobian_matches_finite_differences`):
/// at x + 0.1 nm every start of ball 0 stalled (residual 3.2 N) 10 µm from its solution, while
/// x − 0.1 nm and x solved. The ball solver now restarts from a neighbouring problem's solution;
/// the reaction must be smooth across the three points (second difference ≪ first).
#[test]
fn ball_newton_knife_edge_is_crossed_by_continuation() {
    let b = b7006();
    let laws = ContactLaws::hertz(&b).unwrap();
    let model =
        BearingModel::new(&b, &laws, 7760.6267946695125 * RPM, 0.0, RaceControl::Outer).unwrap();
    let q = [
        2.3691876344347476e-5,
        -7.753754240690137e-6,
        0.0,
        0.0,
        -7.131781859148633e-5,
    ];
    let h = 1e-10;
    let f = |dx: f64| {
        let mut qq = q;
        qq[0] += dx;
        model.evaluate(&qq).unwrap().reaction[0]
    };
    let (fm, f0, fp) = (f(-h), f(0.0), f(h));
    let first = (fp - fm).abs();
    let second = (fp - 2.0 * f0 + fm).abs();
    assert!(first > 1e-3, "no slope: {fm} {f0} {fp}");
    assert!(second < 1e-3 * first, "not smooth: {fm} {f0} {fp}");
}

#[test]
fn stiffness_is_the_jacobian_at_equilibrium_and_symmetric_only_at_rest() {
    let b = b7006();
    let laws = ContactLaws::hertz(&b).unwrap();
    for (rpm, kin, symmetric) in [
        (0.0, Kinematics::GrooveLine, true),
        (15000.0, Kinematics::GrooveLine, false),
        (0.0, Kinematics::OperatingAngles, false),
        (15000.0, Kinematics::OperatingAngles, false),
    ] {
        let e = solve_kin(
            &b,
            &loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, rpm, RaceControl::Outer),
            kin,
        );
        let model = BearingModel::new(&b, &laws, rpm * RPM, 0.0, RaceControl::Outer)
            .unwrap()
            .with_kinematics(kin);
        let j = model.evaluate(&e.displacement).unwrap().jacobian;
        let mut asym = 0.0_f64;
        for r in 0..5 {
            for c in 0..5 {
                assert!((j[r][c] - e.stiffness[r][c]).abs() <= 1e-9 * j[r][r].abs().max(1.0));
                asym = asym.max((e.stiffness[r][c] - e.stiffness[c][r]).abs() / e.stiffness[0][0]);
            }
        }
        // At rest the Hertz model with constant K is conservative: the stiffness is symmetric to
        // round-off. At speed the centrifugal and gyroscopic terms make it (slightly)
        // unsymmetric, and so does a Hertz constant that follows the contact angle (the force
        // stays along the normal while K(α) varies: no potential), and it is not symmetrized.
        if symmetric {
            assert!(asym < 1e-9, "{asym}");
        } else {
            assert!(asym > 1e-7, "{rpm} {kin:?}: {asym}");
        }
    }
}

#[test]
fn a_little_thrust_under_heavy_radial_load_is_carried_and_a_deep_groove_bearing_takes_reversed_thrust(
) {
    // Angular-contact: F_a from 0 to 400 N under F_r = 3000 N all solve (the loaded contacts sit
    // within a degree or two of the groove bottom, above the −5° shoulder limit), consistently.
    let b = b7006();
    for fa in [0.0, 10.0, 50.0, 200.0, 400.0] {
        let e = solve(
            &b,
            &loads(fa, 3000.0, 0.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
        );
        assert!((e.reaction[0] - fa).abs() < 1e-6, "{fa}");
    }
    // Deep-groove bearing given by its clearance (Hamrock's worked example of a 209 bearing):
    // a reversed thrust is carried on the other groove flank.
    let text = "[bearing]\nball_count = 9\nball_diameter_mm = 12.7\npitch_diameter_mm = 64.9985\ninner_conformity = 0.52\nouter_conformity = 0.52\ndiametral_clearance_mm = 0.015\n[operating]\ninner_speed_rpm = 3820\nforce_axial_n = -100\nforce_y_n = 8900\ntilt_y_deg = 0\ntilt_z_deg = 0\n";
    let case = ehl_bearing::io::parse_case(text, "209").unwrap();
    let laws = ContactLaws::hertz(&case.bearing).unwrap();
    let e = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings).unwrap();
    assert!(e.balls[0].inner.contact_angle < 0.0);
    assert!((e.reaction[0] + 100.0).abs() < 1e-6);
}

#[test]
fn no_spin_at_the_controlling_race_and_epicyclic_speeds_for_any_ring_speeds() {
    // Outer-race control: the ball's angular velocity relative to the outer race has no component
    // along the outer contact normal at the kinematic angle α_k (that is what defines β).
    // Epicyclic reference (pure rolling, Harris): ω_m = [ω_i(1 − γ cos α) + ω_o(1 + γ cos α)]/2.
    let b = b7006();
    let gamma = b.geometry.ball_diameter / b.geometry.pitch_diameter;
    for (wi, wo) in [
        (5000.0, 0.0),
        (0.0, 5000.0),
        (4000.0, -3000.0),
        (-5000.0, 0.0),
    ] {
        let mut op = loads(1000.0, 500.0, 0.0, 0.0, 0.0, 0.0, RaceControl::Outer);
        op.inner_speed = wi * RPM;
        op.outer_speed = wo * RPM;
        let e = solve_kin(&b, &op, Kinematics::GrooveLine);
        for ball in &e.balls {
            let ak = ball.kinematic_angle;
            let (beta, wm, wr) = (ball.pitch_angle, ball.orbital_speed, ball.spin_speed);
            // Relative angular velocity in (axial, radial): ω_R·(cos β, −sin β) − (ω_o − ω_m)·(1, 0).
            let rel = [wr * beta.cos() - (wo * RPM - wm), -wr * beta.sin()];
            let spin = rel[0] * ak.sin() + rel[1] * ak.cos();
            assert!(
                spin.abs() < 1e-9 * wr.abs().max(1.0),
                "spin {spin} at {wi}/{wo}"
            );
            let epi =
                0.5 * (wi * RPM * (1.0 - gamma * ak.cos()) + wo * RPM * (1.0 + gamma * ak.cos()));
            // Exact for β = α_k only; β differs from α_k by ~3°, which changes ω_m by < 0.5 %.
            assert!(
                (wm - epi).abs() <= 5e-3 * epi.abs().max(1.0),
                "{wm} vs {epi}"
            );
        }
        // Reversing both ring speeds reverses the kinematics and leaves the loads.
        if (wi, wo) == (-5000.0, 0.0) {
            let fwd = solve_kin(
                &b,
                &loads(1000.0, 500.0, 0.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
                Kinematics::GrooveLine,
            );
            for (a, c) in e.balls.iter().zip(&fwd.balls) {
                assert!((a.inner.load - c.inner.load).abs() < 1e-9 * c.inner.load);
                assert!((a.orbital_speed + c.orbital_speed).abs() < 1e-9 * c.orbital_speed.abs());
            }
        }
    }
}

#[test]
fn approximations_are_flagged_at_very_high_speed() {
    // Groove-line model: at 50 000 rpm the seed's contact angles split far from the groove-centre
    // angle at which the kinematics are evaluated: the result says so. The textbook model
    // evaluates them at the contact angles and has no such warning.
    let b = b7006();
    let op = loads(
        1000.0,
        1000.0,
        1000.0,
        0.0,
        0.0,
        50000.0,
        RaceControl::Outer,
    );
    let e = solve_kin(&b, &op, Kinematics::GrooveLine);
    assert!(
        e.warnings.iter().any(|w| w.contains("groove-centre angle")),
        "{:?}",
        e.warnings
    );
    let e = solve(&b, &op);
    assert!(
        !e.warnings.iter().any(|w| w.contains("groove-centre angle")),
        "{:?}",
        e.warnings
    );
    for kin in [Kinematics::GrooveLine, Kinematics::OperatingAngles] {
        let e = solve_kin(
            &b,
            &loads(1000.0, 1000.0, 1000.0, 0.0, 0.0, 5000.0, RaceControl::Outer),
            kin,
        );
        assert!(e.warnings.is_empty(), "{:?}", e.warnings);
    }
}
