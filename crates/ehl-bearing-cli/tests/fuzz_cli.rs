//! Fuzzing of command lines (docs/robustness.md): generated argument lists, each run
//! as the real binary (clap parsing, validation, the plausibility checks and a bounded run), must
//! end with exit status 0 or 1 and, on failure, a message on stderr: never a panic (status 101),
//! a signal, or a hang. Commands that compute get a `--time-limit` (unless the list already has
//! one), so a run that outlives its budget by `GRACE_S` is reported as a hang with its arguments.
//!
//! Same seeded SplitMix64 scheme as `crates/ehl-bearing/tests/fuzz_inputs.rs` (each list
//! reproducible from its index). Default: a fixed-seed slice of 60 lists. More:
//!
//! ```text
//! FUZZ_CLI_CASES=3000 cargo test -p ehl-bearing-cli --test fuzz_cli -- --ignored --nocapture
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Seconds a run may take beyond its time limit before it counts as a hang.
const GRACE_S: f64 = 60.0;

#[path = "../../ehl-bearing/tests/splitmix/mod.rs"]
mod splitmix;
use splitmix::Rng;

const NUMBERS: [&str; 26] = [
    "100000",
    "1e300",
    "1e-300",
    "3000,1e6",
    "0",
    "-1",
    "nan",
    "inf",
    "-inf",
    "1e308",
    "1e-308",
    "abc",
    "",
    "17",
    "33",
    "1025",
    "2049",
    "0.5",
    "1e-3",
    "3",
    "18446744073709551616",
    "1/0",
    "0/3",
    "2/3",
    "3/2",
    "--json",
];

const FLAGS: [&str; 38] = [
    "--speeds",
    "--points-in-flight",
    "--json",
    "--method",
    "-o",
    "--threads",
    "--tolerance",
    "--max-iterations",
    "--cache-tolerance",
    "--min-load-fraction",
    "--load-reuse-tolerance",
    "--no-load-prediction",
    "--time-limit",
    "--grid",
    "--inlet",
    "--half-width",
    "--max-cycles",
    "--fields",
    "--moes-m",
    "--moes-l",
    "--ry-over-rx",
    "--viscosity",
    "--density",
    "--amplitude",
    "--points",
    "--frequency-fraction",
    "--frequency-rad-s",
    "--settling-periods",
    "--recorded-periods",
    "--steps-per-period",
    "--mass-kg",
    "--no-damping-term",
    "--shard",
    "--overwrite",
    "--bogus",
    "-x",
    "--speeds-rpm",
    "--",
];

/// Does `flag` take a value?
fn takes_value(flag: &str) -> bool {
    !matches!(
        flag,
        "--json"
            | "--no-load-prediction"
            | "--no-damping-term"
            | "--overwrite"
            | "--bogus"
            | "-x"
            | "--"
    )
}

/// The argument list `index`; the second value is the time limit it runs under (None: a
/// command that does not compute long).
fn generate(seed: u64, index: u64, files: &Files) -> (Vec<String>, Option<f64>) {
    let mut r = Rng::new(seed, index);
    let command = *r.pick(&[
        "equilibrium",
        "characterize",
        "study",
        "ehl",
        "contact",
        "coefficients",
        "merge",
        "bogus",
    ]);
    let mut args: Vec<String> = match command {
        "merge" => vec!["study".into(), "merge".into()],
        c => vec![c.into()],
    };
    let file = match (command, r.below(4)) {
        (_, 0) => r.pick(&files.wild).clone(),
        ("equilibrium" | "characterize" | "coefficients", _) => files.case.clone(),
        ("study" | "merge", _) => files.study.clone(),
        ("ehl" | "contact", _) => files.contact.clone(),
        _ => files.case.clone(),
    };
    if command != "ehl" || r.below(3) > 0 {
        args.push(file.display().to_string());
    }
    for _ in 0..r.below(5) {
        let f = *r.pick(&FLAGS);
        args.push(f.into());
        if takes_value(f) {
            let v = match f {
                "-o" | "--fields" => files.out_dirs[r.below(files.out_dirs.len())]
                    .display()
                    .to_string(),
                "--method" => r
                    .pick(&["hertz", "quasi-static", "harmonic", "synthetic", "x", ""])
                    .to_string(),
                "--viscosity" => r.pick(&["roelands", "barus", "x"]).to_string(),
                "--density" => r
                    .pick(&["dowson-higginson", "incompressible", "x"])
                    .to_string(),
                _ => r.pick(&NUMBERS).to_string(),
            };
            args.push(v);
        }
    }
    let mut limit = None;
    if matches!(command, "characterize" | "study" | "ehl" | "contact") {
        match args.iter().position(|a| a == "--time-limit") {
            Some(i) => limit = args.get(i + 1).and_then(|v| v.parse::<f64>().ok()),
            None => {
                args.push("--time-limit".into());
                args.push("2".into());
                limit = Some(2.0);
            }
        }
        if command == "study" && !args.iter().any(|a| a == "-o") {
            args.push("-o".into());
            args.push(files.out_dirs[0].display().to_string());
        }
        // A study gets a time limit per point: run its last point only.
        if command == "study" && !args.iter().any(|a| a == "--shard") {
            args.push("--shard".into());
            args.push("12/12".into());
        }
    }
    if command == "coefficients" && !args.iter().any(|a| a == "--speeds-rpm") {
        // Coefficients have no time limit: give them an unusable output folder, refused first.
        args.push("-o".into());
        args.push(files.case.display().to_string());
    }
    (args, limit)
}

struct Files {
    case: PathBuf,
    study: PathBuf,
    contact: PathBuf,
    wild: Vec<PathBuf>,
    out_dirs: Vec<PathBuf>,
}

fn files(tmp: &Path) -> Files {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let bad = tmp.join("bad.toml");
    std::fs::write(&bad, "[bearing]\nball_count = nan\n").expect("write");
    let bytes = tmp.join("bytes.toml");
    std::fs::write(&bytes, [0u8, 159, 146, 150, b'[', b'\n']).expect("write");
    let heavy = tmp.join("heavy.toml");
    let text = std::fs::read_to_string(ex.join("7006.toml")).expect("example");
    std::fs::write(
        &heavy,
        text.replace("force_axial_n = 1000.0", "force_axial_n = 1e5"),
    )
    .expect("write");
    let file_out = tmp.join("a_file");
    std::fs::write(&file_out, "x").expect("write");
    Files {
        case: ex.join("7006.toml"),
        study: ex.join("study_7006.toml"),
        contact: ex.join("contact_7006_inner.toml"),
        wild: vec![
            bad,
            bytes,
            heavy,
            tmp.join("missing.toml"),
            tmp.to_path_buf(),
            PathBuf::from("/dev/null"),
            PathBuf::from("/dev/zero"),
            ex.join("study_7006.toml"),
        ],
        out_dirs: vec![tmp.join("out"), file_out, PathBuf::from("/proc/nope")],
    }
}

/// Run the binary on `args`; Err on a panic, a signal, a hang or a failure without a message.
fn run(args: &[String], limit: Option<f64>, dir: &Path) -> Result<i32, String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ehl-bearing"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    let budget = limit.filter(|l| l.is_finite() && *l > 0.0).unwrap_or(0.0) + GRACE_S;
    let t0 = Instant::now();
    let mut stderr = child.stderr.take().expect("stderr");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut stderr, &mut s);
        s
    });
    let status = loop {
        if let Some(s) = child.try_wait().map_err(|e| e.to_string())? {
            break s;
        }
        if t0.elapsed().as_secs_f64() > budget {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("hang: more than {budget} s"));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let err = reader.join().unwrap_or_default();
    match status.code() {
        Some(0) => Ok(0),
        Some(c @ (1 | 2)) if !err.trim().is_empty() => Ok(c),
        Some(c) => Err(format!("exit status {c}, stderr: {err}")),
        None => Err(format!("killed by a signal ({status:?}), stderr: {err}")),
    }
}

fn fuzz(seed: u64, cases: u64) -> BTreeMap<String, usize> {
    let tmp = tempfile::tempdir().expect("tempdir");
    let f = files(tmp.path());
    let mut counts = BTreeMap::new();
    let mut findings = Vec::new();
    let t0 = Instant::now();
    for i in 0..cases {
        let (args, limit) = generate(seed, i, &f);
        let key = match run(&args, limit, tmp.path()) {
            Ok(0) => format!("{} ok", args[0]),
            Ok(c) => format!("{} error (status {c})", args[0]),
            Err(e) => {
                findings.push(format!("list {i}: {args:?}: {e}"));
                format!("{} FINDING", args[0])
            }
        };
        *counts.entry(key).or_insert(0) += 1;
    }
    println!(
        "fuzz_cli: seed {seed}, {cases} argument lists in {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    for (k, n) in &counts {
        println!("  {k}: {n}");
    }
    assert!(findings.is_empty(), "findings:\n{}", findings.join("\n"));
    counts
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// CI's slice: fixed seed, 60 argument lists.
#[test]
fn fuzz_cli_slice() {
    let counts = fuzz(15, 60);
    let errors: usize = counts
        .iter()
        .filter(|(k, _)| k.contains("error"))
        .map(|(_, n)| n)
        .sum();
    assert!(errors > 20, "{counts:?}");
}

/// More argument lists: `FUZZ_CLI_CASES=3000 cargo test -p ehl-bearing-cli --test fuzz_cli --
/// --ignored --nocapture`.
#[test]
#[ignore]
fn fuzz_cli_many() {
    fuzz(env_u64("FUZZ_SEED", 15), env_u64("FUZZ_CLI_CASES", 3000));
}

// ---------------------------------------------------------------------------------------------
// Faults planted in a study's output folder
// ---------------------------------------------------------------------------------------------

/// What a planted fault replaces a file of the output folder with.
const FAULTS: [&str; 10] = [
    "link to /dev/zero",
    "FIFO",
    "folder",
    "huge (64 MiB, sparse)",
    "truncated",
    "random bytes",
    "empty",
    "dangling link",
    "another point's file",
    "removed",
];

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for e in std::fs::read_dir(from).expect("read_dir") {
        let e = e.expect("entry");
        let target = to.join(e.file_name());
        if e.file_type().expect("type").is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).expect("copy");
        }
    }
}

/// Replace `path` (a file of the folder) by fault `kind`.
fn plant(path: &Path, kind: &str, other: &Path, r: &mut Rng) {
    // Only regular files are read (an earlier fault may have made this one a FIFO).
    let text = match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_file() && m.len() < 1 << 20 => std::fs::read(path).unwrap_or_default(),
        _ => Vec::new(),
    };
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_dir_all(path);
    match kind {
        "link to /dev/zero" => std::os::unix::fs::symlink("/dev/zero", path).expect("symlink"),
        "FIFO" => {
            let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).expect("path");
            // SAFETY: a valid NUL-terminated path; mkfifo only creates a file system node.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0, "mkfifo");
        }
        "folder" => std::fs::create_dir(path).expect("mkdir"),
        "huge (64 MiB, sparse)" => std::fs::File::create(path)
            .and_then(|f| f.set_len(64 << 20))
            .expect("sparse file"),
        "truncated" => std::fs::write(path, &text[..r.below(text.len().max(1))]).expect("write"),
        "random bytes" => {
            let n = r.below(400);
            let bytes: Vec<u8> = (0..n).map(|_| r.below(256) as u8).collect();
            std::fs::write(path, bytes).expect("write")
        }
        "empty" => std::fs::write(path, "").expect("write"),
        "dangling link" => std::os::unix::fs::symlink("/nonexistent/x.json", path).expect("link"),
        "another point's file" => std::fs::copy(other, path).map(|_| ()).expect("copy"),
        _ => {} // removed
    }
}

/// One planted-fault case: the folder, the command and its expected output (the reference
/// results.csv when a `study` or `study merge` run ends with status 0).
fn folder_case(
    seed: u64,
    index: u64,
    study: &Path,
    bases: &[(PathBuf, bool)],
    work: &Path,
) -> (Vec<String>, String) {
    let mut r = Rng::new(seed, index);
    let (base, sharded) = r.pick(bases).clone();
    let dir = work.join(format!("case{index}"));
    copy_dir(&base, &dir);
    let points: Vec<PathBuf> = std::fs::read_dir(dir.join("points"))
        .expect("points")
        .map(|e| e.expect("entry").path())
        .collect();
    let mut targets: Vec<PathBuf> = points.clone();
    if sharded {
        for m in ["plan.json", "shard-1of2.json", "running"] {
            targets.push(dir.join(".progress").join(m));
        }
    } else {
        for f in ["results.csv", "trends.json", "points.csv"] {
            targets.push(dir.join(f));
        }
    }
    let mut planted = Vec::new();
    for _ in 0..1 + r.below(3) {
        let t = r.pick(&targets).clone();
        let kind = *r.pick(&FAULTS);
        // Another point's file from the untouched base folder (a planted FIFO would block).
        let other = base
            .join("points")
            .join(r.pick(&points).file_name().expect("name"));
        plant(&t, kind, &other, &mut r);
        planted.push(format!(
            "{} → {kind}",
            t.strip_prefix(&dir).unwrap_or(&t).display()
        ));
    }
    let d = dir.display().to_string();
    let s = study.display().to_string();
    let args: Vec<&str> = match r.below(5) {
        0 | 1 => vec![
            "study",
            &s,
            "--method",
            "hertz",
            "-o",
            &d,
            "--time-limit",
            "20",
        ],
        2 => vec!["study", "status", &d],
        3 => vec!["study", "status", &d, "--json"],
        _ => vec!["study", "merge", &s, "--method", "hertz", "-o", &d],
    };
    (
        args.into_iter().map(String::from).collect(),
        planted.join(", "),
    )
}

/// Faults planted in finished and half-finished (one shard of two) study folders: point files,
/// progress markers and outputs replaced by links to /dev/zero, FIFOs, folders, huge sparse
/// files, truncated or random contents, empty files, dangling links, another point's file, or
/// removed; then `study` (resume), `study status [--json]` or `study merge`. Every run ends with
/// status 0, or 1 with a message, within 60 s; a run with status 0 that wrote results.csv wrote
/// the undisturbed run's bytes.
fn fuzz_folders(seed: u64, cases: u64) -> BTreeMap<String, usize> {
    let tmp = tempfile::tempdir().expect("tempdir");
    let study = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/study_7006.toml");
    let bin = env!("CARGO_BIN_EXE_ehl-bearing");
    let s = study.display().to_string();
    let clean = tmp.path().join("clean");
    let half = tmp.path().join("half");
    for (dir, shard) in [(&clean, None), (&half, Some("1/2"))] {
        let mut c = Command::new(bin);
        c.args(["study", &s, "--method", "hertz", "-o"])
            .arg(dir)
            .current_dir(tmp.path());
        if let Some(sh) = shard {
            c.args(["--shard", sh]);
        }
        let out = c.output().expect("run");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let reference = std::fs::read(clean.join("results.csv")).expect("results");
    let bases = vec![(clean, false), (half, true)];
    let mut counts = BTreeMap::new();
    let mut findings = Vec::new();
    let t0 = Instant::now();
    for i in 0..cases {
        let (args, planted) = folder_case(seed, i, &study, &bases, tmp.path());
        let what = if args[1] == "status" || args[1] == "merge" {
            format!("study {}", args[1])
        } else {
            "study (resume)".into()
        };
        let key = match run(&args, Some(60.0), tmp.path()) {
            Ok(0) => {
                let dir =
                    Path::new(&args[args.iter().position(|a| a == "-o").map_or(2, |p| p + 1)]);
                if args[1] != "status"
                    && std::fs::read(dir.join("results.csv")).ok() != Some(reference.clone())
                {
                    findings.push(format!(
                        "case {i} ({planted}): {args:?}: status 0, results.csv differs"
                    ));
                }
                format!("{what} ok")
            }
            Ok(c) => format!("{what} error (status {c})"),
            Err(e) => {
                findings.push(format!("case {i} ({planted}): {args:?}: {e}"));
                format!("{what} FINDING")
            }
        };
        *counts.entry(key).or_insert(0) += 1;
    }
    println!(
        "fuzz_folders: seed {seed}, {cases} folders in {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    for (k, n) in &counts {
        println!("  {k}: {n}");
    }
    assert!(findings.is_empty(), "findings:\n{}", findings.join("\n"));
    counts
}

/// CI's slice: fixed seed, 24 folders.
#[test]
fn fuzz_folders_slice() {
    let counts = fuzz_folders(15, 24);
    assert!(counts.keys().any(|k| k.contains("error")), "{counts:?}");
}

/// More folders: `FUZZ_FOLDER_CASES=1000 cargo test -p ehl-bearing-cli --test fuzz_cli --
/// --ignored --nocapture fuzz_folders_many`.
#[test]
#[ignore]
fn fuzz_folders_many() {
    fuzz_folders(env_u64("FUZZ_SEED", 15), env_u64("FUZZ_FOLDER_CASES", 1000));
}
