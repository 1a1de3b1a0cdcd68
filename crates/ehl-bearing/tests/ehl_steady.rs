//! Steady EHL solver: input validation, the NVM formula's combination rule, agreement with it,
//! grid convergence, Hertz limit, force balance, residual history, warm start.

use ehl_bearing::ehl::formulas::{nijenbanning_asymptotes, nijenbanning_central};
use ehl_bearing::ehl::*;
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

/// The combination rule of the NVM formula (reference README reading) reduces to each asymptote
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
        // rigid-piezoviscous: tiny M, large L
        let [_, _, h_rp, ..] = nijenbanning_asymptotes(0.01, 100.0, d);
        let h = nijenbanning_central(0.01, 100.0, d);
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
