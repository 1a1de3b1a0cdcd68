//! The `equilibrium` command: JSON shape and units, readable table, errors with exit codes.

use assert_cmd::Command;
use serde_json::Value;

const SEED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/7006.toml");

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

#[test]
fn json_has_the_documented_shape_in_si_units() {
    let out = bin()
        .args(["equilibrium", SEED, "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["converged"], Value::Bool(true));
    assert!(v["iterations"].as_u64().unwrap() >= 1);
    for k in ["x", "y", "z", "theta_y", "theta_z"] {
        assert!(v["displacement"][k].is_f64(), "{k}");
    }
    // Imposed tilts come back as given, in rad.
    let tilt = v["displacement"]["theta_y"].as_f64().unwrap();
    assert!((tilt - 0.001f64.to_radians()).abs() < 1e-15);
    for k in ["force_x", "force_y", "force_z"] {
        assert!(
            (v["reaction"][k].as_f64().unwrap() - 1000.0).abs() < 1e-6,
            "{k}"
        );
    }
    for k in ["moment_y", "moment_z"] {
        assert!(v["reaction"][k].is_f64());
    }
    let k = v["stiffness"].as_array().unwrap();
    assert_eq!(k.len(), 5);
    assert!(k.iter().all(|r| r.as_array().unwrap().len() == 5));
    let balls = v["balls"].as_array().unwrap();
    assert_eq!(balls.len(), 11);
    assert_eq!(balls[0]["azimuth"].as_f64().unwrap(), 0.0);
    let step = balls[1]["azimuth"].as_f64().unwrap();
    assert!((step - 2.0 * std::f64::consts::PI / 11.0).abs() < 1e-12);
    for b in balls {
        assert!(b["orbital_speed"].is_f64() && b["spin_speed"].is_f64());
        for race in ["inner", "outer"] {
            for key in [
                "load",
                "contact_angle",
                "deflection",
                "semi_major",
                "semi_minor",
                "max_pressure",
                "rx",
                "ry",
                "sum_velocity",
            ] {
                assert!(b[race][key].is_f64(), "{race}.{key}");
            }
        }
    }
    // SI: contact angles in rad (~0.34), loads in N, radii in m, pressure in Pa.
    let c = &balls[1]["inner"];
    assert!(c["contact_angle"].as_f64().unwrap() < 0.5);
    assert!(c["rx"].as_f64().unwrap() < 0.01);
    assert!(c["max_pressure"].as_f64().unwrap() > 1e8);
}

#[test]
fn table_is_readable_with_engineering_units() {
    let out = bin().args(["equilibrium", SEED]).output().unwrap();
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    for needle in ["7006", "5000 rpm", "µm", "Q_i N", "GPa", "stiffness matrix"] {
        assert!(s.contains(needle), "missing {needle} in\n{s}");
    }
}

#[test]
fn bad_input_exits_non_zero_with_the_field_named() {
    let dir = std::env::temp_dir().join(format!("ehlb-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    let seed = std::fs::read_to_string(SEED).unwrap();
    std::fs::write(
        &bad,
        seed.replace("inner_conformity = 0.51", "inner_conformity = 0.49"),
    )
    .unwrap();
    let out = bin()
        .args(["equilibrium", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("bearing.inner_conformity") && err.contains("0.49"),
        "{err}"
    );
    let out = bin()
        .args(["equilibrium", "/no/such/file.toml"])
        .output()
        .unwrap();
    assert!(!out.status.success());
}

#[test]
fn film_option_reports_ehl_films_of_every_contact() {
    // Coarse grid for speed: the check is that every loaded contact gets a converged film with
    // h_min < h_c, in m, of the order of a micrometre for the seed (docs/ehl.md has the accuracy).
    let out = bin()
        .args(["equilibrium", SEED, "--json", "--film", "--grid", "65"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    for b in v["balls"].as_array().unwrap() {
        for race in ["inner", "outer"] {
            let f = &b[race]["film"];
            assert_eq!(f["converged"], Value::Bool(true), "{f}");
            let (hc, hm) = (
                f["h_central"].as_f64().unwrap(),
                f["h_min"].as_f64().unwrap(),
            );
            assert!(hm > 0.0 && hm < hc && hc > 1e-7 && hc < 2e-6, "{hc} {hm}");
            assert!(f["moes_m"].as_f64().unwrap() > 10.0);
        }
    }
}
