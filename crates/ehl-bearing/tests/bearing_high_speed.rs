//! High-speed fidelity of the bearing model: the textbook (Jones–Harris) kinematics at
//! each contact's operating angle, checked from first principles and against an independent
//! implementation of the textbook equations of docs/bearing.md.
// Index loops mirror the matrix formulas in these checks.
#![allow(clippy::needless_range_loop)]

mod bearing_common;
mod seeded;
use bearing_common::fd_jacobian;
use ehl_bearing::bearing::equilibrium::MU_MAX;
use ehl_bearing::bearing::{
    solve_equilibrium, BallState, Bearing, BearingModel, ContactLaws, Control, Equilibrium,
    EquilibriumSettings, Kinematics, OperatingPoint, RaceControl,
};
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::io::{parse_case, read_case};
use proptest::prelude::*;
use std::f64::consts::PI;

const RPM: f64 = PI / 30.0;
const CASE_218: &str = include_str!("../../../examples/218_high_speed.toml");
const SEED: &str = include_str!("../../../examples/7006.toml");

fn b218() -> Bearing {
    parse_case(CASE_218, "218").unwrap().bearing
}

fn b7006() -> Bearing {
    parse_case(SEED, "7006").unwrap().bearing
}

fn op(fx: f64, fy: f64, fz: f64, rpm: f64, rc: RaceControl) -> OperatingPoint {
    OperatingPoint {
        inner_speed: rpm * RPM,
        outer_speed: 0.0,
        dofs: [
            Control::Load(fx),
            Control::Load(fy),
            Control::Load(fz),
            Control::Load(0.0),
            Control::Load(0.0),
        ],
        race_control: rc,
    }
}

fn solve(b: &Bearing, op: &OperatingPoint) -> Equilibrium {
    let laws = ContactLaws::hertz(b).unwrap();
    solve_equilibrium(b, &laws, op, &EquilibriumSettings::default()).unwrap()
}

type V3 = [f64; 3];
fn cross(a: V3, c: V3) -> V3 {
    [
        a[1] * c[2] - a[2] * c[1],
        a[2] * c[0] - a[0] * c[2],
        a[0] * c[1] - a[1] * c[0],
    ]
}
fn dot(a: V3, c: V3) -> f64 {
    a[0] * c[0] + a[1] * c[1] + a[2] * c[2]
}
fn lin(a: V3, sa: f64, c: V3, sc: f64) -> V3 {
    [
        sa * a[0] + sc * c[0],
        sa * a[1] + sc * c[1],
        sa * a[2] + sc * c[2],
    ]
}

/// The ball's frame in 3-D: x̂, r̂, t̂ and a vector from (axial, radial) components.
struct Frame {
    x: V3,
    r: V3,
    t: V3,
}
impl Frame {
    fn of(ball: &BallState) -> Self {
        let psi = ball.azimuth;
        let x = [1.0, 0.0, 0.0];
        let r = [0.0, psi.cos(), psi.sin()];
        Frame {
            x,
            r,
            t: cross(x, r),
        }
    }
    fn v(&self, ax: f64, ra: f64) -> V3 {
        lin(self.x, ax, self.r, ra)
    }
}

/// Kinematics from 3-D angular velocities, in the inertial frame: the ball centre C at radius
/// d_m/2 orbits at ω_m about x̂; the ball turns at Ω_ball = ω_m x̂ + ω_R ê; a ring turns at ω x̂.
/// At a contact point P (C − (D/2)n̂_i inner, C + (D/2)n̂_o outer) pure rolling means equal
/// material velocities, v_ball = ω_m x̂ × C + Ω_ball × (P − C) and v_ring = ω x̂ × P; spin is the
/// component of Ω_ball − ω x̂ along the normal, roll its component along τ̂ = (cos α, −sin α).
/// Returns (slip speed / pitch-circle speed, spin, roll) for the inner and the outer contact.
fn contact_kinematics(b: &Bearing, ball: &BallState, wi: f64, wo: f64) -> [(f64, f64, f64); 2] {
    let f = Frame::of(ball);
    let d = b.geometry.ball_diameter;
    let c = lin(f.r, 0.5 * b.geometry.pitch_diameter, f.x, 0.0);
    let e = f.v(ball.pitch_angle.cos(), -ball.pitch_angle.sin());
    let omega = lin(f.x, ball.orbital_speed, e, ball.spin_speed);
    let mut out = [(0.0, 0.0, 0.0); 2];
    for (k, (alpha, w, side)) in [
        (ball.inner.contact_angle, wi, -1.0),
        (ball.outer.contact_angle, wo, 1.0),
    ]
    .into_iter()
    .enumerate()
    {
        let n = f.v(alpha.sin(), alpha.cos());
        let tau = f.v(alpha.cos(), -alpha.sin());
        let arm = lin(n, 0.5 * d * side, n, 0.0);
        let p = lin(c, 1.0, arm, 1.0);
        let v_ball = lin(
            cross(lin(f.x, ball.orbital_speed, f.x, 0.0), c),
            1.0,
            cross(omega, arm),
            1.0,
        );
        let v_ring = cross(lin(f.x, w, f.x, 0.0), p);
        let slip = lin(v_ball, 1.0, v_ring, -1.0);
        // Reference speed: the ball centre's and the ring's pitch-circle speeds (a contact on a
        // ring at rest has zero surface speed when it rolls).
        let speed = 0.5 * b.geometry.pitch_diameter * (ball.orbital_speed.abs() + w.abs());
        let rel = lin(omega, 1.0, f.x, -w);
        out[k] = (
            dot(slip, slip).sqrt() / speed.max(1e-300),
            dot(rel, n),
            dot(rel, tau),
        );
    }
    out
}

/// Pure rolling at both contact centres and zero spin at the controlling race, from the 3-D
/// angular velocities, at high speed; the reported spin-to-roll ratios agree with them.
#[test]
fn kinematics_from_3d_angular_velocities_at_high_speed() {
    let cases = [
        (b218(), op(22250.0, 0.0, 0.0, 15000.0, RaceControl::Outer)),
        (b218(), op(22250.0, 0.0, 0.0, 20000.0, RaceControl::Inner)),
        (b218(), op(22250.0, 0.0, 0.0, 10000.0, RaceControl::None)),
        (b218(), op(8000.0, 6000.0, 0.0, 15000.0, RaceControl::Outer)),
        (
            b7006(),
            op(1000.0, 1000.0, 1000.0, 30000.0, RaceControl::Outer),
        ),
        (
            b7006(),
            op(1000.0, 1000.0, 1000.0, 30000.0, RaceControl::Inner),
        ),
    ];
    for (b, o) in cases {
        let e = solve(&b, &o);
        let mut checked = 0;
        for (j, ball) in e.balls.iter().enumerate() {
            if ball.inner.load <= 0.0 {
                continue; // separated: kinematics from the fallback angle (below)
            }
            checked += 1;
            let [(slip_i, spin_i, roll_i), (slip_o, spin_o, roll_o)] =
                contact_kinematics(&b, ball, o.inner_speed, o.outer_speed);
            // Round-off of ~1e-16 times speeds of 100 m/s over surface speeds of tens of m/s.
            assert!(
                slip_i < 1e-10,
                "{:?} ball {j}: inner slip {slip_i}",
                o.race_control
            );
            assert!(
                slip_o < 1e-10,
                "{:?} ball {j}: outer slip {slip_o}",
                o.race_control
            );
            let wr = ball.spin_speed.abs();
            match o.race_control {
                RaceControl::Outer => assert!(spin_o.abs() < 1e-10 * wr, "{spin_o}"),
                RaceControl::Inner => assert!(spin_i.abs() < 1e-10 * wr, "{spin_i}"),
                _ => {
                    // Neither race controls: both contacts spin, in opposite senses about n̂.
                    assert!(spin_i.abs() > 1e-3 * wr && spin_o.abs() > 1e-3 * wr);
                }
            }
            assert!((ball.inner.spin_to_roll - spin_i / roll_i).abs() < 1e-9);
            assert!((ball.outer.spin_to_roll - spin_o / roll_o).abs() < 1e-9);
        }
        assert!(checked >= 3, "{:?}: {checked} loaded balls", o.race_control);
    }
}

/// ΣF = 0 and ΣM = dH/dt per ball in 3-D at high speed, from the reported loads, angles,
/// friction forces and speeds with plain cross products. Where the friction limit μ_max·Q
/// saturates (the ball pivots), the contacts supply the fraction |F|/F_needed of dH/dt: the check
/// is that they supply exactly that and nothing about the other axes.
#[test]
fn newton_euler_per_ball_in_3d_at_high_speed() {
    for (b, o) in [
        (b218(), op(22250.0, 0.0, 0.0, 15000.0, RaceControl::Outer)),
        (b218(), op(22250.0, 0.0, 0.0, 5000.0, RaceControl::Inner)),
        (b218(), op(8000.0, 6000.0, 0.0, 15000.0, RaceControl::Outer)),
        (
            b7006(),
            op(1000.0, 1000.0, 1000.0, 30000.0, RaceControl::None),
        ),
    ] {
        let e = solve(&b, &o);
        let d = b.geometry.ball_diameter;
        let j_ball = b.ball_inertia();
        for ball in &e.balls {
            let f = Frame::of(ball);
            let (ai, ao) = (ball.inner.contact_angle, ball.outer.contact_angle);
            let ni = f.v(ai.sin(), ai.cos());
            let no = f.v(ao.sin(), ao.cos());
            let fi = lin(
                ni,
                ball.inner.load,
                f.v(ai.cos(), -ai.sin()),
                ball.inner_friction,
            );
            let fo = lin(
                no,
                -ball.outer.load,
                f.v(ao.cos(), -ao.sin()),
                ball.outer_friction,
            );
            let fc = lin(f.r, ball.centrifugal_force, f.x, 0.0);
            let sum = lin(lin(fi, 1.0, fo, 1.0), 1.0, fc, 1.0);
            let scale = ball.inner.load + ball.outer.load + ball.centrifugal_force;
            for s in sum {
                assert!(s.abs() < 1e-9 * scale, "force balance {sum:?}");
            }
            let m = lin(
                cross(lin(ni, -0.5 * d, ni, 0.0), fi),
                1.0,
                cross(lin(no, 0.5 * d, no, 0.0), fo),
                1.0,
            );
            let e_axis = f.v(ball.pitch_angle.cos(), -ball.pitch_angle.sin());
            let omega = lin(f.x, ball.orbital_speed, e_axis, ball.spin_speed);
            let hdot = cross(
                lin(f.x, ball.orbital_speed, f.x, 0.0),
                lin(omega, j_ball, f.x, 0.0),
            );
            // dH/dt lies along t̂ and is the reported moment.
            let g = dot(hdot, f.t);
            assert!((g - ball.gyroscopic_moment).abs() < 1e-12 * g.abs().max(1e-12));
            assert!(dot(hdot, f.x).abs() + dot(hdot, f.r).abs() < 1e-12 * g.abs().max(1e-12));
            // Resisted fraction: |F| over the needed friction at the contact(s) that carry it.
            let need = ball.inner.friction_needed + ball.outer.friction_needed;
            let have = ball.inner_friction.abs() + ball.outer_friction.abs();
            let fraction = if need > 0.0 { have / need } else { 1.0 };
            assert!(fraction <= 1.0 + 1e-12 && fraction > 0.5, "{fraction}");
            for k in 0..3 {
                assert!(
                    (m[k] - fraction * hdot[k]).abs() < 1e-9 * scale * d,
                    "moment {m:?} vs {fraction}·dH/dt {hdot:?}"
                );
            }
        }
    }
}

/// An independent implementation of the textbook high-speed equations for pure thrust
/// (docs/bearing.md §1, Jones 1960; Harris, *Rolling Bearing Analysis*), outer-race control,
/// written from the equations in the docs, not from the solver: Harris' geometry with the ball
/// centre (X1, X2) and the inner groove centre (A1, A2) = (A sin α0 + δ_a, A cos α0), his explicit
/// ω_m/ω, ω_R/ω and tan β, M_g = J·ω_R·ω_m·sin β, the λ-form ball equilibrium with the friction
/// limit of docs/bearing.md §2.5, exact Hertz constants at each operating angle (HertzGeometry),
/// and Newton with finite-difference Jacobians.
struct Textbook {
    z: f64,
    d: f64,
    dm: f64,
    ri: f64,
    ro: f64,
    a: f64,
    a0: f64,
    m: f64,
    j: f64,
    ry_i: f64,
    ry_o: f64,
    e_red: f64,
    omega: f64,
    /// No friction limit: the gyroscopic moment fully resisted (the textbook's race control).
    full_control: bool,
}

struct TextbookBall {
    ai: f64,
    ao: f64,
    qi: f64,
    qo: f64,
    fa: f64,
}

impl Textbook {
    fn new(b: &Bearing, rpm: f64) -> Self {
        let g = &b.geometry;
        let d = g.ball_diameter;
        let m = b.ball_material.density * PI * d.powi(3) / 6.0;
        let (e, nu) = (
            b.ball_material.youngs_modulus,
            b.ball_material.poisson_ratio,
        );
        Textbook {
            z: g.ball_count as f64,
            d,
            dm: g.pitch_diameter,
            ri: (g.inner_conformity - 0.5) * d,
            ro: (g.outer_conformity - 0.5) * d,
            a: (g.inner_conformity + g.outer_conformity - 1.0) * d,
            a0: g.free_contact_angle,
            m,
            j: m * d * d / 10.0,
            ry_i: g.inner_conformity * d / (2.0 * g.inner_conformity - 1.0),
            ry_o: g.outer_conformity * d / (2.0 * g.outer_conformity - 1.0),
            e_red: e / (1.0 - nu * nu), // same steel for ball and rings
            omega: rpm * RPM,
            full_control: false,
        }
    }

    fn hertz_k(&self, rx: f64, ry: f64) -> f64 {
        HertzGeometry::new(rx, ry, self.e_red).unwrap().stiffness
    }

    /// Residuals of the ball equilibrium at ball centre x for axial displacement da, and the
    /// ball's state.
    fn ball(&self, x: [f64; 2], da: f64) -> ([f64; 2], TextbookBall) {
        let a1 = self.a * self.a0.sin() + da;
        let a2 = self.a * self.a0.cos();
        let lo = x[0].hypot(x[1]);
        let li = (a1 - x[0]).hypot(a2 - x[1]);
        let (dlo, dli) = (lo - self.ro, li - self.ri);
        let (so, co) = (x[0] / lo, x[1] / lo);
        let (si, ci) = ((a1 - x[0]) / li, (a2 - x[1]) / li);
        let gamma = self.d / self.dm;
        let ki = self.hertz_k(
            self.d * (self.dm - self.d * ci) / (2.0 * self.dm),
            self.ry_i,
        );
        let ko = self.hertz_k(
            self.d * (self.dm + self.d * co) / (2.0 * self.dm),
            self.ry_o,
        );
        let qi = ki * dli.max(0.0).powf(1.5);
        let qo = ko * dlo.max(0.0).powf(1.5);
        // Harris, outer-race control: tan β = sin α_o/(cos α_o + γ);
        // ω_m/ω = 1/(1 + P_i/P_o), ω_R/ω = −1/(γ cos β (P_o + P_i)),
        // P_o = (cos α_o + tan β sin α_o)/(1 + γ cos α_o), P_i = (cos α_i + tan β sin α_i)/(1 − γ cos α_i).
        let tb = so / (co + gamma);
        let beta = tb.atan();
        let po = (co + tb * so) / (1.0 + gamma * co);
        let pi_ = (ci + tb * si) / (1.0 - gamma * ci);
        let wm = self.omega / (1.0 + pi_ / po);
        let wr = -self.omega / (gamma * beta.cos() * (po + pi_));
        let fc = 0.5 * self.m * self.dm * wm * wm;
        let mg = self.j * wr * wm * beta.sin();
        // λ_i = 0, λ_o = 2; friction F^H in full up to 95 % of μ_max·Q, then
        // μ_max·Q·(1 − 0.05/(1 + t + t²)), t = (|F^H|/μ_max·Q − 0.95)/0.05 (docs/bearing.md §2.5);
        // no limit at all with `full_control` (the textbook's assumption).
        let full = self.full_control;
        let sat = |f: f64, lim: f64| {
            if full {
                f
            } else if f == 0.0 || lim <= 0.0 {
                0.0
            } else if f.abs() <= 0.95 * lim {
                f
            } else {
                let t = (f.abs() / lim - 0.95) / 0.05;
                f.signum() * lim * (1.0 - 0.05 / (1.0 + t + t * t))
            }
        };
        let fi_h = 0.0;
        let fo_h = sat(2.0 * mg / self.d, MU_MAX * qo);
        let r1 = qi * si - qo * so - fi_h * ci + fo_h * co;
        let r2 = qi * ci - qo * co + fi_h * si - fo_h * so + fc;
        (
            [r1, r2],
            TextbookBall {
                ai: si.atan2(ci),
                ao: so.atan2(co),
                qi,
                qo,
                fa: self.z * (qi * si - fi_h * ci),
            },
        )
    }

    /// Ball equilibrium at axial displacement da by damped Newton from x.
    fn solve_ball(&self, mut x: [f64; 2], da: f64) -> ([f64; 2], TextbookBall) {
        for _ in 0..200 {
            let (r, _) = self.ball(x, da);
            let h = 1e-11;
            let mut jac = [[0.0; 2]; 2];
            for c in 0..2 {
                let mut xp = x;
                let mut xm = x;
                xp[c] += h;
                xm[c] -= h;
                let (rp, _) = self.ball(xp, da);
                let (rm, _) = self.ball(xm, da);
                for k in 0..2 {
                    jac[k][c] = (rp[k] - rm[k]) / (2.0 * h);
                }
            }
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            let s0 = -(jac[1][1] * r[0] - jac[0][1] * r[1]) / det;
            let s1 = -(-jac[1][0] * r[0] + jac[0][0] * r[1]) / det;
            let n0 = r[0].hypot(r[1]);
            let mut lam = 1.0;
            loop {
                let xn = [x[0] + lam * s0, x[1] + lam * s1];
                let (rn, _) = self.ball(xn, da);
                if rn[0].hypot(rn[1]) < n0 || lam < 1e-6 {
                    x = xn;
                    break;
                }
                lam *= 0.5;
            }
            if s0.abs().max(s1.abs()) < 1e-16 {
                break;
            }
        }
        let (_, st) = self.ball(x, da);
        (x, st)
    }

    /// Axial displacement for thrust fa by the secant method; returns (δ_a, ball, dF_a/dδ_a).
    fn solve_thrust(&self, fa: f64, start: (f64, [f64; 2])) -> (f64, TextbookBall, f64, [f64; 2]) {
        let (mut da, mut x) = start;
        let mut prev: Option<(f64, f64)> = None;
        for _ in 0..100 {
            let (xn, st) = self.solve_ball(x, da);
            x = xn;
            let r = st.fa - fa;
            if r.abs() < 1e-10 * fa {
                break;
            }
            let slope = match prev {
                Some((dp, rp)) if (da - dp).abs() > 0.0 => (r - rp) / (da - dp),
                _ => 1e9,
            };
            prev = Some((da, r));
            da -= r / slope;
        }
        let (_, st) = self.solve_ball(x, da);
        // Axial stiffness by central differences of F_a(δ_a), h = 1 nm (truncation ~h²F‴/F′ ≈ 1e-8).
        let h = 1e-9;
        let fp = self.solve_ball(x, da + h).1.fa;
        let fm = self.solve_ball(x, da - h).1.fa;
        (da, st, (fp - fm) / (2.0 * h), x)
    }
}

/// The 218-size bearing of Harris' high-speed example (22.25 kN thrust, outer-race control) at
/// 0–20000 rpm: the solver against the independent textbook implementation, and the textbook
/// trends (inner angle up, outer angle down, outer load up, axial stiffness down with speed).
#[test]
fn harris_218_high_speed_against_independent_textbook_equations() {
    let b = b218();
    let fa = 22250.0;
    let mut last: Option<(Equilibrium, f64)> = None;
    let t0 = Textbook::new(&b, 0.0);
    let mut start = (
        30e-6,
        [(t0.ro + 10e-6) * t0.a0.sin(), (t0.ro + 10e-6) * t0.a0.cos()],
    );
    for rpm in [0.0, 5000.0, 10000.0, 15000.0, 20000.0] {
        let e = solve(&b, &op(fa, 0.0, 0.0, rpm, RaceControl::Outer));
        let tb = Textbook::new(&b, rpm);
        let (da, st, ka, x) = tb.solve_thrust(fa, start);
        start = (da, x);
        let ball = &e.balls[0];
        // Both solve the same equations to 1e-10 or better; Hertz constants from the Chebyshev fit
        // (1e-12) against exact ones: agreement to 1e-8 relative.
        let tol = 1e-8;
        assert!(
            (ball.inner.contact_angle - st.ai).abs() < tol,
            "{rpm}: α_i {} vs {}",
            ball.inner.contact_angle.to_degrees(),
            st.ai.to_degrees()
        );
        assert!((ball.outer.contact_angle - st.ao).abs() < tol, "{rpm}: α_o");
        assert!((ball.inner.load / st.qi - 1.0).abs() < tol, "{rpm}: Q_i");
        assert!((ball.outer.load / st.qo - 1.0).abs() < tol, "{rpm}: Q_o");
        assert!(
            (e.displacement[0] - da).abs() < 1e-13,
            "{rpm}: δ_a {} vs {da}",
            e.displacement[0]
        );
        // Central differences: ~1e-6 relative (truncation and the inner solves' round-off).
        assert!(
            (e.stiffness[0][0] / ka - 1.0).abs() < 1e-5,
            "{rpm}: k_a {} vs {ka}",
            e.stiffness[0][0]
        );
        if let Some((p, pk)) = &last {
            let pb = &p.balls[0];
            assert!(
                ball.inner.contact_angle > pb.inner.contact_angle + 1e-3,
                "{rpm}"
            );
            assert!(
                ball.outer.contact_angle < pb.outer.contact_angle - 1e-3,
                "{rpm}"
            );
            assert!(ball.outer.load > pb.outer.load, "{rpm}");
            assert!(e.stiffness[0][0] < *pk, "{rpm}");
        }
        last = Some((e.clone(), e.stiffness[0][0]));
    }
}

/// The 218 at 15000 rpm (22.25 kN thrust, outer-race control) needs 88 % of μ_max·Q at the outer
/// contacts: below the friction limit the gyroscopic moment is resisted in full, as the textbook
/// (Jones 1960; Harris) assumes. The solver against the independent implementation with no
/// friction limit at all: the same equations, so agreement to the solvers' tolerances (1e-8 rad,
/// 1e-13 m), far inside the 0.05° and 0.3 µm a published full-control solution is quoted to.
/// The earlier saturation F^H/(1 + (F^H/μQ)^8)^(1/8) removed 3.7 % of the friction here and moved
/// α_o by 0.18° and δ_a by 1.1 µm, so the check can fail.
#[test]
fn harris_218_at_15000_rpm_has_full_race_control_below_the_friction_limit() {
    let b = b218();
    let fa = 22250.0;
    let e = solve(&b, &op(fa, 0.0, 0.0, 15000.0, RaceControl::Outer));
    let mut tb = Textbook::new(&b, 15000.0);
    tb.full_control = true;
    let (da, st, _, _) = tb.solve_thrust(
        fa,
        (
            -20e-6,
            [
                (tb.ro + 30e-6) * 0.4f64.sin(),
                (tb.ro + 30e-6) * 0.4f64.cos(),
            ],
        ),
    );
    for ball in &e.balls {
        // Below the limit: the friction transmitted is the friction needed, to round-off.
        let need = ball.outer.friction_needed;
        assert!(need > 0.85 * ball.outer.friction_limit && need < ball.outer.friction_limit);
        assert!(
            (ball.outer_friction.abs() - need).abs() <= 1e-12 * need,
            "transmitted {} N, needed {need} N",
            ball.outer_friction
        );
        assert!(
            (ball.inner.contact_angle - st.ai).abs() < 1e-8,
            "α_i {}° vs {}°",
            ball.inner.contact_angle.to_degrees(),
            st.ai.to_degrees()
        );
        assert!(
            (ball.outer.contact_angle - st.ao).abs() < 1e-8,
            "α_o {}° vs {}°",
            ball.outer.contact_angle.to_degrees(),
            st.ao.to_degrees()
        );
    }
    assert!(
        (e.displacement[0] - da).abs() < 1e-13,
        "δ_a {} µm vs {} µm",
        e.displacement[0] * 1e6,
        da * 1e6
    );
    // No warning claims the moment is unresisted.
    assert!(
        e.warnings.iter().all(|w| !w.contains("unresisted")),
        "{:?}",
        e.warnings
    );
    println!(
        "218 at 15000 rpm, full race control: α_i = {:.4}°, α_o = {:.4}°, δ_a = {:.4} µm (textbook {:.4}°, {:.4}°, {:.4} µm)",
        e.balls[0].inner.contact_angle.to_degrees(),
        e.balls[0].outer.contact_angle.to_degrees(),
        e.displacement[0] * 1e6,
        st.ai.to_degrees(),
        st.ao.to_degrees(),
        da * 1e6
    );
}

/// The friction limit's shape G(r), r = F^H/(μ_max·Q): the identity up to r0 = 0.95, then
/// increasing, below 1 and tending to 1; continuous with its first and second derivatives at r0
/// (one-sided differences of the value and of the returned slope, step 1e-6),
/// and the returned slope is the derivative everywhere (central differences, 1e-7).
#[test]
fn friction_limit_is_exact_below_and_c2_smooth_into_the_limit() {
    use ehl_bearing::bearing::equilibrium::{friction_limit_shape as g, FRICTION_FULL_CONTROL};
    let r0 = FRICTION_FULL_CONTROL;
    assert_eq!(r0, 0.95);
    for r in [0.0, 0.1, 0.5, 0.88, 0.94, 0.95] {
        assert_eq!(g(r), (r, 1.0));
    }
    let e = 1e-6;
    // Value, slope and curvature from both sides of r0.
    let (below, above) = (g(r0 - e), g(r0 + e));
    assert!((above.0 - below.0 - 2.0 * e).abs() < 1e-12);
    // Above r0, G' = 1 − 3(Δr/0.05)² + … and G'' = −6·Δr/0.05² + …: at Δr = 1e-6 the slope is 1
    // to 1.2e-9 and the curvature 3.6e-3 (a C¹-only blend would curve by ~1/0.05 = 20 there).
    assert!((above.1 - 1.0).abs() < 1e-8 && below.1 == 1.0);
    let curvature_above = (g(r0 + 2.0 * e).1 - g(r0 + e).1) / e;
    assert!(
        curvature_above.abs() < 1e-2,
        "G'' above r0: {curvature_above}"
    );
    let mut prev = g(r0).0;
    let mut r = r0 + 1e-3;
    while r < 50.0 {
        let (v, dv) = g(r);
        assert!(
            v > prev && v < 1.0 && dv > 0.0,
            "r = {r}: G = {v}, G' = {dv}"
        );
        let fd = (g(r + 1e-6).0 - g(r - 1e-6).0) / 2e-6;
        assert!((fd - dv).abs() < 1e-7, "r = {r}: {fd} vs {dv}");
        prev = v;
        r *= 1.01;
    }
    assert!(1.0 - g(50.0).0 < 1e-4);
}

/// The groove-line model departs from the textbook model by degrees and many percent at
/// 15000 rpm (the motivation of the textbook kinematics), and agrees with it at rest.
#[test]
fn groove_line_model_departs_from_the_textbook_at_high_speed() {
    let b = b218();
    let laws = ContactLaws::hertz(&b).unwrap();
    let gl = EquilibriumSettings {
        kinematics: Kinematics::GrooveLine,
        ..Default::default()
    };
    for (rpm, far) in [(0.0, false), (15000.0, true)] {
        let o = op(22250.0, 0.0, 0.0, rpm, RaceControl::Outer);
        let t = solve(&b, &o);
        let g = solve_equilibrium(&b, &laws, &o, &gl).unwrap();
        let dao = (t.balls[0].outer.contact_angle - g.balls[0].outer.contact_angle).to_degrees();
        let dqo = g.balls[0].outer.load / t.balls[0].outer.load - 1.0;
        if far {
            assert!(dao.abs() > 1.0 && dqo.abs() > 0.05, "{dao}° {dqo}");
        } else {
            // At rest only the Hertz constants differ (at the free angle 40° against the operating
            // angle 41.7°): measured 7e-5° in the angles and 1.3e-6 in the loads.
            assert!(dao.abs() < 1e-3 && dqo.abs() < 1e-5, "{dao}° {dqo}");
            assert!(
                dao.abs() > 1e-6,
                "{dao}°: the Hertz constants should differ"
            );
        }
    }
}

/// A ball that leaves the inner race at high speed and light thrust (combined with a radial
/// load), the seed with its tilts up to very high speed, and unloaded balls at rest: the solver
/// stays robust and every ball stays in equilibrium.
#[test]
fn separated_balls_at_high_speed_are_robust() {
    let b = b218();
    for (fx, fy, rpm) in [
        (500.0, 8000.0, 20000.0),
        (200.0, 3000.0, 15000.0),
        (300.0, 9000.0, 0.0),
    ] {
        let e = solve(&b, &op(fx, fy, 0.0, rpm, RaceControl::Outer));
        assert!((e.reaction[0] - fx).abs() < 1e-6 * fy && (e.reaction[1] - fy).abs() < 1e-6 * fy);
        let separated = e.balls.iter().filter(|b| b.inner.deflection < 0.0).count();
        assert!(separated >= 2, "{rpm}: {separated} separated balls");
        for ball in &e.balls {
            let f = Frame::of(ball);
            let (ai, ao) = (ball.inner.contact_angle, ball.outer.contact_angle);
            let fi = lin(
                f.v(ai.sin(), ai.cos()),
                ball.inner.load,
                f.v(ai.cos(), -ai.sin()),
                ball.inner_friction,
            );
            let fo = lin(
                f.v(ao.sin(), ao.cos()),
                -ball.outer.load,
                f.v(ao.cos(), -ao.sin()),
                ball.outer_friction,
            );
            let sum = lin(lin(fi, 1.0, fo, 1.0), 1.0, f.r, ball.centrifugal_force);
            let scale = ball.inner.load + ball.outer.load + ball.centrifugal_force + 1e-9;
            assert!(dot(sum, sum).sqrt() < 1e-9 * scale, "{sum:?}");
        }
    }
    // The seed case with its imposed tilts, from its speeds up to n·d_m ≈ 2 million mm/min.
    let case = read_case("../../examples/7006.toml".as_ref()).unwrap();
    let laws = ContactLaws::hertz(&case.bearing).unwrap();
    for rpm in [3000.0, 5000.0, 20000.0, 50000.0] {
        let mut o = case.operating;
        o.inner_speed = rpm * RPM;
        let e = solve_equilibrium(&case.bearing, &laws, &o, &case.settings).unwrap();
        assert!((e.reaction[0] - 1000.0).abs() < 1e-6, "{rpm}");
    }
}

/// The case-file key that chooses the kinematics model: default, both values, and an invalid
/// value named with its key and the valid values.
#[test]
fn kinematics_key_in_case_files() {
    let c = parse_case(CASE_218, "218").unwrap();
    assert_eq!(c.settings.kinematics, Kinematics::OperatingAngles);
    let seed = parse_case(SEED, "7006").unwrap();
    assert_eq!(seed.settings.kinematics, Kinematics::OperatingAngles);
    let gl = CASE_218.replace(
        "kinematics = \"operating-angles\"",
        "kinematics = \"groove-line\"",
    );
    assert_eq!(
        parse_case(&gl, "gl").unwrap().settings.kinematics,
        Kinematics::GrooveLine
    );
    let bad = CASE_218.replace(
        "kinematics = \"operating-angles\"",
        "kinematics = \"groove-centre\"",
    );
    let err = parse_case(&bad, "bad").unwrap_err().to_string();
    for part in [
        "equilibrium.kinematics",
        "groove-centre",
        "operating-angles",
        "groove-line",
    ] {
        assert!(err.contains(part), "{err}");
    }
    let bad = CASE_218.replace("kinematics = \"operating-angles\"", "kinematics = 3");
    assert!(parse_case(&bad, "bad").is_err());
}

proptest! {
    #![proptest_config(seeded::config(16))]
    /// The exact Jacobian equals central finite differences for the 218 at 15000 rpm (contact
    /// angles split by 30°, gyroscopic friction near its limit), around its thrust equilibrium
    /// (δ_a = −20 µm), for every race control and both kinematics models. Tolerance as in
    /// tests/bearing_equilibrium.rs: 1e-5 of the largest entry in the column.
    #[test]
    fn jacobian_matches_finite_differences_at_high_speed(
        x in -30e-6..-5e-6f64,
        y in -10e-6..10e-6f64,
        z in -10e-6..10e-6f64,
        ty in -1e-4..1e-4f64,
        tz in -1e-4..1e-4f64,
        rc in 0usize..4,
        groove_line in proptest::bool::ANY,
    ) {
        let b = b218();
        let laws = ContactLaws::hertz(&b).unwrap();
        let rc = [RaceControl::Outer, RaceControl::Inner, RaceControl::None, RaceControl::NoGyroscopic][rc];
        let kin = if groove_line { Kinematics::GrooveLine } else { Kinematics::OperatingAngles };
        let model = BearingModel::new(&b, &laws, 15000.0 * RPM, 0.0, rc).unwrap().with_kinematics(kin);
        let q = [x, y, z, ty, tz];
        let an = model.evaluate(&q).unwrap().jacobian;
        let fd = fd_jacobian(&model, &q, 2e-9);
        for c in 0..5 {
            let colmax = (0..5).map(|r| an[r][c].abs()).fold(0.0, f64::max);
            for r in 0..5 {
                prop_assert!((an[r][c] - fd[r][c]).abs() <= 1e-5 * colmax,
                    "J[{}][{}] analytic {} fd {}", r, c, an[r][c], fd[r][c]);
            }
        }
    }
}
