//! Hamrock & Dowson's (1977) starvation correlation against this crate's steady EHL solver with
//! the zero-pressure inlet boundary at the meniscus (m = x_inlet/a_x, a_x the Hertz semi-width
//! along the rolling direction). Prints, per contact and inlet distance m, the starved/flooded
//! central and minimum film ratios of both (docs/lubricant.md §3).
//!
//! ```sh
//! cargo run --release -p ehl-bearing --example starvation_check [GRID]   # GRID 257 (default)
//! ```
//! The domain length is kept fixed (the outlet takes what the inlet does not) so that every
//! solution of a contact has the same grid spacing.

use ehl_bearing::ehl::{solve_steady, EhlContact, EhlSettings};
use ehl_bearing::hertz::HertzGeometry;
use ehl_bearing::lubrication::starvation;
use ehl_bearing::material::Lubricant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let grid: usize = match std::env::args().nth(1) {
        Some(g) => g.parse()?,
        None => 257,
    };
    let e = 2.26e11;
    let rx = 3.3e-3;
    println!("| contact | m | m* (min) | h_c ratio HD | h_c ratio solver | h_min ratio HD | h_min ratio solver |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    // (load N, Ry m, sum velocity m/s, domain length in a_x)
    for (load, ry, us, total) in [(600.0, 0.05, 10.0, 4.5), (100.0, 0.02, 20.0, 6.5)] {
        let c = EhlContact {
            load,
            rx,
            ry,
            sum_velocity: us,
            e_reduced: e,
            lubricant: Lubricant::DEFAULT_MINERAL_OIL,
        };
        let b = HertzGeometry::new(rx, ry, e)?.contact(load).semi_minor;
        let s = EhlSettings {
            grid,
            inlet: Some(total - 1.5),
            outlet: 1.5,
            ..EhlSettings::default()
        };
        let f = solve_steady(&c, &s)?;
        let name = format!(
            "{load} N, Ry/Rx {:.1}, M {:.0}, L {:.1}",
            ry / rx,
            f.moes_m,
            f.moes_l
        );
        for m in [1.1, 1.25, 1.5, 2.0, 2.5, 3.0] {
            if m >= total - 1.0 {
                continue;
            }
            let r = solve_steady(
                &c,
                &EhlSettings {
                    inlet: Some(m),
                    outlet: total - m,
                    ..s
                },
            )?;
            let hd = starvation(f.h_central, f.h_min, rx, b, m * b);
            println!(
                "| {name} | {m:.2} | {:.2} | {:.3} | {:.3}{} | {:.3} | {:.3} |",
                hd.boundary_ratio,
                1.0 - hd.central_reduction,
                r.h_central / f.h_central,
                if r.converged { "" } else { " (not converged)" },
                1.0 - hd.reduction,
                r.h_min / f.h_min,
            );
        }
    }
    Ok(())
}
