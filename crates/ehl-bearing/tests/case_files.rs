//! Case files: the seed parses to the paper's values; every invalid input is a clear error naming
//! the key, never a panic.

mod seeded;
use ehl_bearing::bearing::{Control, RaceControl};
use ehl_bearing::io::parse_case;
use proptest::prelude::*;

const SEED: &str = include_str!("../../../examples/7006.toml");

fn err(text: &str) -> String {
    parse_case(text, "test.toml").unwrap_err().to_string()
}

/// The seed with one line replaced (the line starting with `key =`), or a line appended to a table.
fn with(key: &str, line: &str) -> String {
    let mut out = Vec::new();
    let mut replaced = false;
    for l in SEED.lines() {
        if l.trim_start().starts_with(&format!("{key} =")) {
            out.push(line.to_string());
            replaced = true;
        } else {
            out.push(l.to_string());
        }
    }
    assert!(replaced, "no key {key}");
    out.join("\n")
}

#[test]
fn seed_case_reads_as_the_paper() {
    let c = parse_case(SEED, "7006.toml").unwrap();
    let g = &c.bearing.geometry;
    assert_eq!(g.ball_count, 11);
    assert!((g.ball_diameter - 7e-3).abs() < 1e-15);
    assert!((g.pitch_diameter - 42.5e-3).abs() < 1e-15);
    assert!((g.free_contact_angle - 15f64.to_radians()).abs() < 1e-15);
    assert!((c.operating.inner_speed - 5000.0 * std::f64::consts::PI / 30.0).abs() < 1e-12);
    assert_eq!(c.operating.dofs[0], Control::Load(1000.0));
    assert_eq!(
        c.operating.dofs[3],
        Control::Displacement(0.001f64.to_radians())
    );
    assert_eq!(c.operating.race_control, RaceControl::Outer);
    assert!(c.lubricant_given);
}

#[test]
fn minimal_case_uses_documented_defaults() {
    let c = parse_case(
        "[bearing]\nball_count = 9\nball_diameter_mm = 12.7\npitch_diameter_mm = 65.0\ninner_conformity = 0.52\nouter_conformity = 0.52\ndiametral_clearance_mm = 0.015\n",
        "min",
    )
    .unwrap();
    assert!(!c.lubricant_given);
    assert_eq!(c.operating.dofs, [Control::Load(0.0); 5]);
    assert_eq!(c.operating.inner_speed, 0.0);
    // cos α0 = 1 − P_d/(2(f_i + f_o − 1)D) = 1 − 0.015/(2·0.04·12.7)
    let expect = (1.0_f64 - 0.015 / (2.0 * 0.04 * 12.7)).acos();
    assert!((c.bearing.geometry.free_contact_angle - expect).abs() < 1e-12);
}

#[test]
fn ball_diameter_not_below_pitch() {
    let e = err(&with("ball_diameter_mm", "ball_diameter_mm = 42.5"));
    assert!(
        e.contains("bearing.ball_diameter_mm") && e.contains("swapped"),
        "{e}"
    );
}

#[test]
fn conformity_must_exceed_one_half() {
    let e = err(&with("inner_conformity", "inner_conformity = 0.5"));
    assert!(
        e.contains("bearing.inner_conformity") && e.contains("0.5"),
        "{e}"
    );
    let e = err(&with("outer_conformity", "outer_conformity = -1.0"));
    assert!(e.contains("bearing.outer_conformity"), "{e}");
}

#[test]
fn at_least_three_balls() {
    let e = err(&with("ball_count", "ball_count = 2"));
    assert!(e.contains("bearing.ball_count") && e.contains("3"), "{e}");
    let e = err(&with("ball_count", "ball_count = -4"));
    assert!(e.contains("bearing.ball_count"), "{e}");
}

#[test]
fn balls_must_not_overlap() {
    // Z·D ≥ π·dm: 20 balls of 7 mm on a 42.5 mm pitch circle overlap.
    let e = err(&with("ball_count", "ball_count = 20"));
    assert!(
        e.contains("bearing.ball_count") && e.contains("overlap"),
        "{e}"
    );
}

#[test]
fn nan_and_infinite_values_are_rejected() {
    let e = err(&with("pitch_diameter_mm", "pitch_diameter_mm = nan"));
    assert!(e.contains("bearing.pitch_diameter_mm"), "{e}");
    let e = err(&with("force_axial_n", "force_axial_n = inf"));
    assert!(e.contains("operating.force_axial_n"), "{e}");
    let e = err(&with("inner_speed_rpm", "inner_speed_rpm = -inf"));
    assert!(e.contains("operating.inner_speed_rpm"), "{e}");
    let e = err(&with("viscosity_pa_s", "viscosity_pa_s = nan"));
    assert!(e.contains("lubricant.viscosity_pa_s"), "{e}");
    let e = err(&with("poisson_ratio", "poisson_ratio = 0.7"));
    assert!(e.contains("ball_material.poisson_ratio"), "{e}");
}

#[test]
fn unknown_keys_are_rejected_with_their_name() {
    let e = err(&SEED.replace("[operating]", "[operating]\nforce_radial_n = 5.0"));
    assert!(e.contains("force_radial_n") && e.contains("line"), "{e}");
    let e = err(&format!("{SEED}\n[extra]\nx = 1\n"));
    assert!(e.contains("extra"), "{e}");
}

#[test]
fn tilt_given_as_moment_and_angle_is_a_conflict() {
    let e = err(&SEED.replace(
        "tilt_y_deg = 0.001",
        "tilt_y_deg = 0.001\nmoment_y_nm = 3.0",
    ));
    assert!(
        e.contains("operating.moment_y_nm") && e.contains("operating.tilt_y_deg"),
        "{e}"
    );
    let e = err(&SEED.replace(
        "force_y_n = 1000.0",
        "force_y_n = 1000.0\ndisplacement_y_mm = 0.01",
    ));
    assert!(e.contains("operating.displacement_y_mm"), "{e}");
}

#[test]
fn contact_angle_and_clearance_exclude_each_other_and_one_is_required() {
    let e = err(&SEED.replace(
        "contact_angle_deg = 15.0",
        "contact_angle_deg = 15.0\ndiametral_clearance_mm = 0.01",
    ));
    assert!(e.contains("diametral_clearance_mm"), "{e}");
    let e = err(&SEED.replace("contact_angle_deg = 15.0", ""));
    assert!(
        e.contains("bearing.contact_angle_deg") && e.contains("missing"),
        "{e}"
    );
    let e = err(&with("contact_angle_deg", "contact_angle_deg = 95.0"));
    assert!(e.contains("bearing.contact_angle_deg"), "{e}");
}

#[test]
fn wrong_types_and_enum_values_name_the_key() {
    let e = err(&with("race_control", "race_control = \"cage\""));
    assert!(e.contains("cage") && e.contains("outer"), "{e}");
    let e = err(&with("ball_count", "ball_count = \"eleven\""));
    assert!(e.contains("ball_count"), "{e}");
    let e = err(&with("tilt_y_deg", "tilt_y_deg = 5.0"));
    assert!(e.contains("operating.tilt_y_deg"), "{e}");
}

proptest! {
    #![proptest_config(seeded::config(400))]
    /// Arbitrary text never panics the parser.
    #[test]
    fn arbitrary_text_never_panics(s in "\\PC{0,400}") {
        let _ = parse_case(&s, "fuzz");
    }

    /// The seed with one numeric value replaced by an arbitrary float (including NaN, ±inf,
    /// negative, huge) either parses or gives an error naming a key; never a panic.
    #[test]
    fn any_value_in_any_field_never_panics(line in 0usize..60, v in prop::num::f64::ANY) {
        let lines: Vec<&str> = SEED.lines().collect();
        let l = line % lines.len();
        let text: String = lines
            .iter()
            .enumerate()
            .map(|(i, t)| {
                if i == l {
                    if let Some((k, _)) = t.split_once('=') {
                        let lit = if v.is_nan() { "nan".to_string() } else if v.is_infinite() { if v > 0.0 { "inf".into() } else { "-inf".into() } } else { format!("{v:e}") };
                        return format!("{k}= {lit}");
                    }
                }
                t.to_string()
            })
            .collect::<Vec<_>>()
            .join("\n");
        match parse_case(&text, "fuzz") {
            Ok(c) => prop_assert!(c.bearing.geometry.validate().is_ok()),
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
    }
}

/// A case given as tables (as from a Python dict) is the file's case, and is refused with the
/// file's messages: the one validation, no text written in between.
#[test]
fn a_case_given_as_tables_is_the_files_case_with_its_messages() {
    use ehl_bearing::io::case_from_table;
    for file in [
        "7006.toml",
        "7006_vg46.toml",
        "7205_vg68.toml",
        "218_high_speed.toml",
    ] {
        let path = format!("{}/../../examples/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        let table: toml::Table = text.parse().unwrap();
        let from_table = case_from_table(table, file).unwrap();
        let from_text = parse_case(&text, file).unwrap();
        assert_eq!(
            format!("{from_table:?}"),
            format!("{from_text:?}"),
            "{file}"
        );
    }
    let bad = |text: &str| {
        case_from_table(text.parse().unwrap(), "t")
            .unwrap_err()
            .to_string()
    };
    let unknown = bad(&with("ball_count", "ball_count = 11\nball_size_mm = 7.0"));
    assert!(unknown.contains("ball_size_mm"), "{unknown}");
    let range = bad(&with("ball_count", "ball_count = 2"));
    assert!(
        range.contains("bearing.ball_count") && range.contains('2') && range.contains("3 to 1000"),
        "{range}"
    );
    let kind = bad(&with("ball_count", "ball_count = \"eleven\""));
    assert!(
        kind.contains("ball_count") && kind.contains("eleven"),
        "{kind}"
    );
}
