//! Direct quasi-static characterizations along a line in M through a map's box, beside the map's
//! law (docs/law_map.md §5, "ΔF of heavy contacts"): along such a line the law must vary smoothly,
//! so the scatter of the direct d and ΔF̂ from one point to the next is the direct method's own
//! noise (the steady solutions' iteration error, amplified by the fit), not the map's error.
//!
//! `cargo run --release -p ehl-bearing --example law_map_line_scan -- MAP M0 M1 N L RY_OVER_RX
//! [ALPHA_P0 LN_ETA0_RATIO] [--tolerance-factor F] [--grid N]`
//!
//! N points from M0 to M1 (geometric) at fixed L and Ry/Rx (and the rheology groups, for a map
//! with them as axes), each characterized with the map's settings, the steady solver's tolerances
//! (tol_residual, tol_force, tol_film) times F (default 1; the cycle limit 40·(1 + 2·log10(1/F))
//! below 1: `study::tightened`, as `law-map check --tolerance-factor`), on the map's grid or N × N (the map's
//! law is then only a landmark: it is of its own grid). Printed per point: M, NVM's central film
//! over ΔX² of the grid (`ehl::film_resolution`), the direct and the map's d and ΔF̂ = ΔF/w0, the
//! fit's RMS residual over w0, whether every steady solution met its tolerances, and each
//! solution's approach over the Hertz approach at w0 with its final
//! relative residual (`!` where it stopped short of its tolerances).

use ehl_bearing::contact::characterize_quasi_static;
use ehl_bearing::ehl::film_resolution;
use ehl_bearing::law_map::{hertz_deflection, LawMap};
use ehl_bearing::study::tightened;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut factor = 1.0;
    if let Some(i) = args.iter().position(|a| a == "--tolerance-factor") {
        let v = args.get(i + 1).ok_or("--tolerance-factor needs a value")?;
        factor = v.parse()?;
        args.drain(i..i + 2);
    }
    let mut grid = None;
    if let Some(i) = args.iter().position(|a| a == "--grid") {
        let v = args.get(i + 1).ok_or("--grid needs a value")?;
        grid = Some(v.parse::<usize>()?);
        args.drain(i..i + 2);
    }
    if args.len() != 6 && args.len() != 8 {
        return Err(
            "usage: MAP M0 M1 N L RY_OVER_RX [ALPHA_P0 LN_ETA0_RATIO] [--tolerance-factor F]"
                .into(),
        );
    }
    let map = LawMap::from_json(&std::fs::read_to_string(&args[0])?)?;
    let v: Vec<f64> = args[1..]
        .iter()
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (m0, m1, n) = (v[0], v[1], v[2] as usize);
    if !(m0 > 0.0 && m1 > 0.0 && n >= 1) {
        return Err(format!("M0 = {m0}, M1 = {m1}, N = {n}: expected M0, M1 > 0 and N ≥ 1").into());
    }
    let mut g = map.spec.node_groups(0);
    g.l = v[3];
    g.ry_over_rx = v[4];
    if v.len() == 7 {
        g.alpha_p0 = Some(v[5]);
        g.ln_eta0_ratio = Some(v[6]);
    }
    let mut s = map.spec.settings();
    if let Some(n) = grid {
        s.ehl.grid = n;
    }
    s.ehl = tightened(s.ehl, factor).map_err(|e| e.to_string())?;
    println!("| M | film/ΔX² | d | d (map) | ΔF/w0 | ΔF/w0 (map) | fit RMS/w0 | converged | δ/δ_H (residual) of the solutions |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---|---|");
    for i in 0..n {
        g.m = m0 * (m1 / m0).powf(i as f64 / (n - 1).max(1) as f64);
        let q = map.query(&g)?;
        let c = g.contact(5e-3, 2.286e11)?;
        let fit = characterize_quasi_static(&c, &s)?;
        let dh = hertz_deflection(&c)?;
        let samples: Vec<String> = fit
            .samples
            .iter()
            .map(|x| {
                let mark = if x.converged { "" } else { "!" };
                format!("{:.7} ({:.0e}){mark}", x.approach / dh, x.residual)
            })
            .collect();
        println!(
            "| {:.1} | {:.1} | {:.6} | {:.6} | {:.6} | {:.6} | {:.1e} | {} | {} |",
            g.m,
            film_resolution(&c, &s.ehl)?,
            fit.d,
            q.law.d,
            fit.delta_f / c.load,
            q.law.delta_f_hat,
            fit.rms_residual / c.load,
            fit.converged,
            samples.join(", ")
        );
    }
    Ok(())
}
