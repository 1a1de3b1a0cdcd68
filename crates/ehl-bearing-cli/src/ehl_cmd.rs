//! `ehl-bearing ehl`: one steady EHL point contact, from a contact file (SI/engineering units)
//! or in Moes' dimensionless parameters.
//!
//! ```text
//! ehl-bearing ehl CONTACT.toml [--json] [--grid N] [--fields DIR]   # DIR: fields as CSV + 4 figures
//! ehl-bearing ehl --moes-m M --moes-l L [--ry-over-rx R] [--viscosity barus|roelands]
//!                 [--density incompressible|dowson-higginson] [--grid N] [--json]
//! ```
//!
//! Contact file keys: `load_n`, `rx_mm`, `ry_mm`, `sum_velocity_m_s` (u1 + u2), either
//! `reduced_modulus_gpa` (E′, 2/E′ = Σ(1−ν²)/E) or the tables `[ball_material]` and
//! `[ring_material]` (`youngs_modulus_gpa`, `poisson_ratio`, `density_kg_m3`; default AISI 52100:
//! 208 GPa, 0.3, 7850 kg/m³), and an optional `[lubricant]` table (`viscosity_pa_s` default
//! 0.04, `pressure_viscosity_1_pa` default 2.2e-8, `density_kg_m3` default 870,
//! `viscosity_model` = "roelands" (default) | "barus", `density_model` = "dowson-higginson"
//! (default) | "incompressible"). Unknown keys are rejected.

use anyhow::{bail, Context, Result};
use ehl_bearing::ehl::{self, EhlSettings, EhlSolution, MoesCase};
use ehl_bearing::material::{DensityModel, ViscosityModel};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Viscosity model on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ViscosityArg {
    /// Roelands (default).
    Roelands,
    /// Barus.
    Barus,
}

/// Density model on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DensityArg {
    /// Dowson–Higginson (default).
    DowsonHigginson,
    /// Incompressible.
    Incompressible,
}

/// Arguments of `ehl-bearing ehl`.
#[derive(Debug, Clone, clap::Args)]
pub struct EhlArgs {
    /// Contact file (TOML). Omit it when giving --moes-m and --moes-l.
    #[arg(value_name = "CONTACT.toml", conflicts_with_all = ["moes_m", "moes_l"])]
    pub contact: Option<PathBuf>,
    /// Print the result as JSON (SI units) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Grid points per side on the finest level (2^k + 1, 17 to 1025; default 257).
    #[arg(long)]
    pub grid: Option<usize>,
    /// Inlet length in Hertz semi-axes a_x (default automatic: 4.5 circular to 10.5 elongated).
    #[arg(long)]
    pub inlet: Option<f64>,
    /// Transverse half-width of the domain in semi-axes a_y (default from the solver settings).
    #[arg(long)]
    pub half_width: Option<f64>,
    /// Largest number of multigrid cycles (default from the solver settings, 40).
    #[arg(long)]
    pub max_cycles: Option<usize>,
    /// Wall-time budget in seconds: the solve stops with an error carrying its residual history
    /// when it runs out (default: none; the cycle limit always applies).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Write into this directory pressure.csv and film.csv (long format x_m,y_m,value; Pa and m)
    /// and four figures, each as .png and .svg: pressure_map and film_map (zoomed to the contact,
    /// Hertz ellipse overlaid), centreline_rolling (p/p_h and h along Y = 0) and
    /// centreline_transverse (along X = 0, grid nodes marked, cell sizes in the title); see
    /// docs/gallery.md.
    #[arg(long, value_name = "DIR")]
    pub fields: Option<PathBuf>,
    /// Moes load parameter M = W·U^(-3/4) (dimensionless mode).
    #[arg(long, requires = "moes_l", allow_negative_numbers = true)]
    pub moes_m: Option<f64>,
    /// Moes material parameter L = G·U^(1/4) (dimensionless mode).
    #[arg(long, requires = "moes_m", allow_negative_numbers = true)]
    pub moes_l: Option<f64>,
    /// Ry/Rx in the dimensionless mode (default 1).
    #[arg(long, default_value_t = 1.0)]
    pub ry_over_rx: f64,
    /// Viscosity model in the dimensionless mode.
    #[arg(long, value_enum, default_value_t = ViscosityArg::Roelands)]
    pub viscosity: ViscosityArg,
    /// Density model in the dimensionless mode.
    #[arg(long, value_enum, default_value_t = DensityArg::DowsonHigginson)]
    pub density: DensityArg,
}

fn settings(args: &EhlArgs) -> EhlSettings {
    let mut s = EhlSettings::default();
    if let Some(g) = args.grid {
        s.grid = g;
    }
    if let Some(v) = args.inlet {
        s.inlet = Some(v);
    }
    if let Some(v) = args.max_cycles {
        s.max_cycles = v;
    }
    if let Some(v) = args.half_width {
        s.half_width = Some(v);
    }
    s
}

/// Grids of 513² and more cost seconds per solve and more per characterization: say so at once,
/// with the way to bound it (`ehl --grid 1025` once gave up after 293 s; measured since on
/// the 2-core machine, 2026-11-25: circular M 20 L 10 0.4 s at 513², 1.9 s at 1025²; the seed's
/// inner contact 0.4 s and 12 s, five starts, at 1025²; a quasi-static family of 7 solutions at
/// 513², 9–90 s in docs/contact.md, "Default accuracy").
pub fn large_grid_notice(s: &EhlSettings, time_limit: Option<f64>) {
    if s.grid >= 513 {
        eprintln!(
            "note: a {0}×{0} grid takes seconds per EHL solve (on two cores: 0.4 s at 513², \
             2 s for a circular contact and 12 s for the seed's inner contact at 1025²) and up to \
             minutes for a characterization or a hard case (up to {1} cycles per start){2}",
            s.grid,
            s.max_cycles,
            match time_limit {
                Some(t) => format!("; stopping after {t} s (--time-limit)"),
                None => "; bound it with --time-limit SECONDS".into(),
            }
        );
    }
}

/// Human-readable table in engineering units.
pub fn table(r: &EhlSolution) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "EHL point contact (steady, isothermal)");
    let _ = writeln!(s, "  converged            {}", r.converged);
    let _ = writeln!(s, "  Moes M, L            {:.4}, {:.4}", r.moes_m, r.moes_l);
    let _ = writeln!(s, "  Ry/Rx                {:.4}", r.ry_over_rx);
    let _ = writeln!(
        s,
        "  central film h_c     {:.4} µm   (H_c Moes {:.4})",
        r.h_central * 1e6,
        r.h_central_moes
    );
    let _ = writeln!(
        s,
        "  minimum film h_min   {:.4} µm   (H_min Moes {:.4})",
        r.h_min * 1e6,
        r.h_min_moes
    );
    let _ = writeln!(s, "  max pressure         {:.4} GPa", r.p_max * 1e-9);
    let _ = writeln!(s, "  Hertz pressure p_h   {:.4} GPa", r.p_hertz * 1e-9);
    let _ = writeln!(
        s,
        "  approach δ = −h0     {:.4} µm   (Hertz {:.4} µm)",
        r.approach * 1e6,
        r.approach_hertz * 1e6
    );
    let _ = writeln!(
        s,
        "  force balance        {:.2e} (relative)",
        r.force_balance_residual
    );
    let _ = writeln!(s, "  Reynolds residual    {:.2e} (relative)", r.residual);
    let _ = writeln!(s, "  grid                 {} × {}", r.grid[0], r.grid[1]);
    if let Some(d) = r.discretization_estimate {
        let _ = writeln!(
            s,
            "  discretization err.  {:.1e} (H_c), {:.1e} (H0), relative, estimated from the next coarser grid",
            d[0], d[1]
        );
    }
    let rule = if !r.converged {
        "not met"
    } else if r.stopped_by_discretization {
        "iteration error below a fraction of the discretization error"
    } else {
        "fixed tolerances"
    };
    let _ = writeln!(s, "  stopping rule        {rule}");
    let _ = writeln!(
        s,
        "  cycles               {} ({} starts, {} continuation steps)",
        r.cycles, r.attempts, r.continuation_steps
    );
    let _ = writeln!(s, "  wall time            {:.3} s", r.seconds);
    s
}

/// Writes `pressure.csv` and `film.csv` (x_m,y_m,value) into `dir`.
pub fn write_fields(r: &EhlSolution, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let f = &r.fields;
    let nx = f.x.len();
    for (name, v) in [("pressure.csv", &f.p), ("film.csv", &f.h)] {
        let mut s = String::with_capacity(v.len() * 40);
        s.push_str("x_m,y_m,value\n");
        for (j, y) in f.y.iter().enumerate() {
            for (i, x) in f.x.iter().enumerate() {
                let _ = writeln!(s, "{x:.9e},{y:.9e},{:.9e}", v[j * nx + i]);
            }
        }
        let path = dir.join(name);
        std::fs::write(&path, s).with_context(|| format!("writing {}", path.display()))?;
    }
    crate::plot::fields::plot_fields(r, dir)
}

/// Runs `ehl-bearing ehl`.
pub fn run(args: &EhlArgs) -> Result<()> {
    let s = settings(args);
    s.validate()
        .context("--grid, --inlet, --half-width or --max-cycles")?;
    let deadline = crate::cli_support::deadline(args.time_limit)?;
    if let Some(dir) = &args.fields {
        crate::cli_support::check_output_dir(dir, "--fields")?;
    }
    large_grid_notice(&s, args.time_limit);
    let spinner = crate::cli_support::solve_spinner(format!("EHL solve, {0}×{0} grid", s.grid));
    let result = match (&args.contact, args.moes_m, args.moes_l) {
        (Some(path), _, _) => {
            let text = ehl_bearing::io::read_text(path)?;
            let c = ehl_bearing::io::contact::parse_contact_toml(&text)
                .with_context(|| format!("in {}", path.display()))?;
            for w in ehl_bearing::plausibility::check_contact(&c)
                .with_context(|| format!("{}: outside what the models describe", path.display()))?
            {
                eprintln!("warning: {}: {w}", path.display());
            }
            ehl::solve_steady_within(&c, &s, deadline)?
        }
        (None, Some(m), Some(l)) => {
            let case = MoesCase::new(
                m,
                l,
                args.ry_over_rx,
                match args.viscosity {
                    ViscosityArg::Roelands => ViscosityModel::Roelands,
                    ViscosityArg::Barus => ViscosityModel::Barus,
                },
                match args.density {
                    DensityArg::DowsonHigginson => DensityModel::DowsonHigginson,
                    DensityArg::Incompressible => DensityModel::Incompressible,
                },
            );
            ehl::solve_moes_within(&case, &s, deadline).with_context(|| {
                format!("--moes-m {m} --moes-l {l} --ry-over-rx {}", args.ry_over_rx)
            })?
        }
        _ => bail!("give a contact file, or both --moes-m and --moes-l"),
    };
    spinner.finish_and_clear();
    if args.json {
        println!(
            "{}",
            ehl_bearing::report::to_json_pretty(&ehl_bearing::report::EhlReport::from(&result))
        );
    } else {
        print!("{}", table(&result));
    }
    if let Some(dir) = &args.fields {
        write_fields(&result, dir)?;
    }
    if result.converged && result.h_min <= 0.0 {
        eprintln!(
            "warning: the minimum film is {:.3e} m ≤ 0: the {}² grid does not resolve this \
             film (very thin at this load and L); refine --grid",
            result.h_min, result.grid[0]
        );
    }
    if !result.converged {
        bail!(
            "EHL solution did not converge in {} cycles: relative residual {:.3e}, force balance {:.3e}",
            result.cycles,
            result.residual,
            result.force_balance_residual
        );
    }
    Ok(())
}
