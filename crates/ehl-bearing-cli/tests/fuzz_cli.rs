//! Fuzzing of command lines (issue 15; docs/robustness.md): generated argument lists, each run
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
