//! `contact --method harmonic`: JSON keys, time history CSV, plots, and the errors a user meets.
//! Coarse grid (33²) and 16 steps per period keep it fast; the figures are in docs/contact.md.

use assert_cmd::Command;

const SEED: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../examples/contact_7006_inner.toml"
);

fn fast_harmonic() -> Vec<&'static str> {
    vec![
        "contact",
        SEED,
        "--method",
        "harmonic",
        "--grid",
        "33",
        "--steps-per-period",
        "16",
        "--settling-periods",
        "1",
    ]
}

/// Runs `ehl-bearing` with `args`, asserts that it fails, and returns its stderr.
fn failure<I, S>(args: I) -> String
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let out = Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    assert!(!out.status.success());
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn harmonic_json_history_and_plots() {
    let dir = std::env::temp_dir().join(format!("ehlb-contact-h-{}", std::process::id()));
    let out = Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(fast_harmonic())
        .args(["--step-tol-film", "2e-5"])
        .arg("--json")
        .arg("-o")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for k in [
        "method",
        "k",
        "d",
        "delta_f",
        "c",
        "std_errors",
        "r_squared",
        "rms_residual",
        "delta_range",
        "excitation",
        "converged",
        "seconds",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert_eq!(v["method"], "harmonic");
    assert!(
        v["c"].as_f64().unwrap() > 0.0,
        "squeeze damping is positive"
    );
    let e = &v["excitation"];
    assert_eq!(e["steps_per_period"], 16);
    assert_eq!(e["settling_periods"], 1);
    assert_eq!(e["step_tol_film"], 2e-5);
    // 7 mm AISI 52100 ball: 7850·π/6·(7e-3)³ kg.
    let m = 7850.0 * std::f64::consts::PI / 6.0 * 7e-3f64.powi(3);
    assert!((e["mass_kg"].as_f64().unwrap() / m - 1.0).abs() < 1e-12);
    // Its mass group Ψ_H, as the law maps compute it.
    let file =
        ehl_bearing::io::contact::parse_contact_file(&std::fs::read_to_string(SEED).unwrap())
            .unwrap();
    let psi = ehl_bearing::law_map::mass_group(&file.contact, m).unwrap();
    assert!(
        (e["mass_group_psi_h"].as_f64().unwrap() / psi - 1.0).abs() < 1e-9,
        "{e}"
    );
    // The default excitation (inside the rotor band).
    assert!((e["frequency_over_natural"].as_f64().unwrap() - 0.005).abs() < 1e-12);
    let [lo, hi] = [&v["delta_range"][0], &v["delta_range"][1]].map(|x| x.as_f64().unwrap());
    assert!(lo > 0.0 && hi > lo);

    let csv = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("time_s,load_n,approach_m,approach_rate_m_s,film_force_n,"));
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    // Settling: a quarter period (4 steps), then sixteenths (1 step) until the periodicity is
    // below its bound, at most one period; then one recorded period.
    let settling = e["settling_steps"].as_u64().unwrap() as usize;
    assert!((4..=16).contains(&settling), "{settling}");
    assert_eq!(rows.len(), settling + 16);
    assert_eq!(rows.iter().filter(|r| r[12] == "true").count(), 16);
    for stem in ["time_history", "force_approach"] {
        for ext in ["png", "svg"] {
            let p = dir.join(format!("{stem}.{ext}"));
            assert!(
                std::fs::metadata(&p).unwrap().len() > 1000,
                "{}",
                p.display()
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn harmonic_without_a_ball_mass_is_an_error_naming_the_keys() {
    let text = std::fs::read_to_string(SEED).unwrap();
    let text: String = text
        .lines()
        .filter(|l| !l.starts_with("ball_diameter_mm"))
        .map(|l| format!("{l}\n"))
        .collect();
    let f = std::env::temp_dir().join(format!("ehlb-nomass-{}.toml", std::process::id()));
    std::fs::write(&f, text).unwrap();
    let err = failure([
        std::ffi::OsStr::new("contact"),
        "--method".as_ref(),
        "harmonic".as_ref(),
        f.as_os_str(),
    ]);
    assert!(
        err.contains("ball_mass_kg") && err.contains("--mass-kg"),
        "{err}"
    );
    let _ = std::fs::remove_file(&f);
}

#[test]
fn harmonic_options_are_refused_for_the_quasi_static_method() {
    let err = failure(["contact", SEED, "--steps-per-period", "16"]);
    assert!(
        err.contains("--steps-per-period applies to --method harmonic only"),
        "{err}"
    );
    // Every harmonic-only option given is named.
    let err = failure([
        "contact",
        SEED,
        "--periodicity-tol",
        "0",
        "--mass-kg",
        "0.01",
    ]);
    assert!(
        err.contains("--periodicity-tol, --mass-kg apply to --method harmonic only"),
        "{err}"
    );
}

#[test]
fn invalid_periodicity_tol_names_the_option_and_value() {
    for (value, shown) in [("-1", "-1"), ("nan", "NaN")] {
        let mut args = fast_harmonic();
        let flag = format!("--periodicity-tol={value}");
        args.push(&flag);
        let err = failure(args);
        assert!(
            err.contains(&format!(
                "--periodicity-tol = {shown}: expected a finite number ≥ 0"
            )),
            "{err}"
        );
    }
}

#[test]
fn invalid_harmonic_setting_names_the_setting() {
    let mut args = fast_harmonic();
    args.push("--frequency-fraction=-0.5");
    let err = failure(args);
    assert!(
        err.contains("--frequency-fraction") && err.contains("-0.5"),
        "{err}"
    );
    // The step tolerance: named with its value and range; refused for the quasi-static method.
    let mut args = fast_harmonic();
    args.push("--step-tol-film=0.5");
    let err = failure(args);
    assert!(
        err.contains("--step-tol-film = 0.5") && err.contains("(0, 0.01]"),
        "{err}"
    );
    let err = failure(["contact", SEED, "--step-tol-film", "1e-6"]);
    assert!(
        err.contains("--step-tol-film applies to --method harmonic only"),
        "{err}"
    );
}

/// The quasi-static `contact` reports the Richardson film estimate by default (JSON `film`, one
/// more solution on the twice finer grid), `--no-film-extrapolation` leaves it out, and the flag
/// is refused for the harmonic method.
#[test]
fn quasi_static_film_estimate_in_json_and_its_flag() {
    let run = |extra: &[&str]| {
        Command::cargo_bin("ehl-bearing")
            .unwrap()
            .args(["contact", SEED, "--grid", "33", "--json"])
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let film = &v["film"];
    assert_eq!(film["grid_fine"], 65);
    for k in [
        "h_central",
        "approach",
        "h_central_fine",
        "approach_fine",
        "h_min_fine",
    ] {
        assert!(film[k].as_f64().is_some_and(|x| x > 0.0), "{k}: {film}");
    }
    let out = run(&["--no-film-extrapolation"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["film"].is_null());
    let mut args = fast_harmonic();
    args.push("--no-film-extrapolation");
    let err = failure(args);
    assert!(
        err.contains("--no-film-extrapolation applies to the quasi-static method only"),
        "{err}"
    );
}
