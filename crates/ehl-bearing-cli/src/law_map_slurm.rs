//! `ehl-bearing law-map sbatch SPEC.toml -o DIR --map FILE`: a Slurm job-array script that
//! generates a law map's nodes (array task i runs `law-map generate --shard i/N` into the shared
//! folder DIR), the assemble job's script (`law-map assemble`, after every task succeeded), and
//! with `--submit` the submission of both. The node files are the progress record: a
//! resubmission submits only the shards with nodes left (a finished node is never computed
//! again), or the assemble job alone when every node is done.

use crate::slurm_cmd::{
    absolute, array_ranges, default_job_name, sbatch, script_header, shell_quote, JobArgs,
    JobOptions,
};
use anyhow::Context;
use ehl_bearing::io::FsStore;
use ehl_bearing::law_map::LawMapSpec;
use ehl_bearing::study::shards_with_nodes_left;
use std::path::{Path, PathBuf};

/// Arguments of `law-map sbatch`.
#[derive(clap::Args, Debug)]
pub struct LawMapSbatchArgs {
    /// Map spec (TOML), e.g. examples/law_map_seed_oil.toml.
    pub spec: PathBuf,
    /// Shared folder of the node files (on a file system every node sees); created if needed.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The map file the assemble job writes (.json: JSON text, .bin: the compact binary form);
    /// its folder must exist.
    #[arg(long)]
    pub map: PathBuf,
    /// The job-array options (as `study sbatch`). With --submit, tasks of an earlier submission
    /// still queued or running are not looked for: resubmit once they ended (a node computed
    /// twice is only time lost).
    #[command(flatten)]
    pub job: JobArgs,
}

/// Everything the two scripts depend on, validated and absolute.
struct MapJob {
    /// The spec file (absolute) and the spec it holds.
    spec_path: PathBuf,
    spec: LawMapSpec,
    output: PathBuf,
    map: PathBuf,
    job_dir: PathBuf,
    bin: PathBuf,
    shards: usize,
    cpus_per_task: usize,
    time_limit_min: u64,
    partition: Option<String>,
    job_name: String,
}

impl MapJob {
    fn options<'a>(&'a self, name: &'a str, cpus: usize, log: &'a Path) -> JobOptions<'a> {
        JobOptions {
            name,
            cpus,
            time_limit_min: self.time_limit_min,
            partition: self.partition.as_deref(),
            log,
        }
    }

    fn q(p: &Path) -> String {
        shell_quote(&p.display().to_string())
    }

    /// The job-array script: task i generates the nodes of shard i/N.
    fn array_script(&self) -> String {
        let log = self.job_dir.join("logs").join("%x-%A_%a.out");
        let mut s = script_header(&self.options(&self.job_name, self.cpus_per_task, &log));
        s += &format!("#SBATCH --array=1-{}\n", self.shards);
        s += &format!(
            "# Written by `ehl-bearing law-map sbatch` ({} {}): map spec {}, {} nodes in {n} shards
# (shard i computes the nodes k with k mod {n} = i - 1). Array task i writes only its own node files
# into the shared folder, each atomically; a resubmitted task skips the nodes already done. A task
# with a failed node exits non-zero (the node file holds the error; a rerun retries it). When every
# task succeeded, the assemble job (assemble.sbatch) writes the map file.
set -euo pipefail
: \"${{SLURM_ARRAY_TASK_ID:?submit this script with sbatch: it is a job array}}\"
export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"
echo \"ehl-bearing law-map shard ${{SLURM_ARRAY_TASK_ID}}/{n} on $(hostname) with $RAYON_NUM_THREADS thread(s)\"
exec {} law-map generate {} -o {} --shard \"${{SLURM_ARRAY_TASK_ID}}/{n}\" --threads \"$RAYON_NUM_THREADS\"
",
            env!("CARGO_PKG_NAME"),
            env!("CARGO_PKG_VERSION"),
            self.spec_path.display(),
            self.spec.node_count(),
            Self::q(&self.bin),
            Self::q(&self.spec_path),
            Self::q(&self.output),
            n = self.shards,
        );
        s
    }

    /// The assemble job's script (submitted with `--dependency=afterok:<array job>`).
    fn assemble_script(&self) -> String {
        let name = format!("{}-assemble", self.job_name);
        let log = self.job_dir.join("logs").join("%x-%j.out");
        let mut s = script_header(&self.options(&name, 1, &log));
        s += &format!(
            "# Written by `ehl-bearing law-map sbatch`: builds the map file {} from the node files in
# {}; fails, naming the first missing or failed node, unless every node is done.
set -euo pipefail
exec {} law-map assemble {} -o {} --map {}
",
            self.map.display(),
            self.output.display(),
            Self::q(&self.bin),
            Self::q(&self.spec_path),
            Self::q(&self.output),
            Self::q(&self.map),
        );
        s
    }
}

/// The map file as an absolute path (its folder must exist; the file need not).
fn absolute_map(map: &Path) -> anyhow::Result<PathBuf> {
    crate::law_map_cmd::binary_form(map)?;
    let name = map
        .file_name()
        .with_context(|| format!("--map {}: expected a file name", map.display()))?;
    let dir = match map.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let dir = absolute(&dir).map_err(|e| anyhow::anyhow!("--map: its folder: {e}"))?;
    anyhow::ensure!(
        dir.is_dir(),
        "--map {}: its folder is not a directory",
        map.display()
    );
    Ok(dir.join(name))
}

/// The job from the arguments: spec read and checked, folders created, paths absolute.
fn job(a: &LawMapSbatchArgs) -> anyhow::Result<MapJob> {
    let spec = crate::law_map_cmd::read_spec(&a.spec)?;
    a.job
        .validate(spec.node_count(), "the map's number of nodes")?;
    let bin = a.job.executable()?;
    let map = absolute_map(&a.map)?;
    let (output, job_dir) = a.job.folders(&a.output)?;
    let spec_path = absolute(&a.spec)?;
    Ok(MapJob {
        job_name: a
            .job
            .job_name
            .clone()
            .unwrap_or_else(|| default_job_name("ehl-map-", &spec_path, "map")),
        spec_path,
        spec,
        output,
        map,
        job_dir,
        bin,
        shards: a.job.shards,
        cpus_per_task: a.job.cpus_per_task,
        time_limit_min: a.job.time_limit_min,
        partition: a.job.partition.clone(),
    })
}

/// Runs `law-map sbatch`.
pub fn run(a: &LawMapSbatchArgs) -> anyhow::Result<()> {
    let j = job(a)?;
    let array = j.job_dir.join("law_map.sbatch");
    let assemble = j.job_dir.join("assemble.sbatch");
    crate::cli_support::write_atomic(&array, j.array_script().as_bytes())?;
    crate::cli_support::write_atomic(&assemble, j.assemble_script().as_bytes())?;
    println!(
        "law map {}: {} nodes in {} shards (array tasks 1-{}, {} CPU(s) each, {} min)\n  array script {}\n  assemble script {}\n  logs in {}",
        j.spec_path.display(),
        j.spec.node_count(),
        j.shards,
        j.shards,
        j.cpus_per_task,
        j.time_limit_min,
        array.display(),
        assemble.display(),
        j.job_dir.join("logs").display()
    );
    if !a.job.submit {
        println!(
            "submit:\n  id=$(sbatch --parsable {})\n  sbatch --dependency=afterok:$id --kill-on-invalid-dep=yes {}",
            MapJob::q(&array),
            MapJob::q(&assemble)
        );
        return Ok(());
    }
    let store = FsStore::open(&j.output)?;
    let left = shards_with_nodes_left(&j.spec, &store, j.shards)?;
    let assemble_s = assemble.display().to_string();
    if left.is_empty() {
        println!("  every node is done: submitting the assemble job only");
        let id = sbatch(&a.job.sbatch, &["--parsable".into(), assemble_s])?;
        println!("submitted assemble job {id}");
        return Ok(());
    }
    let tasks = array_ranges(&left);
    let array_id = sbatch(
        &a.job.sbatch,
        &[
            "--parsable".into(),
            format!("--array={tasks}"),
            array.display().to_string(),
        ],
    )?;
    let assemble_id = sbatch(
        &a.job.sbatch,
        &[
            "--parsable".into(),
            format!("--dependency=afterok:{array_id}"),
            "--kill-on-invalid-dep=yes".into(),
            assemble_s,
        ],
    )?;
    println!(
        "submitted array job {array_id} (tasks {tasks}) and assemble job {assemble_id} (runs after every task of {array_id} succeeded)"
    );
    Ok(())
}
