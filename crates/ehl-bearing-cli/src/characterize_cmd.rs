//! `ehl-bearing characterize CASE.toml [--method M] [--json] [-o DIR]`: the coupled loop
//! (equilibrium ↔ per-contact characterization) on one case.

use crate::cli_support::{
    check_output_dir, check_plausible, contact_progress, deadline, progress_container,
    with_threads, write_atomic,
};
use anyhow::{bail, Context};
use ehl_bearing::case::Case;
use ehl_bearing::characterize::{
    characterize_bearing_with_progress, BearingCharacterization, CharacterizeSettings, ContactRow,
    LawSource,
};
use ehl_bearing::contact::{ExcitationFrequency, HarmonicSettings, QuasiStaticSettings};
use ehl_bearing::io::read_case;
use ehl_bearing::method::{HertzCharacterizer, Method, SyntheticCharacterizer};
use ehl_bearing::report::to_json_pretty;
use std::path::PathBuf;

/// Arguments of `characterize`.
#[derive(clap::Args)]
pub struct CharacterizeArgs {
    /// Case file (TOML), e.g. examples/7006.toml.
    pub case: PathBuf,
    /// Characterization method: quasi-static (EHL), harmonic (EHL), hertz (dry reference), map
    /// (quasi-static laws from the embedded law map, milliseconds; docs/law_map.md). Default: the
    /// case file's `method` (with its [method_options]), else quasi-static.
    #[arg(long)]
    pub method: Option<String>,
    /// Relative load amplitude ε of each contact's characterization: loads w0·(1 ± ε)
    /// (quasi-static and harmonic: 0 < ε ≤ 0.9; hertz: 0 < ε < 1). Default: the case file's
    /// [method_options] amplitude, else the method's default (0.2 for the EHL methods).
    #[arg(long)]
    pub amplitude: Option<f64>,
    /// Print JSON in SI units instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also write characterization.json and contacts.csv into this folder.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Threads for the contacts (default: RAYON_NUM_THREADS or the number of cores). Results do
    /// not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Relative load-change tolerance of the loop.
    #[arg(long, default_value_t = CharacterizeSettings::default().tolerance)]
    pub tolerance: f64,
    /// Iteration limit of the loop.
    #[arg(long, default_value_t = CharacterizeSettings::default().max_iterations)]
    pub max_iterations: usize,
    /// Relative key tolerance (M, L, Ry/Rx) for reusing a fitted law; 0 reuses exact matches only.
    #[arg(long, default_value_t = CharacterizeSettings::default().cache_tolerance)]
    pub cache_tolerance: f64,
    /// Contacts lighter than this fraction of the largest contact load are characterized at that
    /// floor load.
    #[arg(long, default_value_t = CharacterizeSettings::default().min_load_fraction)]
    pub min_load_fraction: f64,
    /// Reuse a law of an earlier iteration while the contact's load differs by at most this
    /// relative amount from its characterization load (and lies in its fitted range); 0 re-centres
    /// every law on the new loads.
    #[arg(long, default_value_t = CharacterizeSettings::default().load_reuse_tolerance)]
    pub load_reuse_tolerance: f64,
    /// Wall-time budget in seconds: the loop and its EHL solves stop with an error carrying
    /// their residual history when it runs out (default: none; iteration limits always apply).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Start from the dry Hertz loads instead of the loads predicted by the method (quasi-static:
    /// one loosely converged EHL solution per contact).
    #[arg(long)]
    pub no_load_prediction: bool,
}

/// `method` with the relative load amplitude ε of `--amplitude`, if given, validated (the error
/// names `--amplitude`, the value and the valid range).
pub fn with_amplitude(method: Method, amplitude: Option<f64>) -> anyhow::Result<Method> {
    let Some(a) = amplitude else {
        return Ok(method);
    };
    let m = match method {
        Method::QuasiStatic(s) => Method::QuasiStatic(QuasiStaticSettings { amplitude: a, ..s }),
        Method::Harmonic(s) => Method::Harmonic(HarmonicSettings { amplitude: a, ..s }),
        Method::Hertz(s) => Method::Hertz(HertzCharacterizer { amplitude: a, ..s }),
        Method::Synthetic(s) => Method::Synthetic(SyntheticCharacterizer { amplitude: a, ..s }),
        Method::Map(_) => anyhow::bail!(
            "--amplitude = {a}: the map method's amplitude is the map's (docs/law_map.md); \
             give no --amplitude"
        ),
    };
    m.validate()
        .map_err(|e| anyhow::anyhow!(option_names(&e.to_string())))?;
    Ok(m)
}

/// A library message with the settings `characterize` has options for named as those options:
/// `method_options.amplitude` → `--amplitude`, `min_load_fraction` → `--min-load-fraction`.
pub fn option_names(message: &str) -> String {
    message
        .replace("method_options.amplitude", "--amplitude")
        .replace("min_load_fraction", "--min-load-fraction")
}

/// "1 recorded period", "2 settling periods".
fn periods(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// Contacts as CSV (the columns of [`ContactRow`]).
pub fn contacts_csv(c: &BearingCharacterization) -> String {
    let rows: Vec<ContactRow> = c.contacts.iter().map(ContactRow::from_result).collect();
    ehl_bearing::report::csv(&rows)
}

/// Run `characterize`.
pub fn run(args: &CharacterizeArgs) -> anyhow::Result<()> {
    let case = read_case(&args.case)?;
    let deadline = deadline(args.time_limit)?;
    let ch = case
        .method_or(args.method.as_deref())
        .map_err(|e| anyhow::anyhow!("--method: {e}"))?;
    let ch = with_amplitude(ch, args.amplitude)?;
    if let Some(dir) = &args.output {
        check_output_dir(dir, "-o")?;
    }
    check_plausible(&case, &args.case)?;
    let settings = CharacterizeSettings {
        tolerance: args.tolerance,
        max_iterations: args.max_iterations,
        cache_tolerance: args.cache_tolerance,
        min_load_fraction: args.min_load_fraction,
        load_reuse_tolerance: args.load_reuse_tolerance,
        predict_loads: !args.no_load_prediction,
        ..CharacterizeSettings::default()
    };
    let multi = progress_container();
    let (bar, callback) = contact_progress(&multi);
    let c = with_threads(args.threads, || {
        characterize_bearing_with_progress(&case, &ch, &settings, deadline, &callback)
            .map_err(|e| anyhow::anyhow!(option_names(&e.to_string())))
            .with_context(|| format!("characterizing {}", args.case.display()))
    });
    bar.finish_and_clear();
    let c = c?;
    if let Some(dir) = &args.output {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        let json = to_json_pretty(&c.report(false)) + "\n";
        write_atomic(&dir.join("characterization.json"), json.as_bytes())?;
        write_atomic(&dir.join("contacts.csv"), contacts_csv(&c).as_bytes())?;
        if let Some(l) = &c.lubrication {
            let csv = ehl_bearing::lubrication::contacts_csv(l);
            write_atomic(&dir.join("lubrication.csv"), csv.as_bytes())?;
        }
    }
    if args.json {
        println!("{}", to_json_pretty(&c.report(true)));
    } else {
        print!("{}", table(&case, &c));
        if let Some(l) = &c.lubrication {
            print!("{}", ehl_bearing::lubrication::table(l));
        }
    }
    for w in c.lubrication.iter().flat_map(|l| &l.warnings) {
        eprintln!("warning: {}: {w}", args.case.display());
    }
    // One rule for every command with one result (ehl, contact, characterize, coefficients):
    // a result that did not converge is printed and written, marked, and the exit status is 1.
    if !c.converged {
        bail!(
            "the loop did not converge in {} iterations (largest relative load change {:.3e}, \
             tolerance {:.1e}; the results above are marked NOT converged: raise \
             --max-iterations or loosen --tolerance)",
            c.iterations,
            c.max_load_change,
            settings.tolerance
        );
    }
    Ok(())
}

/// Human-readable report in engineering units.
pub fn table(case: &Case, c: &BearingCharacterization) -> String {
    let mut s = String::new();
    summary_lines(&mut s, case, c);
    history_table(&mut s, c);
    contacts_table(&mut s, c);
    displacement_and_stiffness_tables(&mut s, c);
    s
}

/// The bearing, the method and the loop's outcome (convergence, law use, load prediction).
fn summary_lines(s: &mut String, case: &Case, c: &BearingCharacterization) {
    use std::fmt::Write;
    let rpm = 30.0 / std::f64::consts::PI;
    let op = &case.operating;
    let _ = writeln!(
        s,
        "{}: inner {:.0} rpm, outer {:.0} rpm; method {}: {}",
        case.name.as_deref().unwrap_or("bearing"),
        op.inner_speed * rpm,
        op.outer_speed * rpm,
        c.method,
        settings_summary(&c.method)
    );
    if !case.lubricant_given {
        let _ = writeln!(
            s,
            "lubricant not given in the case: default mineral oil (η0 = {} Pa·s, α = {:e} 1/Pa)",
            case.lubricant.viscosity, case.lubricant.pressure_viscosity
        );
    }
    let _ = writeln!(
        s,
        "{} after {} iterations: largest relative load change {:.3e} (tolerance {:.1e}); largest cache key distance {:.2e}; {:.3} s",
        if c.converged { "converged" } else { "NOT converged" },
        c.iterations,
        c.max_load_change,
        c.settings.tolerance,
        c.max_key_distance,
        c.seconds
    );
    let _ = writeln!(
        s,
        "final laws: used up to {:.2} % from their characterization load; largest fit residual {:.2e} of the load (force error bound in the fitted range)",
        100.0 * c.max_load_offset,
        c.max_relative_residual
    );
    if let Some(p) = &c.prediction {
        let _ = writeln!(
            s,
            "load prediction: {} contacts ({} not converged, {} failed), loads moved up to {:.3e} from dry{}; {:.3} s",
            p.contacts,
            p.not_converged,
            p.failed,
            p.max_load_change,
            p.error
                .as_ref()
                .map(|e| format!("; equilibrium failed, started from dry: {e}"))
                .unwrap_or_default(),
            p.seconds
        );
    }
}

/// One line per iteration of the loop.
fn history_table(s: &mut String, c: &BearingCharacterization) {
    use std::fmt::Write;
    let _ = writeln!(
        s,
        "\n{:>4} {:>12} {:>12} {:>10} {:>11} {:>11} {:>11} {:>8}",
        "iter",
        "max ΔQ/Q",
        "characterized",
        "reused",
        "key dist",
        "load offset",
        "residual/w0",
        "time s"
    );
    for h in &c.history {
        let _ = writeln!(
            s,
            "{:>4} {:>12.3e} {:>12} {:>10} {:>11.2e} {:>11.2e} {:>11.2e} {:>8.3}",
            h.iteration,
            h.max_load_change,
            h.characterized,
            h.reused,
            h.max_key_distance,
            h.max_load_offset,
            h.max_relative_residual,
            h.seconds
        );
    }
}

/// One line per contact: load, approach, angle, law, Moes groups, where its law comes from.
fn contacts_table(s: &mut String, c: &BearingCharacterization) {
    use std::fmt::Write;
    let _ = writeln!(
        s,
        "\n{:>4} {:>5} {:>9} {:>8} {:>7} {:>11} {:>8} {:>9} {:>9} {:>6} {:>7} {:>8} {:>13}",
        "ball",
        "race",
        "Q N",
        "δ µm",
        "α °",
        "K N/m^d",
        "d",
        "ΔF N",
        "M",
        "L",
        "Ry/Rx",
        "Q/w0−1",
        "source"
    );
    for r in &c.contacts {
        let cc = &r.characterized;
        let _ = writeln!(
            s,
            "{:>4} {:>5} {:>9.3} {:>8.4} {:>7.3} {:>11.4e} {:>8.5} {:>9.3e} {:>9.2} {:>6.2} {:>7.2} {:>8.1e} {:>13}{}",
            r.ball,
            format!("{:?}", r.race).to_lowercase(),
            r.state.load,
            r.state.deflection * 1e6,
            r.state.contact_angle.to_degrees(),
            cc.k,
            cc.d,
            cc.delta_f,
            cc.moes_m,
            cc.moes_l,
            cc.ry_over_rx,
            r.load_offset,
            match r.source {
                LawSource::Characterized => "this iter.",
                LawSource::Cached => "earlier iter.",
                LawSource::Deduplicated => "same iter.",
            },
            if cc.law.outside_fit_range(r.state.deflection) { " (outside fit range)" } else { "" }
        );
    }
    let per_iteration: Vec<String> = c
        .history
        .iter()
        .map(|h| format!("{} in iteration {}", h.characterized, h.iteration))
        .collect();
    let _ = writeln!(
        s,
        "source: the iteration the final law was characterized in, relative to the last one \
         (\"earlier iter.\": reused while the load stayed within {:.1} % of its characterization \
         load, column Q/w0−1, or within the cache tolerance of another contact's law). \
         Characterized: {}.",
        100.0 * c.settings.load_reuse_tolerance,
        per_iteration.join(", ")
    );
    // The method of each final law (a map's fallback names itself), counted in the contacts'
    // order of first appearance.
    let mut methods: Vec<(String, usize, Vec<String>)> = Vec::new();
    for r in &c.contacts {
        let label = ehl_bearing::characterize::method_label(&r.characterized.method);
        let who = format!("{} {:?}", r.ball, r.race).to_lowercase();
        match methods.iter_mut().find(|(m, _, _)| *m == label) {
            Some((_, n, w)) => {
                *n += 1;
                w.push(who);
            }
            None => methods.push((label, 1, vec![who])),
        }
    }
    let list: Vec<String> = methods
        .iter()
        .map(|(m, n, w)| {
            if methods.len() > 1 && *n <= 4 {
                format!("{n} by {m} (ball {})", w.join(", "))
            } else {
                format!("{n} by {m}")
            }
        })
        .collect();
    let _ = writeln!(s, "method of the final laws: {}.", list.join("; "));
}

/// The EHL and dry displacements and stiffness diagonals.
fn displacement_and_stiffness_tables(s: &mut String, c: &BearingCharacterization) {
    use std::fmt::Write;
    let names = ["x µm", "y µm", "z µm", "θy mdeg", "θz mdeg"];
    let _ = writeln!(s, "\n{:<9} {:>14} {:>14}", "DOF", "EHL", "dry");
    for (k, name) in names.iter().enumerate() {
        let f = if k < 3 {
            1e6
        } else {
            1e3 * 180.0 / std::f64::consts::PI
        };
        let _ = writeln!(
            s,
            "{:<9} {:>14.5} {:>14.5}",
            name,
            c.equilibrium.displacement[k] * f,
            c.dry.displacement[k] * f
        );
    }
    let dnames = [
        "k_xx N/µm",
        "k_yy N/µm",
        "k_zz N/µm",
        "k_θyθy N·m/mrad",
        "k_θzθz N·m/mrad",
    ];
    let _ = writeln!(
        s,
        "\n{:<16} {:>14} {:>14} {:>9}",
        "stiffness", "EHL", "dry", "EHL/dry"
    );
    for (k, name) in dnames.iter().enumerate() {
        let f = if k < 3 { 1e-6 } else { 1e-3 };
        let e = c.equilibrium.stiffness[k][k];
        let d = c.dry.stiffness[k][k];
        let _ = writeln!(
            s,
            "{:<16} {:>14.5} {:>14.5} {:>9.5}",
            name,
            e * f,
            d * f,
            e / d
        );
    }
}

/// The method settings in words (the full set is in the JSON output).
fn settings_summary(m: &Method) -> String {
    let ehl = |e: &ehl_bearing::ehl::EhlSettings| -> String {
        let inlet = e
            .inlet
            .map_or("automatic domain".into(), |x| format!("inlet {x} a_x"));
        format!(
            "{}² grid, {inlet}, tolerances residual {:e}, force {:e}, film {:e}",
            e.grid, e.tol_residual, e.tol_force, e.tol_film
        )
    };
    match m {
        Method::QuasiStatic(s) => format!(
            "{} steady EHL solutions over w0·(1 ± {}), {}",
            s.points,
            s.amplitude,
            ehl(&s.ehl)
        ),
        Method::Harmonic(s) => {
            let freq = match s.frequency {
                ExcitationFrequency::FractionOfNatural(x) => format!("Ω = {x}·ω_n"),
                ExcitationFrequency::RadPerSecond(x) => format!("Ω = {x} rad/s"),
            };
            format!(
                "w0·(1 + {}·sin Ωt), {freq}, ≤ {} + {}, {} steps per period, {}",
                s.amplitude,
                periods(s.settling_periods, "settling period"),
                periods(s.recorded_periods, "recorded period"),
                s.steps_per_period,
                ehl(&s.ehl)
            )
        }
        Method::Hertz(s) => format!("{} Hertz samples over w0·(1 ± {})", s.samples, s.amplitude),
        Method::Synthetic(s) => {
            format!("{} Hertz samples over w0·(1 ± {})", s.samples, s.amplitude)
        }
        Method::Map(s) => ehl_bearing::report::to_json_line(s),
    }
}
