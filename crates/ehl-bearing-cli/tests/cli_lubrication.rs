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
