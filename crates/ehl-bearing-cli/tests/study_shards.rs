//! Sharded studies: the seed study run as 3 shards — into one folder, or into three folders
//! gathered by `study merge` — gives files identical, byte for byte, to one run; merging before
//! every shard is done fails and names a missing point.

mod study_common;

use std::path::Path;
use study_common::{assert_same_tree, ok, run, s, study_file, tree};

/// Run `study` once into `full`, as 3 shards into `shared` + merge, and as 3 shards into
/// separate folders + merge into `merged`; assert the three trees are identical.
fn shards_equal_one_run(study: &Path, dir: &Path) {
    let full = dir.join("full");
    ok(run(&["study", s(study), "-o", s(&full)]));
    let shared = dir.join("shared");
    for i in 1..=3 {
        let out = ok(run(&[
            "study",
            s(study),
            "-o",
            s(&shared),
            "--shard",
            &format!("{i}/3"),
        ]));
        assert!(out.contains(&format!("shard {i}/3")), "{out}");
        if i < 3 {
            // Not every point is done: merge refuses and names the first missing point.
            let o = run(&["study", "merge", s(study), "-o", s(&shared)]);
            assert!(!o.status.success());
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(
                err.contains("not finished") && err.contains(".json"),
                "{err}"
            );
        }
    }
    ok(run(&["study", "merge", s(study), "-o", s(&shared)]));
    assert_same_tree(&full, &shared);
    let parts: Vec<_> = (1..=3).map(|i| dir.join(format!("part{i}"))).collect();
    for (i, p) in parts.iter().enumerate() {
        ok(run(&[
            "study",
            s(study),
            "-o",
            s(p),
            "--shard",
            &format!("{}/3", i + 1),
        ]));
    }
    let merged = dir.join("merged");
    let mut args = vec!["study", "merge", s(study), "-o", s(&merged)];
    args.extend(parts.iter().map(|p| s(p)));
    ok(run(&args));
    assert_same_tree(&full, &merged);
    let t = tree(&full);
    for f in ["results.csv", "points.csv", "trends.json"] {
        assert!(t.contains_key(f), "{f}");
    }
}

#[test]
fn seed_study_as_three_shards_merges_to_the_same_files_hertz() {
    // The seed study's 12 points (3000/4000/5000 rpm × load scales 0.5–2) with the dry method:
    // the sharding and merging machinery, fast. The EHL version is the ignored test below.
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(
        tmp.path(),
        "hertz",
        "[3000, 4000, 5000]",
        "[0.5, 1.0, 1.5, 2.0]",
        "",
    );
    shards_equal_one_run(&study, tmp.path());
    // Shards are round robin over the study order: shard 2/3 holds points 2, 5, 8, 11.
    let o = ok(run(&[
        "study",
        s(&study),
        "-o",
        s(&tmp.path().join("one")),
        "--shard",
        "2/3",
    ]));
    assert!(o.contains("4 points (4 computed"), "{o}");
    // Bad shards are refused before any work, naming the option.
    for bad in ["0/3", "4/3", "1/0", "a/b", "3"] {
        let o = run(&[
            "study",
            s(&study),
            "-o",
            s(&tmp.path().join("bad")),
            "--shard",
            bad,
        ]);
        assert!(!o.status.success(), "{bad}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("shard"), "{bad}: {err}");
    }
}

#[test]
#[ignore = "seed study by the quasi-static method, 3 points × 3 runs: ≈ 3 min on 2 cores; `cargo test -p ehl-bearing-cli --test study_shards -- --ignored`"]
fn seed_study_as_three_shards_merges_to_the_same_files_quasi_static() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(
        tmp.path(),
        "quasi-static",
        "[3000, 4000, 5000]",
        "[1.0]",
        "",
    );
    shards_equal_one_run(&study, tmp.path());
}
