//! Helpers shared by the study tests (included with `mod`).
#![allow(dead_code)]

use assert_cmd::cargo::CommandCargoExt;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub const SEED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/7006.toml");

/// Run the `ehl-bearing` binary with `args`.
pub fn run(args: &[&str]) -> Output {
    Command::cargo_bin("ehl-bearing")
        .unwrap()
        .args(args)
        .output()
        .unwrap()
}

/// Assert that `o` succeeded (showing its stdout and stderr if not) and return its stdout.
pub fn ok(o: Output) -> String {
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).to_string()
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Write a study file into `dir` and return its path.
pub fn study_file(dir: &Path, method: &str, speeds: &str, scales: &str, extra: &str) -> PathBuf {
    let path = dir.join("study.toml");
    let text = format!(
        "case = {SEED:?}\nmethod = \"{method}\"\ninner_speeds_rpm = {speeds}\nload_scales = {scales}\n{extra}"
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// Every file under `dir` (relative path → bytes).
pub fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().to_string();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// Assert two output folders hold the same files with the same bytes.
pub fn assert_same_tree(a: &Path, b: &Path) {
    let ta = tree(a);
    let tb = tree(b);
    assert_eq!(
        ta.keys().collect::<Vec<_>>(),
        tb.keys().collect::<Vec<_>>(),
        "file lists differ"
    );
    for (name, bytes) in &ta {
        assert!(bytes == &tb[name], "{name} differs");
    }
}
