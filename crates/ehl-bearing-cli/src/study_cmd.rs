//! `ehl-bearing study STUDY.toml -o DIR`: a load × speed sweep of the characterization, with
//! resumable per-point files, a long-format CSV, trend curves and plots.
//!
//! Output folder:
//! - `points/<stem>.json`: one file per (speed, load scale) point, written atomically as soon as
//!   the point is finished; a rerun with the same folder skips every point whose file exists with
//!   the same spec, so a study killed at any moment (even with SIGKILL) redoes only the points
//!   that were in flight;
//! - `results.csv` (one row per point and contact), `points.csv` (one row per point),
//!   `trends.json` (trend curves, loadable by `TrendModel::from_json`), and the plots
//!   `k_vs_load`, `d_vs_load`, `delta_f_vs_load` (`.png`, `.svg`).
//!
//! Every final file is built from the point files alone, so it is identical whether the study ran
//! in one go or was resumed, and whatever the number of threads.

use crate::characterize_cmd::{
    characterizer, contact_progress, progress_container, with_threads, write_atomic,
};
use anyhow::Context;
use ehl_bearing::study::{
    fit_trends, point_rows, read_study, results_csv, run_point_with_progress, ResultRow,
    TrendForceElement, TrendModel,
};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `study`.
#[derive(clap::Args)]
pub struct StudyArgs {
    /// Study file (TOML), e.g. examples/study_7006.toml.
    pub study: PathBuf,
    /// Output folder (created if needed; an existing one is resumed).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Override the study file's method.
    #[arg(long)]
    pub method: Option<String>,
    /// Threads for the contacts of a point (default: RAYON_NUM_THREADS or the number of cores).
    /// Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Testing aid: sleep this many milliseconds before each computed point (to interrupt a
    /// study reliably in the resume test).
    #[arg(long, hide = true, default_value_t = 0)]
    pub delay_ms: u64,
}

fn progress(multi: &MultiProgress, len: u64) -> ProgressBar {
    let bar = multi.add(ProgressBar::new(len));
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} points (eta {eta}) {msg}",
    ) {
        bar.set_style(style);
    }
    bar
}

/// Remove temporary files left by an interrupted run.
fn remove_stale_temporaries(dir: &Path) -> anyhow::Result<()> {
    for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.') && name.contains(".tmp-") {
            std::fs::remove_file(entry.path()).ok();
        }
    }
    Ok(())
}

/// A point file that exists, parses and has the expected spec.
fn load_point(path: &Path, spec: &Value) -> Option<Value> {
    let text = std::fs::read_to_string(path).ok()?;
    let v: Value = serde_json::from_str(&text).ok()?;
    (v.get("spec") == Some(spec)).then_some(v)
}

/// Run `study`.
pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    let mut study = read_study(&args.study)?;
    if let Some(m) = &args.method {
        study.method = m.clone();
    }
    let ch = characterizer(&study.method, &study.method_options)
        .with_context(|| format!("method of {}", args.study.display()))?;
    if args.threads == Some(0) {
        anyhow::bail!("--threads 0: expected at least 1 thread");
    }
    let points_dir = args.output.join("points");
    std::fs::create_dir_all(&points_dir)
        .with_context(|| format!("creating {}", points_dir.display()))?;
    remove_stale_temporaries(&points_dir)?;
    remove_stale_temporaries(&args.output)?;
    let points = study.points();
    let multi = progress_container();
    let bar = progress(&multi, points.len() as u64);
    let (contacts_bar, callback) = contact_progress(&multi);
    let t0 = Instant::now();
    let (mut loaded, mut computed, mut not_converged) = (0usize, 0usize, 0usize);
    let mut files = Vec::with_capacity(points.len());
    for p in &points {
        let path = points_dir.join(format!("{}.json", p.file_stem()));
        let spec = study.point_spec(p, ch.as_ref());
        bar.set_message(format!("{} rpm × {}", p.inner_speed_rpm, p.load_scale));
        if load_point(&path, &spec).is_some() {
            loaded += 1;
        } else {
            if args.delay_ms > 0 {
                std::thread::sleep(std::time::Duration::from_millis(args.delay_ms));
            }
            // A point that fails (e.g. a load the bearing cannot carry) is recorded with its error
            // and the study goes on; the command fails at the end, after writing everything.
            let v = with_threads(args.threads, || {
                run_point_with_progress(&study, p, ch.as_ref(), &callback)
                    .map_err(anyhow::Error::from)
            })
            .unwrap_or_else(|e| serde_json::json!({"spec": spec, "error": format!("{e:#}")}));
            if v["converged"] != Value::Bool(true) {
                not_converged += 1;
            }
            let text = serde_json::to_string_pretty(&v)? + "\n";
            write_atomic(&path, text.as_bytes())?;
            computed += 1;
        }
        files.push(path);
        bar.inc(1);
    }
    contacts_bar.finish_and_clear();
    bar.finish_and_clear();
    // Everything below is built from the point files only.
    let mut values: Vec<Value> = Vec::with_capacity(files.len());
    let mut rows: Vec<ResultRow> = Vec::new();
    let mut failed: Vec<String> = Vec::new();
    for path in &files {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let v: Value =
            serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))?;
        if let Some(e) = v.get("error") {
            failed.push(format!(
                "{} rpm × {}: {}",
                v["spec"]["inner_speed_rpm"],
                v["spec"]["load_scale"],
                e.as_str().unwrap_or_default()
            ));
        } else {
            rows.extend(point_rows(&v).with_context(|| path.display().to_string())?);
        }
        values.push(v);
    }
    write_atomic(
        &args.output.join("results.csv"),
        results_csv(&rows).as_bytes(),
    )?;
    println!(
        "study {}: {} points ({} computed, {} loaded from {}), method {}, {:.2} s",
        args.study.display(),
        points.len(),
        computed,
        loaded,
        points_dir.display(),
        ch.name(),
        t0.elapsed().as_secs_f64()
    );
    if !study.case.lubricant_given {
        println!(
            "  lubricant not given in the case: default mineral oil (η0 = {} Pa·s, α = {:e} 1/Pa)",
            study.case.lubricant.viscosity, study.case.lubricant.pressure_viscosity
        );
    }
    if not_converged > failed.len() {
        eprintln!(
            "warning: {} points did not converge (see points.csv)",
            not_converged - failed.len()
        );
    }
    let trends = match fit_trends(&study, &rows) {
        Ok(model) => {
            write_atomic(
                &args.output.join("trends.json"),
                (model.to_json() + "\n").as_bytes(),
            )?;
            for (race, t) in [("inner", &model.inner), ("outer", &model.outer)] {
                for (name, c) in [
                    ("K", &t.k),
                    ("d", &t.d),
                    ("ΔF", &t.delta_f),
                    ("δ", &t.approach),
                ] {
                    println!(
                        "  {race:<5} {name:<2} {:<62} R² {:<10} rms {:.3e}  (Q {:.1}–{:.1} N)",
                        c.formula,
                        c.r_squared.map_or("n/a".to_string(), |r| format!("{r:.6}")),
                        c.rms_residual,
                        t.load_range_n[0],
                        t.load_range_n[1]
                    );
                }
            }
            Some(model)
        }
        Err(e) => {
            eprintln!("warning: trend curves not fitted: {e}");
            None
        }
    };
    // How well the trend force element reproduces each point's reactions.
    let element = trends.clone().map(TrendForceElement::new).transpose()?;
    let mut summary = String::from(
        "speed_rpm,load_scale,converged,iterations,max_load_change,max_key_distance,max_load_offset,max_relative_residual,characterizations,x_m,y_m,z_m,theta_y_rad,theta_z_rad,dry_x_m,dry_y_m,dry_z_m,k_xx_n_m,k_yy_n_m,k_zz_n_m,dry_k_xx_n_m,dry_k_yy_n_m,dry_k_zz_n_m,trend_reaction_error\n",
    );
    let mut worst = 0.0_f64;
    for v in &values {
        let d = |key: &str, k: &str| v[key][k].to_string();
        let kk = |key: &str, i: usize| v[key][i][i].to_string();
        if v.get("error").is_some() {
            let mut cells = vec![
                v["spec"]["inner_speed_rpm"].to_string(),
                v["spec"]["load_scale"].to_string(),
                "error".to_string(),
            ];
            cells.resize(24, String::new());
            summary.push_str(&cells.join(","));
            summary.push('\n');
            continue;
        }
        let err = match &element {
            Some(e) => match e.reaction_error(v) {
                Ok(x) => {
                    worst = worst.max(x);
                    x.to_string()
                }
                Err(e) => {
                    eprintln!("warning: trend force element: {e}");
                    String::new()
                }
            },
            None => String::new(),
        };
        summary.push_str(
            &[
                v["spec"]["inner_speed_rpm"].to_string(),
                v["spec"]["load_scale"].to_string(),
                v["converged"].to_string(),
                v["iterations"].to_string(),
                v["max_load_change"].to_string(),
                v["max_key_distance"].to_string(),
                v["max_load_offset"].to_string(),
                v["max_relative_residual"].to_string(),
                characterizations(v),
                d("displacement", "x"),
                d("displacement", "y"),
                d("displacement", "z"),
                d("displacement", "theta_y"),
                d("displacement", "theta_z"),
                d("dry_displacement", "x"),
                d("dry_displacement", "y"),
                d("dry_displacement", "z"),
                kk("stiffness_ehl", 0),
                kk("stiffness_ehl", 1),
                kk("stiffness_ehl", 2),
                kk("stiffness_dry", 0),
                kk("stiffness_dry", 1),
                kk("stiffness_dry", 2),
                err,
            ]
            .join(","),
        );
        summary.push('\n');
    }
    write_atomic(&args.output.join("points.csv"), summary.as_bytes())?;
    if element.is_some() {
        println!(
            "  trend force element vs the characterized points: largest relative reaction error {worst:.3e}"
        );
    }
    if !rows.is_empty() {
        plots(&args.output, &rows, trends.as_ref())?;
    }
    println!("results in {}", args.output.display());
    if !failed.is_empty() {
        anyhow::bail!(
            "{} of {} points failed (recorded in {}; delete their files to retry):\n  {}",
            failed.len(),
            points.len(),
            points_dir.display(),
            failed.join("\n  ")
        );
    }
    Ok(())
}

/// Contact characterizations a point needed (the sum over its iterations), as a CSV cell.
fn characterizations(point: &Value) -> String {
    point["history"]
        .as_array()
        .map(|h| {
            h.iter()
                .filter_map(|r| r["characterized"].as_u64())
                .sum::<u64>()
                .to_string()
        })
        .unwrap_or_default()
}

/// Plots of K, d and ΔF against the contact load (the paper's Fig. 2): one figure per parameter,
/// inner and outer raceways in separate panels sharing the load axis, one marker series per speed
/// and the trend curves as lines (K and d: one curve; ΔF: one per speed). The markers sit at the
/// load each law was characterized at (within the load reuse tolerance of the equilibrium load),
/// the abscissa of the trend curves.
fn plots(dir: &Path, rows: &[ResultRow], trends: Option<&TrendModel>) -> anyhow::Result<()> {
    crate::plot::study::study_figures(dir, rows, trends)
}
