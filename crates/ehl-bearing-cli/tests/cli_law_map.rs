//! `ehl-bearing law-map` (docs/law_map.md §5): a small map generated as two shards into one
//! folder, resumed, assembled into a map file that reads back, checked at held-out points; a
//! spec with an invalid group is refused naming it.

use assert_cmd::Command;

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

/// A 3 × 3 × 3 map on grid 33: seconds.
const SPEC: &str = r#"
viscosity_model = "roelands"
density_model = "dowson-higginson"
alpha_p0 = 4.312
ln_eta0_ratio = 6.451124175131799
amplitude = 0.2
points = 7
grid = 33

[[axis]]
group = "m"
min = 300.0
max = 1000.0
nodes = 3
log = true

[[axis]]
group = "l"
min = 20.0
max = 24.0
nodes = 3
log = false

[[axis]]
group = "ry_over_rx"
min = 10.0
max = 20.0
nodes = 3
log = true
"#;

#[test]
fn shards_assemble_and_check() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("spec.toml");
    std::fs::write(&spec, SPEC).unwrap();
    let out = dir.path().join("nodes");
    for shard in ["1/2", "2/2"] {
        let o = bin()
            .args(["law-map", "generate"])
            .arg(&spec)
            .arg("-o")
            .arg(&out)
            .args(["--shard", shard, "--threads", "1"])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    // Resumed: nothing left to compute.
    let o = bin()
        .args(["law-map", "generate"])
        .arg(&spec)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("0 computed") && text.contains("27 already done"),
        "{text}"
    );
    let map = dir.path().join("map.json");
    let o = bin()
        .args(["law-map", "assemble"])
        .arg(&spec)
        .arg("-o")
        .arg(&out)
        .arg("--map")
        .arg(&map)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m =
        ehl_bearing::law_map::LawMap::from_json(&std::fs::read_to_string(&map).unwrap()).unwrap();
    assert_eq!(m.laws.len(), 27);
    binary_form_round_trips(dir.path(), &spec, &out, &map, &m);
    let csv = dir.path().join("check.csv");
    let o = bin()
        .args(["law-map", "check"])
        .arg(&map)
        .args(["--points", "2", "--threads", "1", "--csv"])
        .arg(&csv)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && text.contains("2 of 2 held-out points"),
        "{text}"
    );
    // The references (direct characterizations) kept in a folder: computed from the spec alone
    // (as beside a map's generation), then the map's check reads them — the same CSV.
    references_from_the_spec(dir.path(), &spec, &map, &csv);
    // One row per point, with the rheology groups of the point (the spec's fixed values here).
    let rows = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = rows.lines().collect();
    assert_eq!(lines.len(), 3, "{rows}");
    assert!(
        lines[0].ends_with(",alpha_p0,ln_eta0_ratio,direct_converged"),
        "{rows}"
    );
    assert!(lines[1].contains(",4.312,6.451124175131799,"), "{rows}");
    // The same points against references with the solver's tolerances ten times tighter: the
    // direct laws (columns k_hat, d, delta_f_hat) move, the points do not.
    let tight = dir.path().join("check_tight.csv");
    let o = bin()
        .args(["law-map", "check"])
        .arg(&map)
        .args([
            "--points",
            "2",
            "--threads",
            "1",
            "--tolerance-factor",
            "0.1",
            "--csv",
        ])
        .arg(&tight)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let tight = std::fs::read_to_string(&tight).unwrap();
    let cols = |l: &str, r: std::ops::Range<usize>| -> Vec<String> {
        l.split(',').collect::<Vec<_>>()[r]
            .iter()
            .map(|c| c.to_string())
            .collect()
    };
    for (a, b) in lines[1..].iter().zip(tight.lines().skip(1)) {
        assert_eq!(cols(a, 0..3), cols(b, 0..3), "{rows}\n{tight}");
        assert_ne!(cols(a, 10..13), cols(b, 10..13), "{rows}\n{tight}");
    }
    for bad in ["0", "1.5", "nan"] {
        let o = bin()
            .args(["law-map", "check"])
            .arg(&map)
            .args(["--points", "1", "--tolerance-factor", bad])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("--tolerance-factor") && err.contains("(0, 1]"),
            "{bad}: {err}"
        );
    }
}

/// The binary form of the map `m` assembled into `map` (JSON text) from the nodes in `out`:
/// assembled directly or converted from the JSON text, the same bytes; converted back, the same
/// text; any other extension refused naming both forms; a truncated file refused with its length.
fn binary_form_round_trips(
    dir: &std::path::Path,
    spec: &std::path::Path,
    out: &std::path::Path,
    map: &std::path::Path,
    m: &ehl_bearing::law_map::LawMap,
) {
    let run = |args: &[&std::ffi::OsStr]| bin().args(args).output().unwrap();
    let bin_map = dir.join("map.bin");
    let o = run(&[
        "law-map".as_ref(),
        "assemble".as_ref(),
        spec.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--map".as_ref(),
        bin_map.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let converted = dir.join("converted.bin");
    let o = run(&[
        "law-map".as_ref(),
        "convert".as_ref(),
        map.as_os_str(),
        converted.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&bin_map).unwrap();
    assert_eq!(bytes, std::fs::read(&converted).unwrap());
    assert_eq!(bytes, m.to_binary());
    // `law-map info` of either form: the same summary.
    let o = run(&[
        "law-map".as_ref(),
        "info".as_ref(),
        map.as_os_str(),
        bin_map.as_os_str(),
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert!(o.status.success() && lines.len() == 6, "{text}");
    assert!(
        lines[0].contains("quasi-static law, grid 33²") && lines[0].contains("27 nodes"),
        "{text}"
    );
    assert_eq!(
        lines[0].split_once(": ").unwrap().1,
        lines[3].split_once(": ").unwrap().1
    );
    assert_eq!(lines[1..3], lines[4..6]);
    let back = dir.join("back.json");
    let o = run(&[
        "law-map".as_ref(),
        "convert".as_ref(),
        bin_map.as_os_str(),
        back.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&back).unwrap(), std::fs::read(map).unwrap());
    let o = run(&[
        "law-map".as_ref(),
        "convert".as_ref(),
        map.as_os_str(),
        dir.join("map.txt").as_os_str(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success()
            && err.contains("\"txt\"")
            && err.contains(".json")
            && err.contains(".bin"),
        "{err}"
    );
    // The sparse subset of level 2 (3 × 3 × 3 nodes: depths 1, 1, 1): 19 nodes, the library's.
    let sparse = dir.join("sparse.bin");
    let level = |q: &str| {
        run(&[
            "law-map".as_ref(),
            "convert".as_ref(),
            map.as_os_str(),
            sparse.as_os_str(),
            "--sparse-level".as_ref(),
            q.as_ref(),
        ])
    };
    let o = level("2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("19 nodes"));
    let read = ehl_bearing::law_map::LawMap::parse(&std::fs::read(&sparse).unwrap()).unwrap();
    assert_eq!(read, m.sparse_subset(2).unwrap());
    let o = run(&["law-map".as_ref(), "info".as_ref(), sparse.as_os_str()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("sparse level 2; 19 nodes"), "{text}");
    let o = level("4");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("sparse_level = 4") && err.contains("1 to 3"),
        "{err}"
    );
    let mut damaged = bytes.clone();
    damaged.truncate(bytes.len() - 3);
    std::fs::write(&converted, &damaged).unwrap();
    let o = run(&[
        "law-map".as_ref(),
        "check".as_ref(),
        converted.as_os_str(),
        "--points".as_ref(),
        "1".as_ref(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("converted.bin") && err.contains("bytes, expected"),
        "{err}"
    );
}

#[test]
fn a_spec_with_a_missing_group_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("spec.toml");
    std::fs::write(&spec, SPEC.replace("alpha_p0 = 4.312\n", "")).unwrap();
    let o = bin()
        .args(["law-map", "generate"])
        .arg(&spec)
        .arg("-o")
        .arg(dir.path().join("nodes"))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("alpha_p0"), "{e}");
}

/// The map method says which contacts its fallback characterized: the seed case at half its
/// loads (5000 rpm) has its light inner contact (ball 7, M ≈ 108 < 120) outside every map, so the
/// text names it under the contact table and the `method` column of contacts.csv (and the JSON's
/// contacts) reads `quasi-static (outside the map)` for it and `map` for the 21 others.
#[test]
fn the_map_method_names_the_contacts_of_its_fallback() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/7006.toml"
    ))
    .unwrap();
    assert_eq!(text.matches("= 1000.0").count(), 3);
    let case = dir.path().join("half.toml");
    std::fs::write(&case, text.replace("= 1000.0", "= 500.0")).unwrap();
    let out = dir.path().join("out");
    let o = bin()
        .arg("characterize")
        .arg(&case)
        .args(["--method", "map", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains(
            "method of the final laws: 21 by map; 1 by quasi-static (outside the map) (ball 7 inner)."
        ),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(out.join("contacts.csv")).unwrap();
    assert!(csv.lines().next().unwrap().ends_with(",method"), "{csv}");
    let methods: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(methods.len(), 22);
    assert_eq!(methods.iter().filter(|m| **m == "map").count(), 21, "{csv}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("characterization.json")).unwrap())
            .unwrap();
    let fallback: Vec<&serde_json::Value> = json["contacts"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["method"] != "map")
        .collect();
    assert_eq!(fallback.len(), 1);
    assert_eq!(fallback[0]["method"], "quasi-static (outside the map)");
    assert_eq!(fallback[0]["ball"], 7);
    assert_eq!(fallback[0]["race"], "inner");
}

/// The map method feeds the consumers of fitted laws: a load × speed study of the 218 example
/// (inside the second embedded map's envelope) converges at every point, fits its trend curves
/// and writes them; `coefficients --method map` writes ROSS's table. Milliseconds per point.
#[test]
fn map_method_feeds_studies_trends_and_coefficients() {
    let dir = tempfile::tempdir().unwrap();
    let case = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/218_high_speed.toml"
    );
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        format!(
            "case = {case:?}\nmethod = \"map\"\ninner_speeds_rpm = [10000.0, 15000.0]\n\
             load_scales = [0.7, 1.0, 1.3]\n"
        ),
    )
    .unwrap();
    let out = dir.path().join("out");
    bin()
        .args([
            "study",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .assert()
        .success();
    let points = std::fs::read_to_string(out.join("points.csv")).unwrap();
    let rows: Vec<&str> = points.lines().skip(1).collect();
    assert_eq!(rows.len(), 6, "{points}");
    assert!(
        rows.iter().all(|r| r.split(',').nth(2) == Some("true")),
        "{points}"
    );
    let trends: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("trends.json")).unwrap()).unwrap();
    assert_eq!(trends["method"]["name"], "map");
    let coef = dir.path().join("coef");
    bin()
        .args([
            "coefficients",
            case,
            "--method",
            "map",
            "--speeds",
            "10000,15000",
            "-o",
        ])
        .arg(&coef)
        .assert()
        .success();
    let ross = std::fs::read_to_string(coef.join("ross_bearing.csv")).unwrap();
    assert_eq!(ross.lines().count(), 3, "{ross}");
}

/// A stand-in for sbatch that records its arguments and prints job ids like `sbatch --parsable`.
fn fake_sbatch(dir: &std::path::Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let log = dir.join("sbatch.log");
    let path = dir.join("fake-sbatch");
    std::fs::write(
        &path,
        format!("#!/bin/sh\necho \"$*\" >> {log:?}\nn=$(wc -l < {log:?})\necho \"$((40 + n))\"\n"),
    )
    .unwrap();
    std::process::Command::new("chmod")
        .arg("+x")
        .arg(&path)
        .status()
        .unwrap();
    (path, log)
}

/// `law-map sbatch`: the array script's tasks generate the shards into the shared folder, a
/// resubmission sends only the shards with nodes left, then the assemble job alone, whose script
/// writes the map; invalid options are refused naming them.
#[test]
fn sbatch_runs_the_shards_as_array_tasks_and_resubmits_only_what_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("spec.toml");
    std::fs::write(&spec, SPEC).unwrap();
    let out = dir.path().join("nodes");
    let map = dir.path().join("map.json");
    let (sb, log) = fake_sbatch(dir.path());
    let submit = || {
        let o = bin()
            .args(["law-map", "sbatch"])
            .arg(&spec)
            .arg("-o")
            .arg(&out)
            .arg("--map")
            .arg(&map)
            .args([
                "--shards",
                "3",
                "--cpus-per-task",
                "1",
                "--submit",
                "--sbatch",
            ])
            .arg(&sb)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).to_string()
    };
    let o = submit();
    assert!(
        o.contains("27 nodes in 3 shards")
            && o.contains("submitted array job 41 (tasks 1-3) and assemble job 42"),
        "{o}"
    );
    let calls = std::fs::read_to_string(&log).unwrap();
    let lines: Vec<_> = calls.lines().collect();
    assert!(
        lines[0].starts_with("--parsable --array=1-3 ") && lines[0].ends_with("law_map.sbatch"),
        "{calls}"
    );
    assert!(
        lines[1].starts_with("--parsable --dependency=afterok:41 --kill-on-invalid-dep=yes ")
            && lines[1].ends_with("assemble.sbatch"),
        "{calls}"
    );
    let jobs = dir.path().join("nodes.slurm");
    let task = |i: &str| {
        let o = std::process::Command::new("bash")
            .arg(jobs.join("law_map.sbatch"))
            .env("SLURM_ARRAY_TASK_ID", i)
            .env("SLURM_CPUS_PER_TASK", "1")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).to_string()
    };
    // Task 2 ran: the resubmission sends tasks 1 and 3.
    let t = task("2");
    assert!(
        t.contains("shard 2/3: 9 nodes, 9 computed (0 failed)"),
        "{t}"
    );
    assert!(submit().contains("(tasks 1,3)"));
    task("1");
    task("3");
    let o = submit();
    assert!(
        o.contains("every node is done: submitting the assemble job only"),
        "{o}"
    );
    let calls = std::fs::read_to_string(&log).unwrap();
    let last = calls.lines().last().unwrap();
    assert!(
        last.starts_with("--parsable ")
            && last.ends_with("assemble.sbatch")
            && !last.contains("dependency"),
        "{last}"
    );
    let o = std::process::Command::new("bash")
        .arg(jobs.join("assemble.sbatch"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m =
        ehl_bearing::law_map::LawMap::from_json(&std::fs::read_to_string(&map).unwrap()).unwrap();
    assert_eq!(m.laws.len(), 27);
    sbatch_refuses_invalid_options(&spec, &out, &map);
}

/// `law-map sbatch` with invalid options: refused naming the option, the value and the range.
fn sbatch_refuses_invalid_options(
    spec: &std::path::Path,
    out: &std::path::Path,
    map: &std::path::Path,
) {
    for (args, want) in [
        (
            vec!["--shards", "0"],
            "--shards 0: expected an integer from 1 to 27",
        ),
        (
            vec!["--shards", "28"],
            "--shards 28: expected an integer from 1 to 27",
        ),
        (
            vec!["--cpus-per-task", "0"],
            "--cpus-per-task 0: expected an integer from 1 to 1024",
        ),
        (vec!["--job-name", "a b"], "--job-name \"a b\""),
    ] {
        let o = bin()
            .args(["law-map", "sbatch"])
            .arg(spec)
            .arg("-o")
            .arg(out)
            .arg("--map")
            .arg(map)
            .args(&args)
            .output()
            .unwrap();
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && e.contains(want), "{args:?}: {e}");
    }
    let o = bin()
        .args(["law-map", "sbatch"])
        .arg(spec)
        .arg("-o")
        .arg(out)
        .arg("--map")
        .arg(out.join("absent/map.json"))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("--map"), "{e}");
}

/// `law-map generate` warns when the spec's grid does not resolve the film of some nodes
/// (docs/ehl.md §5.9): low L, high M on 33² (NVM's film well below 10 ΔX²), least resolved node
/// named (whether a resolved spec stays silent is tested in the library: `under_resolved_nodes`
/// of the low-L example spec is empty).
#[test]
fn generate_warns_about_under_resolved_nodes() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("thin.toml");
    std::fs::write(
        &spec,
        r#"
viscosity_model = "roelands"
density_model = "dowson-higginson"
alpha_p0 = 2.9
ln_eta0_ratio = 4.1
l = 10.0
ry_over_rx = 14.0
amplitude = 0.2
points = 7
grid = 33

[[axis]]
group = "m"
min = 5000.0
max = 20000.0
nodes = 3
log = true
"#,
    )
    .unwrap();
    let o = bin()
        .args(["law-map", "generate"])
        .arg(&spec)
        .arg("-o")
        .arg(dir.path().join("thin_nodes"))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("does not resolve the film of 3 of 3 nodes") && e.contains("node 2, M = 20000"),
        "{e}"
    );
}

/// `law-map info` without files: the embedded maps in query order, as text or JSON (the same
/// summary); a file that does not exist or does not parse is named.
#[test]
fn info_lists_the_embedded_maps() {
    let maps = ehl_bearing::law_map::LawMap::embedded_maps();
    let o = bin().args(["law-map", "info"]).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let heads: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("embedded map"))
        .collect();
    assert_eq!(heads.len(), maps.len(), "{text}");
    assert!(
        heads[0].starts_with(&format!(
            "embedded map 1 of {} (seed_oil): quasi-static law, grid 129²",
            maps.len()
        )) && heads[maps.len() - 1].contains("harmonic law"),
        "{text}"
    );
    assert!(
        text.contains(
            "axes: M 120–4000 (17 nodes, log) · L 19–26 (5 nodes) · Ry/Rx 10–65 (9 nodes, log)"
        ),
        "{text}"
    );
    let o = bin().args(["law-map", "info", "--json"]).output().unwrap();
    let v: Vec<serde_json::Value> = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v.len(), maps.len());
    for (j, m) in v.iter().zip(maps) {
        assert_eq!(j["nodes"].as_u64(), Some(m.laws.len() as u64));
        assert_eq!(j["law"], m.spec.law.name());
        assert!(j["name"].as_str().is_some_and(|n| !n.is_empty()));
        assert_eq!(j["spec"]["grid"].as_u64(), Some(m.spec.grid as u64));
        assert!(j["worst_node_rms_hat"].as_f64().unwrap() > 0.0);
    }
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.bin");
    let o = bin()
        .args(["law-map", "info"])
        .arg(&missing)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("missing.bin"), "{err}");
    let junk = dir.path().join("junk.json");
    std::fs::write(&junk, "{}").unwrap();
    let o = bin().args(["law-map", "info"]).arg(&junk).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("junk.json") && err.contains("law map:"),
        "{err}"
    );
}

/// `law-map check SPEC --references DIR` computes the 2 held-out points' direct
/// characterizations into DIR; `law-map check MAP --references DIR` then reads them, computes
/// none and writes the same CSV as `check_csv` (made without a folder); a spec without
/// --references, or a folder holding another spec's references, is refused naming the reason.
fn references_from_the_spec(
    dir: &std::path::Path,
    spec: &std::path::Path,
    map: &std::path::Path,
    check_csv: &std::path::Path,
) {
    let refs = dir.join("refs");
    let check = |what: &std::path::Path, extra: &[&str]| {
        bin()
            .args(["law-map", "check"])
            .arg(what)
            .args(["--points", "2", "--threads", "1"])
            .args(extra)
            .output()
            .unwrap()
    };
    let r = refs.to_str().unwrap();
    let o = check(spec, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--references"), "{err}");
    let o = check(
        spec,
        &["--references", "/nonexistent-never", "--csv", "x.csv"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--csv") && err.contains("a spec, not a map"),
        "{err}"
    );
    assert!(!refs.exists(), "nothing created on a refused run");
    let o = check(spec, &["--references", r]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("2 computed, 0 read"),
        "{out}"
    );
    let csv = dir.join("check_refs.csv");
    let o = check(map, &["--references", r, "--csv", csv.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("0 computed, 2 read"),
        "{out}"
    );
    assert_eq!(
        std::fs::read(&csv).unwrap(),
        std::fs::read(check_csv).unwrap()
    );
    // Another spec's references under the same names: refused, nothing overwritten.
    let other = dir.join("other.toml");
    let text = std::fs::read_to_string(spec).unwrap();
    std::fs::write(&other, text.replace("amplitude = 0.2", "amplitude = 0.15")).unwrap();
    let o = check(&other, &["--references", r]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("different map"),
        "{err}"
    );
}
