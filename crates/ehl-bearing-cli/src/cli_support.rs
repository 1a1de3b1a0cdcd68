//! Helpers the commands share: thread pools (`--threads`), wall-time budgets (`--time-limit`),
//! output folders, the plausibility check of a case, spinners and progress bars on a terminal,
//! atomic file writes.

use anyhow::{bail, Context};
use ehl_bearing::budget::Deadline;
use ehl_bearing::case::Case;
use ehl_bearing::characterize::Progress;
pub use ehl_bearing::io::write_atomic;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// 4 threads per core of this machine (`--threads` accepts up to this, and at least 16). The work is
/// CPU-bound, so threads beyond the cores only add overhead; 100 000 threads took minutes to
/// start and stalled the machine.
pub fn max_threads() -> usize {
    std::thread::available_parallelism().map_or(4, |n| n.get()) * 4
}

/// Checks `--threads N`: at least 1 and at most [`max_threads`].
pub fn check_threads(threads: Option<usize>) -> anyhow::Result<()> {
    let max = max_threads().max(16);
    match threads {
        Some(n) if n == 0 || n > max => bail!(
            "--threads {n}: expected 1 to {max} (4 per core of this machine, at least 16; the \
             work is CPU-bound, more threads than cores only add overhead)"
        ),
        _ => Ok(()),
    }
}

/// Run `f` on a rayon pool of `threads` threads (the global pool, sized by RAYON_NUM_THREADS or
/// the number of cores, when None); `threads` is checked by [`check_threads`].
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> anyhow::Result<T> + Send,
) -> anyhow::Result<T> {
    check_threads(threads)?;
    match threads {
        None | Some(0) => f(),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .context("building the thread pool")?
            .install(f),
    }
}

/// The wall-time budget of `--time-limit SECONDS`, started now.
pub fn deadline(time_limit: Option<f64>) -> anyhow::Result<Option<Deadline>> {
    match time_limit {
        None => Ok(None),
        Some(t) => match Deadline::after_seconds(t) {
            Some(d) => Ok(Some(d)),
            None => bail!("--time-limit {t}: expected a number of seconds, > 0 and at most 3.2e7"),
        },
    }
}

/// Refuses an output folder that cannot be one (an existing file) or cannot be created, before
/// any computation.
pub fn check_output_dir(dir: &std::path::Path, option: &str) -> anyhow::Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!("{option} {}: exists and is not a folder", dir.display());
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{option} {}: cannot create the folder", dir.display()))
}

/// Physical plausibility of a case before any EHL solve: warnings on stderr, an error for
/// inputs outside what the models describe.
pub fn check_plausible(case: &Case, origin: &std::path::Path) -> anyhow::Result<()> {
    let warnings = ehl_bearing::plausibility::check_case(case)
        .with_context(|| format!("{}: outside what the models describe", origin.display()))?;
    for w in warnings {
        eprintln!("warning: {}: {w}", origin.display());
    }
    Ok(())
}

/// A spinner with the elapsed time on stderr for one long solve, when stderr is a terminal
/// (hidden otherwise).
pub fn solve_spinner(message: String) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new_spinner();
    if let Ok(style) = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}") {
        bar.set_style(style);
    }
    bar.set_message(message);
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}

/// A progress container drawing on stderr when it is a terminal, hidden otherwise (piped or
/// redirected output stays clean).
pub fn progress_container() -> MultiProgress {
    if std::io::stderr().is_terminal() {
        MultiProgress::with_draw_target(ProgressDrawTarget::stderr())
    } else {
        MultiProgress::with_draw_target(ProgressDrawTarget::hidden())
    }
}

/// A bar of the contacts characterized in the current iteration of the loop, and the callback
/// that drives it.
pub fn contact_progress(multi: &MultiProgress) -> (ProgressBar, impl Fn(Progress) + Sync) {
    let bar = multi.add(ProgressBar::new(0));
    if let Ok(style) =
        ProgressStyle::with_template("  {prefix:>12} {bar:30} {pos}/{len} contacts {msg}")
    {
        bar.set_style(style);
    }
    let b = bar.clone();
    let callback = move |p: Progress| match p {
        Progress::IterationStarted {
            iteration,
            contacts,
        } => {
            b.set_prefix(if iteration == 0 {
                "prediction".to_string()
            } else {
                format!("iteration {iteration}")
            });
            b.set_length(contacts as u64);
            b.set_position(0);
        }
        Progress::ContactDone { .. } => b.inc(1),
        Progress::IterationDone(h) => {
            b.set_message(format!("max ΔQ/Q {:.2e}", h.max_load_change));
        }
    };
    (bar, callback)
}
