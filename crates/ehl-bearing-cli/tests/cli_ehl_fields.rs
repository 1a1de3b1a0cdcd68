//! `ehl --fields DIR`: field CSVs and the pictures (pressure and film maps, centre lines).

use assert_cmd::Command;

#[test]
fn fields_writes_csv_and_pictures() {
    let contact = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/contact_7006_inner.toml"
    );
    let dir = std::env::temp_dir().join(format!("ehlb-fields-{}", std::process::id()));
    let out = Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(["ehl", contact, "--grid", "65", "--fields"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["pressure.csv", "film.csv"] {
        let text = std::fs::read_to_string(dir.join(f)).unwrap();
        assert!(text.starts_with("x_m,y_m,value\n"));
        assert_eq!(text.lines().count(), 65 * 65 + 1, "{f}");
    }
    for stem in [
        "pressure_map",
        "film_map",
        "centreline_rolling",
        "centreline_transverse",
    ] {
        let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}");
        let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.contains("<svg"), "{stem}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
