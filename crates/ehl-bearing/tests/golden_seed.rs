//! Golden regression: the seed characterization (quasi-static method, defaults) gives the laws
//! and displacements recorded in `tests/golden/seed_characterization.json` (written by
//! `ehl-bearing characterize examples/7006.toml --json` at commit 3f52913, before the library
//! was restructured), to every digit its JSON prints: the restructuring changed no number.
//!
//! The fixture changes only with a deliberate change of physics or defaults, and the commit
//! that changes it says which.

use ehl_bearing::characterize::{characterize_bearing, CharacterizeSettings};
use ehl_bearing::io::read_case;
use ehl_bearing::method::Method;
use serde_json::Value;
use std::path::Path;

#[test]
fn seed_characterization_matches_the_golden_laws_and_displacements() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let golden: Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("tests/golden/seed_characterization.json")).unwrap(),
    )
    .unwrap();
    let case = read_case(&root.join("../../examples/7006.toml")).unwrap();
    let c =
        characterize_bearing(&case, &Method::default(), &CharacterizeSettings::default()).unwrap();
    let report = serde_json::to_value(c.report(false)).unwrap();
    assert_eq!(report["iterations"], golden["iterations"]);
    for key in ["displacement", "dry_displacement", "stiffness_ehl"] {
        assert_eq!(report[key], golden[key], "{key}");
    }
    let contacts = report["contacts"].as_array().unwrap();
    let want = golden["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), want.len());
    for (got, want) in contacts.iter().zip(want) {
        for (key, value) in want.as_object().unwrap() {
            assert_eq!(
                &got[key], value,
                "ball {} {} {key}",
                want["ball"], want["race"]
            );
        }
    }
}
