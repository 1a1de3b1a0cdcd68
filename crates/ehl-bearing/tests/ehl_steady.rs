//! Steady EHL solver: input validation, the NVM formula's combination rule, agreement with it,
//! grid convergence, Hertz limit, force balance, residual history, warm start.

mod seeded;
use ehl_bearing::ehl::formulas::{nijenbanning_asymptotes, nijenbanning_central};
use ehl_bearing::ehl::*;
use ehl_bearing::io::contact as input;
use ehl_bearing::material::Lubricant;

fn barus(m: f64, l: f64, r: f64) -> MoesCase {
    MoesCase::new(m, l, r, ViscosityModel::Barus, DensityModel::Incompressible)
}

fn seed_contact() -> EhlContact {
    // examples/contact_7006_inner.toml
    EhlContact {
        load: 600.0,
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: 208e9 / 0.91,
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn field_of(e: EhlError) -> &'static str {
    match e {
        EhlError::Invalid { field, .. } => field,
        other => panic!("expected Invalid, got {other}"),
    }
}

#[test]
fn rejects_invalid_input_naming_the_field() {
    let s = EhlSettings::default();
    let ok = seed_contact();
    let cases: Vec<(EhlContact, &str)> = vec![
        (EhlContact { load: 0.0, ..ok }, "load"),
        (
            EhlContact {
                load: f64::NAN,
                ..ok
            },
            "load",
        ),
        (EhlContact { rx: -1.0, ..ok }, "rx"),
        (
            EhlContact {
                ry: f64::INFINITY,
                ..ok
            },
            "ry",
        ),
        (
            EhlContact {
                ry: ok.rx * 0.5,
                ..ok
            },
            "ry/rx",
        ),
        (
            EhlContact {
                ry: ok.rx * 2000.0,
                ..ok
            },
            "ry/rx",
        ),
        (
            EhlContact {
                sum_velocity: 0.0,
                ..ok
            },
            "sum_velocity",
        ),
        (
            EhlContact {
                e_reduced: -2.0,
                ..ok
            },
            "e_reduced",
        ),
        (
            EhlContact {
                lubricant: Lubricant {
                    viscosity: -0.1,
                    ..ok.lubricant
                },
                ..ok
            },
            "viscosity",
        ),
    ];
    for (c, name) in cases {
        let e = solve_steady(&c, &s).expect_err(name);
        let msg = e.to_string();
        assert!(field_of(e).contains(name), "{name}: {msg}");
        assert!(msg.contains("valid range"), "{msg}");
    }
    let bad_grid = EhlSettings {
        grid: 100,
        ..Default::default()
    };
    assert!(field_of(solve_steady(&ok, &bad_grid).unwrap_err()).contains("grid"));
    assert!(solve_moes(&barus(-1.0, 10.0, 1.0), &s).is_err());
    assert!(solve_moes(&barus(20.0, f64::NAN, 1.0), &s).is_err());
    assert!(solve_moes(&barus(20.0, 10.0, 0.9), &s).is_err());
}

/// The combination rule of the NVM formula (docs/ehl.md §5.4) reduces to each asymptote
/// where the others are negligible.
#[test]
fn nvm_combination_rule_reproduces_its_asymptotes() {
    for d in [1.0, 1.0 / 12.0, 1.0 / 61.0] {
        // rigid-isoviscous: tiny M, negligible L
        let [h_ri, ..] = nijenbanning_asymptotes(0.01, 1e-9, d);
        let h = nijenbanning_central(0.01, 1e-9, d);
        assert!((h / h_ri - 1.0).abs() < 0.01, "RI d={d}: {h} vs {h_ri}");
        // elastic-isoviscous: large M, negligible L -> (H_EI^-4 + H00^-4)^(-1/4)
        let [_, h_ei, _, _, _, h00] = nijenbanning_asymptotes(1e4, 1e-9, d);
        let he = (h_ei.powi(-4) + h00.powi(-4)).powf(-0.25);
        let h = nijenbanning_central(1e4, 1e-9, d);
        assert!((h / he - 1.0).abs() < 0.01, "EI d={d}: {h} vs {he}");
        // rigid-piezoviscous: very large L at moderate M (H_RP ∝ L^(2/3) outgrows H_RI ∝ M^-2)
        let [_, _, h_rp, ..] = nijenbanning_asymptotes(10.0, 1e4, d);
        let h = nijenbanning_central(10.0, 1e4, d);
        assert!((h / h_rp - 1.0).abs() < 0.02, "RP d={d}: {h} vs {h_rp}");
        // elastic-piezoviscous: large M and L (the isoviscous part adds a few percent)
        let [_, _, _, h_ep, ..] = nijenbanning_asymptotes(1e5, 50.0, d);
        let h = nijenbanning_central(1e5, 50.0, d);
        assert!((h / h_ep - 1.0).abs() < 0.03, "EP d={d}: {h} vs {h_ep}");
    }
    // Circular M = 20, L = 10: 4.708 in Moes scaling = 0.488 in Venner–Lubrecht's H = H_M/(1.5M)^(2/3).
    let h = nijenbanning_central(20.0, 10.0, 1.0);
    assert!((h - 4.708).abs() < 1e-3, "{h}");
}

fn settings(grid: usize) -> EhlSettings {
    EhlSettings {
        grid,
        ..Default::default()
    }
}

fn rel(a: f64, b: f64) -> f64 {
    a / b - 1.0
}

/// NVM (1994) is a fit to numerical solutions with Barus viscosity and an incompressible
/// lubricant; over its range it reproduces them to a few percent. Tolerance: 5 % (fit scatter
/// plus our discretization error on 257², < 1 % by the grid-convergence study).
#[test]
fn agrees_with_nijenbanning_venner_moes() {
    let s = settings(257);
    for (m, l, r) in [(20.0, 10.0, 1.0), (200.0, 20.0, 61.0), (300.0, 20.0, 12.0)] {
        let x = solve_moes(&barus(m, l, r), &s).unwrap();
        let n = nijenbanning_central(m, l, 1.0 / r);
        println!(
            "M {m} L {l} Ry/Rx {r}: H_c {:.4} NVM {n:.4} ({:+.2} %)",
            x.h_central_moes,
            100.0 * rel(x.h_central_moes, n)
        );
        assert!(x.converged);
        assert!(rel(x.h_central_moes, n).abs() < 0.05, "M {m} L {l} R {r}");
    }
}

/// Second-order discretization: H_c and H_min on 65, 129, 257 points (circular, M = 20, L = 10,
/// Barus, incompressible); observed order log2(|H65 − H129|/|H129 − H257|) within [1.5, 2.5].
/// The fixed tolerances alone (discretization-following rule off): the test measures the
/// discretization, so the iteration error must be far below the differences (the default rule
/// leaves up to a quarter of the discretization error, enough to move the observed order).
#[test]
fn grid_convergence_is_second_order() {
    let c = barus(20.0, 10.0, 1.0);
    let v: Vec<EhlSolution> = [65, 129, 257]
        .iter()
        .map(|&g| {
            let s = EhlSettings {
                discretization_fraction: 0.0,
                ..settings(g)
            };
            solve_moes(&c, &s).unwrap()
        })
        .collect();
    let order =
        |f: fn(&EhlSolution) -> f64| ((f(&v[0]) - f(&v[1])) / (f(&v[1]) - f(&v[2]))).abs().log2();
    let (oc, om) = (order(|x| x.h_central_moes), order(|x| x.h_min_moes));
    println!(
        "H_c {:?} order {oc:.2}; H_min {:?} order {om:.2}",
        v.iter().map(|x| x.h_central_moes).collect::<Vec<_>>(),
        v.iter().map(|x| x.h_min_moes).collect::<Vec<_>>()
    );
    assert!(v.iter().all(|x| x.converged));
    assert!((1.5..=2.5).contains(&oc), "H_c order {oc}");
    assert!((1.5..=2.5).contains(&om), "H_min order {om}");
}

/// At high load the pressure tends to the Hertz ellipse: Ry/Rx = 12, L = 10 (Roelands +
/// Dowson–Higginson), 129²: the largest |P − √(1 − X² − Y²)| inside X² + Y² ≤ 0.5 falls as M
/// grows from 300 to 1000 to 3000 and is below 3 % of p_h at M = 3000; the approach tends to the
/// Hertz deflection.
#[test]
fn high_load_pressure_tends_to_hertz() {
    let mut last = (f64::INFINITY, 0.0);
    for m in [300.0, 1000.0, 3000.0] {
        let c = MoesCase::new(
            m,
            10.0,
            12.0,
            ViscosityModel::Roelands,
            DensityModel::DowsonHigginson,
        );
        let x = solve_moes(&c, &settings(129)).unwrap();
        assert!(x.converged);
        let f = &x.fields;
        let nx = f.x.len();
        let mut dev: f64 = 0.0;
        for (j, y) in f.y.iter().enumerate() {
            for (i, xx) in f.x.iter().enumerate() {
                let (xh, yh) = (xx / f.a_x, y / f.a_y);
                let r2 = xh * xh + yh * yh;
                if r2 <= 0.5 {
                    dev = dev.max((f.p_dimensionless[j * nx + i] - (1.0 - r2).sqrt()).abs());
                }
            }
        }
        let ratio = x.approach / x.approach_hertz;
        println!("M {m}: max |P - P_Hertz| = {dev:.4}, δ/δ_H = {ratio:.4}");
        assert!(dev < last.0 && ratio > last.1, "M {m}");
        last = (dev, ratio);
    }
    assert!(last.0 < 0.03, "{}", last.0);
    assert!(last.1 > 0.9, "{}", last.1);
}

/// Force balance to tolerance and the residual falling every multigrid cycle (down to the
/// tolerance), across the range.
#[test]
fn residual_falls_every_cycle_and_force_balance_holds() {
    let cases = [
        (20.0, 10.0, 1.0, 129),
        (5.0, 2.0, 1.0, 129),
        (100.0, 20.0, 12.0, 129),
        (300.0, 21.0, 61.0, 129),
        (2000.0, 25.0, 100.0, 257),
    ];
    for (m, l, r, g) in cases {
        let c = MoesCase::new(
            m,
            l,
            r,
            ViscosityModel::Roelands,
            DensityModel::DowsonHigginson,
        );
        let x = solve_moes(&c, &settings(g)).unwrap();
        println!(
            "M {m} L {l} R {r}: cycles {} fb {:.1e} history {:?}",
            x.cycles, x.force_balance_residual, x.residual_history
        );
        assert!(x.converged, "M {m} L {l} R {r}");
        assert!(x.force_balance_residual <= x.tolerances(&settings(g)).1);
        // Every cycle lowers the residual until it is below the tolerance; below it (~1e-5) the
        // complementarity noise of the cavitation boundary may bounce it while the film and h0
        // criteria finish converging.
        let tol = EhlSettings::default().tol_residual;
        for w in x.residual_history.windows(2) {
            if w[0] > tol {
                assert!(w[1] < w[0], "M {m} L {l} R {r}: {:?}", x.residual_history);
            }
        }
    }
}

#[test]
fn non_converged_run_is_flagged() {
    // One cycle: the discretization-following rule needs two to measure a convergence factor.
    let s = EhlSettings {
        max_cycles: 1,
        grid: 65,
        ..Default::default()
    };
    let x = solve_moes(&barus(20.0, 10.0, 1.0), &s).unwrap();
    assert!(!x.converged);
    assert_eq!(x.residual_history.len(), 1);
    assert!(x.residual > 0.0);
}

/// Nearly rigid elongated contact (Ry/Rx 61, M 5): the automatic domain follows the rigid
/// scales and the load is carried (it used to stagnate with 1 % of the load, docs/ehl.md §5.8).
/// H_c 232.9 on 129², 237.1 on 257²; the band allows for the domain dependence.
#[test]
fn nearly_rigid_elongated_contact_converges() {
    let x = solve_moes(&barus(5.0, 10.0, 61.0), &settings(129)).unwrap();
    assert!(x.converged, "residual {}", x.residual);
    assert!(x.force_balance_residual <= x.tolerances(&settings(129)).1);
    assert!(x.cycles <= 30, "cycles {}", x.cycles);
    assert!(
        (215.0..260.0).contains(&x.h_central_moes),
        "H_c {}",
        x.h_central_moes
    );
}

/// Nearly isoviscous, highly loaded, very elongated contact (Ry/Rx 100, M 500, L 2): the line
/// Gauss–Seidel relaxation oscillates at ω_GS = 0.3–0.4 (the first five starts stagnate at a
/// relative residual of ~1e-3–1e-2); the strongly under-relaxed sixth start converges
/// (docs/ehl.md §5.8). H_c = 2.736 on 129², 2.777 on 257² (where start 5 converges).
#[test]
fn isoviscous_elongated_high_load_converges() {
    let c = MoesCase::new(
        500.0,
        2.0,
        100.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let x = solve_moes(&c, &settings(129)).unwrap();
    assert!(x.converged, "residual {}", x.residual);
    assert_eq!(x.attempts, 6);
    assert!(x.force_balance_residual <= x.tolerances(&settings(129)).1);
    assert!(
        rel(x.h_central_moes, 2.777).abs() < 0.03,
        "H_c {}",
        x.h_central_moes
    );
}

/// Prints a fallback run's summary and asserts it converged in start `start` (`attempts`), below
/// the residual and force-balance bounds of the default stopping rules.
fn assert_converged_in_start(x: &EhlSolution, start: usize) {
    println!(
        "cycles {} steps {} t {:.2}s H_c {:.4} H_min {:.4} p_max/p_h {:.3} res {:.2e} fb {:.1e}",
        x.cycles,
        x.continuation_steps,
        x.seconds,
        x.h_central_moes,
        x.h_min_moes,
        x.p_max / x.p_hertz,
        x.residual,
        x.force_balance_residual
    );
    assert!(x.converged, "residual {}", x.residual);
    assert_eq!(x.attempts, start);
    let (res, fb) = x.tolerances(&EhlSettings::default());
    assert!(x.residual < res);
    assert!(x.force_balance_residual <= fb);
}

/// Barus at large αp_h (circular, M 5, L 25: αp_h = 17.9): every direct start diverges within a
/// few cycles and so does load continuation; the continuation in α from L/4 (start 8, ω_GS ≤ 0.1
/// and a coarsest grid of 65² on the warm-started steps) converges (docs/ehl.md §5.8). (The case
/// of this test was M 20 until the line relaxation's active set was iterated: since
/// then M 20 converges on 129² in start 4, and still needs start 8 on 257²; M 5 needs start 8 on
/// both.)
#[test]
fn barus_large_alpha_converges_by_alpha_continuation() {
    let x = solve_moes(&barus(5.0, 25.0, 1.0), &settings(129)).unwrap();
    assert_converged_in_start(&x, 8);
    // Every start is in the log, in ladder order; only the last one converged, and the cycles
    // of all of them add up to the reported total.
    let log = &x.attempt_log;
    assert_eq!(log.len(), 8, "{log:?}");
    for (k, a) in log.iter().enumerate() {
        assert_eq!(a.strategy, StartStrategy::LADDER[k]);
        assert_eq!(a.strategy.number(), k + 1);
        assert_eq!(a.outcome == AttemptOutcome::Converged, k == 7, "{a:?}");
    }
    assert_eq!(log.iter().map(|a| a.cycles).sum::<usize>(), x.cycles);
    // Force balance from the returned pressure field: ∬p dx dy = w = (2π/3)·p_h·a_x·a_y.
    let f = &x.fields;
    let (dx, dy) = (f.x[1] - f.x[0], f.y[1] - f.y[0]);
    let w = 2.0 * std::f64::consts::PI / 3.0 * x.p_hertz * f.a_x * f.a_y;
    let integral: f64 = f.p.iter().sum::<f64>() * dx * dy;
    assert!(rel(integral, w).abs() < 1e-4, "{integral} vs {w}");
    assert!(f.p.iter().all(|p| *p >= 0.0));
    // A positive film, within 5 % of the 257² solution (7.997, start 8 as well; 129²: 7.967).
    assert!(x.h_min > 0.0 && x.h_central > x.h_min);
    println!(
        "p_max/p_h {:.3}, NVM H_c {:.3}",
        x.p_max / x.p_hertz,
        nijenbanning_central(5.0, 25.0, 1.0)
    );
    assert!(
        rel(x.h_central_moes, 7.997).abs() < 0.05,
        "H_c {}",
        x.h_central_moes
    );
    assert!((3.0..6.0).contains(&(x.p_max / x.p_hertz)));
}

/// Barus, Ry/Rx 100, M 2000, L 25 on 257² (αp_h = 37, a pressure spike one node wide): every
/// multigrid start, load continuation and the α-continuation end in a period-2 limit cycle at a
/// relative residual of ≈ 1.2e-3; the last resort (start 9: the α-continuation's best iterate
/// relaxed on the finest grid alone) converges (docs/ehl.md §5.8). ≈ 22 s, hence ignored:
/// `cargo test --release -p ehl-bearing --test ehl_steady -- --ignored barus_spike_single_grid`.
/// (On 129² the same case converges in start 1; no faster case reaching start 9 was found.)
#[test]
#[ignore]
fn barus_spike_single_grid_polish_converges() {
    let x = solve_moes(&barus(2000.0, 25.0, 100.0), &settings(257)).unwrap();
    assert_converged_in_start(&x, 9);
    assert!(x.h_min > 0.0 && x.h_central > x.h_min);
    // 9.89 on 257² (9.61 on 129², start 1).
    assert!(
        rel(x.h_central_moes, 9.89).abs() < 0.01,
        "H_c {}",
        x.h_central_moes
    );
}

/// `s` iterated far below its stopping tolerances (film and residual 1e-8, force 1e-9, up to 200
/// cycles): the reference a solution stopped at the fixed tolerances is compared with.
fn tightly(s: &EhlSettings) -> EhlSettings {
    EhlSettings {
        tol_film: 1e-8,
        tol_residual: 1e-8,
        tol_force: 1e-9,
        max_cycles: 200,
        ..*s
    }
}

/// The seed's most loaded inner contact converges; a warm start from it at 10 % more load gives
/// the cold-start answer in fewer cycles. Both to the fixed tolerances (the quasi-static family's
/// setting), against the same contact iterated to 1e-8: each within 1e-3 in H_c and 1e-5 in δ
/// (the film-change tolerance 1e-4 with a convergence factor up to 0.6 leaves ≲ 2e-4). With the
/// discretization-following rule the cold start stops 1.5e-3 from it in H_c (its promise, a
/// quarter of the capped estimate, is 1e-3: the factor it measures over the first cycles, 0.38,
/// misses the slower mode of this elongated contact; docs/ehl.md §2, a known weakness).
#[test]
fn seed_contact_and_warm_start() {
    let s = EhlSettings {
        discretization_fraction: 0.0,
        ..settings(129)
    };
    let c = seed_contact();
    let a = solve_steady(&c, &s).unwrap();
    assert!(a.converged);
    assert!(a.moes_m > 2000.0 && a.moes_m < 2800.0, "{}", a.moes_m);
    let c2 = EhlContact { load: 660.0, ..c };
    let cold = solve_steady(&c2, &s).unwrap();
    let warm = solve_steady_from(&c2, &s, &a).unwrap();
    let tight = solve_steady(&c2, &tightly(&s)).unwrap();
    println!(
        "cold {} cycles h_c {:+.2e} δ {:+.2e}; warm {} cycles h_c {:+.2e} δ {:+.2e} (relative to \
         the tightly converged solution)",
        cold.cycles,
        rel(cold.h_central, tight.h_central),
        rel(cold.approach, tight.approach),
        warm.cycles,
        rel(warm.h_central, tight.h_central),
        rel(warm.approach, tight.approach)
    );
    assert!(warm.converged && cold.converged && tight.converged);
    for x in [&cold, &warm] {
        assert!(rel(x.h_central, tight.h_central).abs() < 1e-3);
        assert!(rel(x.approach, tight.approach).abs() < 1e-5);
    }
    assert!(warm.cycles <= cold.cycles);
}

/// Family warm starts: the seed's most loaded inner contact on one domain
/// (the quasi-static family's), 640 N warm-started from 600 N, and 680 N either warm-started from
/// 640 N alone or extrapolated linearly in load from 600 and 640 N (`solve_steady_extrapolated`,
/// Hertz-scaled pressure and H0). Every start stops at the family's fixed tolerances within 1e-3
/// in H_c and 1e-5 in δ of the tightly converged 680 N solution, and the extrapolated start takes
/// no more cycles than the single one (measured: 600 N cold 8 cycles, 640 N warm 5, 680 N single
/// 5, extrapolated 3; the Hertz-scaled warm start itself took the seed family's members from 7–8
/// to 4–5 cycles against the physical-coordinate start of before).
#[test]
fn extrapolated_family_start() {
    let s = EhlSettings {
        discretization_fraction: 0.0,
        inlet: Some(4.5),
        outlet: 1.5,
        half_width: Some(1.5),
        ..settings(129)
    };
    let at = |w: f64| EhlContact {
        load: w,
        ..seed_contact()
    };
    let a = solve_steady(&at(600.0), &s).unwrap();
    let b = solve_steady_from(&at(640.0), &s, &a).unwrap();
    let single = solve_steady_from(&at(680.0), &s, &b).unwrap();
    let extra = solve_steady_extrapolated(&at(680.0), &s, (&b, 640.0), (&a, 600.0)).unwrap();
    let tight = solve_steady(&at(680.0), &tightly(&s)).unwrap();
    println!(
        "cycles: 600 N cold {}, 640 N warm {}, 680 N single {} extrapolated {}",
        a.cycles, b.cycles, single.cycles, extra.cycles
    );
    for x in [&a, &b, &single, &extra, &tight] {
        assert!(x.converged && x.attempts == 1, "{} attempts", x.attempts);
    }
    for x in [&single, &extra] {
        assert!(rel(x.h_central, tight.h_central).abs() < 1e-3);
        assert!(rel(x.approach, tight.approach).abs() < 1e-5);
    }
    assert!(extra.cycles <= single.cycles);
    assert!(b.cycles < a.cycles);
    // A wild extrapolation ratio (|r| > 4) falls back to the single warm start.
    let far = solve_steady_extrapolated(&at(680.0), &s, (&b, 640.0), (&a, 639.0)).unwrap();
    assert_eq!(far.cycles, single.cycles);
    assert_eq!(far.approach, single.approach);
}

#[test]
fn contact_file_parsing() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/contact_7006_inner.toml"
    ))
    .unwrap();
    let c = input::parse_contact_toml(&text).unwrap();
    assert_eq!(c.load, 600.0);
    assert!((c.rx - 2.9487e-3).abs() < 1e-12);
    assert!((c.e_reduced - 208e9 / 0.91).abs() < 1.0);
    let e = input::parse_contact_toml(&format!("{text}\nbogus = 1\n")).unwrap_err();
    assert!(e.to_string().contains("bogus"), "{e}");
    let bad = text.replace("poisson_ratio = 0.3", "poisson_ratio = 0.7");
    let e = input::parse_contact_toml(&bad).unwrap_err().to_string();
    assert!(
        e.contains("poisson_ratio") && e.contains("0.7") && e.contains("−1 < ν < 0.5"),
        "{e}"
    );
    let bad = text.replace("load_n = 600.0", "load_n = -5.0");
    let e = input::parse_contact_toml(&bad).unwrap_err().to_string();
    assert!(e.contains("load_n") && e.contains("-5"), "{e}");
}

#[test]
fn contact_file_gives_the_ball_mass_for_the_harmonic_method() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/contact_7006_inner.toml"
    ))
    .unwrap();
    // ball_diameter_mm = 7 with the ball material's 7850 kg/m³: ρ·π/6·D³.
    let f = input::parse_contact_file(&text).unwrap();
    let m = 7850.0 * std::f64::consts::PI / 6.0 * 7e-3f64.powi(3);
    assert!((f.ball_mass.unwrap() / m - 1.0).abs() < 1e-12);
    let no_d: String = text
        .lines()
        .filter(|l| !l.starts_with("ball_diameter_mm"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(input::parse_contact_file(&no_d).unwrap().ball_mass, None);
    let given = format!("ball_mass_kg = 0.002\n{no_d}");
    assert_eq!(
        input::parse_contact_file(&given).unwrap().ball_mass,
        Some(0.002)
    );
    let both = format!("ball_mass_kg = 0.002\n{text}");
    let e = input::parse_contact_file(&both).unwrap_err().to_string();
    assert!(
        e.contains("ball_mass_kg") && e.contains("ball_diameter_mm"),
        "{e}"
    );
    for (key, v) in [("ball_mass_kg", "-1.0"), ("ball_diameter_mm", "nan")] {
        let bad = format!("{key} = {v}\n{no_d}");
        let e = input::parse_contact_file(&bad).unwrap_err().to_string();
        assert!(
            e.contains(key) && e.to_lowercase().contains(&v.replace(".0", "")),
            "{e}"
        );
    }
}

proptest::proptest! {
    #![proptest_config(seeded::config(256))]
    /// Any float in the ball-mass keys gives a contact or an error, never a panic.
    #[test]
    fn ball_mass_keys_never_panic(m in proptest::num::f64::ANY, d in proptest::num::f64::ANY, which in 0..3u8) {
        let base = "load_n = 600.0\nrx_mm = 2.9\nry_mm = 178.5\nsum_velocity_m_s = 10.85\n";
        let text = match which {
            0 => format!("{base}ball_mass_kg = {m:?}\n"),
            1 => format!("{base}ball_diameter_mm = {d:?}\n"),
            _ => format!("{base}ball_mass_kg = {m:?}\nball_diameter_mm = {d:?}\n"),
        };
        if let Ok(f) = input::parse_contact_file(&text) {
            let mass = f.ball_mass.unwrap();
            proptest::prop_assert!(mass.is_finite() && mass > 0.0);
        }
    }
}

/// The default stopping rule follows the discretization error (docs/ehl.md §2): on the circular
/// Roelands/D–H case (M 20, L 10) at 129² it stops with H_c within the estimate it promises
/// (a quarter of the estimated discretization error, at most 0.1 %) of the same grid iterated to
/// a residual of 1e-9, in fewer cycles than the fixed tolerances, and says that it stopped there.
/// A warm start carries the estimate over.
#[test]
fn discretization_rule_stops_within_its_estimate() {
    let c = MoesCase::new(
        20.0,
        10.0,
        1.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let s = settings(129);
    let fixed = EhlSettings {
        discretization_fraction: 0.0,
        ..s
    };
    let tight = EhlSettings {
        tol_residual: 1e-9,
        tol_film: 1e-10,
        tol_force: 1e-11,
        max_cycles: 80,
        ..fixed
    };
    let full = solve_moes(&c, &tight).unwrap();
    let rule = solve_moes(&c, &s).unwrap();
    let old = solve_moes(&c, &fixed).unwrap();
    assert!(full.converged && rule.converged && old.converged);
    assert!(rule.stopped_by_discretization && !old.stopped_by_discretization);
    let d = rule
        .discretization_estimate
        .expect("a cold start has an estimate");
    let promised = s.discretization_fraction
        * d[0].clamp(
            ehl_bearing::ehl::DISCRETIZATION_FLOOR,
            ehl_bearing::ehl::DISCRETIZATION_CAP,
        );
    let err = rel(rule.h_central, full.h_central).abs();
    println!(
        "cycles rule {} fixed {}; H_c error {err:.2e}, promised {promised:.2e}, estimate {d:?}",
        rule.cycles, old.cycles
    );
    assert!(err <= promised && err <= 1e-3);
    assert!(rule.cycles < old.cycles);
    let s65 = settings(65);
    let a = solve_steady(&seed_contact(), &s65).unwrap();
    let c2 = EhlContact {
        load: 660.0,
        ..seed_contact()
    };
    let warm = solve_steady_from(&c2, &s65, &a).unwrap();
    assert!(a.discretization_estimate.is_some());
    assert_eq!(warm.discretization_estimate, a.discretization_estimate);
}

/// The converged discrete solution does not depend on the start that reached it:
/// the seed's inner contact at 240 N (M ≈ 945, L ≈ 25, Ry/Rx 60; a light member of the 300 N
/// family, on that family's domain) solved to tight tolerances from four cold starts whose
/// relaxation settings differ. Before the line relaxation's active set was iterated and the
/// complementarity at P = 0 nodes entered the residual, nodes next to the outlet's side lobes
/// stayed at zero where their equation asked for pressure, and the four "converged" answers
/// differed by 9e-5 in δ and 0.5 % in h_min (which moved the fitted ΔF of a quasi-static family
/// by up to 5 % with the relaxation settings). Now they agree to round-off of the stopping
/// tolerances (1e-8).
#[test]
fn converged_solution_does_not_depend_on_the_start() {
    let c = EhlContact {
        load: 240.0,
        ..seed_contact()
    };
    let s = EhlSettings {
        grid: 129,
        inlet: Some(6.0),
        outlet: 1.5,
        half_width: Some(2.0),
        discretization_fraction: 0.0,
        tol_film: 1e-8,
        tol_residual: 1e-8,
        tol_force: 1e-9,
        max_cycles: 300,
        ..Default::default()
    };
    let starts = [
        StartStrategy::Given,
        StartStrategy::SmallH0Gain,
        StartStrategy::WideJacobi,
        StartStrategy::Conservative,
    ];
    let x: Vec<EhlSolution> = starts
        .iter()
        .map(|st| solve_steady_starts(&c, &s, &[*st], None).unwrap())
        .collect();
    for (st, a) in starts.iter().zip(&x) {
        println!(
            "{st:?}: {} cycles, δ {:.10e} m, h_min {:.8e} m, residual {:.2e}",
            a.cycles, a.approach, a.h_min, a.residual
        );
        assert!(a.converged, "{st:?}: residual {}", a.residual);
        assert_eq!(a.attempts, st.number(), "{st:?}");
    }
    for a in &x[1..] {
        assert!(rel(a.approach, x[0].approach).abs() < 1e-8);
        assert!(rel(a.h_central, x[0].h_central).abs() < 1e-6);
        assert!(rel(a.h_min, x[0].h_min).abs() < 1e-6);
    }
}
