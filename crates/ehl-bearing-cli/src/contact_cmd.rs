//! `ehl-bearing contact CONTACT.toml [--method quasi-static|harmonic] [--json] [-o DIR]`:
//! characterize one lubricated contact by the law Q = K·δ^d + ΔF.

use anyhow::{bail, Context, Result};
use ehl_bearing::contact::{
    characterize_harmonic_within, characterize_quasi_static_within, ContactFit,
};
use std::fmt::Write as _;
use std::path::PathBuf;

/// How the force–approach data are produced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// A family of steady EHL solutions over w0·(1 ± ε).
    QuasiStatic,
    /// Transient EHL with the ball's equation of motion under w0·(1 + ε·sin Ωt).
    Harmonic,
}

/// Arguments of `contact`.
#[derive(Debug, Clone, clap::Args)]
pub struct ContactArgs {
    /// Contact file (TOML): load_n, rx_mm, ry_mm, sum_velocity_m_s, materials, [lubricant].
    #[arg(value_name = "CONTACT.toml")]
    pub contact: PathBuf,
    /// Characterization method.
    #[arg(long, value_enum, default_value_t = Method::QuasiStatic)]
    pub method: Method,
    /// Relative load amplitude ε (default 0.2).
    #[arg(long)]
    pub amplitude: Option<f64>,
    /// Number of steady solutions of the quasi-static family (default 7).
    #[arg(long)]
    pub points: Option<usize>,
    /// Grid points per side of the EHL solutions (2^k + 1; default 129).
    #[arg(long)]
    pub grid: Option<usize>,
    /// Quasi-static method: skip the Richardson estimate of the central film and the approach at
    /// w0 (by default one more steady solution at w0 on the twice finer grid, for grids up to 513;
    /// the law is the family's either way).
    #[arg(long)]
    pub no_film_extrapolation: bool,
    /// Harmonic method: excitation frequency Ω as a fraction of the contact's linearized natural
    /// frequency (default 0.005, inside the rotor band).
    #[arg(long, conflicts_with = "frequency_rad_s")]
    pub frequency_fraction: Option<f64>,
    /// Harmonic method: excitation frequency Ω in rad/s.
    #[arg(long)]
    pub frequency_rad_s: Option<f64>,
    /// Harmonic method: largest number of periods before recording (default 2; settling stops
    /// after a quarter period, or more quarter periods, once the periodicity is below its bound)
    #[arg(long)]
    pub settling_periods: Option<usize>,
    /// Harmonic method: periodicity bound that ends the settling (default 1e-3; 0 settles
    /// --settling-periods whole periods)
    #[arg(long)]
    pub periodicity_tol: Option<f64>,
    /// Harmonic method: periods recorded and fitted (default 1).
    #[arg(long)]
    pub recorded_periods: Option<usize>,
    /// Harmonic method: time steps per period (default 64).
    #[arg(long)]
    pub steps_per_period: Option<usize>,
    /// Harmonic method: per-step film tolerance, a relative change in (0, 0.01] (default:
    /// 7e-6·Ψ_H within [7e-8, 7e-5], following the contact's mass group Ψ_H, below which a
    /// looser tolerance biases the damping c upward: docs/contact.md, "Known limits").
    #[arg(long)]
    pub step_tol_film: Option<f64>,
    /// Harmonic method: mass on the contact in kg (default: the ball's mass from the contact
    /// file's ball_mass_kg or ball_diameter_mm).
    #[arg(long)]
    pub mass_kg: Option<f64>,
    /// Harmonic method: fit Q = K·δ^d + ΔF without the damping term c·δ̇.
    #[arg(long)]
    pub no_damping_term: bool,
    /// Wall-time budget in seconds: the EHL solves stop with an error carrying their residual
    /// history when it runs out (default: none; the cycle limits always apply).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Print JSON (SI units) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write samples.csv, fit.json and the plot force_approach.{png,svg} into this directory;
    /// for the harmonic method also history.csv and time_history.{png,svg}.
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
}

fn table(f: &ContactFit) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} characterization: w0 = {:.2} N, M = {:.1}, L = {:.2}, Ry/Rx = {:.2}",
        f.method, f.load, f.moes_m, f.moes_l, f.ry_over_rx
    );
    let _ = writeln!(
        s,
        "Q = K·δ^d + ΔF:  K = {:.5e} N/m^d (±{:.1e}),  d = {:.4} (±{:.4}),  ΔF = {:.3} N (±{:.3})",
        f.k, f.std_errors.k, f.d, f.std_errors.d, f.delta_f, f.std_errors.delta_f
    );
    if let Some(c) = f.c {
        let _ = writeln!(
            s,
            "damping term: c = {:.4e} N·s/m (±{:.1e})",
            c,
            f.std_errors.c.unwrap_or(f64::NAN)
        );
    }
    if let ehl_bearing::contact::Excitation::Harmonic(h) = &f.excitation {
        let count = crate::plot::contact::count;
        let _ = writeln!(
            s,
            "excitation: ε = {}, Ω = {:.5e} rad/s = {:.3}·ω_n (ω_n = {:.5e} rad/s; dry Hertz {:.5e}), \
             m = {:.4e} kg (Ψ_H = {:.3}), {} (at most {}) + {} × {} steps; periodicity {:.1e} (bound {:.0e}: \
             {}); {} not converged",
            h.amplitude,
            h.frequency_rad_s,
            h.frequency_over_natural,
            h.natural_frequency_rad_s,
            h.natural_frequency_hertz_rad_s,
            h.mass_kg,
            h.mass_group_psi_h,
            count(h.settling_steps, "settling step"),
            count(h.settling_periods, "period"),
            count(h.recorded_periods, "recorded period"),
            h.steps_per_period,
            h.periodicity,
            h.periodicity_tol,
            if h.settled { "settled" } else { "NOT settled" },
            count(h.steps_not_converged, "step"),
        );
    }
    let _ = writeln!(
        s,
        "fit: R² = {:.8}, RMS residual {:.3e} N; δ range {:.4}–{:.4} µm; approach at w0 {:.4} µm",
        f.r_squared,
        f.rms_residual,
        f.delta_range[0] * 1e6,
        f.delta_range[1] * 1e6,
        f.approach * 1e6
    );
    if let Some(x) = &f.film {
        let _ = writeln!(
            s,
            "film at w0, Richardson {}²/{}²: h_c = {:.5} µm (±{:.1e}), δ = {:.5} µm (±{:.1e}); \
             on {}²: h_c {:.5} µm, h_min {:.5} µm, δ {:.5} µm{}",
            x.grid_fine.div_ceil(2),
            x.grid_fine,
            x.h_central * 1e6,
            x.h_central_correction * 1e6,
            x.approach * 1e6,
            x.approach_correction * 1e6,
            x.grid_fine,
            x.h_central_fine * 1e6,
            x.h_min_fine * 1e6,
            x.approach_fine * 1e6,
            if x.converged { "" } else { " (NOT CONVERGED)" }
        );
    }
    let _ = writeln!(
        s,
        "\n{:>10} {:>11} {:>10} {:>10} {:>9} {:>10} {:>5}",
        "load N", "δ µm", "h_c µm", "h_min µm", "p_max GPa", "fit err N", "conv"
    );
    for x in &f.samples {
        let q = f.k * x.approach.powf(f.d) + f.delta_f;
        let _ = writeln!(
            s,
            "{:>10.3} {:>11.5} {:>10.5} {:>10.5} {:>9.4} {:>10.2e} {:>5}",
            x.load,
            x.approach * 1e6,
            x.h_central * 1e6,
            x.h_min * 1e6,
            x.p_max * 1e-9,
            q - x.load,
            x.converged
        );
    }
    let _ = writeln!(
        s,
        "\n{} in {:.2} s",
        if f.converged {
            "converged"
        } else {
            "NOT CONVERGED (see the residuals of the samples)"
        },
        f.seconds
    );
    s
}

/// The time history as CSV, SI units, one row per step.
fn history_csv(f: &ContactFit) -> String {
    let mut csv = String::from(
        "time_s,load_n,approach_m,approach_rate_m_s,film_force_n,h_central_m,h_min_m,p_max_pa,\
         residual,force_residual,cycles,converged,recorded\n",
    );
    for (i, x) in f.history.iter().enumerate() {
        let _ = writeln!(
            csv,
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{}",
            x.time,
            x.load,
            x.approach,
            x.velocity,
            x.film_force,
            x.h_central,
            x.h_min,
            x.p_max,
            x.residual,
            x.force_residual,
            x.cycles,
            x.converged,
            i >= f.settling_steps
        );
    }
    csv
}

/// The method of the command line's options, through the library's one parser and validation
/// (`Method::parse`); errors name the option as a flag.
fn method_of(args: &ContactArgs) -> Result<ehl_bearing::method::Method> {
    let mut t = toml::Table::new();
    let mut put = |k: &str, v: Option<toml::Value>| {
        if let Some(v) = v {
            t.insert(k.to_string(), v);
        }
    };
    let int = |n: Option<usize>| n.map(|n| toml::Value::Integer(n.min(i64::MAX as usize) as i64));
    put("amplitude", args.amplitude.map(toml::Value::Float));
    put("grid", int(args.grid));
    let name = match args.method {
        Method::QuasiStatic => {
            put("points", int(args.points));
            "quasi-static"
        }
        Method::Harmonic => {
            put(
                "frequency_fraction",
                args.frequency_fraction.map(toml::Value::Float),
            );
            put(
                "frequency_rad_s",
                args.frequency_rad_s.map(toml::Value::Float),
            );
            put("settling_periods", int(args.settling_periods));
            put(
                "periodicity_tol",
                args.periodicity_tol.map(toml::Value::Float),
            );
            put("recorded_periods", int(args.recorded_periods));
            put("steps_per_period", int(args.steps_per_period));
            put("step_tol_film", args.step_tol_film.map(toml::Value::Float));
            put("mass_kg", args.mass_kg.map(toml::Value::Float));
            put(
                "damping_term",
                args.no_damping_term.then_some(toml::Value::Boolean(false)),
            );
            "harmonic"
        }
    };
    let keys: Vec<String> = t.keys().cloned().collect();
    ehl_bearing::method::Method::parse(name, Some(&t)).map_err(|e| {
        let mut msg = e.to_string();
        for k in &keys {
            msg = msg.replace(
                &format!("method_options.{k}"),
                &format!("--{}", k.replace('_', "-")),
            );
        }
        anyhow::anyhow!(msg)
    })
}

/// A library error with the method option it names as this command's option
/// (`method_options.amplitude` → `--amplitude`, e.g. in the hydrodynamic-regime error).
fn option_names(e: ehl_bearing::Error) -> anyhow::Error {
    anyhow::anyhow!(e
        .to_string()
        .replace("method_options.amplitude", "--amplitude"))
}

/// An error naming every option given (`(given, name)`) that applies to `scope` only.
fn refuse_options(options: &[(bool, &str)], scope: &str) -> Result<()> {
    let given: Vec<&str> = options
        .iter()
        .filter_map(|&(set, name)| set.then_some(name))
        .collect();
    if !given.is_empty() {
        bail!(
            "{} {} to {scope}",
            given.join(", "),
            if given.len() == 1 { "applies" } else { "apply" }
        );
    }
    Ok(())
}

/// Run `contact`.
pub fn run(args: &ContactArgs) -> Result<()> {
    let text = ehl_bearing::io::read_text(&args.contact)?;
    let file = ehl_bearing::io::contact::parse_contact_file(&text)
        .with_context(|| format!("in {}", args.contact.display()))?;
    let c = file.contact;
    let deadline = crate::cli_support::deadline(args.time_limit)?;
    if let Some(dir) = &args.output {
        crate::cli_support::check_output_dir(dir, "-o")?;
    }
    for w in ehl_bearing::plausibility::check_contact(&c).with_context(|| {
        format!(
            "{}: outside what the models describe",
            args.contact.display()
        )
    })? {
        eprintln!("warning: {}: {w}", args.contact.display());
    }
    let method = match args.method {
        Method::Harmonic => {
            refuse_options(
                &[
                    (args.points.is_some(), "--points"),
                    (args.no_film_extrapolation, "--no-film-extrapolation"),
                ],
                "the quasi-static method only",
            )?;
            method_of(args)?
        }
        Method::QuasiStatic => {
            refuse_options(
                &[
                    (args.frequency_fraction.is_some(), "--frequency-fraction"),
                    (args.frequency_rad_s.is_some(), "--frequency-rad-s"),
                    (args.settling_periods.is_some(), "--settling-periods"),
                    (args.periodicity_tol.is_some(), "--periodicity-tol"),
                    (args.recorded_periods.is_some(), "--recorded-periods"),
                    (args.steps_per_period.is_some(), "--steps-per-period"),
                    (args.step_tol_film.is_some(), "--step-tol-film"),
                    (args.mass_kg.is_some(), "--mass-kg"),
                    (args.no_damping_term, "--no-damping-term"),
                ],
                "--method harmonic only (the method is quasi-static)",
            )?;
            method_of(args)?
        }
    };
    if let Some(g) = method.grid() {
        let s = ehl_bearing::ehl::EhlSettings {
            grid: g,
            ..Default::default()
        };
        crate::ehl_cmd::large_grid_notice(&s, args.time_limit);
    }
    let spinner =
        crate::cli_support::solve_spinner(format!("characterizing {}", args.contact.display()));
    let fit = match method {
        ehl_bearing::method::Method::Harmonic(s) => {
            let mass = match (s.mass, file.ball_mass) {
                (Some(m), _) | (None, Some(m)) => m,
                (None, None) => bail!(
                    "the harmonic method needs the ball's mass: give ball_mass_kg or \
                     ball_diameter_mm in {}, or --mass-kg",
                    args.contact.display()
                ),
            };
            characterize_harmonic_within(&c, mass, &s, deadline).map_err(option_names)?
        }
        ehl_bearing::method::Method::QuasiStatic(s) => {
            // The estimate needs the twice finer grid: none beyond 513² (1025 is the finest).
            let s = ehl_bearing::contact::QuasiStaticSettings {
                film_extrapolation: !args.no_film_extrapolation && s.ehl.grid <= 513,
                ..s
            };
            characterize_quasi_static_within(&c, &s, deadline).map_err(option_names)?
        }
        other => bail!("method {other} does not characterize a single contact"),
    };
    spinner.finish_and_clear();
    if let Some(dir) = &args.output {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        let mut csv = String::from(
            "load_n,approach_m,h_central_m,h_min_m,p_max_pa,residual,force_balance_residual,converged\n",
        );
        for x in &fit.samples {
            let _ = writeln!(
                csv,
                "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
                x.load,
                x.approach,
                x.h_central,
                x.h_min,
                x.p_max,
                x.residual,
                x.force_balance_residual,
                x.converged
            );
        }
        std::fs::write(dir.join("samples.csv"), csv)?;
        std::fs::write(
            dir.join("fit.json"),
            ehl_bearing::report::to_json_pretty(&fit),
        )?;
        crate::plot::contact::force_approach(&fit, &c, dir)?;
        if !fit.history.is_empty() {
            std::fs::write(dir.join("history.csv"), history_csv(&fit))?;
            crate::plot::contact::time_history(&fit, &c, dir)?;
        }
    }
    if args.json {
        println!("{}", ehl_bearing::report::to_json_pretty(&fit));
    } else {
        print!("{}", table(&fit));
    }
    if !fit.converged {
        bail!("the characterization did not converge (see the sample residuals above)");
    }
    Ok(())
}
