//! The groups of the harmonic law (docs/law_map.md §7): does the damping c made dimensionless
//! depend only on the quasi-static groups (M, L, Ry/Rx and the oil's), or also on the ball's
//! mass through Ψ = ω_n·b/u_s (the contact's natural frequency times the time the oil takes to
//! cross the Hertz semi-width)? Four harmonic characterizations at the default Ω = 0.005·ω_n:
//!
//! 1. a seed-like contact;
//! 2. the same contact scaled by λ = 2 (lengths ×2, load ×4, sum velocity ×2: M, L, Ry/Rx
//!    unchanged) with the mass ×2, which keeps Ψ;
//! 3. the scaled contact with the mass a real ball of twice the size has (×8): Ψ halves;
//! 4. the first contact with the mass ×4: Ψ halves too.
//!
//! Printed per run: Ψ, d, ΔF/w0, ĉ = c·δ_H·(u_s/b)/w0 (δ_H the Hertz approach at w0) and the time.
//! If c depends on Ψ, runs 1 and 2 agree with each other, runs 3 and 4 with each other, and the two
//! pairs differ.
//!
//! `cargo run --release -p ehl-bearing --example harmonic_groups [GRID]` (GRID 65 default).

use ehl_bearing::contact::{ball_mass, characterize_harmonic, Excitation, HarmonicSettings};
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::material::{Lubricant, Solid};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let grid: usize = match std::env::args().nth(1) {
        Some(g) => g.parse()?,
        None => 65,
    };
    let mut s = HarmonicSettings::default();
    s.ehl.grid = grid;
    let base = EhlContact {
        load: 500.0,
        rx: 3.0e-3,
        ry: 0.04,
        sum_velocity: 10.0,
        e_reduced: 2.26e11,
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    };
    let scaled = |l: f64| EhlContact {
        load: base.load * l * l,
        rx: base.rx * l,
        ry: base.ry * l,
        sum_velocity: base.sum_velocity * l,
        ..base
    };
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    println!("| run | λ | mass | Ψ = ω_n·b/u_s | d | ΔF/w0 | ĉ = c·δ_H·u_s/(w0·b) | s |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut laws = Vec::new();
    for (run, (c, mass)) in [
        (base, m),
        (scaled(2.0), 2.0 * m),
        (scaled(2.0), 8.0 * m),
        (base, 4.0 * m),
    ]
    .into_iter()
    .enumerate()
    {
        let fit = characterize_harmonic(&c, mass, &s)?;
        let Excitation::Harmonic(x) = fit.excitation else {
            return Err("the harmonic method records a harmonic excitation".into());
        };
        let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?.contact(c.load);
        let damping = fit.law.c().unwrap_or(f64::NAN);
        let psi = x.natural_frequency_rad_s * h.semi_minor / c.sum_velocity;
        let c_hat = damping * h.deflection * c.sum_velocity / (c.load * h.semi_minor);
        laws.push([fit.d, fit.delta_f / c.load, c_hat]);
        println!(
            "| {} | {:.0} | {:.0}·m | {psi:.5} | {:.5} | {:.6} | {:.6} | {:.1} |",
            run + 1,
            c.rx / base.rx,
            mass / m,
            fit.d,
            fit.delta_f / c.load,
            c_hat,
            fit.seconds
        );
    }
    let rel = |a: &[f64; 3], b: &[f64; 3]| {
        [
            (a[0] - b[0]).abs(),
            (a[1] / b[1] - 1.0).abs(),
            (a[2] / b[2] - 1.0).abs(),
        ]
    };
    println!(
        "equal Ψ (1 vs 2, 3 vs 4): |Δd|, ΔF/w0 and ĉ relative: {:.1e} {:.1e} {:.1e} / {:.1e} {:.1e} {:.1e}",
        rel(&laws[0], &laws[1])[0],
        rel(&laws[0], &laws[1])[1],
        rel(&laws[0], &laws[1])[2],
        rel(&laws[2], &laws[3])[0],
        rel(&laws[2], &laws[3])[1],
        rel(&laws[2], &laws[3])[2]
    );
    let r = rel(&laws[2], &laws[0]);
    println!(
        "Ψ halved (3 vs 1): |Δd| {:.1e}, ΔF/w0 {:+.2} %, ĉ {:+.2} %",
        r[0],
        100.0 * (laws[2][1] / laws[0][1] - 1.0),
        100.0 * (laws[2][2] / laws[0][2] - 1.0)
    );
    Ok(())
}
