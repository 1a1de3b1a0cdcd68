//! `ehl-bearing equilibrium CASE.toml [--json]`.

use anyhow::Context;
use ehl_bearing::bearing::{solve_equilibrium, ContactLaws, Control, Equilibrium, DOF_NAMES};
use ehl_bearing::io::{json::equilibrium_json, read_case, Case};
use std::path::PathBuf;

/// Arguments of `equilibrium`.
#[derive(clap::Args)]
pub struct EquilibriumArgs {
    /// Case file (TOML), e.g. examples/7006.toml.
    pub case: PathBuf,
    /// Print JSON in SI units instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Run `equilibrium`.
pub fn run(args: &EquilibriumArgs) -> anyhow::Result<()> {
    let case = read_case(&args.case)?;
    let laws = ContactLaws::hertz(&case.bearing)?;
    let eq = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
        .with_context(|| format!("solving {}", args.case.display()))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&equilibrium_json(&eq))?);
    } else {
        print!("{}", table(&case, &eq));
    }
    Ok(())
}

/// Human-readable report in engineering units.
pub fn table(case: &Case, eq: &Equilibrium) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let g = &case.bearing.geometry;
    let op = &case.operating;
    let rpm = 30.0 / std::f64::consts::PI;
    let _ = writeln!(
        s,
        "{}: Z = {}, D = {} mm, dm = {} mm, f_i = {}, f_o = {}, α0 = {:.2}°",
        case.name.as_deref().unwrap_or("bearing"),
        g.ball_count,
        g.ball_diameter * 1e3,
        g.pitch_diameter * 1e3,
        g.inner_conformity,
        g.outer_conformity,
        g.free_contact_angle.to_degrees()
    );
    let _ = writeln!(
        s,
        "speeds: inner {:.0} rpm, outer {:.0} rpm; race control {:?}; dry Hertz contacts",
        op.inner_speed * rpm,
        op.outer_speed * rpm,
        op.race_control
    );
    let _ = writeln!(
        s,
        "converged in {} Newton iterations, residual {:.2e} N\n",
        eq.iterations, eq.residual
    );
    let _ = writeln!(
        s,
        "{:<8} {:>10} {:>14} {:>16}",
        "DOF", "control", "displacement", "load"
    );
    for (k, name) in DOF_NAMES.iter().enumerate() {
        let (dunit, dfac, lunit) = if k < 3 {
            ("µm", 1e6, "N")
        } else {
            ("mdeg", 1e3 * 180.0 / std::f64::consts::PI, "N·m")
        };
        let ctl = match op.dofs[k] {
            Control::Load(_) => "load",
            Control::Displacement(_) => "imposed",
        };
        let _ = writeln!(
            s,
            "{:<8} {:>10} {:>11.4} {:<4} {:>11.4} {:<4}",
            name,
            ctl,
            eq.displacement[k] * dfac,
            dunit,
            eq.reaction[k],
            lunit
        );
    }
    let _ = writeln!(
        s,
        "\n{:>4} {:>7} | {:>8} {:>7} {:>7} {:>6} {:>6} | {:>8} {:>7} {:>7} {:>6} {:>6} | {:>8} {:>7}",
        "ball", "ψ °", "Q_i N", "α_i °", "δ_i µm", "p GPa", "u_s", "Q_o N", "α_o °", "δ_o µm", "p GPa", "u_s", "ω_m rpm", "F_c N"
    );
    for (j, b) in eq.balls.iter().enumerate() {
        let _ = writeln!(
            s,
            "{:>4} {:>7.1} | {:>8.2} {:>7.3} {:>7.3} {:>6.3} {:>6.2} | {:>8.2} {:>7.3} {:>7.3} {:>6.3} {:>6.2} | {:>8.1} {:>7.2}",
            j,
            b.azimuth.to_degrees(),
            b.inner.load,
            b.inner.contact_angle.to_degrees(),
            b.inner.deflection * 1e6,
            b.inner.max_pressure * 1e-9,
            b.inner.sum_velocity,
            b.outer.load,
            b.outer.contact_angle.to_degrees(),
            b.outer.deflection * 1e6,
            b.outer.max_pressure * 1e-9,
            b.outer.sum_velocity,
            b.orbital_speed * rpm,
            b.centrifugal_force
        );
    }
    let _ = writeln!(
        s,
        "\nstiffness matrix (rows: reaction F_x, F_y, F_z [N], M_y, M_z [N·m]; columns: x, y, z [m], θy, θz [rad])"
    );
    for row in &eq.stiffness {
        let _ = writeln!(
            s,
            "  {}",
            row.iter()
                .map(|v| format!("{v:>12.4e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    s
}
