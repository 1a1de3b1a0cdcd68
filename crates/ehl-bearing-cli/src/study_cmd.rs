//! `ehl-bearing study STUDY.toml -o DIR [--shard i/N]` and `ehl-bearing study merge STUDY.toml
//! -o DIR [SHARD_DIR...]`: a load × speed sweep of the characterization through the library's
//! study runner (`ehl_bearing::study`), with resumable per-point files, a long-format CSV, trend
//! curves and plots.
//!
//! Output folder:
//! - `points/<stem>.json`: one file per (speed, load scale) point, written atomically as soon as
//!   the point is finished; a rerun with the same folder skips every point whose file exists with
//!   the same spec, so a study killed at any moment (even with SIGKILL) redoes only the points
//!   that were in flight; a folder holding points of another study is refused before any work;
//! - `results.csv` (one row per point and contact), `points.csv` (one row per point),
//!   `trends.json` (trend curves, loadable by `TrendModel::from_json`), and the plots
//!   `k_vs_load`, `d_vs_load`, `delta_f_vs_load` (`.png`, `.svg`).
//!
//! Every final file is built from the point files alone, so it is identical whether the study ran
//! in one go, was resumed, or ran as shards, and whatever the number of threads.

use crate::cli_support::{contact_progress, progress_container, with_threads};
use crate::progress;
use anyhow::Context;
use ehl_bearing::io::{read_study, FsStore};
use ehl_bearing::study::{
    finish_study, merge_points, run_study, PointStore, ResultRow, RunOptions, Shard, Study,
    StudyEvent, StudyOutputs, StudyPoint, TrendModel,
};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

/// Arguments of `study`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct StudyArgs {
    /// `merge`: gather shards and write the study's outputs.
    #[command(subcommand)]
    pub command: Option<StudyCommand>,
    /// Study file (TOML), e.g. examples/study_7006.toml.
    #[arg(required = true)]
    pub study: Option<PathBuf>,
    /// Output folder (created if needed; an existing one of the same study is resumed).
    #[arg(short = 'o', long = "output", required = true)]
    pub output: Option<PathBuf>,
    /// Override the study file's method (quasi-static, harmonic, hertz, map); the file's
    /// [method_options] apply only to its own method.
    #[arg(long)]
    pub method: Option<String>,
    /// Run only shard i of N (1-based, e.g. 2/3): the points whose index k has k mod N = i − 1.
    /// The outputs are written by `study merge` once every shard is done.
    #[arg(long)]
    pub shard: Option<Shard>,
    /// Recompute point files of the output folder that belong to a different study (different
    /// method, case or settings) instead of refusing to run.
    #[arg(long)]
    pub overwrite: bool,
    /// Threads for the contacts of a point (default: RAYON_NUM_THREADS or the number of cores).
    /// Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Wall-time budget of each point in seconds: a point that runs out of it fails with an
    /// error carrying its residual history and is not saved (a rerun computes it).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Points computed at once, at least 1: a second point fills the threads that one point
    /// leaves idle (its equilibrium solves, the last contacts of an iteration); 1 runs them one
    /// after the other. With --time-limit the points run one at a time. Results do not depend
    /// on it.
    #[arg(long, value_name = "N", default_value_t = RunOptions::default().points_in_flight)]
    pub points_in_flight: usize,
    /// Testing aid: sleep this many milliseconds before each computed point (to interrupt a
    /// study reliably in the resume test).
    #[arg(long, hide = true, default_value_t = 0)]
    pub delay_ms: u64,
}

/// Subcommands of `study`.
#[derive(clap::Subcommand)]
pub enum StudyCommand {
    /// Gather the points of shards (run into this folder, or into the SHARD_DIR folders) and
    /// write results.csv, points.csv, trends.json and the plots; fails, listing the first
    /// missing point, unless every point is done.
    Merge(MergeArgs),
    /// Write a Slurm job-array script for the study (one array task per shard, all writing into
    /// the shared output folder) and the dependent merge job's script; `--submit` submits both.
    Sbatch(crate::slurm_cmd::SbatchArgs),
    /// Points done, failed, in flight, interrupted and pending, per shard, read from an output
    /// folder (its point files and the progress markers in DIR/.progress).
    Status(StatusArgs),
}

/// Arguments of `study status`.
#[derive(clap::Args)]
pub struct StatusArgs {
    /// The study's output folder.
    pub dir: PathBuf,
    /// Print JSON (for programs) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// A running shard of another host counts as interrupted when its heartbeat (rewritten every
    /// 20 s) is older than this, s; from 30 to 86400. On this host the process id decides.
    #[arg(long, default_value_t = crate::progress::DEFAULT_STALE_AFTER_S)]
    pub stale_after_s: u64,
}

/// Arguments of `study merge`.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// Study file (TOML) the shards ran.
    pub study: PathBuf,
    /// Output folder: receives the points of the shard folders and the outputs.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Output folders of shards run apart (none: the shards ran into the output folder).
    pub shards: Vec<PathBuf>,
    /// The method the shards ran with, if it overrode the study file's.
    #[arg(long)]
    pub method: Option<String>,
}

fn point_bar(total: u64) -> ProgressBar {
    let multi = progress_container();
    let bar = multi.add(ProgressBar::new(total));
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} points (eta {eta}) {msg}",
    ) {
        bar.set_style(style);
    }
    bar
}

fn load_study(path: &Path, method: Option<&str>) -> anyhow::Result<Study> {
    let mut study = read_study(path)?;
    if let Some(m) = method {
        study
            .set_method(m)
            .map_err(|e| anyhow::anyhow!("--method: {e}"))?;
    }
    Ok(study)
}

/// The lock of one shard's run: the file is removed when the run ends (a finished folder holds
/// exactly what a single run writes); the kernel releases the lock if the process dies.
struct ShardLock {
    path: std::path::PathBuf,
    _file: std::fs::File,
}

impl Drop for ShardLock {
    fn drop(&mut self) {
        std::fs::remove_file(&self.path).ok();
    }
}

/// An exclusive lock on `DIR/.lock-shard-I-of-N` (flock), so that two runs of the same shard
/// (or of the whole study) on one folder do not both compute every point: the second is refused
/// at once. Array tasks of other shards take other locks and run side by side.
fn lock_shard(output: &std::path::Path, shard: Shard) -> anyhow::Result<ShardLock> {
    let path = output.join(format!(".lock-shard-{}-of-{}", shard.index, shard.count));
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .with_context(|| format!("creating the lock file {}", path.display()))?;
    #[cfg(unix)]
    {
        use std::os::unix::io::AsRawFd;
        // SAFETY: flock on a file descriptor this function owns; no memory is passed.
        let rc = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
        if rc != 0 {
            let e = std::io::Error::last_os_error();
            if e.kind() == std::io::ErrorKind::WouldBlock {
                anyhow::bail!(
                    "-o {}: another `ehl-bearing study` is computing {} in this folder (lock {}); \
                     wait for it to finish, or give another -o",
                    output.display(),
                    if shard == Shard::ALL {
                        "the whole study".to_string()
                    } else {
                        format!("shard {shard}")
                    },
                    path.display()
                );
            }
            return Err(e).with_context(|| format!("locking {}", path.display()));
        }
    }
    Ok(ShardLock { path, _file: file })
}

/// Run `study` (or `study merge`).
pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    match &args.command {
        Some(StudyCommand::Merge(m)) => return merge(m),
        Some(StudyCommand::Sbatch(a)) => return crate::slurm_cmd::run(a),
        Some(StudyCommand::Status(a)) => return status(a),
        None => {}
    }
    let (Some(study_path), Some(output)) = (&args.study, &args.output) else {
        anyhow::bail!("give a study file and -o DIR (or `study merge`)");
    };
    let study = load_study(study_path, args.method.as_deref())?;
    check_run(args, &study, study_path)?;
    // The output folder is checked (and created) before any work.
    let store = FsStore::create(output)?;
    let shard = args.shard.unwrap_or(Shard::ALL);
    // Held until the run ends (the kernel releases it if the process dies).
    let _lock = lock_shard(output, shard)?;
    let options = RunOptions {
        shard,
        overwrite: args.overwrite,
        point_time_limit_s: args.time_limit,
        points_in_flight: args.points_in_flight,
    };
    let t0 = Instant::now();
    let progress = RunProgress::new(output, study_path, &study, &options, args.delay_ms);
    let run = run_with_progress(args.threads, &study, &store, &options, &progress);
    let outcome = report_run(run, &study, study_path, &store, &options, t0);
    match (progress.markers.into_inner(), &outcome) {
        (Some(Some(m)), _) => m.finish(&outcome),
        (None, Err(e)) => progress::record_early_failure(output, options.shard, e),
        _ => {}
    }
    outcome?;
    if options.shard.count > 1 {
        println!(
            "when every shard is done: ehl-bearing study merge {} -o {}",
            study_path.display(),
            output.display()
        );
        return Ok(());
    }
    finish(&study, &store)
}

/// The options of a run and every point's case (its shard's points) are checked before any
/// work: threads, points in flight, the time limit, and each case's physical plausibility.
fn check_run(args: &StudyArgs, study: &Study, study_path: &Path) -> anyhow::Result<()> {
    crate::cli_support::check_threads(args.threads)?;
    if args.points_in_flight == 0 {
        anyhow::bail!("--points-in-flight 0: expected at least 1 point");
    }
    crate::cli_support::deadline(args.time_limit)?;
    // Every point's case is checked for physical plausibility before any work.
    for p in study.shard_points(args.shard.unwrap_or(Shard::ALL)) {
        crate::cli_support::check_plausible(&study.point_case(&p), study_path).with_context(
            || {
                format!(
                    "point {} ({} rpm × load scale {})",
                    p.index + 1,
                    p.inner_speed_rpm,
                    p.load_scale
                )
            },
        )?;
    }
    Ok(())
}

/// Run the study's shard on `threads` threads, with the points bar and the contacts bar (the
/// contacts of every running point when several run at once) and the progress markers of
/// `progress`; the bars are cleared when the run ends.
fn run_with_progress(
    threads: Option<usize>,
    study: &Study,
    store: &FsStore,
    options: &RunOptions,
    progress: &RunProgress,
) -> anyhow::Result<ehl_bearing::study::StudyRun> {
    let multi = progress_container();
    let (contacts_bar, callback) = contact_progress(&multi);
    // Several points at once: the contacts bar counts the contacts of all running points.
    let concurrent = options.points_at_once() > 1;
    let callback = |l: ehl_bearing::characterize::Progress| match l {
        ehl_bearing::characterize::Progress::IterationStarted { contacts, .. } if concurrent => {
            contacts_bar.set_prefix("running points");
            contacts_bar.inc_length(contacts as u64);
        }
        _ => callback(l),
    };
    let events = |e: StudyEvent| match e {
        StudyEvent::Planned {
            points,
            to_compute,
            redone,
        } => progress.planned(points, to_compute, redone),
        StudyEvent::PointStarted(p) => progress.point_started(&p),
        StudyEvent::Loop(_, l) => callback(l),
        StudyEvent::PointDone {
            point,
            converged,
            error,
            seconds,
        } => progress.point_done(&point, converged, error.as_deref(), seconds),
    };
    let run = with_threads(threads, || {
        run_study(study, store, options, &events).map_err(anyhow::Error::from)
    });
    contacts_bar.finish_and_clear();
    progress.bar.finish_and_clear();
    run
}

/// What a study run shows while it runs: the points bar, the progress markers in DIR/.progress
/// (started once the run has checked the folder and planned its points, so that a refused run
/// leaves the folder untouched), and a log line per point when stderr is not a terminal.
struct RunProgress<'a> {
    /// The output folder.
    output: &'a Path,
    /// The study file.
    study_path: &'a Path,
    /// The study.
    study: &'a Study,
    /// The shard that runs.
    shard: Shard,
    /// The markers: unset before the plan, `None` when they are not written.
    markers: OnceLock<Option<progress::ShardMarkers>>,
    /// Points of the shard done.
    bar: ProgressBar,
    /// Whether stderr is a terminal (else a log line per point).
    terminal: bool,
    /// Testing aid: sleep before each computed point, ms.
    delay_ms: u64,
    /// Points finished; its lock serializes the log lines of points finishing together.
    done: Mutex<usize>,
}

impl<'a> RunProgress<'a> {
    /// The progress of the shard of `options`; the points bar is shown at once.
    fn new(
        output: &'a Path,
        study_path: &'a Path,
        study: &'a Study,
        options: &RunOptions,
        delay_ms: u64,
    ) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = point_bar(study.shard_points(options.shard).len() as u64);
        Self {
            output,
            study_path,
            study,
            shard: options.shard,
            markers: OnceLock::new(),
            bar,
            terminal,
            delay_ms,
            done: Mutex::new(0),
        }
    }

    /// Start the progress markers (the plan and this shard's marker); a warning, not an error,
    /// if they cannot be written.
    fn start_markers(&self) -> Option<progress::ShardMarkers> {
        let started =
            progress::ensure_plan(self.output, self.study_path, self.study, self.shard.count)
                .and_then(|()| progress::ShardMarkers::start(self.output, self.shard));
        match started {
            Ok(m) => Some(m),
            Err(e) => {
                eprintln!("warning: progress markers not written ({e:#}); `study status` will not see this run");
                None
            }
        }
    }

    /// The run planned `to_compute` of its `points` points (`redone` of them had an unreadable
    /// file): the markers start, the bar counts the points already done.
    fn planned(&self, points: usize, to_compute: usize, redone: usize) {
        // A late task of a merged study (every point stored, the outputs written, no markers
        // left) leaves the folder as the merge left it: no markers that would ask for a
        // merge again.
        let merged = to_compute == 0
            && self.output.join("points.csv").is_file()
            && !progress::progress_dir(self.output).exists();
        if merged {
            self.markers.get_or_init(|| None);
        } else {
            self.markers.get_or_init(|| self.start_markers());
        }
        self.bar.set_position((points - to_compute) as u64);
        if redone > 0 {
            eprintln!(
                "{redone} unreadable point file(s) (e.g. truncated by a crash) will be recomputed"
            );
        }
    }

    /// Point `p` starts: its marker, the bar's message, and the testing delay.
    fn point_started(&self, p: &StudyPoint) {
        if let Some(Some(m)) = self.markers.get() {
            m.point_started(&p.file_stem());
        }
        self.bar
            .set_message(format!("{} rpm × {}", p.inner_speed_rpm, p.load_scale));
        if self.delay_ms > 0 {
            std::thread::sleep(std::time::Duration::from_millis(self.delay_ms));
        }
    }

    /// `point` finished after `seconds` s, converged or not, or failed with `error`.
    fn point_done(&self, point: &StudyPoint, converged: bool, error: Option<&str>, seconds: f64) {
        if let Some(Some(m)) = self.markers.get() {
            m.point_done(&point.file_stem());
        }
        self.bar.inc(1);
        let mut n = self.done.lock().unwrap_or_else(|p| p.into_inner());
        *n += 1;
        if !self.terminal {
            // A log line per point when nobody watches a progress bar (pipes, batch jobs).
            eprintln!(
                "point {} ({} rpm × {}): {} in {seconds:.1} s",
                point.index + 1,
                point.inner_speed_rpm,
                point.load_scale,
                match (error, converged) {
                    (Some(e), _) => format!("failed: {e}"),
                    (None, true) => "converged".into(),
                    (None, false) => "NOT converged".into(),
                }
            );
        }
    }
}

/// Print what a run did; a shard run with failed points is an error (its task fails visibly).
fn report_run(
    run: anyhow::Result<ehl_bearing::study::StudyRun>,
    study: &Study,
    study_path: &Path,
    store: &FsStore,
    options: &RunOptions,
    t0: Instant,
) -> anyhow::Result<()> {
    let run = run?;
    println!(
        "study {}: shard {}: {} points ({} computed, {} loaded from {}), method {}, {:.2} s",
        study_path.display(),
        run.shard,
        run.points,
        run.computed,
        run.loaded,
        store.dir().join("points").display(),
        study.method,
        t0.elapsed().as_secs_f64()
    );
    if options.shard.count > 1 && !run.failed.is_empty() {
        anyhow::bail!(
            "{} of {} points of shard {} failed (recorded in their point files; delete them to retry):\n  {}",
            run.failed.len(),
            run.points,
            run.shard,
            failures(&run.failed)
        );
    }
    Ok(())
}

/// `study status`.
fn status(args: &StatusArgs) -> anyhow::Result<()> {
    if !(30..=86_400).contains(&args.stale_after_s) {
        anyhow::bail!(
            "--stale-after-s {}: expected seconds from 30 to 86400",
            args.stale_after_s
        );
    }
    let st = progress::read_status(&args.dir, args.stale_after_s)?;
    if args.json {
        println!("{}", ehl_bearing::report::to_json_pretty(&st.report()));
    } else {
        println!("{}", st.to_text());
    }
    Ok(())
}

fn failures(failed: &[(ehl_bearing::study::StudyPoint, String)]) -> String {
    failed
        .iter()
        .map(|(p, e)| format!("{} rpm × {}: {e}", p.inner_speed_rpm, p.load_scale))
        .collect::<Vec<_>>()
        .join("\n  ")
}

/// `study merge`.
fn merge(args: &MergeArgs) -> anyhow::Result<()> {
    let study = load_study(&args.study, args.method.as_deref())?;
    let store = FsStore::create(&args.output)?;
    let sources = args
        .shards
        .iter()
        .map(|d| FsStore::open(d))
        .collect::<Result<Vec<_>, _>>()?;
    let refs: Vec<&dyn PointStore> = sources.iter().map(|s| s as &dyn PointStore).collect();
    let copied = merge_points(&study, &store, &refs)?;
    println!(
        "study {}: merged {} point files from {} shard folder(s) into {}",
        args.study.display(),
        copied,
        sources.len(),
        store.dir().display()
    );
    finish(&study, &store)
}

/// Build and report the outputs from the point files.
fn finish(study: &Study, store: &FsStore) -> anyhow::Result<()> {
    let out: StudyOutputs = finish_study(study, store)?;
    // Every point is finished and the outputs are written: the progress markers and the
    // temporaries of killed writers are no longer needed, and the folder holds what a single
    // run writes.
    progress::remove_progress(store.dir())?;
    progress::remove_stale_temporaries(store.dir())?;
    if !study.case.lubricant_given {
        println!(
            "  lubricant not given in the case: default mineral oil (η0 = {} Pa·s, α = {:e} 1/Pa)",
            study.case.lubricant.viscosity, study.case.lubricant.pressure_viscosity
        );
    }
    if out.not_converged() > 0 {
        eprintln!(
            "warning: {} points did not converge (see points.csv)",
            out.not_converged()
        );
    }
    if let Some(l) = out.lubrication_summary() {
        let at = |e: &ehl_bearing::study::LubricationExtreme| {
            format!(
                "{} rpm × {}, ball {} {}",
                e.inner_speed_rpm, e.load_scale, e.ball, e.race
            )
        };
        println!(
            "  lubrication (docs/lubricant.md; per point in points.csv): smallest Λ {}; largest \
             thermal film reduction {}; {} of {} points with warnings",
            l.min_lambda
                .as_ref()
                .map_or("-".into(), |e| format!("{:.2} ({})", e.value, at(e))),
            l.max_thermal_reduction
                .as_ref()
                .map_or("-".into(), |e| format!(
                    "{:.1} % ({})",
                    100.0 * e.value,
                    at(e)
                )),
            l.points_with_warnings,
            l.points
        );
        if let Some(e) = &l.max_starvation_reduction {
            println!(
                "  starvation: largest reduction of the minimum film {:.1} % ({})",
                100.0 * e.value,
                at(e)
            );
        }
    }
    match &out.trends {
        Ok(model) => {
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
            if out.trend_errors.iter().any(|e| e.is_some()) {
                println!(
                    "  trend force element vs the characterized points: largest relative reaction error {:.3e}",
                    out.worst_trend_error()
                );
            }
        }
        Err(e) => eprintln!("warning: trend curves not fitted: {e}"),
    }
    if !out.rows.is_empty() {
        plots(store.dir(), &out.rows, out.trends.as_ref().ok())?;
    }
    println!("results in {}", store.dir().display());
    if !out.failed.is_empty() {
        anyhow::bail!(
            "{} of {} points failed (recorded in {}; delete their files to retry):\n  {}",
            out.failed.len(),
            out.records.len(),
            store.dir().join("points").display(),
            failures(&out.failed)
        );
    }
    Ok(())
}

/// Plots of K, d and ΔF against the contact load (the paper's Fig. 2): one figure per parameter,
/// inner and outer raceways in separate panels sharing the load axis, one marker series per speed
/// and the trend curves as lines (K and d: one curve; ΔF: one per speed). The markers sit at the
/// load each law was characterized at (within the load reuse tolerance of the equilibrium load),
/// the abscissa of the trend curves.
fn plots(dir: &Path, rows: &[ResultRow], trends: Option<&TrendModel>) -> anyhow::Result<()> {
    crate::plot::study::study_figures(dir, rows, trends)
}
