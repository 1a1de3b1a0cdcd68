//! Inputs outside what the models describe are refused at once, naming the key, and long
//! solves are bounded by `--time-limit` (each of these ran for minutes before).

use assert_cmd::cargo::CommandCargoExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The seed case with `from` replaced by `to`.
fn case_with(dir: &Path, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(examples().join("7006.toml")).unwrap();
    assert!(text.contains(from));
    let path = dir.join("case.toml");
    std::fs::write(&path, text.replace(from, to)).unwrap();
    path
}

fn run(args: &[&str]) -> (Output, Duration) {
    let t0 = Instant::now();
    let o = Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    (o, t0.elapsed())
}

fn refused_at_once(args: &[&str], needles: &[&str]) {
    let (o, t) = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in: {err}");
    }
    assert!(t < Duration::from_secs(5), "took {t:?}");
}

#[test]
fn the_issues_characterize_examples_are_refused_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let c = case_with(
        tmp.path(),
        "inner_speed_rpm = 5000.0",
        "inner_speed_rpm = 1e5",
    );
    refused_at_once(
        &["characterize", c.to_str().unwrap()],
        &["operating.inner_speed_rpm = 100000", "n·d_m ≤ 4.0e6"],
    );
    let c = case_with(
        tmp.path(),
        "youngs_modulus_gpa = 208.0",
        "youngs_modulus_gpa = 1e6",
    );
    refused_at_once(
        &["characterize", c.to_str().unwrap()],
        &[
            "ball_material.youngs_modulus_gpa = 1000000",
            "0.1 to 1200 GPa",
        ],
    );
    let c = case_with(tmp.path(), "force_axial_n = 1000.0", "force_axial_n = 1e5");
    refused_at_once(
        &["characterize", c.to_str().unwrap()],
        &["operating.force_axial_n", "100000", "≤ 5.0 GPa"],
    );
    // The same in a study: refused before the output folder is made.
    let study = tmp.path().join("study.toml");
    std::fs::write(
        &study,
        "case = \"case.toml\"\nmethod = \"hertz\"\ninner_speeds_rpm = [3000.0]\n",
    )
    .unwrap();
    let out = tmp.path().join("out");
    refused_at_once(
        &[
            "study",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        &["point 1", "operating.force_axial_n"],
    );
    assert!(!out.exists());
    // The dry equilibrium itself still runs, with a warning.
    let (o, _) = run(&["equilibrium", c.to_str().unwrap()]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("warning"));
    // A contact file beyond the pressure limit.
    let text = std::fs::read_to_string(examples().join("contact_7006_inner.toml")).unwrap();
    let contact = tmp.path().join("contact.toml");
    std::fs::write(&contact, text.replace("load_n = 600.0", "load_n = 60000.0")).unwrap();
    for cmd in ["ehl", "contact"] {
        refused_at_once(
            &[cmd, contact.to_str().unwrap()],
            &["load_n = 60000", "GPa"],
        );
    }
}

#[test]
fn large_grids_say_so_at_once_and_stop_at_the_time_limit() {
    let contact = examples().join("contact_7006_inner.toml");
    let (o, t) = run(&[
        "ehl",
        contact.to_str().unwrap(),
        "--grid",
        "1025",
        "--time-limit",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("note: a 1025×1025 grid takes seconds per EHL solve"),
        "{err}"
    );
    assert!(
        err.contains("time limit of 1 s") && err.contains("relative residual after each cycle"),
        "{err}"
    );
    // One multigrid cycle at 1025² after the budget at most (about 10 s on a loaded machine).
    assert!(t < Duration::from_secs(60), "took {t:?}");
    let (o, _) = run(&["ehl", contact.to_str().unwrap(), "--time-limit", "0"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--time-limit 0"));
}

#[test]
fn the_coupled_loop_and_a_study_point_stop_at_their_time_limit() {
    let case = examples().join("7006.toml");
    let (o, t) = run(&["characterize", case.to_str().unwrap(), "--time-limit", "1"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("time limit of 1 s"), "{err}");
    assert!(t < Duration::from_secs(30), "took {t:?}");
    // A study point out of its budget fails and leaves no point file (a rerun computes it).
    let tmp = tempfile::tempdir().unwrap();
    let study = examples().join("study_7006.toml");
    let out = tmp.path().join("out");
    let (o, _) = run(&[
        "study",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--shard",
        "12/12",
        "--time-limit",
        "0.5",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("time limit") && err.contains("not saved"),
        "{err}"
    );
    let files = std::fs::read_dir(out.join("points")).unwrap().count();
    assert_eq!(files, 0, "{err}");
}

/// Found by tests/ehl_edges.rs: at M = 557, L = 0.5 the 33² grid converges to a negative film
/// (the true one, ≈ 0.1 nm at 257², is not resolved). The solution is finite and `ehl` says so.
#[test]
fn an_unresolved_film_is_reported() {
    let (o, _) = run(&[
        "ehl",
        "--moes-m",
        "556.78",
        "--moes-l",
        "0.5",
        "--ry-over-rx",
        "3.7376",
        "--grid",
        "33",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("does not resolve this film"), "{err}");
}

/// Values that entered without the checks the case file's values get: a speeds list beyond the
/// speed-factor limit, Moes L far beyond real contacts (it returned a "converged" film of
/// −4.4e6 m), and absurd thread counts (100 000 threads took 90 s to start).
#[test]
fn every_door_applies_the_plausibility_rules() {
    let case = examples().join("7006.toml");
    let case = case.to_str().unwrap();
    refused_at_once(
        &[
            "coefficients",
            case,
            "--method",
            "hertz",
            "--speeds",
            "3000,100000",
        ],
        &["speeds[1] = 100000", "n·d_m ≤ 4.0e6"],
    );
    // 200 000 speeds ran out of memory (found by the Python API fuzzer).
    let many = vec!["3000"; 1001].join(",");
    refused_at_once(
        &["coefficients", case, "--method", "hertz", "--speeds", &many],
        &["speeds = 1001 values", "at most 1000 speeds"],
    );
    refused_at_once(
        &[
            "ehl", "--moes-m", "20", "--moes-l", "1e6", "--grid", "33", "--json",
        ],
        &["L = 1000000", "0 < L ≤ 100"],
    );
    for cmd in [
        vec!["characterize", case, "--method", "hertz"],
        vec!["coefficients", case, "--method", "hertz"],
    ] {
        for n in ["0", "100000"] {
            let mut args = cmd.clone();
            args.extend(["--threads", n]);
            refused_at_once(&args, &[&format!("--threads {n}: expected 1 to")]);
        }
    }
}

/// Values refused with their key, value and range at whichever door: a conformity at 0.5
/// (the Hertz constant's table failed), a ball density of 1e30 kg/m³ (residual 4e58 N), an axial
/// force of 1e300 N (residual NaN), and grids outside 2^k + 1, 17 to 1025 refused before any
/// solve (the equilibrium printed "22 EHL contact solutions did not converge"; `ehl --grid 2049`
/// first printed how long such a solve takes).
#[test]
fn absurd_case_values_and_grids_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    for (from, to, needles) in [
        (
            "inner_conformity = 0.51",
            "inner_conformity = 0.5000001",
            &["bearing.inner_conformity = 0.5000001", "at least 0.501"][..],
        ),
        (
            "density_kg_m3 = 7850.0",
            "density_kg_m3 = 1e30",
            &["ball_material.density_kg_m3", "500 to 25000 kg/m³"][..],
        ),
        (
            "force_axial_n = 1000.0",
            "force_axial_n = 1e300",
            &[
                "operating.force_axial_n = 1e300",
                "GPa limit of the inner contact",
            ][..],
        ),
    ] {
        let c = case_with(tmp.path(), from, to);
        refused_at_once(&["characterize", c.to_str().unwrap()], needles);
    }
    let case = examples().join("7006.toml");
    for g in ["0", "18", "100000"] {
        refused_at_once(
            &["equilibrium", case.to_str().unwrap(), "--film", "--grid", g],
            &[&format!("--grid {g}"), "2^k + 1, 17 to 1025"],
        );
    }
    let contact = examples().join("contact_7006_inner.toml");
    let (o, _) = run(&["ehl", contact.to_str().unwrap(), "--grid", "2049"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("settings.grid = 2049") && !err.contains("note:"),
        "{err}"
    );
}

/// One rule for commands with one result: a loop that did not converge prints its result
/// marked and exits 1 (characterize exited 0 with a warning).
#[test]
fn a_loop_that_did_not_converge_exits_1_after_printing() {
    let case = examples().join("7006.toml");
    let (o, _) = run(&[
        "characterize",
        case.to_str().unwrap(),
        "--method",
        "hertz",
        "--tolerance",
        "1e-15",
        "--max-iterations",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(out.contains("NOT converged"), "{out}");
    assert!(
        err.contains("did not converge in 1 iterations") && err.contains("--max-iterations"),
        "{err}"
    );
}
