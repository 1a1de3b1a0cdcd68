//! `ehl-bearing law-map generate SPEC.toml -o DIR [--shard i/N]`, `law-map assemble SPEC.toml -o
//! DIR --map FILE`, `law-map convert IN OUT [--sparse-level Q]` (JSON text ⇄ the compact binary
//! form; a tensor map's sparse subset), `law-map info
//! [FILE…]` (what map files or the embedded maps hold), `law-map sbatch
//! SPEC.toml -o DIR --map FILE` (a Slurm job array of the
//! shards and the assemble job: `law_map_slurm`) and `law-map check FILE --points N`: the map of the dimensionless quasi-static
//! law over the groups (`ehl_bearing::law_map`, docs/law_map.md). The nodes are point files in
//! DIR/points (atomic, resumable, shardable as a study's); `assemble` writes the map file from
//! them; `check` compares the map with direct characterizations at random held-out points.

use anyhow::Context;
use ehl_bearing::io::FsStore;
use ehl_bearing::law_map::{LawMap, LawMapSpec};
use ehl_bearing::study::{
    assemble_map, generate_map, held_out_compare, held_out_references, under_resolved_nodes,
    HeldOutPoint, NodeRecord, PointStore, Shard,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Arguments of `law-map`.
#[derive(clap::Args)]
pub struct LawMapArgs {
    /// What to do.
    #[command(subcommand)]
    pub command: LawMapCommand,
}

/// Subcommands of `law-map`.
#[derive(clap::Subcommand)]
pub enum LawMapCommand {
    /// Characterize the map's nodes (those of one shard with --shard) into DIR/points.
    Generate {
        /// Map spec (TOML), e.g. examples/law_map_seed_oil.toml.
        spec: PathBuf,
        /// Output folder (created if needed; an existing one of the same map is resumed).
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// Run only shard i of N (1-based): the nodes whose index k has k mod N = i − 1.
        #[arg(long)]
        shard: Option<Shard>,
        /// Recompute node files of another map instead of refusing.
        #[arg(long)]
        overwrite: bool,
        /// Threads (default: RAYON_NUM_THREADS or the number of cores).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Build the map file from the node files (every node must be done).
    Assemble {
        /// Map spec (TOML).
        spec: PathBuf,
        /// The folder the nodes were generated into.
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// The map file to write: JSON text if it ends in .json, the compact binary form if in
        /// .bin (docs/law_map.md §5).
        #[arg(long)]
        map: PathBuf,
    },
    /// Print what map files hold (spec, nodes, generation cost, fit quality): the given files,
    /// or without any the maps embedded in the library, in the order a query tries them.
    Info {
        /// Map files (JSON text or the binary form); none: the embedded maps.
        maps: Vec<PathBuf>,
        /// One JSON array of the maps' summaries on stdout instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a map file in the other form: JSON text (.json) or the compact binary form (.bin),
    /// by the output's extension; the numbers are the same, bit for bit. With --sparse-level,
    /// the sparse map of that level on a tensor map's nodes (a subset of them, e.g. to measure
    /// how a sparse map of the same axes would do: docs/law_map.md §5, "Sparse maps").
    Convert {
        /// The map file to read (either form).
        input: PathBuf,
        /// The map file to write (.json or .bin).
        output: PathBuf,
        /// Keep only the nodes of the sparse map of this level (1 to the sum of the axes'
        /// depths m, nodes = 2^m + 1 on every axis).
        #[arg(long)]
        sparse_level: Option<u32>,
    },
    /// Write (and with --submit, submit) a Slurm job array that generates the nodes, one shard
    /// per task, and the dependent job that assembles the map file.
    Sbatch(crate::law_map_slurm::LawMapSbatchArgs),
    /// Compare the map with direct characterizations at random points inside its envelope
    /// (with --references DIR, kept there and reused; given a spec instead of a map, only those
    /// references are computed, e.g. beside the map's generation).
    Check(CheckArgs),
}

/// Arguments of `law-map check`.
#[derive(clap::Args)]
pub struct CheckArgs {
    /// Map file (JSON text or the binary form), or a map spec (.toml): then only the direct
    /// characterizations are computed, into --references, for a later check of the map.
    map: PathBuf,
    /// Number of random points.
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// Seed of the random points.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write one CSV row per point here.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Threads (default: RAYON_NUM_THREADS or the number of cores).
    #[arg(long)]
    threads: Option<usize>,
    /// The direct characterizations' solver tolerances (tol_residual, tol_force, tol_film)
    /// times this factor, in (0, 1]; below 1 their cycle limit grows to 40·(1 + 2·log10(1/F))
    /// (1: the map's own settings, its spec's tolerance_factor included; below 1, those times
    /// F).
    #[arg(long, default_value_t = 1.0)]
    tolerance_factor: f64,
    /// Folder of the direct characterizations (one file per point, written as each is done;
    /// created if needed): a rerun, or the check after a run on the map's spec, computes only
    /// the points not there yet.
    #[arg(long)]
    references: Option<PathBuf>,
}

fn pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        anyhow::ensure!(t >= 1, "--threads = {t}: expected at least 1");
        b = b.num_threads(t);
    }
    Ok(b.build()?)
}

/// The map spec file `p`, read and validated (errors name the file).
pub(crate) fn read_spec(p: &Path) -> anyhow::Result<LawMapSpec> {
    let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    LawMapSpec::from_toml(&text).with_context(|| format!("in {}", p.display()))
}

/// Quantiles of `v` (sorted copy): (median, 95 %, max).
fn quantiles(v: &[f64]) -> (f64, f64, f64) {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let at = |q: f64| s[((s.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.95), s[s.len() - 1])
}

/// Runs `law-map`.
pub fn run(a: &LawMapArgs) -> anyhow::Result<()> {
    match &a.command {
        LawMapCommand::Generate {
            spec,
            output,
            shard,
            overwrite,
            threads,
        } => generate(
            spec,
            output,
            shard.unwrap_or(Shard::ALL),
            *overwrite,
            *threads,
        ),
        LawMapCommand::Assemble { spec, output, map } => assemble(spec, output, map),
        LawMapCommand::Convert {
            input,
            output,
            sparse_level,
        } => convert(input, output, *sparse_level),
        LawMapCommand::Info { maps, json } => info(maps, *json),
        LawMapCommand::Sbatch(args) => crate::law_map_slurm::run(args),
        LawMapCommand::Check(args) => check(args),
    }
}

/// `law-map generate`: characterize the nodes of `shard` of the map `spec` into `output`,
/// logging each node (every node on a terminal, the failed ones otherwise); an error if a node
/// failed.
fn generate(
    spec: &Path,
    output: &Path,
    shard: Shard,
    overwrite: bool,
    threads: Option<usize>,
) -> anyhow::Result<()> {
    let s = read_spec(spec)?;
    warn_under_resolved(&s)?;
    let store = FsStore::create(output)?;
    let total = s.node_count().div_ceil(shard.count);
    let done = AtomicUsize::new(0);
    let t0 = Instant::now();
    let quiet = !std::io::IsTerminal::is_terminal(&std::io::stderr());
    let on_node = |r: &NodeRecord| {
        let k = done.fetch_add(1, Ordering::Relaxed) + 1;
        if !quiet || r.law.is_none() {
            eprintln!(
                "node {} ({k} of ≤ {total}) M = {:.4} L = {:.4} Ry/Rx = {:.4}{}: {} ({:.2} s, {:.2} CPU s)",
                r.index,
                r.groups.m,
                r.groups.l,
                r.groups.ry_over_rx,
                r.psi_h.map_or(String::new(), |p| format!(" Ψ_H = {p:.4}")),
                r.error.as_deref().unwrap_or("ok"),
                r.seconds,
                r.cost_seconds()
            );
        }
    };
    let g = pool(threads)?.install(|| generate_map(&s, &store, shard, overwrite, &on_node))?;
    println!(
        "shard {shard}: {} nodes, {} computed ({} failed), {} already done; {:.1} CPU s, {:.1} s wall",
        g.nodes,
        g.computed,
        g.failed,
        g.loaded,
        g.cpu_seconds,
        t0.elapsed().as_secs_f64()
    );
    if g.failed > 0 {
        anyhow::bail!(
            "{} node(s) failed (their files hold the error; a rerun retries them)",
            g.failed
        );
    }
    Ok(())
}

/// Warns (stderr) if the spec's grid does not resolve the film of some of its nodes
/// (`study::under_resolved_nodes`): such nodes are slow and their films wrong (docs/ehl.md §5.9).
fn warn_under_resolved(s: &LawMapSpec) -> anyhow::Result<()> {
    let thin = under_resolved_nodes(s)?;
    if let Some(&(i, r)) = thin.first() {
        let g = s.node_groups(i);
        eprintln!(
            "warning: the grid ({0}²) does not resolve the film of {1} of {2} nodes (NVM's central film \
             below {3} ΔX²; least {r:.2} at node {i}, M = {4:.4} L = {5:.4} Ry/Rx = {6:.4}): such nodes \
             are slow and their films wrong (docs/ehl.md §5.9); a finer grid or a smaller box avoids them",
            s.grid,
            thin.len(),
            s.node_count(),
            ehl_bearing::ehl::FILM_RESOLUTION_MIN,
            g.m,
            g.l,
            g.ry_over_rx
        );
    }
    Ok(())
}

/// `law-map assemble`: build the map file `map` from the node files in `output`.
fn assemble(spec: &Path, output: &Path, map: &Path) -> anyhow::Result<()> {
    let s = read_spec(spec)?;
    binary_form(map)?;
    let store = FsStore::open(output)?;
    let m = assemble_map(&s, &store)?;
    let text = map_file_bytes(&m, map)?;
    ehl_bearing::io::write_atomic(map, &text)?;
    println!("{} ({} bytes): {}", map.display(), text.len(), m.summary());
    Ok(())
}

/// The map file `p` (either form), read and checked (errors name the file).
fn read_map(p: &Path) -> anyhow::Result<LawMap> {
    let bytes = std::fs::read(p).with_context(|| format!("reading {}", p.display()))?;
    LawMap::parse(&bytes).with_context(|| format!("in {}", p.display()))
}

/// Whether the map file `p` is to be written in the binary form (.bin) rather than as JSON text
/// (.json); any other extension an error naming both.
pub(crate) fn binary_form(p: &Path) -> anyhow::Result<bool> {
    match p.extension().and_then(|e| e.to_str()) {
        Some("json") => Ok(false),
        Some("bin") => Ok(true),
        other => anyhow::bail!(
            "{}: the extension {:?} names no map file form: expected .json (JSON text) or .bin \
             (the compact binary form)",
            p.display(),
            other.unwrap_or("")
        ),
    }
}

/// The map file's bytes in the form `p`'s extension names ([`binary_form`]).
fn map_file_bytes(m: &LawMap, p: &Path) -> anyhow::Result<Vec<u8>> {
    Ok(if binary_form(p)? {
        m.to_binary()
    } else {
        m.to_json().into_bytes()
    })
}

/// `law-map convert`: write the map file `input` (or its sparse subset of level
/// `sparse_level`) in the form of `output`'s extension.
fn convert(input: &Path, output: &Path, sparse_level: Option<u32>) -> anyhow::Result<()> {
    let mut m = read_map(input)?;
    if let Some(q) = sparse_level {
        m = m
            .sparse_subset(q)
            .with_context(|| format!("{}: its sparse map of level {q}", input.display()))?;
    }
    let bytes = map_file_bytes(&m, output)?;
    ehl_bearing::io::write_atomic(output, &bytes)?;
    println!(
        "{}: {} nodes, {} bytes",
        output.display(),
        m.laws.len(),
        bytes.len()
    );
    Ok(())
}

/// `law-map info`: the summaries of the map files `maps` (or of the embedded maps), as text or
/// as one JSON array.
fn info(maps: &[PathBuf], json: bool) -> anyhow::Result<()> {
    let (names, all): (Vec<String>, Vec<_>) = if maps.is_empty() {
        let n = LawMap::embedded_names().len();
        let names = LawMap::embedded_names()
            .enumerate()
            .map(|(i, name)| format!("embedded map {} of {n} ({name})", i + 1));
        (names.collect(), LawMap::embedded_summaries())
    } else {
        let s = maps.iter().map(|p| read_map(p).map(|m| m.summary()));
        (
            maps.iter().map(|p| p.display().to_string()).collect(),
            s.collect::<Result<_, _>>()?,
        )
    };
    if json {
        println!("{}", serde_json::to_string_pretty(&all)?);
    } else {
        for (name, m) in names.iter().zip(&all) {
            println!("{name}: {m}");
        }
    }
    Ok(())
}

/// `law-map check`: compare the map file `a.map` with direct characterizations at `a.points`
/// random points (seed `a.seed`), their tolerances times `a.tolerance_factor`, kept in
/// `a.references` if given; write one CSV row per point to `a.csv` if given, and print the error
/// quantiles. Given a spec (.toml) instead of a map, compute only the references.
fn check(a: &CheckArgs) -> anyhow::Result<()> {
    let spec_only = a.map.extension().and_then(|e| e.to_str()) == Some("toml");
    anyhow::ensure!(
        !(spec_only && a.csv.is_some()),
        "--csv: {} is a spec, not a map: no map to compare, so no CSV (give the map file)",
        a.map.display()
    );
    let map = if spec_only {
        None
    } else {
        Some(read_map(&a.map)?)
    };
    let spec = match &map {
        Some(m) => m.spec.clone(),
        None => read_spec(&a.map)?,
    };
    let store = match &a.references {
        Some(dir) => Some(FsStore::create(dir)?),
        None if spec_only => anyhow::bail!(
            "{}: a spec, not a map: give --references DIR to compute the direct characterizations \
             into (a later `law-map check MAP --references DIR` compares the map with them)",
            a.map.display()
        ),
        None => None,
    };
    let t0 = Instant::now();
    let quiet = !std::io::IsTerminal::is_terminal(&std::io::stderr());
    let on_point = |r: &NodeRecord| {
        if !quiet || r.law.is_none() {
            eprintln!(
                "held-out point {} M = {:.4} L = {:.4} Ry/Rx = {:.4}: {} ({:.2} s, {:.2} CPU s)",
                r.index,
                r.groups.m,
                r.groups.l,
                r.groups.ry_over_rx,
                r.error.as_deref().unwrap_or("ok"),
                r.seconds,
                r.cost_seconds()
            )
        }
    };
    let store_ref = store.as_ref().map(|s| s as &dyn PointStore);
    let refs = pool(a.threads)?
        .install(|| {
            held_out_references(
                &spec,
                a.points,
                a.seed,
                a.tolerance_factor,
                store_ref,
                &on_point,
            )
        })
        .context("--tolerance-factor, --references")?;
    let failed = refs.records.iter().filter(|r| r.law.is_none()).count();
    let read = match &a.references {
        Some(dir) => format!(", {} read from {}", a.points - refs.computed, dir.display()),
        None => String::new(),
    };
    println!(
        "{} direct characterizations: {} computed{read}, {failed} failed ({:.1} s wall)",
        a.points,
        refs.computed,
        t0.elapsed().as_secs_f64()
    );
    let Some(m) = map else {
        return Ok(());
    };
    let r = held_out_compare(&m, &refs.records);
    anyhow::ensure!(!r.is_empty(), "no held-out point could be characterized");
    if let Some(p) = &a.csv {
        write_check_csv(p, &r)?;
    }
    println!("{} of {} held-out points characterized", r.len(), a.points);
    print_check_summary(&r);
    Ok(())
}

/// One CSV row per held-out point: its groups, the map's errors against the direct law and the
/// map's own error estimates, the direct law (dimensionless), and the point's rheology groups;
/// for a harmonic map also its mass group Ψ_H, the relative ĉ error, the map's estimate of it
/// (relative) and the direct ĉ.
fn write_check_csv(p: &Path, r: &[HeldOutPoint]) -> anyhow::Result<()> {
    let harmonic = r.iter().any(|h| h.psi_h.is_some());
    let mut out = String::from(
        "m,l,ry_over_rx,force_error,d_error,delta_f_error,delta_f_error_over_load,\
         estimate_force,estimate_d,estimate_delta_f_over_load,k_hat,d,delta_f_hat,\
         alpha_p0,ln_eta0_ratio,direct_converged",
    );
    out.push_str(if harmonic {
        ",psi_h,c_hat_error,estimate_c_hat,c_hat\n"
    } else {
        "\n"
    });
    // The rheology groups of the point (empty where the map's models do not use them).
    let cell = |v: Option<f64>| v.map_or(String::new(), |x| x.to_string());
    for h in r {
        out.push_str(&format!(
            "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{},{},{},{}",
            h.groups.m,
            h.groups.l,
            h.groups.ry_over_rx,
            h.force_error,
            h.d_error,
            h.delta_f_error,
            h.delta_f_error_hat,
            h.map.force_error,
            h.map.error.d,
            h.map.error.delta_f_hat,
            h.direct.k_hat,
            h.direct.d,
            h.direct.delta_f_hat,
            cell(h.groups.alpha_p0),
            cell(h.groups.ln_eta0_ratio),
            h.direct_converged
        ));
        if harmonic {
            let c_hat = h.direct.c_hat.unwrap_or(f64::NAN);
            out.push_str(&format!(
                ",{},{:e},{:e},{}",
                cell(h.psi_h),
                h.c_error.unwrap_or(f64::NAN),
                h.map.error.c_hat.unwrap_or(f64::NAN) / c_hat.abs(),
                c_hat
            ));
        }
        out.push('\n');
    }
    ehl_bearing::io::write_atomic(p, out.as_bytes())?;
    Ok(())
}

/// Median, 95 % quantile and maximum of each error of the held-out points, and how many points
/// the map's force-error estimate falls below the actual error at.
fn print_check_summary(r: &[HeldOutPoint]) {
    println!("quantity: median / 95 % / max");
    let rows: [(&str, Vec<f64>); 7] = [
        (
            "force at δ0, relative",
            r.iter().map(|h| h.force_error).collect(),
        ),
        ("d, absolute", r.iter().map(|h| h.d_error).collect()),
        ("ΔF, relative", r.iter().map(|h| h.delta_f_error).collect()),
        (
            "ΔF over w0",
            r.iter().map(|h| h.delta_f_error_hat).collect(),
        ),
        (
            "estimate: force over w0",
            r.iter().map(|h| h.map.force_error).collect(),
        ),
        ("estimate: d", r.iter().map(|h| h.map.error.d).collect()),
        (
            "estimate / actual, force",
            r.iter()
                .map(|h| h.map.force_error / h.force_error.max(1e-300))
                .collect(),
        ),
    ];
    for (name, v) in rows {
        let (a, b, c) = quantiles(&v);
        println!("  {name}: {a:.2e} / {b:.2e} / {c:.2e}");
    }
    if r.iter().any(|h| h.c_error.is_some()) {
        let c_rows: [(&str, Vec<f64>); 2] = [
            ("ĉ, relative", r.iter().filter_map(|h| h.c_error).collect()),
            (
                "estimate: ĉ, relative",
                r.iter()
                    .filter_map(|h| Some(h.map.error.c_hat? / h.direct.c_hat?.abs()))
                    .collect(),
            ),
        ];
        for (name, v) in c_rows {
            let (a, b, c) = quantiles(&v);
            println!("  {name}: {a:.2e} / {b:.2e} / {c:.2e}");
        }
    }
    let under = r
        .iter()
        .filter(|h| h.map.force_error < h.force_error)
        .count();
    println!("  points where the estimate is below the actual force error: {under}");
    println!(
        "  direct characterizations with a steady solution short of its tolerances: {}",
        r.iter().filter(|h| !h.direct_converged).count()
    );
}
