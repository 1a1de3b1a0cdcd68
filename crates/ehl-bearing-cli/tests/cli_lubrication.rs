//! The lubrication report (docs/lubricant.md) in the CLI: `equilibrium` and `characterize` carry it
//! for a described oil (JSON key, table, stderr warnings, `-o` lubrication.csv) and not for the
//! seed given by its constants; an invalid description names its key.

use assert_cmd::Command;
use serde_json::Value;

const SEED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/7006.toml");
const VG46: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/7006_vg46.toml");

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

/// Run `ehl-bearing study` with the dry method on `case` at the given speeds and load scales
/// (TOML arrays) in `dir`; the output folder and stdout.
fn hertz_study(
    dir: &std::path::Path,
    case: &std::path::Path,
    speeds: &str,
    scales: &str,
) -> (std::path::PathBuf, String) {
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        format!(
            "case = \"{}\"\nmethod = \"hertz\"\ninner_speeds_rpm = {speeds}\nload_scales = {scales}\n",
            case.display()
        ),
    )
    .unwrap();
    let outdir = dir.join("out");
    let out = bin()
        .arg("study")
        .arg(&study)
        .arg("-o")
        .arg(&outdir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (outdir, String::from_utf8_lossy(&out.stdout).into_owned())
}

#[test]
fn equilibrium_reports_the_lubrication_of_a_described_oil_only() {
    let out = bin()
        .args(["equilibrium", VG46, "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let l = &v["lubrication"];
    assert_eq!(l["contacts"].as_array().unwrap().len(), 22);
    assert_eq!(l["oil"]["iso_vg"], 46);
    assert!(l["oil"]["sources"].as_array().unwrap().len() >= 9);
    assert!(l["kappa"].as_f64().unwrap() > 4.0);
    assert!(l["min_lambda"].as_f64().unwrap() > 3.0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("inlet shear heating"), "{stderr}");
    let table = bin().args(["equilibrium", VG46]).output().unwrap();
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(
        text.contains("ISO VG 46 mineral oil") && text.contains("κ = "),
        "{text}"
    );
    let seed = bin()
        .args(["equilibrium", SEED, "--json"])
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&seed.stdout).unwrap();
    assert!(v.get("lubrication").is_none());
}

#[test]
fn characterize_writes_lubrication_csv() {
    let dir = tempfile::tempdir().unwrap();
    let out = bin()
        .args(["characterize", VG46, "--method", "hertz", "--json", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["lubrication"]["contacts"].as_array().unwrap().len(), 22);
    let csv = std::fs::read_to_string(dir.path().join("lubrication.csv")).unwrap();
    assert_eq!(csv.lines().count(), 23);
    assert!(csv.starts_with("ball,race,load_n,"));
    let saved: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("characterization.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(saved["lubrication"], v["lubrication"]);
}

#[test]
fn an_invalid_description_names_its_key() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(VG46)
        .unwrap()
        .replace("iso_vg = 46", "iso_vg = 47");
    let path = dir.path().join("case.toml");
    std::fs::write(&path, text).unwrap();
    let out = bin().arg("equilibrium").arg(&path).output().unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("lubricant.iso_vg = 47"), "{stderr}");
}

/// With `--film` the films (and Λ) are those of the steady EHL solutions.
#[test]
fn equilibrium_film_uses_the_ehl_solutions() {
    let out = bin()
        .args(["equilibrium", VG46, "--film", "--grid", "65", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let l = &v["lubrication"];
    let sigma = l["composite_roughness_m"].as_f64().unwrap();
    for (j, b) in v["balls"].as_array().unwrap().iter().enumerate() {
        for (k, race) in ["inner", "outer"].iter().enumerate() {
            let c = &l["contacts"][2 * j + k];
            assert_eq!(c["film_source"], "ehl-solution", "ball {j} {race}");
            let h = b[race]["film"]["h_min"].as_f64().unwrap();
            assert_eq!(c["min_film_m"].as_f64().unwrap(), h);
            let lambda = c["lambda"].as_f64().unwrap();
            assert!((lambda - c["min_film_m"].as_f64().unwrap() / sigma).abs() < 1e-9);
        }
    }
}

/// Ring temperatures: each raceway's contacts at its ring's oil (`oil_temperature_c`, the JSON's
/// `ring_oils`, a table line per ring); a missing one is named.
#[test]
fn ring_temperatures_reach_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(VG46).unwrap().replace(
        "temperature_c = 40.0",
        "temperature_c = 40.0\ninner_ring_temperature_c = 50.0\nouter_ring_temperature_c = 45.0",
    );
    let path = dir.path().join("case.toml");
    std::fs::write(&path, &text).unwrap();
    let out = bin()
        .arg("equilibrium")
        .arg(&path)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let l = &v["lubrication"];
    assert_eq!(l["ring_oils"]["inner"]["temperature_c"], 50.0);
    assert_eq!(l["ring_oils"]["outer"]["temperature_c"], 45.0);
    for c in l["contacts"].as_array().unwrap() {
        let want = if c["race"] == "inner" { 50.0 } else { 45.0 };
        assert_eq!(c["oil_temperature_c"], want);
    }
    let table = bin().arg("equilibrium").arg(&path).output().unwrap();
    let t = String::from_utf8_lossy(&table.stdout);
    assert!(
        t.contains("inner ring at 50 °C") && t.contains("outer ring at 45 °C"),
        "{t}"
    );
    std::fs::write(&path, text.replace("outer_ring_temperature_c = 45.0", "")).unwrap();
    let bad = bin().arg("equilibrium").arg(&path).output().unwrap();
    assert!(!bad.status.success());
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(e.contains("operating.outer_ring_temperature_c"), "{e}");
}

/// A study of the described-oil case through the command: `results.csv` and `points.csv` carry
/// the lubrication columns (docs/lubricant.md §2.5).
#[test]
fn study_tables_carry_the_lubrication_columns() {
    let dir = tempfile::tempdir().unwrap();
    let (outdir, stdout) = hertz_study(dir.path(), VG46.as_ref(), "[3000, 5000]", "[1.0]");
    assert!(
        stdout.contains("smallest Λ") && stdout.contains("largest thermal film reduction"),
        "{stdout}"
    );
    let results = std::fs::read_to_string(outdir.join("results.csv")).unwrap();
    let header = results.lines().next().unwrap();
    assert!(
        header.ends_with(",central_film_m,min_film_m,lambda,thermal_reduction,min_film_thermal_m"),
        "{header}"
    );
    assert_eq!(results.lines().count(), 1 + 2 * 22);
    let points = std::fs::read_to_string(outdir.join("points.csv")).unwrap();
    let mut lines = points.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let lambda: f64 = cells[col("min_lambda")].parse().unwrap();
        assert!(lambda > 1.0, "{line}");
        assert!(["inner", "outer"].contains(&cells[col("min_lambda_race")]));
        let kappa: f64 = cells[col("kappa")].parse().unwrap();
        assert!(kappa > 1.0, "{line}");
    }
}

/// An oil supply (`operating.inlet_meniscus_distance_mm`) reaches every output: the JSON's
/// per-contact `starvation`, the table's columns, `lubrication.csv`, and a study's
/// `results.csv`/`points.csv` columns and summary line (docs/lubricant.md §3).
#[test]
fn an_oil_supply_reaches_json_table_csv_and_study() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(VG46).unwrap().replace(
        "temperature_c = 40.0",
        "temperature_c = 40.0\ninlet_meniscus_distance_mm = 0.25",
    );
    assert!(text.contains("inlet_meniscus_distance_mm"));
    let case = dir.path().join("starved.toml");
    std::fs::write(&case, text).unwrap();
    let out = bin()
        .args(["characterize", "--method", "hertz", "--json", "-o"])
        .arg(dir.path().join("ch"))
        .arg(&case)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let l = &v["lubrication"];
    assert_eq!(l["inlet_meniscus_distance_m"].as_f64(), Some(2.5e-4));
    let worst = l["max_starvation_reduction"].as_f64().unwrap();
    assert!(worst > 0.05 && worst < 0.5, "{worst}");
    let s = &l["contacts"][1]["starvation"];
    assert!(s["inlet_distance_ratio"].as_f64().unwrap() > 1.0, "{s}");
    let csv = std::fs::read_to_string(dir.path().join("ch/lubrication.csv")).unwrap();
    assert!(csv
        .lines()
        .next()
        .unwrap()
        .contains(",starvation_reduction,min_film_starved_m,flags"));
    let table = bin().args(["equilibrium"]).arg(&case).output().unwrap();
    let t = String::from_utf8_lossy(&table.stdout);
    assert!(
        t.contains("oil supply: meniscus at 0.250 mm") && t.contains("h_min,S"),
        "{t}"
    );
    let (outdir, stdout) = hertz_study(dir.path(), &case, "[3000]", "[1.0, 2.0]");
    assert!(
        stdout.contains("starvation: largest reduction of the minimum film"),
        "{stdout}"
    );
    let results = std::fs::read_to_string(outdir.join("results.csv")).unwrap();
    assert!(results.lines().next().unwrap().ends_with(
        ",min_film_thermal_m,inlet_distance_ratio,starvation_reduction,min_film_starved_m"
    ));
    let points = std::fs::read_to_string(outdir.join("points.csv")).unwrap();
    let mut lines = points.lines();
    assert!(lines
        .next()
        .unwrap()
        .ends_with(",lubrication_warnings,max_starvation_reduction"));
    for line in lines {
        let x: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
        assert!(x > 0.0 && x < 1.0, "{line}");
    }
}
