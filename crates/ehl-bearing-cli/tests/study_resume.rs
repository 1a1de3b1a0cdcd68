//! A study killed with SIGKILL midway and started again with the same output folder redoes only
//! the points in flight, and its final files are identical, byte for byte, to an uninterrupted
//! run's.

mod study_common;

use assert_cmd::cargo::CommandCargoExt;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use study_common::{assert_same_tree, study_file, tree};

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

#[test]
fn killed_study_resumes_to_identical_files() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0, 2.0]", "");
    let full = tmp.path().join("full");
    let out = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            full.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("6 computed, 0 loaded"));
    // Piped: no progress bar on stderr, one log line per finished point instead.
    let log = String::from_utf8_lossy(&out.stderr);
    assert_eq!(log.lines().count(), 6, "{log}");
    assert!(
        log.lines()
            .all(|l| l.starts_with("point ") && l.contains("converged")),
        "{log}"
    );

    // Interrupted run: each point waits 400 ms before it is computed, so the kill lands while a
    // later point is in flight.
    let resumed = tmp.path().join("resumed");
    let points = resumed.join("points");
    let mut child = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            resumed.to_str().unwrap(),
            "--delay-ms",
            "400",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let finished_points = || {
        std::fs::read_dir(&points)
            .map(|d| {
                d.filter_map(|e| e.ok())
                    .filter(|e| {
                        let n = e.file_name().to_string_lossy().to_string();
                        n.ends_with(".json") && !n.starts_with('.')
                    })
                    .count()
            })
            .unwrap_or(0)
    };
    while finished_points() == 0 {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "no point file appeared"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    // A second run on the same folder while the first computes is refused at once (both used to
    // compute every point).
    let second = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            resumed.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(
        !second.status.success()
            && err.contains("another `ehl-bearing study` is computing the whole study"),
        "{err}"
    );
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let done = finished_points();
    assert!((1..6).contains(&done), "killed after {done} of 6 points");
    assert!(!resumed.join("results.csv").exists());

    let out = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            resumed.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("{} computed, {} loaded", 6 - done, done)),
        "{stdout}"
    );
    assert_same_tree(&full, &resumed);
    assert!(tree(&full).contains_key("results.csv"));
    assert!(tree(&full).contains_key("trends.json"));
    assert!(tree(&full).contains_key("k_vs_load.png"));
}

#[test]
fn point_files_of_another_study_are_refused_or_recomputed_on_request() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let a = study_file(
        tmp.path(),
        "hertz",
        "[3000]",
        "[0.5, 1.0, 2.0]",
        "[method_options]\nsamples = 9\n",
    );
    let run = |s: &std::path::Path, extra: &[&str]| {
        bin()
            .args(["study", s.to_str().unwrap(), "-o", out.to_str().unwrap()])
            .args(extra)
            .output()
            .unwrap()
    };
    let ok = |o: std::process::Output| {
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).to_string()
    };
    assert!(ok(run(&a, &[])).contains("3 computed, 0 loaded"));
    assert!(ok(run(&a, &[])).contains("0 computed, 3 loaded"));
    let before = tree(&out);
    let b = study_file(
        tmp.path(),
        "hertz",
        "[3000]",
        "[0.5, 1.0, 2.0]",
        "[method_options]\nsamples = 11\n",
    );
    // Another study's points are not overwritten: refused before any work, naming the file and
    // what differs.
    let o = run(&b, &[]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("different study") && err.contains("samples") && err.contains("--overwrite"),
        "{err}"
    );
    assert_eq!(tree(&out), before);
    // On request they are recomputed.
    assert!(ok(run(&b, &["--overwrite"])).contains("3 computed, 0 loaded"));
}

#[test]
fn unusable_output_is_refused_before_any_work_and_a_closed_stdout_ends_quietly() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    // -o naming an existing file: refused at once, the file untouched.
    let file = tmp.path().join("a_file");
    std::fs::write(&file, "keep me").unwrap();
    let t0 = Instant::now();
    let o = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            file.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("a_file") && err.contains("not a folder"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
    assert!(t0.elapsed() < Duration::from_secs(10));
    // A truncated point file (a crash mid-write on a file system without atomic renames) is
    // recomputed, and the result equals a clean run.
    let clean = tmp.path().join("clean");
    let o = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            clean.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success());
    let broken = tmp.path().join("broken");
    std::fs::create_dir_all(broken.join("points")).unwrap();
    let name = "points/n3000rpm_s0.5.json";
    let good = std::fs::read(clean.join(name)).unwrap();
    std::fs::write(broken.join(name), &good[..good.len() / 2]).unwrap();
    let o = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            broken.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unreadable point file"));
    assert_same_tree(&clean, &broken);
    // stdout closed after its first line: quiet end (no panic message), finished files intact.
    let piped = tmp.path().join("piped");
    let mut child = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            piped.to_str().unwrap(),
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader goes away at once
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_ne!(out.status.code(), Some(101), "{err}");
}
