//! Progress markers of a study's output folder and `ehl-bearing study status DIR`.
//!
//! While a study (or one shard of it) runs, it keeps small marker files in `DIR/.progress/`:
//! - `plan.json`: the study file, the method, the number of shards and every point's file stem
//!   in study order (so the status knows the points without the study file);
//! - `shard-<i>of<N>.json`: one per shard run: `state` (`running`, `done`, `failed`), host, process
//!   id, Slurm job, start time, a heartbeat time rewritten every [`HEARTBEAT_S`] seconds while the
//!   process lives, and the error message of a failed run;
//! - `running/<stem>.json`: the point a shard is computing (removed when its point file is written).
//!
//! Every marker is written atomically (temporary file + rename). Stale markers are harmless: a
//! marker of a process that no longer runs (same host: the process id is gone; another host: no
//! heartbeat for `stale_after_s`) is reported as *interrupted*, its points are redone by the next
//! run of the shard, and a new run of a shard overwrites its marker. The point files are the only
//! results: when the study's outputs are written (a complete single run, or `study merge`), the
//! whole `.progress` folder is removed, so a finished folder holds exactly what a single run writes.

use ehl_bearing::io::write_atomic;
use ehl_bearing::study::{PointRecord, Shard, Study};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

/// The marker folder inside a study's output folder.
pub const PROGRESS_DIR: &str = ".progress";
/// Seconds between two heartbeats of a running shard.
pub const HEARTBEAT_S: u64 = 20;
/// Default age of the last heartbeat after which a running shard of another host counts as
/// interrupted, s.
pub const DEFAULT_STALE_AFTER_S: u64 = 90;

/// `plan.json`: the study run as shards and the Slurm submissions recorded for it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
struct Plan {
    /// The study file.
    study: Option<String>,
    /// The study's method.
    method: Option<String>,
    /// Number of shards.
    shards: Option<u64>,
    /// Every point's file stem, in study order.
    points: Option<Vec<String>>,
    /// Slurm submissions of `study sbatch --submit`.
    submissions: Vec<Submission>,
}

/// One Slurm submission of a study.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
struct Submission {
    /// The array job (None: the shards ran in one job).
    array_job_id: Option<String>,
    /// Its task list.
    array_tasks: String,
    /// The merge job.
    merge_job_id: String,
    /// Submission time (absent in submissions read back without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    submitted_unix_s: Option<u64>,
}

/// `shard-<i>of<N>.json`: one run of a shard.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
struct ShardMarker {
    /// The shard, `i/N`.
    shard: Option<String>,
    /// `running`, `done` or `failed`.
    state: Option<String>,
    /// Host of the process.
    host: Option<String>,
    /// Process id.
    pid: Option<i64>,
    /// Slurm job of the process.
    slurm_job: Option<String>,
    /// Start time, s since the Unix epoch.
    started_unix_s: Option<u64>,
    /// Last heartbeat, s since the Unix epoch.
    heartbeat_unix_s: Option<u64>,
    /// End time (a finished run).
    #[serde(skip_serializing_if = "Option::is_none")]
    finished_unix_s: Option<u64>,
    /// Error of a failed run.
    #[serde(skip_serializing_if = "Option::is_none")]
    message: Option<String>,
}

impl ShardMarker {
    /// A marker of `shard` in `state` by this process, started and beating at `t`.
    fn new(shard: Shard, state: &str, t: u64) -> Self {
        ShardMarker {
            shard: Some(shard.to_string()),
            state: Some(state.into()),
            host: Some(hostname()),
            pid: Some(i64::from(std::process::id())),
            slurm_job: slurm_job(),
            started_unix_s: Some(t),
            heartbeat_unix_s: Some(t),
            finished_unix_s: None,
            message: None,
        }
    }
}

/// `running/<stem>.json`: the point a shard is computing.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
struct PointMarker {
    /// The shard computing it.
    shard: Option<String>,
    /// Host of the shard's process.
    host: Option<String>,
    /// Process id.
    pid: Option<i64>,
    /// Start time, s since the Unix epoch.
    started_unix_s: Option<u64>,
}

fn now_s() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0)
}

/// This machine's host name ("unknown" if it cannot be read).
pub fn hostname() -> String {
    let mut buf = [0u8; 256];
    // SAFETY: gethostname writes at most buf.len() bytes into buf.
    let rc = unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) };
    if rc != 0 {
        return "unknown".into();
    }
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    String::from_utf8_lossy(&buf[..end]).into_owned()
}

/// Whether process `pid` exists on this machine.
fn pid_alive(pid: i64) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: signal 0 only checks that the process exists and may be signalled.
    let rc = unsafe { libc::kill(pid, 0) };
    rc == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

/// The marker folder of output folder `out`.
pub fn progress_dir(out: &Path) -> PathBuf {
    out.join(PROGRESS_DIR)
}

fn shard_file(out: &Path, shard: Shard) -> PathBuf {
    progress_dir(out).join(format!("shard-{}of{}.json", shard.index, shard.count))
}

fn write_json<T: Serialize>(path: &Path, v: &T) -> anyhow::Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| anyhow::anyhow!("creating {}: {e}", d.display()))?;
    }
    let text = serde_json::to_string_pretty(v)? + "\n";
    write_atomic(path, text.as_bytes())?;
    Ok(())
}

fn read_json<T: DeserializeOwned>(path: &Path) -> Option<T> {
    let text = ehl_bearing::io::read_own_file(path).ok()??;
    serde_json::from_str(&text).ok()
}

/// A marker file that must be this program's when present: `Ok(None)` if absent, an error
/// naming the file if it cannot be read or is not a JSON object (a garbage plan or shard marker
/// showed as "0 points, pending").
fn read_marker<T: DeserializeOwned>(path: &Path) -> anyhow::Result<Option<T>> {
    let text = match ehl_bearing::io::read_own_file(path) {
        Ok(Some(t)) => t,
        Ok(None) => return Ok(None),
        Err(e) => anyhow::bail!("{}: unreadable ({e})", path.display()),
    };
    let object = text.trim_start().starts_with('{');
    match serde_json::from_str::<T>(&text) {
        Ok(v) if object => Ok(Some(v)),
        _ => anyhow::bail!(
            "{}: not a marker written by this program (not a JSON object); remove the folder {} \
             and run the study (or `study sbatch`) again to rewrite it",
            path.display(),
            path.parent()
                .map_or(String::new(), |p| p.display().to_string())
        ),
    }
}

/// The outputs of a finished study folder: the library's tables and the CLI's figures
/// (`trends.json` is absent when no trend could be fitted, so it is not required).
pub const STUDY_OUTPUTS: [&str; 8] = [
    "results.csv",
    "points.csv",
    "k_vs_load.png",
    "k_vs_load.svg",
    "d_vs_load.png",
    "d_vs_load.svg",
    "delta_f_vs_load.png",
    "delta_f_vs_load.svg",
];

/// The outputs of [`STUDY_OUTPUTS`] missing from `out`.
pub fn missing_outputs(out: &Path) -> Vec<&'static str> {
    STUDY_OUTPUTS
        .into_iter()
        .filter(|n| !out.join(n).is_file())
        .collect()
}

/// Write `DIR/.progress/plan.json` for `study` run as `shards` shards.
pub fn write_plan(
    out: &Path,
    study_path: &Path,
    study: &Study,
    shards: usize,
) -> anyhow::Result<()> {
    let stems: Vec<String> = study.points().iter().map(|p| p.file_stem()).collect();
    let old: Plan = read_json(&progress_dir(out).join("plan.json")).unwrap_or_default();
    let plan = Plan {
        study: Some(study_path.display().to_string()),
        method: Some(study.method.name().to_string()),
        shards: Some(shards as u64),
        points: Some(stems),
        submissions: old.submissions,
    };
    write_json(&progress_dir(out).join("plan.json"), &plan)
}

/// Write the plan unless one with the same shard count and points is there (a shard run must
/// not overwrite the submissions recorded by `study sbatch`).
pub fn ensure_plan(
    out: &Path,
    study_path: &Path,
    study: &Study,
    shards: usize,
) -> anyhow::Result<()> {
    let stems: Vec<String> = study.points().iter().map(|p| p.file_stem()).collect();
    if let Some(plan) = read_json::<Plan>(&progress_dir(out).join("plan.json")) {
        if plan.shards == Some(shards as u64) && plan.points.as_ref() == Some(&stems) {
            return Ok(());
        }
    }
    let path = std::fs::canonicalize(study_path).unwrap_or_else(|_| study_path.to_path_buf());
    write_plan(out, &path, study, shards)
}

/// Remove the temporary files of writers that were killed between writing and renaming
/// (`points/.<name>.tmp-<pid>`, `points/.probe-<pid>`). Called only once every point is
/// finished and the outputs are written.
pub fn remove_stale_temporaries(out: &Path) -> anyhow::Result<()> {
    let points = out.join("points");
    for e in std::fs::read_dir(&points)
        .map_err(|e| anyhow::anyhow!("reading {}: {e}", points.display()))?
    {
        let e = e?;
        let name = e.file_name().to_string_lossy().to_string();
        if name.starts_with('.') && (name.contains(".tmp-") || name.starts_with(".probe-")) {
            std::fs::remove_file(e.path()).ok();
        }
    }
    Ok(())
}

/// Record a Slurm submission (array job id, its task list, merge job id) in the plan.
pub fn record_submission(
    out: &Path,
    array_job: Option<&str>,
    tasks: &str,
    merge_job: &str,
) -> anyhow::Result<()> {
    let path = progress_dir(out).join("plan.json");
    let mut plan: Plan = read_json(&path).unwrap_or_default();
    plan.submissions.push(Submission {
        array_job_id: array_job.map(str::to_string),
        array_tasks: tasks.to_string(),
        merge_job_id: merge_job.to_string(),
        submitted_unix_s: Some(now_s()),
    });
    write_json(&path, &plan)
}

/// Remove the marker folder (the study's outputs are written; nothing is in flight).
pub fn remove_progress(out: &Path) -> anyhow::Result<()> {
    match std::fs::remove_dir_all(progress_dir(out)) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(anyhow::anyhow!(
            "removing {}: {e}",
            progress_dir(out).display()
        )),
    }
}

/// The Slurm job of this process, e.g. `12_3` for array task 3 of job 12, or `14`.
fn slurm_job() -> Option<String> {
    let get = |k: &str| std::env::var(k).ok().filter(|s| !s.is_empty());
    match (get("SLURM_ARRAY_JOB_ID"), get("SLURM_ARRAY_TASK_ID")) {
        (Some(a), Some(t)) => Some(format!("{a}_{t}")),
        _ => get("SLURM_JOB_ID"),
    }
}

/// The markers of one running shard: its shard file (with a heartbeat thread) and the marker of
/// the point in flight.
pub struct ShardMarkers {
    out: PathBuf,
    marker: Arc<Mutex<ShardMarker>>,
    path: PathBuf,
    stop: Option<Sender<()>>,
    heartbeat: Option<JoinHandle<()>>,
}

impl ShardMarkers {
    /// Mark `shard` of the study in `out` as running by this process and start its heartbeat.
    pub fn start(out: &Path, shard: Shard) -> anyhow::Result<Self> {
        let t = now_s();
        let marker = ShardMarker::new(shard, "running", t);
        let path = shard_file(out, shard);
        write_json(&path, &marker)?;
        let marker = Arc::new(Mutex::new(marker));
        let (tx, rx) = channel::<()>();
        let (m, p) = (Arc::clone(&marker), path.clone());
        let heartbeat = std::thread::spawn(move || {
            while let Err(RecvTimeoutError::Timeout) =
                rx.recv_timeout(Duration::from_secs(HEARTBEAT_S))
            {
                let v = {
                    let mut v = m.lock().unwrap_or_else(|e| e.into_inner());
                    v.heartbeat_unix_s = Some(now_s());
                    v.clone()
                };
                // A failed heartbeat only makes the status pessimistic; the run goes on.
                write_json(&p, &v).ok();
            }
        });
        Ok(ShardMarkers {
            out: out.to_path_buf(),
            marker,
            path,
            stop: Some(tx),
            heartbeat: Some(heartbeat),
        })
    }

    fn point_file(&self, stem: &str) -> PathBuf {
        progress_dir(&self.out)
            .join("running")
            .join(format!("{stem}.json"))
    }

    /// The point `stem` starts.
    pub fn point_started(&self, stem: &str) {
        let shard = self.marker.lock().ok().and_then(|m| m.shard.clone());
        let v = PointMarker {
            shard,
            host: Some(hostname()),
            pid: Some(i64::from(std::process::id())),
            started_unix_s: Some(now_s()),
        };
        write_json(&self.point_file(stem), &v).ok();
    }

    /// The point `stem` is written.
    pub fn point_done(&self, stem: &str) {
        std::fs::remove_file(self.point_file(stem)).ok();
    }

    /// Stop the heartbeat and write the shard's final state (`done` or `failed` with `message`).
    pub fn finish(mut self, result: &anyhow::Result<()>) {
        self.stop_heartbeat();
        let v = {
            let mut v = self.marker.lock().unwrap_or_else(|e| e.into_inner());
            let t = now_s();
            v.heartbeat_unix_s = Some(t);
            v.finished_unix_s = Some(t);
            match result {
                Ok(()) => v.state = Some("done".into()),
                Err(e) => {
                    v.state = Some("failed".into());
                    v.message = Some(format!("{e:#}"));
                }
            }
            v.clone()
        };
        write_json(&self.path, &v).ok();
    }

    fn stop_heartbeat(&mut self) {
        self.stop.take();
        if let Some(h) = self.heartbeat.take() {
            h.join().ok();
        }
    }
}

impl Drop for ShardMarkers {
    fn drop(&mut self) {
        self.stop_heartbeat();
    }
}

/// Record that a run of `shard` failed before it started its markers (e.g. the folder holds
/// another study's points), if the folder is tracked (`plan.json` exists, as after `study
/// sbatch`); an untracked folder is left untouched.
pub fn record_early_failure(out: &Path, shard: Shard, error: &anyhow::Error) {
    if !progress_dir(out).join("plan.json").is_file() {
        return;
    }
    let t = now_s();
    let marker = ShardMarker {
        finished_unix_s: Some(t),
        message: Some(format!("{error:#}")),
        ..ShardMarker::new(shard, "failed", t)
    };
    write_json(&shard_file(out, shard), &marker).ok();
}

/// State of a point in the output folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointState {
    /// A point file with a result.
    Done,
    /// A point file with an error (the characterization failed; not retried).
    Failed,
    /// A marker of a live shard process.
    InFlight,
    /// A marker of a shard process that is gone (cancelled, killed, timed out): redone by the
    /// next run of its shard.
    Interrupted,
    /// Nothing yet (or an unreadable point file, which is redone).
    Pending,
}

/// Counts of points by state.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Points of the set.
    pub points: usize,
    /// Done.
    pub done: usize,
    /// Failed.
    pub failed: usize,
    /// In flight.
    pub in_flight: usize,
    /// Interrupted.
    pub interrupted: usize,
    /// Pending.
    pub pending: usize,
}

impl Counts {
    fn add(&mut self, s: PointState) {
        self.points += 1;
        match s {
            PointState::Done => self.done += 1,
            PointState::Failed => self.failed += 1,
            PointState::InFlight => self.in_flight += 1,
            PointState::Interrupted => self.interrupted += 1,
            PointState::Pending => self.pending += 1,
        }
    }

    /// Every point has a point file (done or failed).
    pub fn finished(&self) -> bool {
        self.done + self.failed == self.points
    }
}

/// Status of one shard.
#[derive(Debug, Clone)]
pub struct ShardStatus {
    /// The shard.
    pub shard: Shard,
    /// `pending` (never started), `running`, `interrupted`, `done`, `failed`, or `finished` (all
    /// its points have files, without a marker).
    pub state: String,
    /// Its points by state.
    pub counts: Counts,
    /// Slurm job of the last run (e.g. `12_3`), host and message of a failed run.
    pub slurm_job: Option<String>,
    /// Host of the last run.
    pub host: Option<String>,
    /// Error of a failed run.
    pub message: Option<String>,
}

/// Status of a study's output folder.
#[derive(Debug, Clone)]
pub struct StudyStatus {
    /// The output folder.
    pub dir: PathBuf,
    /// Study file of the plan (None without a plan).
    pub study: Option<String>,
    /// Method of the plan.
    pub method: Option<String>,
    /// All points.
    pub counts: Counts,
    /// Per shard (empty without a plan).
    pub shards: Vec<ShardStatus>,
    /// `results.csv`, `points.csv` are present and no markers: the outputs are written.
    pub merged: bool,
    /// Slurm jobs recorded by `study sbatch --submit` (array job, tasks, merge job).
    pub submissions: Vec<(Option<String>, String, String)>,
}

fn point_file_state(out: &Path, stem: &str) -> Option<PointState> {
    let text =
        ehl_bearing::io::read_own_file(&out.join("points").join(format!("{stem}.json"))).ok()??;
    let r = PointRecord::from_json(&text).ok()?;
    Some(if r.error.is_some() {
        PointState::Failed
    } else {
        PointState::Done
    })
}

/// What decides whether the process of a `running` marker still runs: this host, the time now,
/// and how old the last heartbeat of another host's process may be.
struct Liveness {
    /// This machine's host name.
    me: String,
    /// Now, s since the Unix epoch.
    now: u64,
    /// Largest age of a live heartbeat, s.
    stale_after_s: u64,
}

impl Liveness {
    /// Liveness as of now, on this host.
    fn now(stale_after_s: u64) -> Self {
        Self {
            me: hostname(),
            now: now_s(),
            stale_after_s,
        }
    }

    /// Whether the process of a `running` shard marker still runs: on this host its process
    /// exists; on another its heartbeat is at most `stale_after_s` old.
    fn alive(&self, m: &ShardMarker) -> bool {
        if m.host.as_deref().unwrap_or("") == self.me {
            return m.pid.is_some_and(pid_alive);
        }
        let beat = m.heartbeat_unix_s.unwrap_or(0);
        self.now.saturating_sub(beat) <= self.stale_after_s
    }
}

/// Read the status of output folder `out`: every point of the plan by state, per shard of the
/// plan. A `running` marker is live if its process exists (same host) or its heartbeat is at
/// most `stale_after_s` old (another host).
pub fn read_status(out: &Path, stale_after_s: u64) -> anyhow::Result<StudyStatus> {
    if !out.join("points").is_dir() {
        anyhow::bail!(
            "{}: no points folder: not the output folder of a study",
            out.display()
        );
    }
    let pdir = progress_dir(out);
    let plan: Option<Plan> = read_marker(&pdir.join("plan.json"))?;
    // Merged: no markers left and every output present (each is written atomically, so a present
    // file is whole; a disk that filled while plotting leaves a figure missing, not truncated).
    let merged = plan.is_none() && missing_outputs(out).is_empty();
    let live = Liveness::now(stale_after_s);
    let Some(plan) = plan else {
        // No plan: a finished (merged) folder, or a folder of an older version; count files.
        return status_without_plan(out, merged);
    };
    let (stems, n) = plan_points(&plan, &pdir)?;
    let mut shards = shard_statuses(out, n, &live)?;
    let mut counts = Counts::default();
    for (k, stem) in stems.iter().enumerate() {
        let state = point_state(out, stem, &live);
        counts.add(state);
        shards[k % n].counts.add(state);
    }
    for s in &mut shards {
        if s.state == "pending" && s.counts.points > 0 && s.counts.finished() {
            s.state = "finished".into();
        }
    }
    let submissions = plan
        .submissions
        .iter()
        .map(|s| {
            (
                s.array_job_id.clone(),
                s.array_tasks.clone(),
                s.merge_job_id.clone(),
            )
        })
        .collect();
    Ok(StudyStatus {
        dir: out.to_path_buf(),
        study: plan.study.clone(),
        method: plan.method.clone(),
        counts,
        shards,
        merged,
        submissions,
    })
}

/// The status of a folder without a plan (a merged folder, or one of an older version): its
/// point files counted by state, no shards.
fn status_without_plan(out: &Path, merged: bool) -> anyhow::Result<StudyStatus> {
    let mut counts = Counts::default();
    let mut stems: Vec<String> = std::fs::read_dir(out.join("points"))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| !n.starts_with('.'))
        .filter_map(|n| n.strip_suffix(".json").map(str::to_string))
        .collect();
    stems.sort();
    for s in &stems {
        counts.add(point_file_state(out, s).unwrap_or(PointState::Pending));
    }
    Ok(StudyStatus {
        dir: out.to_path_buf(),
        study: None,
        method: None,
        counts,
        shards: Vec::new(),
        merged,
        submissions: Vec::new(),
    })
}

/// The plan's points (file stems, in study order) and its number of shards (from 1 to the
/// number of points); an error naming `plan.json` in `pdir` if either is missing or invalid.
fn plan_points(plan: &Plan, pdir: &Path) -> anyhow::Result<(Vec<String>, usize)> {
    let plan_error = |what: &str| {
        anyhow::anyhow!(
            "{}: {what}; remove the folder {} and run the study (or `study sbatch`) again to \
             rewrite it",
            pdir.join("plan.json").display(),
            pdir.display()
        )
    };
    let stems: Vec<String> = plan
        .points
        .clone()
        .ok_or_else(|| plan_error("no list of points"))?;
    let n = plan
        .shards
        .and_then(|n| usize::try_from(n).ok())
        .filter(|&n| (1..=stems.len().max(1)).contains(&n))
        .ok_or_else(|| plan_error("no shard count between 1 and the number of points"))?;
    Ok((stems, n))
}

/// The state of each of the `n` shards from its marker (`pending` without one; a `running`
/// marker whose process is gone is `interrupted`), with no point counted yet.
fn shard_statuses(out: &Path, n: usize, live: &Liveness) -> anyhow::Result<Vec<ShardStatus>> {
    let markers: Vec<Option<ShardMarker>> = (1..=n)
        .map(|i| read_marker(&shard_file(out, Shard { index: i, count: n })))
        .collect::<anyhow::Result<_>>()?;
    Ok((1..=n)
        .zip(markers)
        .map(|(i, m)| {
            let shard = Shard { index: i, count: n };
            let (state, slurm_job, host, message) = match &m {
                None => ("pending".to_string(), None, None, None),
                Some(m) => {
                    let s = m.state.as_deref().unwrap_or("unknown");
                    let state = if s == "running" && !live.alive(m) {
                        "interrupted"
                    } else {
                        s
                    };
                    (
                        state.to_string(),
                        m.slurm_job.clone(),
                        m.host.clone(),
                        m.message.clone(),
                    )
                }
            };
            ShardStatus {
                shard,
                state,
                counts: Counts::default(),
                slurm_job,
                host,
                message,
            }
        })
        .collect())
}

/// The state of the point `stem`: from its point file if it has one, else in flight if it has
/// a marker of a live run of its shard (same process), interrupted if it has a marker of a run
/// that is gone, pending without a marker.
fn point_state(out: &Path, stem: &str, live: &Liveness) -> PointState {
    if let Some(s) = point_file_state(out, stem) {
        return s;
    }
    let marker = progress_dir(out)
        .join("running")
        .join(format!("{stem}.json"));
    match read_json::<PointMarker>(&marker) {
        None => PointState::Pending,
        Some(p) => {
            // The point's marker is live while its shard's process is.
            let owner = p
                .shard
                .as_deref()
                .and_then(|s| s.parse::<Shard>().ok())
                .and_then(|s| read_json::<ShardMarker>(&shard_file(out, s)));
            let live = owner.is_some_and(|m| {
                m.state.as_deref() == Some("running")
                    && m.pid == p.pid
                    && m.host == p.host
                    && live.alive(&m)
            });
            if live {
                PointState::InFlight
            } else {
                PointState::Interrupted
            }
        }
    }
}

impl StudyStatus {
    /// Shards that still have points to compute (pending or interrupted) and no live process.
    pub fn shards_to_run(&self) -> Vec<usize> {
        self.shards
            .iter()
            .filter(|s| !s.counts.finished() && s.state != "running")
            .map(|s| s.shard.index)
            .collect()
    }

    /// The status as a record (`study status --json`).
    pub fn report(&self) -> StatusReport<'_> {
        StatusReport {
            dir: self.dir.display().to_string(),
            study: self.study.as_deref(),
            method: self.method.as_deref(),
            complete: self.counts.points > 0 && self.counts.finished(),
            merged: self.merged,
            missing_outputs: missing_outputs(&self.dir),
            counts: self.counts,
            shards: self
                .shards
                .iter()
                .map(|s| ShardReport {
                    shard: s.shard.to_string(),
                    state: &s.state,
                    slurm_job: s.slurm_job.as_deref(),
                    host: s.host.as_deref(),
                    message: s.message.as_deref(),
                    counts: s.counts,
                })
                .collect(),
            submissions: self
                .submissions
                .iter()
                .map(|(a, t, m)| Submission {
                    array_job_id: a.clone(),
                    array_tasks: t.clone(),
                    merge_job_id: m.clone(),
                    submitted_unix_s: None,
                })
                .collect(),
        }
    }

    /// The status as a table for people.
    pub fn to_text(&self) -> String {
        let c = &self.counts;
        let mut out = format!(
            "{}: {} points: {} done, {} failed, {} in flight, {} interrupted, {} pending",
            self.dir.display(),
            c.points,
            c.done,
            c.failed,
            c.in_flight,
            c.interrupted,
            c.pending
        );
        if let Some(s) = &self.study {
            out += &format!("\n  study {s}");
            if let Some(m) = &self.method {
                out += &format!(", method {m}");
            }
        }
        let missing = missing_outputs(&self.dir);
        if self.merged {
            out += "\n  outputs written (merged); no progress markers left";
        } else if c.points > 0
            && c.finished()
            && !missing.is_empty()
            && missing.len() < STUDY_OUTPUTS.len()
        {
            out += &format!(
                "\n  every point is finished but outputs are missing ({}): run `ehl-bearing study merge` to write them",
                missing.join(", ")
            );
        } else if c.points > 0 && c.finished() {
            out +=
                "\n  every point is finished: run `ehl-bearing study merge` to write the outputs";
        }
        if !self.shards.is_empty() {
            out += &format!(
                "\n  {:<7} {:<12} {:>6} {:>6} {:>6} {:>9} {:>11} {:>7}  job",
                "shard", "state", "points", "done", "failed", "in flight", "interrupted", "pending"
            );
            for s in &self.shards {
                let k = &s.counts;
                out += &format!(
                    "\n  {:<7} {:<12} {:>6} {:>6} {:>6} {:>9} {:>11} {:>7}  {}",
                    s.shard.to_string(),
                    s.state,
                    k.points,
                    k.done,
                    k.failed,
                    k.in_flight,
                    k.interrupted,
                    k.pending,
                    [s.slurm_job.clone(), s.host.clone()]
                        .into_iter()
                        .flatten()
                        .collect::<Vec<_>>()
                        .join(" on ")
                );
                if let Some(m) = &s.message {
                    out += &format!("\n          failed: {}", m.replace('\n', "\n          "));
                }
            }
        }
        for (a, t, m) in &self.submissions {
            out += &format!(
                "\n  submitted: array job {} (tasks {t}), merge job {m}",
                a.as_deref().unwrap_or("none")
            );
        }
        let todo = self.shards_to_run();
        if !todo.is_empty() {
            out += &format!(
                "\n  shards with points left and no live process: {} (resubmit: ehl-bearing study sbatch … --submit)",
                todo.iter()
                    .map(|i| i.to_string())
                    .collect::<Vec<_>>()
                    .join(",")
            );
        }
        out
    }
}

/// `study status --json`: the folder, the plan's study and method, the points by state, per
/// shard, and the Slurm submissions.
#[derive(Debug, Clone, Serialize)]
pub struct StatusReport<'a> {
    dir: String,
    study: Option<&'a str>,
    method: Option<&'a str>,
    complete: bool,
    merged: bool,
    missing_outputs: Vec<&'static str>,
    #[serde(flatten)]
    counts: Counts,
    shards: Vec<ShardReport<'a>>,
    submissions: Vec<Submission>,
}

/// One shard in [`StatusReport`].
#[derive(Debug, Clone, Serialize)]
struct ShardReport<'a> {
    shard: String,
    state: &'a str,
    slurm_job: Option<&'a str>,
    host: Option<&'a str>,
    message: Option<&'a str>,
    #[serde(flatten)]
    counts: Counts,
}
