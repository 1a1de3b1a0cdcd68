//! `ehl-bearing coefficients CASE.toml [--speeds RPM,...] [--method M | --trends trends.json]
//! [-o DIR] [--json]`: the lubricated bearing's linearized 5×5 stiffness and damping at each
//! speed, beside the dry stiffness, in SI; and ROSS's bearing table.

use crate::cli_support::{contact_progress, progress_container, with_threads};
use anyhow::Context;
use ehl_bearing::characterize::CharacterizeSettings;
use ehl_bearing::coefficients::{
    coefficients_csv, from_characterization, from_element, ross_table_csv, SpeedCoefficients,
};
use ehl_bearing::force_element::TrendForceElement;
use ehl_bearing::io::{read_case, write_atomic};
use std::path::PathBuf;

/// Arguments of `coefficients`.
#[derive(clap::Args)]
pub struct CoefficientsArgs {
    /// Case file (TOML); its loads and outer-ring speed are used at every speed.
    pub case: PathBuf,
    /// Inner-ring speeds in rpm, comma separated (default: the case's speed).
    #[arg(long, value_delimiter = ',')]
    pub speeds: Vec<f64>,
    /// Characterization method at each speed: quasi-static, harmonic (gives the damping c·δ̇
    /// of every contact), hertz (dry), map (quasi-static laws from the embedded law map).
    /// Default: the case file's `method`, else quasi-static.
    #[arg(long, conflicts_with = "trends")]
    pub method: Option<String>,
    /// Use a study's trend curves (trends.json) instead of characterizing: no EHL run, no damping.
    #[arg(long)]
    pub trends: Option<PathBuf>,
    /// Print JSON (SI) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write coefficients.json, coefficients.csv and ross_bearing.csv into this folder.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Threads for the contacts (default: RAYON_NUM_THREADS or the number of cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Run `coefficients`.
pub fn run(args: &CoefficientsArgs) -> anyhow::Result<()> {
    let case = read_case(&args.case)?;
    crate::cli_support::check_plausible(&case, &args.case)?;
    let speeds = if args.speeds.is_empty() {
        vec![case.operating.inner_speed * 30.0 / std::f64::consts::PI]
    } else {
        args.speeds.clone()
    };
    if let Some(dir) = &args.output {
        ehl_bearing::io::FsStore::create(dir)?;
    }
    let coeffs: Vec<SpeedCoefficients> = match &args.trends {
        Some(path) => {
            let text = ehl_bearing::io::read_text(path)?;
            let element = TrendForceElement::from_json(&text)
                .with_context(|| format!("trend model {}", path.display()))?;
            from_element(&case, &speeds, &element, "trends")?
        }
        None => {
            let m = case
                .method_or(args.method.as_deref())
                .map_err(|e| anyhow::anyhow!("--method: {e}"))?;
            let multi = progress_container();
            let (bar, callback) = contact_progress(&multi);
            let r = with_threads(args.threads, || {
                from_characterization(
                    &case,
                    &speeds,
                    &m,
                    &CharacterizeSettings::default(),
                    &|_, p| {
                        callback(p);
                        std::ops::ControlFlow::Continue(())
                    },
                )
                .map_err(anyhow::Error::from)
            });
            bar.finish_and_clear();
            r?
        }
    };
    let json = serde_json::to_string_pretty(&coeffs)? + "\n";
    if let Some(dir) = &args.output {
        write_atomic(&dir.join("coefficients.json"), json.as_bytes())?;
        write_atomic(
            &dir.join("coefficients.csv"),
            coefficients_csv(&coeffs).as_bytes(),
        )?;
        write_atomic(
            &dir.join("ross_bearing.csv"),
            ross_table_csv(&coeffs).as_bytes(),
        )?;
    }
    if args.json {
        print!("{json}");
    } else {
        print!("{}", table(&coeffs));
    }
    // As for characterize: results are printed and written, and a loop that did not converge
    // at any speed gives exit status 1.
    let failed: Vec<String> = coeffs
        .iter()
        .filter(|x| !x.converged)
        .map(|x| format!("{} rpm", x.inner_speed_rpm))
        .collect();
    if !failed.is_empty() {
        anyhow::bail!(
            "the coupled loop did not converge at {} (marked NOT converged above)",
            failed.join(", ")
        );
    }
    Ok(())
}

fn table(c: &[SpeedCoefficients]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:>8} {:>11} {:>11} {:>11} {:>13} {:>13} {:>11} {:>11} {:>11}",
        "rpm",
        "k_xx N/µm",
        "k_yy N/µm",
        "k_zz N/µm",
        "k_θyθy N·m/mrad",
        "dry k_xx N/µm",
        "c_xx N·s/m",
        "c_yy N·s/m",
        "c_zz N·s/m"
    );
    for x in c {
        let _ = writeln!(
            s,
            "{:>8.0} {:>11.4} {:>11.4} {:>11.4} {:>13.4} {:>13.4} {:>11.4} {:>11.4} {:>11.4}{}",
            x.inner_speed_rpm,
            x.stiffness[0][0] * 1e-6,
            x.stiffness[1][1] * 1e-6,
            x.stiffness[2][2] * 1e-6,
            x.stiffness[3][3] * 1e-3,
            x.dry_stiffness[0][0] * 1e-6,
            x.damping[0][0],
            x.damping[1][1],
            x.damping[2][2],
            if x.converged {
                ""
            } else {
                "  (loop NOT converged)"
            }
        );
    }
    let _ = writeln!(
        s,
        "source: {}; full 5×5 K and C (SI) with --json or -o DIR (coefficients.json, coefficients.csv, ross_bearing.csv)",
        c.first().map(|x| x.source.as_str()).unwrap_or("")
    );
    s
}
