//! Where the time of one law-map node goes: the node's quasi-static family (the seven steady
//! solutions of `study::law_map::characterize_groups`, same settings, same order and warm starts)
//! solved step by step, printing per solution the starts tried, their cycles and residuals, and the
//! residual history; then the node itself timed through `characterize_groups`.
//!
//! ```sh
//! cargo run --release -p ehl-bearing --example law_map_node_profile -- M L RY_OVER_RX [ALPHA_P0 LN_ETA0_RATIO [GRID]]
//! ```
//! Defaults: the seed oil's groups α·p0 = 4.312, ln(η0/η∞) = 6.451, grid 65 (the maps' grid).

use ehl_bearing::ehl::{
    solve_steady, solve_steady_extrapolated, solve_steady_from, DensityModel, EhlSettings,
    EhlSolution, ViscosityModel,
};
use ehl_bearing::law_map::{LawGroups, LawMapSpec};
use ehl_bearing::study::{characterize_groups, node_film_resolution};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    if a.len() < 3 {
        return Err(
            "usage: law_map_node_profile M L RY_OVER_RX [ALPHA_P0 LN_ETA0_RATIO [GRID]]".into(),
        );
    }
    let g = LawGroups {
        m: a[0],
        l: a[1],
        ry_over_rx: a[2],
        alpha_p0: Some(*a.get(3).unwrap_or(&4.312)),
        ln_eta0_ratio: Some(*a.get(4).unwrap_or(&6.451)),
        viscosity: ViscosityModel::Roelands,
        density: DensityModel::DowsonHigginson,
    };
    let grid = a.get(5).map_or(65, |&x| x as usize);
    let spec_text = format!(
        "viscosity_model = \"roelands\"\ndensity_model = \"dowson-higginson\"\namplitude = 0.2\npoints = 7\ngrid = {grid}\nl = {}\nry_over_rx = {}\nalpha_p0 = {}\nln_eta0_ratio = {}\n[[axis]]\ngroup = \"m\"\nmin = {}\nmax = {}\nnodes = 3\nlog = true\n",
        g.l, g.ry_over_rx, g.alpha_p0.unwrap(), g.ln_eta0_ratio.unwrap(),
        0.9 * g.m,
        1.1 * g.m
    );
    let spec = LawMapSpec::from_toml(&spec_text)?;
    let qs = spec.settings();
    let c = g.contact(5e-3, 2.286e11)?;
    let n = qs.points;
    let loads: Vec<f64> = (0..n)
        .map(|k| c.load * (1.0 + qs.amplitude * (2.0 * k as f64 / (n - 1) as f64 - 1.0)))
        .collect();
    let mid = n / 2;
    let mut sols: Vec<Option<EhlSolution>> = vec![None; n];
    let report = |k: usize, s: &EhlSolution, t: f64| {
        println!(
            "  load {k} ({:.3} w0): M {:.0} conv {} cycles {} attempts {} t {:.3}s res {:.2e} force {:.2e} Hc {:.4} Hmin {:.4} delta/dH {:.5}",
            loads[k] / c.load,
            s.moes_m,
            s.converged,
            s.cycles,
            s.attempts,
            t,
            s.residual,
            s.force_balance_residual,
            s.h_central_moes,
            s.h_min_moes,
            s.approach / s.approach_hertz
        );
        for at in &s.attempt_log {
            println!(
                "      {:?} {:?} cycles {} res {:.2e} {:.3}s",
                at.strategy, at.outcome, at.cycles, at.residual, at.seconds
            );
        }
        let h: Vec<String> = s
            .residual_history
            .iter()
            .map(|r| format!("{r:.1e}"))
            .collect();
        println!("      history [{}]", h.join(" "));
    };
    if std::env::var_os("NODE_ONLY").is_some() {
        return node(&g, &spec, f64::NAN);
    }
    let t0 = Instant::now();
    let c_mid = ehl_bearing::ehl::EhlContact {
        load: loads[mid],
        ..c
    };
    let t = Instant::now();
    let centre = solve_steady(&c_mid, &qs.ehl)?;
    report(mid, &centre, t.elapsed().as_secs_f64());
    let f = &centre.fields;
    let ehl = EhlSettings {
        inlet: Some(-f.x[0] / f.a_x),
        outlet: f.x.last().unwrap() / f.a_x,
        half_width: Some(f.y.last().unwrap() / f.a_y),
        ..qs.ehl
    };
    // The film against the grid: NVM's central film in units a_x²/Rx and the mesh ΔX (in a_x).
    let nvm = ehl_bearing::ehl::formulas::nijenbanning_central(g.m, g.l, 1.0 / g.ry_over_rx);
    let to_dimless = centre.h_central / centre.h_central_moes * c.rx / (f.a_x * f.a_x);
    let dx = (f.x[1] - f.x[0]) / f.a_x;
    println!(
        "  domain: inlet {:.3} outlet {:.3} half_width {:.3} a_y/a_x {:.3}; NVM H_c {:.3} Moes = {:.3e} a_x²/Rx, dX {:.4}, H_nvm/dX² {:.3}",
        ehl.inlet.unwrap(),
        ehl.outlet,
        ehl.half_width.unwrap(),
        f.a_y / f.a_x,
        nvm,
        nvm * to_dimless,
        dx,
        nvm * to_dimless / (dx * dx)
    );
    sols[mid] = Some(centre);
    for k in (0..mid).rev().chain(mid + 1..n) {
        let from = if k < mid { k + 1 } else { k - 1 };
        let before = if k < mid { k + 2 } else { k.wrapping_sub(2) };
        let ck = ehl_bearing::ehl::EhlContact {
            load: loads[k],
            ..c
        };
        let prev = sols[from].as_ref().unwrap();
        let t = Instant::now();
        let s = match sols.get(before).and_then(|x| x.as_ref()) {
            Some(e) => {
                solve_steady_extrapolated(&ck, &ehl, (prev, loads[from]), (e, loads[before]))?
            }
            None => solve_steady_from(&ck, &ehl, prev)?,
        };
        report(k, &s, t.elapsed().as_secs_f64());
        sols[k] = Some(s);
    }
    node(&g, &spec, t0.elapsed().as_secs_f64())
}

/// Times the node through `characterize_groups` and prints its law.
fn node(g: &LawGroups, spec: &LawMapSpec, fam: f64) -> Result<(), Box<dyn std::error::Error>> {
    let t = Instant::now();
    let r = characterize_groups(g, spec);
    let node = t.elapsed().as_secs_f64();
    let head = format!(
        "node M {} L {} Ry/Rx {} alpha_p0 {} ln_eta0_ratio {} grid {} (film/ΔX² {:.2}): family {fam:.2}s, characterize_groups {node:.2}s,",
        g.m,
        g.l,
        g.ry_over_rx,
        g.alpha_p0.unwrap_or(f64::NAN),
        g.ln_eta0_ratio.unwrap_or(f64::NAN),
        spec.grid,
        node_film_resolution(g, spec)?
    );
    match r {
        Ok((law, q)) => println!(
            "{head} converged {}, rms/w0 {:.2e}, d {:.5} dF/w0 {:.5e}",
            q.converged, q.rms_hat, law.d, law.delta_f_hat
        ),
        Err(e) => println!("{head} error {e}"),
    }
    Ok(())
}
