//! `ehl-bearing equilibrium CASE.toml [--json]`.

use anyhow::Context;
use ehl_bearing::bearing::{solve_equilibrium, ContactLaws, Control, Equilibrium, DOF_NAMES};
use ehl_bearing::case::Case;
use ehl_bearing::io::read_case;
use ehl_bearing::report::{to_json_pretty, EquilibriumReport, FilmReport, FilmSummary};
use std::path::PathBuf;

/// Arguments of `equilibrium`.
#[derive(clap::Args)]
pub struct EquilibriumArgs {
    /// Case file (TOML), e.g. examples/7006.toml.
    pub case: PathBuf,
    /// Print JSON in SI units instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also solve the steady EHL problem of every loaded contact and report its central and
    /// minimum film (uses the case's [lubricant]).
    #[arg(long)]
    pub film: bool,
    /// Grid of the EHL solutions for --film (2^k + 1; default that of `ehl`, 257).
    #[arg(long, requires = "film")]
    pub grid: Option<usize>,
}

/// Contacts whose load is below this fraction of the largest contact load are reported unloaded.
const UNLOADED_FRACTION: f64 = 1e-6;
/// Contacts whose sum velocity is below this fraction of the largest are reported without
/// entrainment (dry Hertz contact, no EHL film).
const NO_ENTRAINMENT_FRACTION: f64 = 1e-6;

/// EHL film of one contact.
// One value per contact, a few dozen at most: boxing the solution would buy nothing.
#[allow(clippy::large_enum_variant)]
pub enum Film {
    /// Load below `UNLOADED_FRACTION` of the largest.
    Unloaded,
    /// No entrainment (e.g. co-rotating rings): a dry contact, no film.
    NoEntrainment,
    /// The steady solution, or the solver's message.
    Solved(Result<ehl_bearing::ehl::EhlSolution, String>),
}

/// Solve the steady EHL problem of every loaded contact, in parallel; index 2j inner, 2j+1 outer.
pub fn films(case: &Case, eq: &Equilibrium, grid: Option<usize>) -> Vec<Film> {
    use ehl_bearing::ehl::{solve_steady, EhlContact, EhlSettings};
    use rayon::prelude::*;
    let mut settings = EhlSettings::default();
    if let Some(g) = grid {
        settings.grid = g;
    }
    let e_reduced = case.bearing.reduced_modulus();
    let contacts = eq.contact_states();
    let qmax = contacts.iter().map(|(_, _, c)| c.load).fold(0.0, f64::max);
    let umax = contacts
        .iter()
        .map(|(_, _, c)| c.sum_velocity)
        .fold(0.0, f64::max);
    contacts
        .par_iter()
        .map(|(_, race, c)| {
            if c.load <= UNLOADED_FRACTION * qmax {
                return Film::Unloaded;
            }
            if c.sum_velocity <= NO_ENTRAINMENT_FRACTION * umax || umax == 0.0 {
                return Film::NoEntrainment;
            }
            let ec = EhlContact {
                load: c.load,
                rx: c.rx,
                ry: c.ry,
                sum_velocity: c.sum_velocity,
                e_reduced,
                lubricant: case.lubricant_of(*race),
            };
            Film::Solved(solve_steady(&ec, &settings).map_err(|e| e.to_string()))
        })
        .collect()
}

/// Run `equilibrium`.
pub fn run(args: &EquilibriumArgs) -> anyhow::Result<()> {
    let case = read_case(&args.case)?;
    // The dry equilibrium stays meaningful as a Hertz computation: outside the models' range
    // it warns; with --film (EHL solves) it refuses.
    match ehl_bearing::plausibility::check_case(&case) {
        Ok(warnings) => {
            for w in warnings {
                eprintln!("warning: {}: {w}", args.case.display());
            }
        }
        Err(e) if args.film => {
            return Err(e).with_context(|| {
                format!("{}: outside what the models describe", args.case.display())
            })
        }
        Err(e) => eprintln!(
            "warning: {}: outside what the models describe: {e}",
            args.case.display()
        ),
    }
    let laws = ContactLaws::hertz(&case.bearing)?;
    let eq = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
        .with_context(|| format!("solving {}", args.case.display()))?;
    if let Some(g) = args.grid {
        ehl_bearing::ehl::EhlSettings {
            grid: g,
            ..Default::default()
        }
        .validate()
        .with_context(|| format!("--grid {g}"))?;
    }
    let films = if args.film {
        Some(films(&case, &eq, args.grid))
    } else {
        None
    };
    // Film, Λ, κ and thermal reduction at the dry equilibrium (docs/lubricant.md), when the case
    // describes its oil or gives roughness.
    let lubrication = ehl_bearing::lubrication::wanted(&case).then(|| {
        let states = eq.contact_states();
        // With --film, the films of the converged EHL solutions (index 2j inner, 2j+1 outer).
        let solved: Vec<_> = films
            .iter()
            .flatten()
            .map(|f| match f {
                Film::Solved(Ok(s)) if s.converged => Some((s.h_central, s.h_min)),
                _ => None,
            })
            .collect();
        ehl_bearing::lubrication::assess_with_films(&case, &states, &solved)
    });
    if args.json {
        let mut v = EquilibriumReport::from(&eq);
        if let Some(f) = &films {
            v = v.with_films(f.iter().map(film_report));
        }
        v.lubrication = lubrication.clone();
        println!("{}", to_json_pretty(&v));
    } else {
        print!("{}", table(&case, &eq));
        if let Some(f) = &films {
            print!("{}", film_table(&case, &eq, f));
        }
        if let Some(l) = &lubrication {
            print!("{}", ehl_bearing::lubrication::table(l));
        }
    }
    for w in lubrication.iter().flat_map(|l| &l.warnings) {
        eprintln!("warning: {}: {w}", args.case.display());
    }
    if let Some(f) = &films {
        let failed = f
            .iter()
            .filter(|x| matches!(x, Film::Solved(r) if !matches!(r, Ok(s) if s.converged)))
            .count();
        if failed > 0 {
            anyhow::bail!("{failed} EHL contact solution(s) did not converge (see the film table)");
        }
    }
    Ok(())
}

/// Needed over available friction as a percentage, or "—" for an unloaded contact.
fn friction_use(c: &ehl_bearing::bearing::ContactState) -> String {
    if c.friction_limit > 0.0 {
        format!("{:.0} %", 100.0 * c.friction_needed / c.friction_limit)
    } else if c.friction_needed > 0.0 {
        "unloaded".into()
    } else {
        "—".into()
    }
}

/// Human-readable report in engineering units.
pub fn table(case: &Case, eq: &Equilibrium) -> String {
    let mut s = String::new();
    bearing_and_dofs(&mut s, case, eq);
    balls_table(&mut s, eq);
    race_control_table(&mut s, eq);
    stiffness_matrix(&mut s, eq);
    s
}

/// The bearing, its speeds and the solve, and each DOF's control, displacement and load.
fn bearing_and_dofs(s: &mut String, case: &Case, eq: &Equilibrium) {
    use std::fmt::Write;
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
        "speeds: inner {:.0} rpm, outer {:.0} rpm; race control {:?}; kinematics {:?}; dry Hertz contacts",
        op.inner_speed * rpm,
        op.outer_speed * rpm,
        op.race_control,
        case.settings.kinematics
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
}

/// One line per ball: both contacts' loads, angles, approaches, pressures and sum velocities.
fn balls_table(s: &mut String, eq: &Equilibrium) {
    use std::fmt::Write;
    let rpm = 30.0 / std::f64::consts::PI;
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
}

/// One line per ball: pitch, roll speed, gyroscopic moment, spin-to-roll and friction use; then
/// the equilibrium's warnings.
fn race_control_table(s: &mut String, eq: &Equilibrium) {
    use std::fmt::Write;
    let rpm = 30.0 / std::f64::consts::PI;
    let _ = writeln!(
        s,
        "\nrace control (spin/roll: spin-to-roll ratio; friction: what the gyroscopic moment needs, in % of μ_max·Q, μ_max = {})",
        ehl_bearing::bearing::equilibrium::MU_MAX
    );
    let _ = writeln!(
        s,
        "{:>4} {:>8} {:>10} {:>10} | {:>10} {:>10} | {:>10} {:>10}",
        "ball", "β °", "ω_R rpm", "G N·m", "spin/roll i", "spin/roll o", "friction i", "friction o"
    );
    for (j, b) in eq.balls.iter().enumerate() {
        let _ = writeln!(
            s,
            "{:>4} {:>8.3} {:>10.0} {:>10.4} | {:>11.4} {:>11.4} | {:>10} {:>10}",
            j,
            b.pitch_angle.to_degrees(),
            b.spin_speed * rpm,
            b.gyroscopic_moment,
            b.inner.spin_to_roll,
            b.outer.spin_to_roll,
            friction_use(&b.inner),
            friction_use(&b.outer)
        );
    }
    for w in &eq.warnings {
        let _ = writeln!(s, "warning: {w}");
    }
}

/// The 5 × 5 stiffness matrix.
fn stiffness_matrix(s: &mut String, eq: &Equilibrium) {
    use std::fmt::Write;
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
}

fn film_report(f: &Film) -> FilmReport {
    match f {
        Film::Unloaded => FilmReport::Unloaded,
        Film::NoEntrainment => FilmReport::NoEntrainment,
        Film::Solved(Ok(s)) => FilmReport::Solved(FilmSummary::from(s)),
        Film::Solved(Err(e)) => FilmReport::Failed {
            converged: false,
            error: e.clone(),
        },
    }
}

/// Film table in engineering units.
pub fn film_table(case: &Case, eq: &Equilibrium, films: &[Film]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let l = &case.lubricant;
    let _ = writeln!(
        s,
        "\nEHL films ({}lubricant: η0 = {} Pa·s, α = {:.3e} 1/Pa, {:?}, {:?})",
        if case.lubricant_given { "" } else { "default " },
        l.viscosity,
        l.pressure_viscosity,
        l.viscosity_model,
        l.density_model
    );
    let _ = writeln!(
        s,
        "{:>4} {:>5} | {:>8} {:>7} {:>8} {:>8} {:>8} {:>7} | conv",
        "ball", "race", "Q N", "M", "L", "h_c µm", "h_min µm", "p GPa"
    );
    for (j, b) in eq.balls.iter().enumerate() {
        for (k, (race, c)) in [("inner", &b.inner), ("outer", &b.outer)]
            .iter()
            .enumerate()
        {
            match &films[2 * j + k] {
                Film::Unloaded => {
                    let _ = writeln!(s, "{j:>4} {race:>5} | {:>8.2}  unloaded", c.load);
                }
                Film::NoEntrainment => {
                    let _ = writeln!(
                        s,
                        "{j:>4} {race:>5} | {:>8.2}  no entrainment (dry contact)",
                        c.load
                    );
                }
                Film::Solved(Ok(x)) => {
                    let _ = writeln!(
                        s,
                        "{:>4} {:>5} | {:>8.2} {:>7.1} {:>8.2} {:>8.4} {:>8.4} {:>7.3} | {}",
                        j,
                        race,
                        c.load,
                        x.moes_m,
                        x.moes_l,
                        x.h_central * 1e6,
                        x.h_min * 1e6,
                        x.p_max * 1e-9,
                        if x.converged { "yes" } else { "NO" }
                    );
                }
                Film::Solved(Err(e)) => {
                    let _ = writeln!(s, "{j:>4} {race:>5} | {:>8.2}  failed: {e}", c.load);
                }
            }
        }
    }
    s
}
