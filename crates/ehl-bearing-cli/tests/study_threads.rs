//! Study output does not depend on the number of threads (bitwise), with --threads and with
//! RAYON_NUM_THREADS, nor on the number of points computed at once (--points-in-flight).

mod study_common;

use assert_cmd::cargo::CommandCargoExt;
use std::process::Command;
use study_common::{assert_same_tree, study_file};

#[test]
fn one_and_two_threads_give_identical_files() {
    let tmp = tempfile::tempdir().unwrap();
    // The synthetic method with a generous cache tolerance exercises deduplication and reuse.
    let study = study_file(
        tmp.path(),
        "synthetic",
        "[3000, 5000]",
        "[0.5, 1.5]",
        "[characterize]\ncache_tolerance = 0.02\ntolerance = 1e-5\n",
    );
    let run = |name: &str, threads: Option<&str>, env: Option<&str>, in_flight: &str| {
        let out = tmp.path().join(name);
        let mut c = Command::cargo_bin("ehl-bearing").unwrap();
        c.args([
            "study",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        if let Some(t) = threads {
            c.args(["--threads", t]);
        }
        c.args(["--points-in-flight", in_flight]);
        if let Some(e) = env {
            c.env("RAYON_NUM_THREADS", e);
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out
    };
    // One thread, one point at a time: the reference.
    let one = run("t1", Some("1"), None, "1");
    let two = run("t2", Some("2"), None, "2");
    let env2 = run("e2", None, Some("2"), "1");
    let four_points = run("p4", Some("2"), None, "4");
    assert_same_tree(&one, &two);
    assert_same_tree(&one, &env2);
    assert_same_tree(&one, &four_points);
    let csv = std::fs::read_to_string(one.join("results.csv")).unwrap();
    assert!(
        csv.contains("deduplicated") || csv.contains("cached"),
        "no reuse exercised"
    );
    assert_eq!(csv.lines().count(), 1 + 4 * 22);
}

#[test]
fn invalid_thread_and_point_counts_are_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path(), "hertz", "[3000]", "[1.0]", "");
    for option in ["--threads", "--points-in-flight"] {
        let o = Command::cargo_bin("ehl-bearing")
            .unwrap()
            .args([
                "study",
                study.to_str().unwrap(),
                "-o",
                tmp.path().join("o").to_str().unwrap(),
                option,
                "0",
            ])
            .output()
            .unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(&format!("{option} 0")), "{err}");
    }
}
