//! `characterize` and `study` command lines: outputs, units, errors.

mod study_common;

use assert_cmd::cargo::CommandCargoExt;
use serde_json::Value;
use std::process::Command;
use study_common::{study_file, SEED};

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

#[test]
fn characterize_json_has_every_contact_and_both_stiffnesses() {
    let o = bin()
        .args(["characterize", SEED, "--method", "hertz", "--json"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["converged"], Value::Bool(true));
    assert_eq!(v["method"]["name"], "hertz");
    let contacts = v["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), 22);
    for c in contacts {
        for key in [
            "k",
            "d",
            "delta_f_n",
            "load_n",
            "approach_m",
            "contact_angle_rad",
            "moes_m",
            "moes_l",
        ] {
            assert!(c[key].is_f64(), "{key}: {c}");
        }
        assert!((c["d"].as_f64().unwrap() - 1.5).abs() < 1e-9);
    }
    for key in ["stiffness_dry", "stiffness_ehl"] {
        assert_eq!(v[key].as_array().unwrap().len(), 5);
    }
    assert!(v["history"][0]["seconds"].is_f64());
    assert!(v["displacement"]["x"].as_f64().unwrap() > 0.0);
}

#[test]
fn characterize_table_and_output_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let o = bin()
        .args([
            "characterize",
            SEED,
            "--method",
            "synthetic",
            "-o",
            tmp.path().to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("converged after"), "{s}");
    assert!(s.contains("EHL/dry"), "{s}");
    let csv = std::fs::read_to_string(tmp.path().join("contacts.csv")).unwrap();
    assert_eq!(csv.lines().count(), 23);
    assert!(csv.starts_with("ball,race,load_n,approach_m,contact_angle_rad,k,d,delta_f_n"));
    let v: Value = serde_json::from_str(
        &std::fs::read_to_string(tmp.path().join("characterization.json")).unwrap(),
    )
    .unwrap();
    // Files are reproducible: no timings.
    assert!(v.get("seconds").is_none());
}

#[test]
fn unknown_methods_are_clear_errors() {
    let o = bin()
        .args(["characterize", SEED, "--method", "magic"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown method"));
}

#[test]
fn study_rejects_bad_files_with_the_key_named() {
    let tmp = tempfile::tempdir().unwrap();
    for (extra, key) in [
        ("[method_options]\nsamples = 2\n", "method_options.samples"),
        (
            "[method_options]\nwhatever = 1\n",
            "method_options.whatever",
        ),
    ] {
        let study = study_file(tmp.path(), "hertz", "[3000]", "[1.0]", extra);
        let o = bin()
            .args([
                "study",
                study.to_str().unwrap(),
                "-o",
                tmp.path().join("o").to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(!o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains(key), "{key}");
    }
    // The harmonic method's options are checked before any EHL run.
    for (extra, key) in [
        (
            "[method_options]\nsteps_per_period = 2\n",
            "method_options.steps_per_period",
        ),
        ("[method_options]\npoints = 7\n", "method_options.points"),
    ] {
        let study = study_file(tmp.path(), "harmonic", "[3000]", "[1.0]", extra);
        let o = bin()
            .args([
                "study",
                study.to_str().unwrap(),
                "-o",
                tmp.path().join("h").to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(key), "{key}: {err}");
    }
    let study = study_file(tmp.path(), "hertz", "[3000, -5]", "[1.0]", "");
    let o = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            tmp.path().join("o").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("inner_speeds_rpm[1] = -5"), "{err}");
}

#[test]
fn study_writes_long_csv_and_loadable_trends() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(
        tmp.path(),
        "synthetic",
        "[3000, 4000, 5000]",
        "[0.5, 1.0, 2.0]",
        "",
    );
    let out = tmp.path().join("out");
    let o = bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for col in [
        "speed_rpm",
        "load_scale",
        "ball",
        "race",
        "load_n",
        "approach_m",
        "contact_angle_rad",
        "k",
        "d",
        "delta_f_n",
        "moes_m",
        "moes_l",
        "ry_over_rx",
        "r_squared",
    ] {
        assert!(header.contains(&col), "{col}");
    }
    assert_eq!(csv.lines().count(), 1 + 9 * 22);
    let points = std::fs::read_to_string(out.join("points.csv")).unwrap();
    assert_eq!(points.lines().count(), 10);
    // The trend force element reproduces every point's reactions (measured 2.3e-5, docs/study.md).
    let col = points
        .lines()
        .next()
        .unwrap()
        .split(',')
        .position(|c| c == "trend_reaction_error")
        .unwrap();
    for line in points.lines().skip(1) {
        let e: f64 = line.split(',').nth(col).unwrap().parse().unwrap();
        assert!(e < 1e-3, "{line}");
    }
    // Each point reports how far from their characterization loads its laws are used and how
    // many characterizations it needed.
    let header: Vec<&str> = points.lines().next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let (off, res, n) = (
        at("max_load_offset"),
        at("max_relative_residual"),
        at("characterizations"),
    );
    for line in points.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let offset: f64 = cells[off].parse().unwrap();
        let residual: f64 = cells[res].parse().unwrap();
        let count: usize = cells[n].parse().unwrap();
        assert!((0.0..=0.01 + 1e-3).contains(&offset), "{line}");
        assert!((0.0..1e-3).contains(&residual), "{line}");
        assert!(count >= 22, "{line}");
    }
    let trends = std::fs::read_to_string(out.join("trends.json")).unwrap();
    let model = ehl_bearing::study::TrendModel::from_json(&trends).unwrap();
    assert_eq!(model.inner.d.form, "hertz_limit");
    assert_eq!(std::fs::read_dir(out.join("points")).unwrap().count(), 9);
    for stem in ["k_vs_load", "d_vs_load", "delta_f_vs_load"] {
        for ext in ["png", "svg"] {
            let f = out.join(format!("{stem}.{ext}"));
            assert!(
                std::fs::metadata(&f).unwrap().len() > 1000,
                "{}",
                f.display()
            );
        }
    }
    let svg = std::fs::read_to_string(out.join("d_vs_load.svg")).unwrap();
    assert!(svg.contains("inner") && svg.contains("outer") && svg.contains("5000 rpm"));
}

#[test]
fn a_failing_point_is_recorded_and_the_others_finish() {
    let tmp = tempfile::tempdir().unwrap();
    // 100 × the seed loads needs deflections beyond 2 % of the ball diameter: an error.
    let study = study_file(tmp.path(), "hertz", "[3000]", "[1.0, 0.5, 100.0]", "");
    let out = tmp.path().join("out");
    let run = || {
        bin()
            .args([
                "study",
                study.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ])
            .output()
            .unwrap()
    };
    let o = run();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("1 of 3 points failed"), "{err}");
    assert!(err.contains("cannot carry"), "{err}");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 22);
    let points = std::fs::read_to_string(out.join("points.csv")).unwrap();
    assert!(points.contains("3000.0,100.0,error"), "{points}");
    // The failure is remembered: a rerun recomputes nothing and fails the same way.
    let o = run();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("0 computed, 3 loaded"));
}
