//! `ehl-bearing study sbatch STUDY.toml -o DIR`: a Slurm job-array script for a study (one array
//! task per shard, every task writing its own points into the shared folder DIR), the merge job's
//! script, and with `--submit` the submission of both (`sbatch --parsable`, the merge with
//! `--dependency=afterok:<array job>`). A resubmission submits only the shards that still have
//! points to compute.

use crate::progress;
use ehl_bearing::io::read_study;
use ehl_bearing::study::Study;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Arguments of `study sbatch`.
#[derive(clap::Args, Debug)]
pub struct SbatchArgs {
    /// Study file (TOML).
    pub study: PathBuf,
    /// Shared output folder of the study (on a file system every node sees); created if needed.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The job-array options.
    #[command(flatten)]
    pub job: JobArgs,
    /// Override the study file's method (quasi-static, harmonic, hertz, map), for the tasks and the merge.
    #[arg(long)]
    pub method: Option<String>,
    /// With --submit: a running shard of another host whose heartbeat is older than this counts
    /// as interrupted and is resubmitted, s; from 30 to 86400 (as `study status`).
    #[arg(long, default_value_t = progress::DEFAULT_STALE_AFTER_S)]
    pub stale_after_s: u64,
}

/// The options of a job array and the job after it, shared by `study sbatch` and `law-map
/// sbatch`.
#[derive(clap::Args, Debug)]
pub struct JobArgs {
    /// Number of array tasks = shards (round robin over the study's points or the map's
    /// nodes); from 1 to their number.
    #[arg(long, default_value_t = 4)]
    pub shards: usize,
    /// CPUs per array task (`#SBATCH --cpus-per-task`); the task's threads (RAYON_NUM_THREADS)
    /// are taken from SLURM_CPUS_PER_TASK. From 1 to 1024.
    #[arg(long, default_value_t = 2)]
    pub cpus_per_task: usize,
    /// Time limit of each array task and of the job after them (merge or assemble), minutes
    /// (`#SBATCH --time`); from 1 to 525600 (a year). A task stopped by it keeps its finished
    /// points or nodes; resubmit.
    #[arg(long, default_value_t = 120)]
    pub time_limit_min: u64,
    /// Slurm partition (`#SBATCH --partition`); default: the cluster's default partition.
    #[arg(long)]
    pub partition: Option<String>,
    /// Job name (default: ehl-<study file stem>, ehl-map-<map spec stem>).
    #[arg(long)]
    pub job_name: Option<String>,
    /// Folder for the scripts and the Slurm logs (`logs/`); default: `<DIR>.slurm` next to the
    /// output folder, so that the output folder holds results only.
    #[arg(long)]
    pub job_dir: Option<PathBuf>,
    /// The ehl-bearing executable the jobs run (default: this one); must be reachable from the
    /// compute nodes.
    #[arg(long)]
    pub bin: Option<PathBuf>,
    /// Submit the array and the dependent job after it (merge or assemble) with sbatch; only
    /// the shards with work left are submitted (for a study also: with no live task).
    #[arg(long)]
    pub submit: bool,
    /// The sbatch command (default: sbatch on the PATH).
    #[arg(long, default_value = "sbatch")]
    pub sbatch: String,
}

impl JobArgs {
    /// Check the options against their ranges; `units` bounds the shards and `what` names it in
    /// the message (e.g. "the study's number of points").
    pub fn validate(&self, units: usize, what: &str) -> anyhow::Result<()> {
        if !(1..=units.min(100_000)).contains(&self.shards) {
            anyhow::bail!(
                "--shards {}: expected an integer from 1 to {} ({what})",
                self.shards,
                units.min(100_000)
            );
        }
        if !(1..=1024).contains(&self.cpus_per_task) {
            anyhow::bail!(
                "--cpus-per-task {}: expected an integer from 1 to 1024",
                self.cpus_per_task
            );
        }
        if !(1..=525_600).contains(&self.time_limit_min) {
            anyhow::bail!(
                "--time-limit-min {}: expected minutes from 1 to 525600 (a year)",
                self.time_limit_min
            );
        }
        if let Some(p) = &self.partition {
            if !slurm_name_ok(p) {
                anyhow::bail!("--partition {p:?}: expected a partition name of 1 to 64 letters, digits, '.', '_' or '-'");
            }
        }
        if let Some(j) = &self.job_name {
            if !slurm_name_ok(j) {
                anyhow::bail!(
                    "--job-name {j:?}: expected 1 to 64 letters, digits, '.', '_' or '-'"
                );
            }
        }
        Ok(())
    }

    /// The output folder `output` (with its `points` folder) and the job folder (`--job-dir`,
    /// else [`default_job_dir`]; with its `logs` folder), created if needed, as absolute paths;
    /// the job folder must lie outside the output folder.
    pub fn folders(&self, output: &Path) -> anyhow::Result<(PathBuf, PathBuf)> {
        std::fs::create_dir_all(output.join("points"))
            .map_err(|e| anyhow::anyhow!("creating {}: {e}", output.display()))?;
        let output = absolute(output)?;
        let job_dir = self
            .job_dir
            .clone()
            .unwrap_or_else(|| default_job_dir(&output));
        std::fs::create_dir_all(job_dir.join("logs"))
            .map_err(|e| anyhow::anyhow!("creating {}: {e}", job_dir.join("logs").display()))?;
        let job_dir = absolute(&job_dir)?;
        if job_dir.starts_with(&output) {
            anyhow::bail!(
                "--job-dir {}: expected a folder outside the output folder {} (which holds results only)",
                job_dir.display(),
                output.display()
            );
        }
        Ok((output, job_dir))
    }

    /// The executable the jobs run: `--bin` made absolute and checked, else this one.
    pub fn executable(&self) -> anyhow::Result<PathBuf> {
        match &self.bin {
            Some(b) => {
                let bin = absolute(b).map_err(|e| anyhow::anyhow!("--bin: {e}"))?;
                check_bin(&bin)?;
                Ok(bin)
            }
            None => Ok(std::env::current_exe()?),
        }
    }
}

/// Everything a script depends on, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct ScriptParams {
    /// Absolute study file.
    pub study: PathBuf,
    /// Absolute output folder.
    pub output: PathBuf,
    /// Absolute job folder.
    pub job_dir: PathBuf,
    /// The executable.
    pub bin: PathBuf,
    /// Method override.
    pub method: Option<String>,
    /// Shards.
    pub shards: usize,
    /// Points of the study.
    pub points: usize,
    /// CPUs per task.
    pub cpus_per_task: usize,
    /// Time limit, min.
    pub time_limit_min: u64,
    /// Partition.
    pub partition: Option<String>,
    /// Job name.
    pub job_name: String,
}

/// A shell word: single-quoted unless it is plainly safe.
pub fn shell_quote(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "/._-+:=,@%".contains(c))
    {
        return s.to_string();
    }
    format!("'{}'", s.replace('\'', r"'\''"))
}

pub(crate) fn slurm_name_ok(s: &str) -> bool {
    !s.is_empty()
        && s.len() <= 64
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "._-".contains(c))
}

/// Check the options against their ranges (the study's point count bounds the shards).
pub fn validate(args: &SbatchArgs, points: usize) -> anyhow::Result<()> {
    args.job.validate(points, "the study's number of points")?;
    if !(30..=86_400).contains(&args.stale_after_s) {
        anyhow::bail!(
            "--stale-after-s {}: expected seconds from 30 to 86400",
            args.stale_after_s
        );
    }
    Ok(())
}

fn time_hms(min: u64) -> String {
    let (d, h, m) = (min / 1440, (min % 1440) / 60, min % 60);
    if d > 0 {
        format!("{d}-{h:02}:{m:02}:00")
    } else {
        format!("{h:02}:{m:02}:00")
    }
}

fn header(p: &ScriptParams, name: &str, output: &str, cpus: usize) -> String {
    script_header(&JobOptions {
        name,
        cpus,
        time_limit_min: p.time_limit_min,
        partition: p.partition.as_deref(),
        log: &p.job_dir.join("logs").join(output),
    })
}

/// The `#SBATCH` lines every job script of the command line starts with.
pub(crate) struct JobOptions<'a> {
    /// Job name.
    pub name: &'a str,
    /// CPUs per task.
    pub cpus: usize,
    /// Time limit, min.
    pub time_limit_min: u64,
    /// Partition (None: the cluster's default).
    pub partition: Option<&'a str>,
    /// Log file pattern (`%x`, `%A`, `%a`, `%j` as Slurm expands them).
    pub log: &'a Path,
}

/// `#!/bin/bash` and the `#SBATCH` lines of `o`.
pub(crate) fn script_header(o: &JobOptions) -> String {
    let mut s = String::from("#!/bin/bash\n");
    s += &format!("#SBATCH --job-name={}\n", o.name);
    s += "#SBATCH --ntasks=1\n";
    s += &format!("#SBATCH --cpus-per-task={}\n", o.cpus);
    s += &format!("#SBATCH --time={}\n", time_hms(o.time_limit_min));
    if let Some(part) = o.partition {
        s += &format!("#SBATCH --partition={part}\n");
    }
    s += &format!("#SBATCH --output={}\n", o.log.display());
    s
}

fn method_arg(p: &ScriptParams) -> String {
    p.method
        .as_ref()
        .map(|m| format!(" --method {}", shell_quote(m)))
        .unwrap_or_default()
}

/// The job-array script: task i runs shard i/N into the shared output folder.
pub fn array_script(p: &ScriptParams) -> String {
    let mut s = header(p, &p.job_name, "%x-%A_%a.out", p.cpus_per_task);
    s += &format!("#SBATCH --array=1-{}\n", p.shards);
    s += &format!(
        "# Written by `ehl-bearing study sbatch` ({} {}): study {}, {} points in {} shards
# (shard i runs the points k with k mod {} = i - 1). Array task i runs shard i/{} and writes
# only its own point files into the shared output folder, each atomically; a resubmitted task
# skips the points already finished. A task that fails exits non-zero with the message in its
# log. When every task succeeded, the merge job (merge.sbatch) writes the study's outputs.
# Watch: {} study status {}
set -euo pipefail
: \"${{SLURM_ARRAY_TASK_ID:?submit this script with sbatch: it is a job array}}\"
# The library's threads (rayon): the CPUs Slurm gave the task.
export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"
echo \"ehl-bearing shard ${{SLURM_ARRAY_TASK_ID}}/{} on $(hostname) with $RAYON_NUM_THREADS thread(s)\"
exec {} study {} -o {} --shard \"${{SLURM_ARRAY_TASK_ID}}/{}\"{}
",
        env!("CARGO_PKG_NAME"),
        env!("CARGO_PKG_VERSION"),
        p.study.display(),
        p.points,
        p.shards,
        p.shards,
        p.shards,
        shell_quote(&p.bin.display().to_string()),
        shell_quote(&p.output.display().to_string()),
        p.shards,
        shell_quote(&p.bin.display().to_string()),
        shell_quote(&p.study.display().to_string()),
        shell_quote(&p.output.display().to_string()),
        p.shards,
        method_arg(p),
    );
    s
}

/// The merge job's script (submitted with `--dependency=afterok:<array job>`).
pub fn merge_script(p: &ScriptParams) -> String {
    let mut s = header(p, &format!("{}-merge", p.job_name), "%x-%j.out", 1);
    s += &format!(
        "# Written by `ehl-bearing study sbatch`: gathers the points of study {} in {} and writes
# results.csv, points.csv, trends.json and the plots; fails, naming the first missing point,
# unless every point is finished.
set -euo pipefail
export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"
exec {} study merge {} -o {}{}
",
        p.study.display(),
        p.output.display(),
        shell_quote(&p.bin.display().to_string()),
        shell_quote(&p.study.display().to_string()),
        shell_quote(&p.output.display().to_string()),
        method_arg(p),
    );
    s
}

pub(crate) fn absolute(p: &Path) -> anyhow::Result<PathBuf> {
    std::fs::canonicalize(p).map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))
}

/// `<DIR>.slurm` next to DIR.
fn default_job_dir(output: &Path) -> PathBuf {
    let name = output
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "study".into());
    output.with_file_name(format!("{name}.slurm"))
}

/// The job id printed by `sbatch --parsable` (`12` or `12;cluster`).
pub fn parse_job_id(stdout: &str) -> anyhow::Result<String> {
    let line = stdout.lines().map(str::trim).find(|l| !l.is_empty());
    let id = line
        .and_then(|l| l.split(';').next())
        .map(str::trim)
        .unwrap_or("");
    if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
        anyhow::bail!("sbatch --parsable printed {stdout:?}: expected a job id");
    }
    Ok(id.to_string())
}

pub(crate) fn sbatch(cmd: &str, args: &[String]) -> anyhow::Result<String> {
    let out = Command::new(cmd)
        .args(args)
        .output()
        .map_err(|e| anyhow::anyhow!("running {cmd} (--sbatch): {e}"))?;
    if !out.status.success() {
        anyhow::bail!(
            "{cmd} {} failed ({}): {}",
            args.join(" "),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    parse_job_id(&String::from_utf8_lossy(&out.stdout))
}

/// The `squeue` next to the `--sbatch` command (`squeue` on the PATH for a bare `sbatch`).
fn squeue_command(sbatch_cmd: &str) -> PathBuf {
    let p = std::path::Path::new(sbatch_cmd);
    match p.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join("squeue"),
        _ => PathBuf::from("squeue"),
    }
}

/// Array tasks Slurm still holds: task number → (array job, state).
type Queued = std::collections::BTreeMap<usize, (String, String)>;

/// Array tasks of the jobs `array_ids` that Slurm still holds (any state before completion:
/// pending, held, running, …), task number → (job, state), from
/// `squeue --noheader --array --jobs IDS --format "%i %T"` (one line per task, e.g.
/// `41_2 PENDING`). Jobs Slurm no longer knows are simply absent.
fn queued_tasks(sbatch_cmd: &str, array_ids: &[String]) -> anyhow::Result<Queued> {
    let mut out = Queued::new();
    if array_ids.is_empty() {
        return Ok(out);
    }
    let squeue = squeue_command(sbatch_cmd);
    let o = Command::new(&squeue)
        .args([
            "--noheader",
            "--array",
            "--jobs",
            &array_ids.join(","),
            "--format",
            "%i %T",
        ])
        .output()
        .map_err(|e| anyhow::anyhow!("running {}: {e}", squeue.display()))?;
    // squeue fails for job ids it has forgotten entirely: nothing of them is queued.
    let text = String::from_utf8_lossy(&o.stdout);
    if !o.status.success() && text.trim().is_empty() {
        let err = String::from_utf8_lossy(&o.stderr);
        if err.contains("Invalid job id") {
            return Ok(out);
        }
        anyhow::bail!("{} failed ({}): {}", squeue.display(), o.status, err.trim());
    }
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let (Some(id), Some(state)) = (words.next(), words.next()) else {
            continue;
        };
        let Some((job, task)) = id.split_once('_') else {
            continue;
        };
        if !array_ids.iter().any(|a| a == job) {
            continue;
        }
        if let Ok(t) = task.parse::<usize>() {
            out.insert(t, (job.to_string(), state.to_string()));
        }
    }
    Ok(out)
}

/// Compress sorted task numbers into Slurm's array syntax, e.g. `1-3,5`.
pub fn array_ranges(tasks: &[usize]) -> String {
    let mut parts = Vec::new();
    let mut i = 0;
    while i < tasks.len() {
        let mut j = i;
        while j + 1 < tasks.len() && tasks[j + 1] == tasks[j] + 1 {
            j += 1;
        }
        parts.push(if j > i {
            format!("{}-{}", tasks[i], tasks[j])
        } else {
            tasks[i].to_string()
        });
        i = j + 1;
    }
    parts.join(",")
}

fn load(args: &SbatchArgs) -> anyhow::Result<Study> {
    let mut study = read_study(&args.study)?;
    if let Some(m) = &args.method {
        study
            .set_method(m)
            .map_err(|e| anyhow::anyhow!("--method: {e}"))?;
    }
    Ok(study)
}

/// `--bin`: an executable file where it exists on this machine (a folder or a file without
/// execute permission is refused); a path absent here is accepted with a warning, since it may
/// exist only on the compute nodes.
pub(crate) fn check_bin(bin: &std::path::Path) -> anyhow::Result<()> {
    match std::fs::metadata(bin) {
        Err(_) => {
            eprintln!(
                "warning: --bin {}: not found on this machine; the jobs fail unless it exists on \
                 the compute nodes",
                bin.display()
            );
            Ok(())
        }
        Ok(m) if !m.is_file() => anyhow::bail!(
            "--bin {}: not a file (expected the ehl-bearing executable)",
            bin.display()
        ),
        Ok(m) => {
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                if m.permissions().mode() & 0o111 == 0 {
                    anyhow::bail!(
                        "--bin {}: not executable (expected the ehl-bearing executable)",
                        bin.display()
                    );
                }
            }
            let _ = m;
            Ok(())
        }
    }
}

/// Run `study sbatch`.
pub fn run(args: &SbatchArgs) -> anyhow::Result<()> {
    let study = load(args)?;
    let points = study.points().len();
    validate(args, points)?;
    let bin = args.job.executable()?;
    let (output, job_dir) = args.job.folders(&args.output)?;
    let study_path = absolute(&args.study)?;
    let p = ScriptParams {
        study: study_path.clone(),
        output: output.clone(),
        job_dir: job_dir.clone(),
        bin,
        method: args.method.clone(),
        shards: args.job.shards,
        points,
        cpus_per_task: args.job.cpus_per_task,
        time_limit_min: args.job.time_limit_min,
        partition: args.job.partition.clone(),
        job_name: args
            .job
            .job_name
            .clone()
            .unwrap_or_else(|| default_job_name("ehl-", &study_path, "study")),
    };
    let array = job_dir.join("study.sbatch");
    let merge = job_dir.join("merge.sbatch");
    crate::cli_support::write_atomic(&array, array_script(&p).as_bytes())?;
    crate::cli_support::write_atomic(&merge, merge_script(&p).as_bytes())?;
    progress::write_plan(&output, &study_path, &study, args.job.shards)?;
    println!(
        "study {}: {} points in {} shards (array tasks 1-{}, {} CPU(s) each, {} min)\n  array script {}\n  merge script {}\n  logs in {}",
        study_path.display(),
        points,
        args.job.shards,
        args.job.shards,
        args.job.cpus_per_task,
        args.job.time_limit_min,
        array.display(),
        merge.display(),
        job_dir.join("logs").display()
    );
    if !args.job.submit {
        println!(
            "submit:\n  id=$(sbatch --parsable {})\n  sbatch --dependency=afterok:$id --kill-on-invalid-dep=yes {}\nwatch: ehl-bearing study status {}",
            shell_quote(&array.display().to_string()),
            shell_quote(&merge.display().to_string()),
            shell_quote(&output.display().to_string())
        );
        return Ok(());
    }
    submit(args, &output, &array, &merge)
}

/// `<prefix><file stem>` (`<prefix><fallback>` without one), every character Slurm does not
/// take in a job name replaced by `_`, at most 64 characters: the default job name of `study
/// sbatch` (`ehl-`) and `law-map sbatch` (`ehl-map-`).
pub(crate) fn default_job_name(prefix: &str, path: &Path, fallback: &str) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| fallback.into());
    format!("{prefix}{stem}")
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .take(64)
        .collect()
}

/// What one submission submitted.
struct Submitted {
    /// The array job, if one was submitted.
    array_id: Option<String>,
    /// Its tasks in Slurm's array syntax (empty without an array job).
    tasks: String,
    /// The merge job.
    merge_id: String,
}

/// `--submit`: submit the shards with points left and neither a live task (markers) nor a task
/// Slurm still holds, and the merge job after them; only the merge job when every point has its
/// file; an error when the shards with points left are all still running. The submission is
/// recorded in the plan.
fn submit(args: &SbatchArgs, output: &Path, array: &Path, merge: &Path) -> anyhow::Result<()> {
    let status = progress::read_status(output, args.stale_after_s)?;
    let live: Vec<String> = status
        .shards
        .iter()
        .filter(|s| s.state == "running")
        .map(|s| s.shard.to_string())
        .collect();
    if !live.is_empty() {
        println!(
            "  still running, not resubmitted: shard(s) {}",
            live.join(", ")
        );
    }
    let queued = still_queued(&args.job.sbatch, &status);
    let tasks: Vec<usize> = status
        .shards_to_run()
        .into_iter()
        .filter(|t| !queued.contains_key(t))
        .collect();
    let live: Vec<String> = live
        .into_iter()
        .chain(queued.keys().map(|t| format!("{t}/{}", args.job.shards)))
        .collect();
    if tasks.is_empty() && !live.is_empty() {
        anyhow::bail!(
            "nothing to submit: the shards with points left are still running ({}); watch them with `ehl-bearing study status {}`",
            live.join(", "),
            output.display()
        );
    }
    let s = submit_jobs(&args.job.sbatch, array, merge, &tasks, &queued)?;
    progress::record_submission(output, s.array_id.as_deref(), &s.tasks, &s.merge_id)?;
    match &s.array_id {
        Some(a) => println!(
            "submitted array job {a} (tasks {}) and merge job {} (runs after every task of {a} succeeded)",
            s.tasks, s.merge_id
        ),
        None => println!("submitted merge job {}", s.merge_id),
    }
    println!(
        "watch: ehl-bearing study status {}",
        shell_quote(&output.display().to_string())
    );
    Ok(())
}

/// Tasks of earlier submissions (recorded in `status`) that Slurm still holds (pending, held or
/// running): they are not submitted again, since a pending task has no marker. If Slurm cannot
/// be asked, a warning, and none.
fn still_queued(sbatch_cmd: &str, status: &progress::StudyStatus) -> Queued {
    let array_ids: Vec<String> = status
        .submissions
        .iter()
        .filter_map(|(a, _, _)| a.clone())
        .collect();
    let queued = match queued_tasks(sbatch_cmd, &array_ids) {
        Ok(q) => q,
        Err(e) => {
            eprintln!(
                "warning: could not ask Slurm which tasks are still queued ({e}); \
                 resubmitting from the progress markers alone"
            );
            Queued::new()
        }
    };
    if !queued.is_empty() {
        let list: Vec<String> = queued
            .iter()
            .map(|(t, (job, state))| format!("{t} ({job}, {state})"))
            .collect();
        println!(
            "  still queued in Slurm, not resubmitted: shard(s) {}",
            list.join(", ")
        );
    }
    queued
}

/// Submit the `array` script's `tasks` and the `merge` script after them (and after the
/// earlier arrays' tasks still `queued`); the merge script alone when there is no task.
fn submit_jobs(
    sbatch_cmd: &str,
    array: &Path,
    merge: &Path,
    tasks: &[usize],
    queued: &Queued,
) -> anyhow::Result<Submitted> {
    let merge_s = merge.display().to_string();
    if tasks.is_empty() {
        println!("  every point has its file: submitting the merge job only");
        let m = sbatch(sbatch_cmd, &["--parsable".into(), merge_s])?;
        return Ok(Submitted {
            array_id: None,
            tasks: String::new(),
            merge_id: m,
        });
    }
    let list = array_ranges(tasks);
    let a = sbatch(
        sbatch_cmd,
        &[
            "--parsable".into(),
            format!("--array={list}"),
            array.display().to_string(),
        ],
    )?;
    // The merge also waits for the earlier arrays' tasks still queued (whatever their end:
    // a missing point then fails the merge visibly).
    let earlier: std::collections::BTreeSet<&String> =
        queued.values().map(|(job, _)| job).collect();
    let earlier: String = earlier.iter().map(|j| format!(",afterany:{j}")).collect();
    let m = sbatch(
        sbatch_cmd,
        &[
            "--parsable".into(),
            format!("--dependency=afterok:{a}{earlier}"),
            "--kill-on-invalid-dep=yes".into(),
            merge_s,
        ],
    )?;
    Ok(Submitted {
        array_id: Some(a),
        tasks: list,
        merge_id: m,
    })
}
