//! The typed characterization methods (`ehl_bearing::method::Method`): one parser and one set of
//! ranges for case files, study files, the command line and the bindings; errors name the key,
//! the value and the range; settings round-trip through JSON; no input panics.

mod seeded;
use ehl_bearing::method::{Method, MethodError, GRID_RANGE};
use proptest::prelude::*;

fn parse(name: &str, options: &str) -> Result<Method, MethodError> {
    let table: toml::Table = toml::from_str(options).unwrap();
    Method::parse(name, Some(&table))
}

#[test]
fn names_defaults_and_options() {
    assert_eq!(Method::NAMES, ["quasi-static", "harmonic", "hertz", "map"]);
    assert_eq!(Method::default().name(), "quasi-static");
    for name in Method::NAMES {
        let m = Method::parse(name, None).unwrap();
        assert_eq!(m.name(), name);
        m.validate().unwrap();
    }
    // The test fixture is accepted by name but not listed.
    assert_eq!(
        Method::parse("synthetic", None).unwrap().name(),
        "synthetic"
    );
    let Method::QuasiStatic(q) =
        parse("quasi-static", "amplitude = 0.1\npoints = 9\ngrid = 257").unwrap()
    else {
        panic!()
    };
    assert_eq!((q.amplitude, q.points, q.ehl.grid), (0.1, 9, 257));
    let Method::Harmonic(h) = parse(
        "harmonic",
        "frequency_fraction = 0.2\nsteps_per_period = 32\nsettling_periods = 1\nmass_kg = 1e-3\ndamping_term = false\nstep_tol_film = 7e-7",
    )
    .unwrap() else {
        panic!()
    };
    assert_eq!(h.steps_per_period, 32);
    assert_eq!(h.settling_periods, 1);
    assert_eq!(h.mass, Some(1e-3));
    assert!(!h.damping_term);
    assert_eq!(h.step_tol_film, Some(7e-7));
}

#[test]
fn errors_name_the_key_the_value_and_the_range() {
    let cases = [
        (
            "quasi-static",
            "grid = 100",
            "method_options.grid",
            "100",
            "2^k + 1 from 17 to 1025",
        ),
        (
            "quasi-static",
            "grid = 2049",
            "method_options.grid",
            "2049",
            "17 to 1025",
        ),
        (
            "quasi-static",
            "amplitude = 0.95",
            "method_options.amplitude",
            "0.95",
            "≤ 0.9",
        ),
        (
            "quasi-static",
            "points = 3",
            "method_options.points",
            "3",
            "4 to 101",
        ),
        (
            "harmonic",
            "amplitude = 1.0",
            "method_options.amplitude",
            "1",
            "≤ 0.9",
        ),
        (
            "harmonic",
            "steps_per_period = 4",
            "method_options.steps_per_period",
            "4",
            "8 to 4096",
        ),
        (
            "harmonic",
            "frequency_fraction = 0.0",
            "method_options.frequency_fraction",
            "0",
            "≤ 10",
        ),
        (
            "harmonic",
            "step_tol_film = 0.05",
            "method_options.step_tol_film",
            "0.05",
            "(0, 0.01]",
        ),
        (
            "harmonic",
            "mass_kg = -1.0",
            "method_options.mass_kg",
            "-1",
            "> 0",
        ),
        (
            "hertz",
            "samples = 2",
            "method_options.samples",
            "2",
            "4 to 10000",
        ),
        (
            "hertz",
            "amplitude = 1.0",
            "method_options.amplitude",
            "1",
            "< 1",
        ),
    ];
    for (name, opts, key, value, range) in cases {
        let e = parse(name, opts).unwrap_err().to_string();
        assert!(e.contains(key), "{name} {opts}: {e}");
        assert!(e.contains(value), "{name} {opts}: {e}");
        assert!(e.contains(range), "{name} {opts}: {e}");
    }
    // Unknown keys and wrong types name the key.
    let e = parse("quasi-static", "gird = 129").unwrap_err().to_string();
    assert!(e.contains("gird"), "{e}");
    let e = parse("hertz", "grid = 129").unwrap_err().to_string();
    assert!(e.contains("grid"), "hertz has no grid: {e}");
    let e = parse("quasi-static", "grid = \"fine\"")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("method_options.grid") && e.contains("fine"),
        "{e}"
    );
    let e = parse(
        "harmonic",
        "frequency_fraction = 0.1\nfrequency_rad_s = 100.0",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("not both"), "{e}");
    let e = Method::parse("magic", None).unwrap_err().to_string();
    assert!(
        e.contains("magic") && e.contains("quasi-static, harmonic, hertz"),
        "{e}"
    );
    // The grid range is the EHL solver's.
    assert_eq!(GRID_RANGE, (17, 1025));
}

#[test]
fn methods_round_trip_through_json() {
    for m in [
        Method::parse("quasi-static", None).unwrap(),
        parse("harmonic", "frequency_rad_s = 2.5e4\ngrid = 65").unwrap(),
        Method::parse("hertz", None).unwrap(),
        Method::parse("synthetic", None).unwrap(),
    ] {
        let json = serde_json::to_string(&m).unwrap();
        let back: Method = serde_json::from_str(&json).unwrap();
        assert_eq!(back, m, "{json}");
        assert!(
            json.starts_with(&format!("{{\"name\":\"{}\"", m.name())),
            "{json}"
        );
    }
}

proptest! {
    #![proptest_config(seeded::config(512))]
    #[test]
    fn arbitrary_options_never_panic(
        name in prop::sample::select(vec!["quasi-static", "harmonic", "hertz", "synthetic", "x"]),
        key in prop::sample::select(vec![
            "amplitude", "points", "grid", "samples", "frequency_fraction", "frequency_rad_s",
            "settling_periods", "recorded_periods", "steps_per_period", "mass_kg",
            "damping_term", "load_ref", "bogus",
        ]),
        value in prop_oneof![
            any::<f64>().prop_map(toml::Value::Float),
            any::<i64>().prop_map(toml::Value::Integer),
            any::<bool>().prop_map(toml::Value::Boolean),
            "[a-z]{0,5}".prop_map(toml::Value::String),
        ],
    ) {
        let mut t = toml::Table::new();
        t.insert(key.to_string(), value);
        if let Ok(m) = Method::parse(name, Some(&t)) {
            // Whatever parses is valid, and serializes.
            prop_assert!(m.validate().is_ok());
            prop_assert!(serde_json::to_string(&m).is_ok());
        }
    }
}

#[test]
fn case_files_carry_a_method_that_the_command_line_can_override() {
    let seed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/7006.toml"
    ))
    .unwrap();
    let with = |head: &str| ehl_bearing::io::parse_case(&format!("{head}\n{seed}"), "t.toml");
    let c = with("method = \"harmonic\"\n[method_options]\nsteps_per_period = 32").unwrap();
    let Some(Method::Harmonic(h)) = c.method else {
        panic!("{:?}", c.method)
    };
    assert_eq!(h.steps_per_period, 32);
    assert_eq!(c.method_or(None).unwrap(), Method::Harmonic(h));
    assert_eq!(c.method_or(Some("harmonic")).unwrap(), Method::Harmonic(h));
    assert_eq!(c.method_or(Some("hertz")).unwrap().name(), "hertz");
    assert!(c
        .method_or(Some("magic"))
        .unwrap_err()
        .to_string()
        .contains("magic"));
    let plain = with("").unwrap();
    assert_eq!(plain.method, None);
    assert_eq!(plain.method_or(None).unwrap(), Method::default());
    // Errors name the key, the value and the range; options without a method are refused.
    let e = with("method = \"quasi-static\"\n[method_options]\ngrid = 100").unwrap_err();
    assert!(e.to_string().contains("method_options.grid"), "{e}");
    let e = with("[method_options]\ngrid = 257").unwrap_err();
    assert!(e.to_string().contains("method"), "{e}");
    let e = with("method = \"fast\"").unwrap_err();
    assert!(
        e.to_string().contains("fast") && e.to_string().contains("quasi-static"),
        "{e}"
    );
}

/// The steps' multigrid settings of a harmonic method built in code (they are not
/// `[method_options]` keys) are checked with the rest before any solve: a coarsest level that is
/// not 2^k + 1 in 9–1025, or 0 sweeps, names the setting, the value and the range.
#[test]
fn harmonic_step_multigrid_settings_are_validated() {
    use ehl_bearing::contact::HarmonicSettings;
    for (s, field, value, range) in [
        (
            HarmonicSettings {
                step_coarsest: 16,
                ..HarmonicSettings::default()
            },
            "step_coarsest",
            "16",
            "2^k + 1 from 9 to 1025",
        ),
        (
            HarmonicSettings {
                step_coarse_sweeps: 0,
                ..HarmonicSettings::default()
            },
            "step_coarse_sweeps",
            "0",
            "1 to 100",
        ),
    ] {
        let msg = Method::Harmonic(s).validate().unwrap_err().to_string();
        assert!(
            msg.contains(field) && msg.contains(value) && msg.contains(range),
            "{msg}"
        );
    }
    assert!(Method::Harmonic(HarmonicSettings::default())
        .validate()
        .is_ok());
}
