//! How the harmonic method's damping ĉ depends on the time steps' film tolerance
//! (`HarmonicSettings::step_tol_film`; by default 7e-6·Ψ_H within [7e-8, 7e-5]) and on the mass
//! group Ψ_H
//! (docs/contact.md, "Known limits"; docs/law_map.md §7).
//!
//! One contact — the centre of the mineral-oils map's box: M 1162, L 19.25, Ry/Rx 25.1,
//! α·p0 3.975, ln(η0/η∞) 5.55, on a contact with Rx = 5 mm and a steel pair's E′ — with the
//! masses that give Ψ_H = 0.1, 0.3, 1, 3 and 10 (`law_map::mass_for_group`), each characterized
//! by the harmonic method at its defaults (Ω = 0.005·ω_n, 64 steps a period, grid 129²) with the
//! default step tolerance (which follows Ψ_H) and the fixed ones 7e-5, 7e-6, 7e-7 and 7e-8.
//! Printed: the tolerance used, ĉ (c·δ_H·u_s/(w0·b)) at each, its difference from the 7e-8
//! value, d, and the cycles per step and seconds of each run.
//!
//! `cargo run --release -p ehl-bearing --example harmonic_step_tolerance` (≈ 3 min on 2 cores).

use ehl_bearing::contact::{characterize_harmonic, Excitation, HarmonicSettings};
use ehl_bearing::law_map::{mass_for_group, DimensionlessLaw, LawGroups};
use ehl_bearing::material::{DensityModel, ViscosityModel};
use rayon::prelude::*;

/// `None`: the default, which follows Ψ_H. The last is the reference.
const TOLERANCES: [Option<f64>; 5] = [None, Some(7e-5), Some(7e-6), Some(7e-7), Some(7e-8)];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let g = LawGroups {
        m: 1162.0,
        l: 19.25,
        ry_over_rx: (14.0_f64 * 45.0).sqrt(),
        alpha_p0: Some(3.975),
        ln_eta0_ratio: Some(5.55),
        viscosity: ViscosityModel::Roelands,
        density: DensityModel::DowsonHigginson,
    };
    let c = g.contact(5e-3, 2.286e11)?;
    let psis = [0.1, 0.3, 1.0, 3.0, 10.0];
    let runs: Vec<(f64, Option<f64>)> = psis
        .iter()
        .flat_map(|&p| TOLERANCES.iter().map(move |&t| (p, t)))
        .collect();
    let results = runs
        .par_iter()
        .map(|&(psi, tol)| {
            let s = HarmonicSettings {
                step_tol_film: tol,
                ..HarmonicSettings::default()
            };
            let t0 = std::time::Instant::now();
            let fit = characterize_harmonic(&c, mass_for_group(&c, psi)?, &s)?;
            let law = DimensionlessLaw::of_fit(&fit, &c)?;
            let (cycles, used) = match &fit.excitation {
                Excitation::Harmonic(h) => (h.cycles_per_step, h.step_tol_film),
                Excitation::QuasiStatic { .. } => (f64::NAN, f64::NAN),
            };
            Ok((law, cycles, used, t0.elapsed().as_secs_f64()))
        })
        .collect::<Result<Vec<_>, Box<dyn std::error::Error + Send + Sync>>>()
        .map_err(|e| e.to_string())?;
    println!("| Ψ_H | step tolerance | ĉ | ĉ against 7e-8 | d | cycles per step | s |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for (i, &psi) in psis.iter().enumerate() {
        let row = &results[i * TOLERANCES.len()..(i + 1) * TOLERANCES.len()];
        let converged = row[TOLERANCES.len() - 1].0.c_hat.unwrap_or(f64::NAN);
        for (&tol, (law, cycles, used, secs)) in TOLERANCES.iter().zip(row) {
            let ch = law.c_hat.unwrap_or(f64::NAN);
            let label = match tol {
                Some(_) => format!("{used:.0e}"),
                None => format!("default: {used:.1e}"),
            };
            println!(
                "| {psi} | {label} | {ch:.4} | {:+.2} % | {:.5} | {cycles:.2} | {secs:.1} |",
                100.0 * (ch / converged - 1.0),
                law.d
            );
        }
    }
    Ok(())
}
