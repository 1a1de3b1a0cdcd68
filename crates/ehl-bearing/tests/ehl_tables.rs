//! Validation tables for docs/ehl.md (slow; run with
//! `cargo test --release -p ehl-bearing --test ehl_tables -- --ignored --nocapture --test-threads 1`).

use ehl_bearing::ehl::formulas::nijenbanning_central;
use ehl_bearing::ehl::*;

fn case(m: f64, l: f64, r: f64) -> MoesCase {
    MoesCase::new(
        m,
        l,
        r,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    )
}

#[test]
#[ignore]
fn explore() {
    let args: Vec<f64> = std::env::var("EHL_CASE")
        .unwrap_or("20,10,1,129".into())
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let mut s = EhlSettings {
        grid: args[3] as usize,
        ..Default::default()
    };
    if let Ok(v) = std::env::var("EHL_INLET") {
        s.inlet = Some(v.parse().unwrap());
    }
    if let Ok(v) = std::env::var("EHL_HALF") {
        s.half_width = Some(v.parse().unwrap());
    }
    if let Ok(v) = std::env::var("EHL_CYCLE") {
        s.cycle = if v == "V" { CycleType::V } else { CycleType::W };
    }
    if let Ok(v) = std::env::var("EHL_SET") {
        for kv in v.split(',') {
            let (k, val) = kv.split_once('=').unwrap();
            let x: f64 = val.parse().unwrap();
            match k {
                "omega_jd" => s.omega_jd = x,
                "omega_gs" => s.omega_gs = x,
                "coarsest" => s.coarsest = x as usize,
                "h0_gain" => s.h0_gain = x,
                "jd" => s.jd_threshold = x,
                "coarse_sweeps" => s.coarse_sweeps = x as usize,
                "pre" => s.pre_sweeps = x as usize,
                "post" => s.post_sweeps = x as usize,
                "max_cycles" => s.max_cycles = x as usize,
                "outlet" => s.outlet = x,
                _ => panic!("unknown {k}"),
            }
        }
    }
    let mut c = case(args[0], args[1], args[2]);
    if std::env::var("EHL_BARUS").is_ok() {
        c.viscosity = ViscosityModel::Barus;
        c.density = DensityModel::Incompressible;
    }
    match solve_moes(&c, &s) {
        Ok(r) => {
            println!(
                "M {} L {} R {} conv {} cyc {} t {:.3}s Hc {:.5} Hmin {:.5} NVM {:.5} pmax/ph {:.4} delta/dH {:.4} fb {:.2e} steps {} inlet {:.2} hw {:.2}",
                r.moes_m, r.moes_l, r.ry_over_rx, r.converged, r.cycles, r.seconds, r.h_central_moes,
                r.h_min_moes, nijenbanning_central(r.moes_m, r.moes_l, 1.0 / r.ry_over_rx),
                r.p_max / r.p_hertz, r.approach / r.approach_hertz, r.force_balance_residual, r.continuation_steps,
                -r.fields.x[0] / r.fields.a_x, r.fields.y[r.fields.y.len() - 1] / r.fields.a_y
            );
            println!(
                "hist {:?}",
                r.residual_history
                    .iter()
                    .map(|v| format!("{v:.2e}"))
                    .collect::<Vec<_>>()
            );
        }
        Err(e) => println!("error {e}"),
    }
}
