//! `ehl::film_resolution`: NVM's central film against the grid's ΔX² (docs/ehl.md §5.9), and the
//! law-map check built on it (`study::under_resolved_nodes`).

use ehl_bearing::ehl::{
    film_resolution, formulas::nijenbanning_central, solve_steady, DensityModel, EhlSettings,
    ViscosityModel, FILM_RESOLUTION_MIN,
};
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::law_map::{LawGroups, LawMapSpec};
use ehl_bearing::study::{node_film_resolution, under_resolved_nodes};

fn groups(m: f64, l: f64, ry_over_rx: f64) -> LawGroups {
    LawGroups {
        m,
        l,
        ry_over_rx,
        alpha_p0: Some(2.9),
        ln_eta0_ratio: Some(4.1),
        viscosity: ViscosityModel::Roelands,
        density: DensityModel::DowsonHigginson,
    }
}

/// The ratio by hand: H_NVM (Moes) → h = H·√U·Rx → H = h·Rx/a_x², over ΔX² with the automatic
/// domain of an elongated contact at M ≥ 1000 (inlet 6, outlet 1.5 a_x: docs/ehl.md §3).
#[test]
fn ratio_is_the_nvm_film_over_the_mesh_squared() {
    let (m, l, q) = (3000.0, 10.0, 14.0);
    let c = groups(m, l, q).contact(5e-3, 2.286e11).unwrap();
    let u = c.lubricant.viscosity * c.sum_velocity / (c.e_reduced * c.rx);
    let ax = HertzGeometry::new(c.rx, c.ry, c.e_reduced)
        .unwrap()
        .contact(c.load)
        .semi_minor;
    let h = nijenbanning_central(m, l, 1.0 / q) * u.sqrt() * c.rx;
    let film = h * c.rx / (ax * ax);
    for grid in [65, 129, 257] {
        let s = EhlSettings {
            grid,
            ..EhlSettings::default()
        };
        let dx = 7.5 / (grid - 1) as f64;
        let expected = film / (dx * dx);
        let r = film_resolution(&c, &s).unwrap();
        assert!(
            ((r - expected) / expected).abs() < 1e-9,
            "grid {grid}: {r} against {expected}"
        );
    }
    // The measured cases of docs/ehl.md §5.9: 3.6 on 65², 14 on 129².
    let r65 = film_resolution(
        &c,
        &EhlSettings {
            grid: 65,
            ..EhlSettings::default()
        },
    )
    .unwrap();
    assert!((r65 - 3.57).abs() < 0.01, "{r65}");
}

/// Below the threshold the 65² solution's nodal film is negative (M 10000, L 8: ratio 1.25,
/// H_min −6.2 Moes, docs/ehl.md §5.9); a node above it has a positive film on the same grid
/// (M 1000, L 8: ratio 7.0 — a light node is also resolved below 10, the threshold is a bound
/// measured on the slow nodes, not a sharp edge).
#[test]
fn under_resolved_contact_has_a_negative_nodal_film() {
    let s = EhlSettings {
        grid: 65,
        discretization_fraction: 0.0,
        ..EhlSettings::default()
    };
    let thin = groups(10000.0, 8.0, 14.0).contact(5e-3, 2.286e11).unwrap();
    let r = film_resolution(&thin, &s).unwrap();
    assert!(r < 1.5, "{r}");
    let sol = solve_steady(&thin, &s).unwrap();
    assert!(sol.h_min < 0.0, "h_min {}", sol.h_min);
    let thick = groups(1000.0, 8.0, 14.0).contact(5e-3, 2.286e11).unwrap();
    let r = film_resolution(&thick, &s).unwrap();
    assert!(r > 5.0 && r < FILM_RESOLUTION_MIN, "{r}");
    let sol = solve_steady(&thick, &s).unwrap();
    assert!(sol.converged && sol.h_min > 0.0, "h_min {}", sol.h_min);
}

/// The heavy oils box on 65² and up to M 10000 (the shipped heavy maps' predecessor) reaches
/// under-resolved nodes at its high-M end; the low-L spec (grid 129², M ≤ 3900) has none.
#[test]
fn law_map_specs_checked_for_resolution() {
    let mut heavy = LawMapSpec::from_toml(include_str!(
        "../../../examples/law_map_mineral_oils_heavy.toml"
    ))
    .unwrap();
    heavy.grid = 65;
    heavy.tolerance_factor = 1.0;
    heavy.axes[0].max = 10000.0;
    let bad = under_resolved_nodes(&heavy).unwrap();
    assert!(!bad.is_empty());
    assert!(
        bad.windows(2).all(|w| w[0].1 <= w[1].1),
        "least resolved first"
    );
    let (worst, r) = bad[0];
    let g = heavy.node_groups(worst);
    assert_eq!(node_film_resolution(&g, &heavy).unwrap(), r);
    assert!(g.m > 9999.0, "worst node at M {}", g.m);
    let low_l = LawMapSpec::from_toml(include_str!(
        "../../../examples/law_map_mineral_oils_low_l.toml"
    ))
    .unwrap();
    assert_eq!(under_resolved_nodes(&low_l).unwrap(), vec![]);
}

/// Prints the resolution of the example specs (`cargo test -p ehl-bearing --test film_resolution
/// -- --ignored --nocapture`).
#[test]
#[ignore]
fn print_example_specs() {
    for (name, text) in [
        (
            "mineral_oils",
            include_str!("../../../examples/law_map_mineral_oils.toml"),
        ),
        (
            "mineral_oils_light",
            include_str!("../../../examples/law_map_mineral_oils_light.toml"),
        ),
        (
            "mineral_oils_heavy",
            include_str!("../../../examples/law_map_mineral_oils_heavy.toml"),
        ),
        (
            "mineral_oils_heaviest",
            include_str!("../../../examples/law_map_mineral_oils_heaviest.toml"),
        ),
        (
            "mineral_oils_low_l",
            include_str!("../../../examples/law_map_mineral_oils_low_l.toml"),
        ),
        (
            "mineral_oils_low_l_light",
            include_str!("../../../examples/law_map_mineral_oils_low_l_light.toml"),
        ),
        (
            "mineral_oils_high_l",
            include_str!("../../../examples/law_map_mineral_oils_high_l.toml"),
        ),
        (
            "mineral_oils_lightest",
            include_str!("../../../examples/law_map_mineral_oils_lightest.toml"),
        ),
        (
            "seed_oil",
            include_str!("../../../examples/law_map_seed_oil.toml"),
        ),
        (
            "seed_oil_high_l",
            include_str!("../../../examples/law_map_seed_oil_high_l.toml"),
        ),
        (
            "seed_oil_low_m",
            include_str!("../../../examples/law_map_seed_oil_low_m.toml"),
        ),
        (
            "seed_oil_high_m",
            include_str!("../../../examples/law_map_seed_oil_high_m.toml"),
        ),
    ] {
        let spec = LawMapSpec::from_toml(text).unwrap();
        let bad = under_resolved_nodes(&spec).unwrap();
        let below5 = bad.iter().filter(|x| x.1 < 5.0).count();
        let min = (0..spec.node_count())
            .map(|i| node_film_resolution(&spec.node_groups(i), &spec).unwrap())
            .fold(f64::INFINITY, f64::min);
        let worst = bad.first().map(|&(i, _)| spec.node_groups(i));
        println!(
            "{name}: {} nodes, {} below {FILM_RESOLUTION_MIN}, {below5} below 5, least {min:.2}{}",
            spec.node_count(),
            bad.len(),
            worst.map_or(String::new(), |g| format!(
                " at M {:.0} L {:.2} Ry/Rx {:.1} alpha_p0 {:?} ln {:?}",
                g.m, g.l, g.ry_over_rx, g.alpha_p0, g.ln_eta0_ratio
            ))
        );
    }
}
