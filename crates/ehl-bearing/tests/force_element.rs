//! The bearing force element for rotor use (`ehl_bearing::force_element`): reactions, stiffness
//! and damping against central differences of the reactions, zero damping for dry laws, the
//! fitted-law element at its characterization's equilibrium, the varying compliance at Z times
//! the cage frequency, and the warm-start state.

mod seeded;
use ehl_bearing::bearing::{solve_equilibrium, Control};
use ehl_bearing::case::Case;
use ehl_bearing::characterize::{characterize_bearing, CharacterizeSettings};
use ehl_bearing::fit::FittedLaw;
use ehl_bearing::force_element::{
    ElementInput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::io::read_case;
use ehl_bearing::method::{HertzCharacterizer, Method};
use proptest::prelude::*;
use std::f64::consts::PI;
use std::path::Path;

fn seed() -> Case {
    read_case(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/7006.toml")).unwrap()
}

/// Lubricated-looking laws with a damping term: per contact K from the Hertz constant at α0
/// (so the magnitudes are the seed's), d = 1.45, ΔF = 20 N, c = 150 N·s/m (the order of the
/// harmonic method's c, docs/contact.md), fitted range 1–12 µm.
fn damped_laws(case: &Case, c: f64) -> Vec<FittedLaw> {
    let b = &case.bearing;
    let a0 = b.geometry.free_contact_angle;
    let mut out = Vec::new();
    for _ in 0..b.geometry.ball_count {
        for race in [
            ehl_bearing::bearing::Race::Inner,
            ehl_bearing::bearing::Race::Outer,
        ] {
            let (rx, ry) = b.geometry.curvature_radii(race, a0);
            let kh = HertzGeometry::new(rx, ry, b.reduced_modulus())
                .unwrap()
                .stiffness;
            // K·δ^1.45 equals K_H·δ^1.5 at δ = 5 µm.
            let k = kh * 5e-6_f64.powf(0.05);
            let law = FittedLaw::new(k, 1.45, 20.0, 1e-6, 12e-6).unwrap();
            out.push(if c > 0.0 {
                law.with_damping(c).unwrap()
            } else {
                law
            });
        }
    }
    out
}

fn element(case: &Case, c: f64) -> LawElement {
    LawElement::from_fitted(
        &case.bearing,
        case.operating.race_control,
        &damped_laws(case, c),
    )
    .unwrap()
}

/// Central differences of the reactions in q (steps 1 nm, 1 µrad) and in q̇ (steps 1 µm/s,
/// 1 mrad/s).
fn differences(e: &dyn ForceElement, input: &ElementInput) -> ([[f64; 5]; 5], [[f64; 5]; 5]) {
    let mut k = [[0.0; 5]; 5];
    let mut c = [[0.0; 5]; 5];
    for n in 0..5 {
        let h = if n < 3 { 1e-9 } else { 1e-6 };
        let hv = if n < 3 { 1e-6 } else { 1e-3 };
        let (mut p, mut m) = (*input, *input);
        p.displacement[n] += h;
        m.displacement[n] -= h;
        let (fp, fm) = (e.reaction(&p).unwrap(), e.reaction(&m).unwrap());
        let (mut pv, mut mv) = (*input, *input);
        pv.velocity[n] += hv;
        mv.velocity[n] -= hv;
        let (gp, gm) = (e.reaction(&pv).unwrap(), e.reaction(&mv).unwrap());
        for r in 0..5 {
            k[r][n] = (fp[r] - fm[r]) / (2.0 * h);
            c[r][n] = (gp[r] - gm[r]) / (2.0 * hv);
        }
    }
    (k, c)
}

/// Largest |a − b| over the matrix relative to the largest |b| of its row block (translations
/// and tilts scaled apart).
fn matrix_error(a: &[[f64; 5]; 5], b: &[[f64; 5]; 5]) -> f64 {
    let scale = b
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(1e-300);
    let mut worst = 0.0_f64;
    for r in 0..5 {
        for n in 0..5 {
            // Tilt columns/rows carry lever arms of d_m/2 ≈ 0.02 m: compare in force units.
            let w = |i: usize| if i < 3 { 1.0 } else { 0.02125 };
            let e = (a[r][n] - b[r][n]).abs() * w(r) * w(n) / scale;
            worst = worst.max(e);
        }
    }
    worst
}

fn seed_displacement(case: &Case) -> [f64; 5] {
    let laws = ehl_bearing::bearing::ContactLaws::hertz(&case.bearing).unwrap();
    solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
        .unwrap()
        .displacement
}

#[test]
fn element_types_are_owned_send_sync_clone() {
    fn owned<T: Send + Sync + Clone + 'static>() {}
    owned::<LawElement>();
    owned::<TrendForceElement>();
    owned::<ElementState>();
    owned::<ehl_bearing::bearing::BearingModel>();
}

#[test]
fn dry_element_has_zero_damping_and_reproduces_the_dry_equilibrium() {
    let case = seed();
    let e = LawElement::hertz_case(&case).unwrap();
    assert!(!e.has_damping());
    let laws = ehl_bearing::bearing::ContactLaws::hertz(&case.bearing).unwrap();
    let eq = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings).unwrap();
    let mut input = ElementInput::at(
        eq.displacement,
        case.operating.inner_speed,
        case.operating.outer_speed,
    );
    input.velocity = [1e-3, -2e-3, 5e-4, 1e-2, -1e-2];
    let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
    assert_eq!(out.damping, [[0.0; 5]; 5]);
    // Rates do not change a dry bearing's reactions; at the dry equilibrium they are the loads
    // (the equilibrium's residual is 1e-11 relative).
    for k in 0..3 {
        let Control::Load(f) = case.operating.dofs[k] else {
            panic!("seed DOF {k} is load-controlled")
        };
        assert!((out.reaction[k] - f).abs() < 1e-6 * f.abs(), "{k}: {out:?}");
    }
    // The same Jacobian: the equilibrium's came from warm-started ball solves, these from cold
    // ones, both converged to 1e-9 of the ball loads.
    assert!(matrix_error(&out.stiffness, &eq.stiffness) < 1e-9);
    assert!(out.outside_range.is_empty());
    assert!(out.overloaded.is_empty());
    // A 1 rad tilt (a 26 MN contact load came back unflagged): the contacts beyond 2 % of D are
    // flagged, the numbers returned as computed.
    let mut q = eq.displacement;
    q[3] = 1.0;
    let input = ElementInput::at(q, case.operating.inner_speed, case.operating.outer_speed);
    let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
    let limit =
        ehl_bearing::force_element::OVERLOAD_DEFLECTION_RATIO * case.bearing.geometry.ball_diameter;
    assert!(!out.overloaded.is_empty());
    for &(j, race) in &out.overloaded {
        assert!(out.approaches[j][race as usize] > limit, "{out:?}");
    }
}

#[test]
fn damped_element_stiffness_and_damping_match_central_differences() {
    let case = seed();
    let e = element(&case, 150.0);
    assert!(e.has_damping());
    let q = seed_displacement(&case);
    let input = ElementInput::at(q, case.operating.inner_speed, case.operating.outer_speed);
    let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
    let (k_fd, c_fd) = differences(&e, &input);
    let ek = matrix_error(&out.stiffness, &k_fd);
    let ec = matrix_error(&out.damping, &c_fd);
    eprintln!("K vs central differences {ek:.2e}, C vs central differences {ec:.2e}");
    // Central differences with 1 nm steps on a K of ~5e7 N/m: truncation ~ (h/δ)² ≈ 1e-7,
    // round-off ~ 1e-16·F/(h·K) ≈ 1e-9; the ball solves are converged to 1e-9 of their loads.
    assert!(ek < 1e-4, "{ek}");
    // The reaction is linear in q̇: central differences are exact to round-off.
    assert!(ec < 1e-6, "{ec}");
    // C = Σ c_k g_k g_kᵀ: symmetric, positive semi-definite (diagonal ≥ 0).
    for r in 0..5 {
        assert!(out.damping[r][r] >= 0.0);
        for n in 0..5 {
            let s = out.damping[r][n] - out.damping[n][r];
            assert!(s.abs() <= 1e-12 * out.damping[0][0], "{r}{n}");
        }
    }
    // A single damped contact pair per ball in series: c_axial ≈ Σ_j c·(∂δ/∂x)² > 0.
    assert!(out.damping[0][0] > 0.0);
}

proptest! {
    #![proptest_config(seeded::config(12))]
    #[test]
    fn jacobians_match_differences_over_displacements_rates_and_cage_angles(
        dx in -2e-6f64..2e-6, dy in -2e-6f64..2e-6, dz in -2e-6f64..2e-6,
        ty in -2e-5f64..2e-5, tz in -2e-5f64..2e-5,
        cage in 0.0f64..(2.0 * PI),
        rpm in 0.0f64..8000.0,
    ) {
        let case = seed();
        let e = element(&case, 120.0);
        let q0 = seed_displacement(&case);
        let q = [q0[0] + dx, q0[1] + dy, q0[2] + dz, q0[3] + ty, q0[4] + tz];
        let mut input = ElementInput::at(q, rpm * PI / 30.0, 0.0);
        input.cage_angle = cage;
        let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
        let (k_fd, c_fd) = differences(&e, &input);
        prop_assert!(matrix_error(&out.stiffness, &k_fd) < 1e-4);
        prop_assert!(matrix_error(&out.damping, &c_fd) < 1e-6);
    }
}

#[test]
fn reactions_with_rates_add_c_times_rates() {
    let case = seed();
    let e = element(&case, 150.0);
    let q = seed_displacement(&case);
    let mut input = ElementInput::at(q, case.operating.inner_speed, 0.0);
    let rest = e.evaluate(&input, &mut ElementState::default()).unwrap();
    input.velocity = [2e-4, -1e-4, 3e-4, 5e-3, -2e-3];
    let moving = e.evaluate(&input, &mut ElementState::default()).unwrap();
    for r in 0..5 {
        let cv: f64 = (0..5).map(|n| rest.damping[r][n] * input.velocity[n]).sum();
        let got = moving.reaction[r] - rest.reaction[r];
        assert!(
            (got - cv).abs() <= 1e-9 * rest.reaction[0].abs(),
            "{r}: {got} vs {cv}"
        );
    }
}

#[test]
fn fitted_element_reproduces_its_characterization_equilibrium() {
    // The coupled loop with the Hertz reference method (fast); the element built from its fitted
    // laws, evaluated at the loop's final displacement, must give the applied loads back — to
    // the equilibrium tolerance (1e-11 relative) plus the round trip of the laws.
    let case = seed();
    let c = characterize_bearing(
        &case,
        &Method::Hertz(HertzCharacterizer::default()),
        &CharacterizeSettings::default(),
    )
    .unwrap();
    assert!(c.converged);
    let e = LawElement::from_characterization(&case, &c).unwrap();
    let input = ElementInput::at(
        c.equilibrium.displacement,
        case.operating.inner_speed,
        case.operating.outer_speed,
    );
    let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
    for k in 0..3 {
        let Control::Load(f) = case.operating.dofs[k] else {
            panic!()
        };
        assert!(
            (out.reaction[k] - f).abs() < 1e-6 * f,
            "{k}: {}",
            out.reaction[k]
        );
    }
    assert!(matrix_error(&out.stiffness, &c.equilibrium.stiffness) < 1e-9);
    // The same laws read back from the report (what a point file or characterization.json holds).
    let report = c.report(false);
    let json = serde_json::to_string(&report).unwrap();
    let back: ehl_bearing::characterize::CharacterizationReport =
        serde_json::from_str(&json).unwrap();
    assert_eq!(back, report);
    let e2 = LawElement::from_report(&case.bearing, case.operating.race_control, &back).unwrap();
    let out2 = e2.evaluate(&input, &mut ElementState::default()).unwrap();
    for k in 0..5 {
        assert!((out2.reaction[k] - out.reaction[k]).abs() <= 1e-9 * out.reaction[0].abs());
    }
}

#[test]
fn warm_state_gives_the_cold_result() {
    let case = seed();
    let e = element(&case, 150.0);
    let q = seed_displacement(&case);
    let mut state = ElementState::default();
    let mut input = ElementInput::at(q, case.operating.inner_speed, 0.0);
    for step in 0..20 {
        input.cage_angle = 0.01 * step as f64;
        input.displacement[1] = q[1] + 1e-7 * (step as f64 * 0.3).sin();
        let warm = e.evaluate(&input, &mut state).unwrap();
        let cold = e.evaluate(&input, &mut ElementState::default()).unwrap();
        for r in 0..5 {
            let scale = cold.reaction[0].abs();
            assert!(
                (warm.reaction[r] - cold.reaction[r]).abs() <= 1e-8 * scale,
                "step {step} dof {r}: {} vs {}",
                warm.reaction[r],
                cold.reaction[r]
            );
        }
    }
    // A state used with another bearing is rebuilt, not misused.
    let mut other = case.clone();
    other.bearing.geometry.ball_count = 12;
    let e12 = LawElement::hertz_case(&other).unwrap();
    let out = e12.evaluate(&input, &mut state).unwrap();
    assert_eq!(out.loads.len(), 12);
}

#[test]
fn radially_loaded_bearing_reactions_vary_at_ball_pass_frequency() {
    // Varying compliance: with a fixed radial displacement and the cage turning, the balls pass
    // the load zone Z times per cage revolution, so the reaction's spectrum peaks at Z·f_cage.
    let mut case = seed();
    case.operating.inner_speed = 3000.0 * PI / 30.0;
    let e = LawElement::hertz_case(&case).unwrap();
    let z = e.ball_count();
    let w_cage = e.cage_speed(case.operating.inner_speed, 0.0);
    assert!(w_cage > 0.0);
    // Axial preload plus a radial offset: the loaded zone is a part of the circumference.
    let q = [15e-6, 8e-6, 0.0, 0.0, 0.0];
    let revolutions = 4.0;
    let samples = 256;
    let t_end = revolutions * 2.0 * PI / w_cage;
    let mut state = ElementState::default();
    let mut fy = Vec::with_capacity(samples);
    for i in 0..samples {
        let t = t_end * i as f64 / samples as f64;
        let mut input = ElementInput::at(q, case.operating.inner_speed, 0.0);
        input.cage_angle = w_cage * t;
        fy.push(e.evaluate(&input, &mut state).unwrap().reaction[1]);
    }
    // Discrete Fourier transform magnitudes; bin m is the frequency m/t_end.
    let mean = fy.iter().sum::<f64>() / samples as f64;
    let mag = |m: usize| {
        let (mut re, mut im) = (0.0, 0.0);
        for (i, f) in fy.iter().enumerate() {
            let a = 2.0 * PI * (m * i) as f64 / samples as f64;
            re += (f - mean) * a.cos();
            im -= (f - mean) * a.sin();
        }
        (re * re + im * im).sqrt()
    };
    let (best, _) = (1..samples / 2)
        .map(|m| (m, mag(m)))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    // Z·f_cage falls on bin Z·revolutions exactly.
    let expected = z * revolutions as usize;
    assert_eq!(best, expected, "peak bin {best}, expected {expected}");
    // Its second harmonic is present too (a non-sinusoidal pass).
    assert!(mag(2 * expected) > 1e-3 * mag(expected));
    // The variation is real: peak-to-peak well above round-off.
    let (lo, hi) = fy
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &f| {
            (a.min(f), b.max(f))
        });
    assert!(hi - lo > 1e-4 * hi.abs(), "{lo} {hi}");
}

#[test]
fn element_rejects_non_finite_inputs_naming_them() {
    let case = seed();
    let e = LawElement::hertz_case(&case).unwrap();
    let mut state = ElementState::default();
    let mut input = ElementInput::at([1e-5, 0.0, 0.0, 0.0, 0.0], 100.0, 0.0);
    input.velocity[2] = f64::NAN;
    let err = e.evaluate(&input, &mut state).unwrap_err().to_string();
    assert!(err.contains('z'), "{err}");
    input.velocity[2] = 0.0;
    input.cage_angle = f64::INFINITY;
    let err = e.evaluate(&input, &mut state).unwrap_err().to_string();
    assert!(err.contains("cage_angle"), "{err}");
    // The state still works after errors.
    input.cage_angle = 0.0;
    assert!(e.evaluate(&input, &mut state).is_ok());
}

/// Laws by load (`LoadInterpolatedLaw`): at every knot the force and stiffness of that
/// contact's own law (to the inversion's 1e-12), monotone and C¹ everywhere (one-sided
/// differences across knots and ends agree to 1e-4 of the stiffness, step 1e-12 m), the damping
/// interpolated between the knots' c, the lowest and highest laws outside the knots. Knots whose
/// approaches do not grow with the load are pooled. The element built from the
/// Hertz-method characterization of the seed reproduces the characterization's equilibrium
/// reactions within 1e-4 (the balls carry loads within 1e-4 of their characterization loads).
#[test]
fn laws_by_load_interpolate_the_characterized_laws_over_the_load() {
    use ehl_bearing::contact_law::ContactLaw;
    use ehl_bearing::force_element::LoadInterpolatedLaw;
    // Knots: K·δ^d + ΔF with d and K drifting with the load, damping growing with it.
    let pts: Vec<(f64, FittedLaw)> = (0..6)
        .map(|k| {
            let w = 50.0 * 1.6f64.powi(k);
            let d = 1.3 + 0.03 * k as f64;
            let df = 20.0 + 3.0 * k as f64;
            let delta = 1e-6 * 1.4f64.powi(k);
            let kk = (w - df) / delta.powf(d);
            let law = FittedLaw::new(kk, d, df, 0.8 * delta, 1.2 * delta)
                .unwrap()
                .with_damping(100.0 + 10.0 * k as f64)
                .unwrap();
            (w, law)
        })
        .collect();
    let l = LoadInterpolatedLaw::new(&pts).unwrap();
    assert_eq!(l.knots(), 6);
    assert_eq!(l.limited_knots(), 0);
    for (w, law) in &pts {
        let delta = law.approach_at(*w).unwrap();
        let (q, dq) = l.force(delta);
        let (q0, dq0) = law.force(delta);
        assert!((q / q0 - 1.0).abs() < 1e-12, "{q} vs {q0}");
        assert!((dq / dq0 - 1.0).abs() < 1e-6, "{dq} vs {dq0}");
        assert!((l.approach_at(*w).unwrap() / delta - 1.0).abs() < 1e-12);
        // C¹ across the knot.
        let h = 1e-12;
        let left = (l.force(delta).0 - l.force(delta - h).0) / h;
        let right = (l.force(delta + h).0 - l.force(delta).0) / h;
        assert!((left / right - 1.0).abs() < 1e-3, "{left} vs {right}");
        assert!((l.damping(delta) - law.damping(delta)).abs() < 1e-9);
    }
    // Monotone in between, the returned slope the derivative, round trip with approach_at.
    let (d0, d1) = (
        pts[0].1.approach_at(pts[0].0).unwrap(),
        pts[5].1.approach_at(pts[5].0).unwrap(),
    );
    let mut prev = 0.0;
    for i in 0..=400 {
        let delta = 0.5 * d0 + (1.5 * d1 - 0.5 * d0) * i as f64 / 400.0;
        let (q, dq) = l.force(delta);
        assert!(q > prev && dq > 0.0, "{delta}: {q}");
        let h = 1e-13;
        let fd = (l.force(delta + h).0 - l.force(delta - h).0) / (2.0 * h);
        assert!((fd / dq - 1.0).abs() < 1e-4, "{delta}: {fd} vs {dq}");
        assert!((l.approach_at(q).unwrap() / delta - 1.0).abs() < 1e-9);
        let c = l.damping(delta);
        assert!((100.0..=150.0).contains(&c) || delta < d0, "{c}");
        prev = q;
    }
    // Outside the knots: the end laws as fitted.
    assert_eq!(l.force(0.5 * d0), pts[0].1.force(0.5 * d0));
    assert_eq!(l.force(1.5 * d1), pts[5].1.force(1.5 * d1));
    // Knots out of order (knot 3 ten times stiffer: its approach at its load falls below knot
    // 2's) are pooled with their neighbour into one knot at the mean load and approach; the law
    // stays monotone, C¹ and through the other knots.
    let mut bad = pts.clone();
    let l3 = bad[3].1;
    let [lo3, hi3] = l3.fit_range();
    bad[3].1 = FittedLaw::new(10.0 * l3.k(), l3.d(), l3.delta_f(), 0.3 * lo3, 0.3 * hi3).unwrap();
    let lb = LoadInterpolatedLaw::new(&bad).unwrap();
    assert!(lb.pooled_knots() >= 1, "{}", lb.pooled_knots());
    assert_eq!(lb.knots() + lb.pooled_knots(), 6);
    let mut prev = 0.0;
    for i in 0..=400 {
        let delta = 0.5 * d0 + (1.5 * d1 - 0.5 * d0) * i as f64 / 400.0;
        let (q, dq) = lb.force(delta);
        assert!(q > prev && dq > 0.0, "pooled, {delta}: {q}");
        prev = q;
    }
    for k in [0, 5] {
        let (w, law) = bad[k];
        let delta = law.approach_at(w).unwrap();
        assert!((lb.force(delta).0 / w - 1.0).abs() < 1e-12);
    }
    assert!(LoadInterpolatedLaw::new(&[]).is_err());

    // The element by load from a characterization (Hertz method: fast).
    let case = seed();
    let c = characterize_bearing(
        &case,
        &Method::Hertz(HertzCharacterizer::default()),
        &CharacterizeSettings::default(),
    )
    .unwrap();
    let e = LawElement::by_load_from_characterization(&case, &c).unwrap();
    let input = ElementInput::at(
        c.equilibrium.displacement,
        case.operating.inner_speed,
        case.operating.outer_speed,
    );
    let out = e.evaluate(&input, &mut ElementState::default()).unwrap();
    for k in 0..3 {
        let Control::Load(f) = case.operating.dofs[k] else {
            panic!()
        };
        assert!(
            (out.reaction[k] - f).abs() < 1e-4 * f,
            "{k}: {}",
            out.reaction[k]
        );
    }
    // Every ball on a raceway shares one law: the reaction repeats every 2π/Z of cage angle.
    let z = case.bearing.geometry.ball_count as f64;
    let mut turned = input;
    turned.cage_angle = 2.0 * PI / z;
    let out2 = e.evaluate(&turned, &mut ElementState::default()).unwrap();
    for k in 0..5 {
        assert!((out2.reaction[k] - out.reaction[k]).abs() <= 1e-9 * out.reaction[0].abs());
    }
    // From the report: the same element.
    let e2 = LawElement::by_load_from_report(
        &case.bearing,
        case.operating.race_control,
        &c.report(false),
    )
    .unwrap();
    let out3 = e2.evaluate(&input, &mut ElementState::default()).unwrap();
    for k in 0..5 {
        assert!((out3.reaction[k] - out.reaction[k]).abs() <= 1e-9 * out.reaction[0].abs());
    }
}
