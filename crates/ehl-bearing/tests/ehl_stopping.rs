//! Iteration error against cycles: how far H_c and δ after k finest-grid cycles are from the
//! grid's fully converged values, for the stopping-rule study of docs/ehl.md §2.
//!
//!     cargo test --release -p ehl-bearing --test ehl_stopping -- --ignored --nocapture
//!     (EHL_STOP_GRID=257 by default)

use ehl_bearing::ehl::{
    solve_moes, solve_steady_starts, DensityModel, EhlContact, EhlSettings, EhlSolution, MoesCase,
    StartStrategy, ViscosityModel,
};
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

fn seed(load: f64, us: f64, rx: f64, ry: f64) -> EhlContact {
    EhlContact {
        load,
        rx,
        ry,
        sum_velocity: us,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn run(name: &str, f: &dyn Fn(&EhlSettings) -> EhlSolution, grid: usize) {
    let tight = EhlSettings {
        grid,
        tol_residual: 1e-7,
        tol_force: 1e-10,
        tol_film: 1e-9,
        max_cycles: 60,
        ..Default::default()
    };
    let full = f(&tight);
    let def = f(&EhlSettings {
        grid,
        ..Default::default()
    });
    println!(
        "{name}: fully converged {} in {} cycles (residual {:.2e}): H_c {:.6}, δ {:.6} µm; \
         defaults stop at {} cycles, H_c err {:+.2e}, δ err {:+.2e}",
        full.converged,
        full.cycles,
        full.residual,
        full.h_central_moes,
        full.approach * 1e6,
        def.cycles,
        def.h_central / full.h_central - 1.0,
        def.approach / full.approach - 1.0
    );
    println!("  k residual H_c_err delta_err");
    for k in 1..=full.cycles.min(12) {
        let r = f(&EhlSettings {
            max_cycles: k,
            ..tight
        });
        println!(
            "  {k} {:.2e} {:+.2e} {:+.2e}",
            r.residual,
            r.h_central / full.h_central - 1.0,
            r.approach / full.approach - 1.0
        );
    }
}

#[test]
#[ignore]
fn iteration_error_by_cycle() {
    let grid: usize = std::env::var("EHL_STOP_GRID")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(257);
    let circ = MoesCase::new(
        20.0,
        10.0,
        1.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    run(
        "circular M 20 L 10 Roelands/DH",
        &|s| solve_moes(&circ, s).expect("solves"),
        grid,
    );
    let heavy = seed(600.0, 10.85, 2.9487e-3, 178.5e-3);
    run(
        "seed inner 600 N 5000 rpm",
        &|s| solve_steady_starts(&heavy, s, &[StartStrategy::Given], None).expect("solves"),
        grid,
    );
    let light = seed(122.5, 10.858789909551989, 2.956517394901299e-3, 0.1785);
    run(
        "seed inner 122 N 5000 rpm",
        &|s| solve_steady_starts(&light, s, &[StartStrategy::Conservative], None).expect("solves"),
        grid,
    );
    let outer = seed(561.7, 10.858789909551989, 3.6e-3, 42.0e-3);
    run(
        "outer-like 562 N Ry/Rx 11.7",
        &|s| solve_steady_starts(&outer, s, &[StartStrategy::Given], None).expect("solves"),
        grid,
    );
}
