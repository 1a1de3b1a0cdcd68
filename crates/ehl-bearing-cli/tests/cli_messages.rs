//! Messages that name what the user can change: the hydrodynamic-regime error of a light
//! contact names the options that fix it (`--amplitude`, `--min-load-fraction`), `characterize
//! --amplitude` is applied and validated, and counts read "1 recorded period". Coarse grids
//! (33²) keep every run within a few seconds.

use assert_cmd::Command;
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// `file` of the examples with `from` replaced by `to`, written into `dir`.
fn example_with(dir: &Path, file: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(examples().join(file)).unwrap();
    assert!(text.contains(from), "{from:?} not in {file}");
    let path = dir.join(file);
    std::fs::write(&path, text.replace(from, to)).unwrap();
    path
}

/// The seed case, quasi-static on the 33² grid.
fn coarse_case(dir: &Path) -> PathBuf {
    example_with(
        dir,
        "7006.toml",
        "[bearing]",
        "method = \"quasi-static\"\n[method_options]\ngrid = 33\n\n[bearing]",
    )
}

fn run(args: &[&std::ffi::OsStr]) -> std::process::Output {
    Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(args)
        .output()
        .unwrap()
}

fn stderr_of_failure(args: &[&std::ffi::OsStr]) -> String {
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{err}");
    err
}

#[test]
fn characterize_names_the_options_that_fix_a_hydrodynamic_contact() {
    let tmp = tempfile::tempdir().unwrap();
    let case = coarse_case(tmp.path());
    // ±90 %: the lightest loads of the lighter contacts' ranges run hydrodynamic.
    let err = stderr_of_failure(&[
        "characterize".as_ref(),
        case.as_os_str(),
        "--amplitude".as_ref(),
        "0.9".as_ref(),
    ]);
    for needle in [
        "runs in the hydrodynamic regime",
        "lower the relative load amplitude --amplitude (now 0.9;",
        "0 < ε ≤ 0.9",
        "Contacts lighter than --min-load-fraction × the largest contact load (now 0.01 × ",
        "raise --min-load-fraction (0 < f < 1)",
    ] {
        assert!(err.contains(needle), "{needle:?} not in: {err}");
    }
    assert!(
        !err.contains("method_options") && !err.contains("min_load_fraction"),
        "{err}"
    );
}

#[test]
fn characterize_amplitude_is_validated_and_applied() {
    let tmp = tempfile::tempdir().unwrap();
    let case = coarse_case(tmp.path());
    for bad in ["1.5", "0", "nan"] {
        let err = stderr_of_failure(&[
            "characterize".as_ref(),
            case.as_os_str(),
            "--amplitude".as_ref(),
            bad.as_ref(),
        ]);
        assert!(
            err.contains(&format!("--amplitude = {}", bad.replace("nan", "NaN")))
                && err.contains("expected a relative amplitude ε with 0 < ε ≤ 0.9"),
            "{bad}: {err}"
        );
    }
    // Applied on top of the case file's method and its other options (the dry reference here,
    // which is quick): the report records it.
    let out = run(&[
        "characterize".as_ref(),
        case.as_os_str(),
        "--method".as_ref(),
        "hertz".as_ref(),
        "--amplitude".as_ref(),
        "0.05".as_ref(),
        "--json".as_ref(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let found = find_amplitude(&v);
    assert_eq!(found, Some(0.05), "{text}");
}

/// The first `amplitude` of the report's method settings.
fn find_amplitude(v: &serde_json::Value) -> Option<f64> {
    match v {
        serde_json::Value::Object(m) => m
            .get("amplitude")
            .and_then(|a| a.as_f64())
            .or_else(|| m.values().find_map(find_amplitude)),
        serde_json::Value::Array(a) => a.iter().find_map(find_amplitude),
        _ => None,
    }
}

#[test]
fn contact_names_the_amplitude_option_of_a_hydrodynamic_range() {
    let tmp = tempfile::tempdir().unwrap();
    let light = example_with(
        tmp.path(),
        "contact_7006_inner.toml",
        "load_n = 600.0",
        "load_n = 30.0",
    );
    let err = stderr_of_failure(&[
        "contact".as_ref(),
        light.as_os_str(),
        "--grid".as_ref(),
        "33".as_ref(),
        "--amplitude".as_ref(),
        "0.9".as_ref(),
        "--no-film-extrapolation".as_ref(),
    ]);
    assert!(
        err.contains("at load 3.0000 N")
            && err.contains("lower the relative load amplitude --amplitude (now 0.9;"),
        "{err}"
    );
    assert!(!err.contains("method_options"), "{err}");
}

#[test]
fn one_recorded_period_is_singular_in_the_table_and_the_figure() {
    let tmp = tempfile::tempdir().unwrap();
    let seed = examples().join("contact_7006_inner.toml");
    let out = run(&[
        "contact".as_ref(),
        seed.as_os_str(),
        "--method".as_ref(),
        "harmonic".as_ref(),
        "--grid".as_ref(),
        "33".as_ref(),
        "--steps-per-period".as_ref(),
        "16".as_ref(),
        "--settling-periods".as_ref(),
        "1".as_ref(),
        "-o".as_ref(),
        tmp.path().as_os_str(),
    ]);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        table.contains("(at most 1 period) + 1 recorded period × 16 steps"),
        "{table}"
    );
    assert!(!table.contains("1 recorded periods"), "{table}");
    let svg = std::fs::read_to_string(tmp.path().join("time_history.svg")).unwrap();
    assert!(
        svg.contains("settling steps + 1 recorded period —"),
        "title"
    );
    assert!(!svg.contains("recorded periods"), "title");
}
