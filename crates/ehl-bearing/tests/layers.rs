//! The layer lint: a module of the library imports (`use crate::x`, `crate::x::` paths) only
//! modules on lower floors of the table `crates/ehl-bearing/layers.txt` (explained in
//! `docs/architecture.md`). The imports that still run back up are listed below, each with its
//! reason; a new one fails the test, and so does an entry that no longer occurs, so the list can
//! only shrink. `scripts/architecture_metrics.py` counts the same imports.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Imports running back up that are known, as (from, to, reason).
const ALLOWED: &[(&str, &str, &str)] = &[];

struct Layers {
    floor: BTreeMap<String, u32>,
    any: BTreeSet<String>,
}

fn layers() -> Layers {
    let text = include_str!("../layers.txt");
    let mut floor = BTreeMap::new();
    let mut any = BTreeSet::new();
    for raw in text.lines() {
        let line = raw.split('#').next().unwrap().trim();
        if line.is_empty() {
            continue;
        }
        let (key, mods) = line.split_once(':').expect("layers.txt: `floor: modules`");
        for m in mods.split_whitespace() {
            if key.trim() == "any" {
                any.insert(m.to_string());
            } else {
                let f: u32 = key.trim().parse().expect("layers.txt: a floor number");
                assert!(
                    floor.insert(m.to_string(), f).is_none(),
                    "{m} twice in layers.txt"
                );
            }
        }
    }
    Layers { floor, any }
}

/// The source with comments and the contents of string and char literals blanked (newlines
/// kept), so that paths in doc comments and messages are not taken for imports.
fn blank(text: &str) -> Vec<char> {
    let s: Vec<char> = text.chars().collect();
    let mut out = s.clone();
    let n = s.len();
    let wipe = |out: &mut Vec<char>, a: usize, b: usize| {
        for c in out.iter_mut().take(b.min(n)).skip(a) {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    let starts = |i: usize, p: &str| p.chars().enumerate().all(|(k, c)| s.get(i + k) == Some(&c));
    let mut i = 0;
    while i < n {
        if starts(i, "//") {
            let mut j = i;
            while j < n && s[j] != '\n' {
                j += 1;
            }
            wipe(&mut out, i, j);
            i = j;
        } else if starts(i, "/*") {
            let (mut depth, mut j) = (1, i + 2);
            while j < n && depth > 0 {
                if starts(j, "/*") {
                    depth += 1;
                    j += 2;
                } else if starts(j, "*/") {
                    depth -= 1;
                    j += 2;
                } else {
                    j += 1;
                }
            }
            wipe(&mut out, i, j);
            i = j;
        } else if s[i] == 'r'
            && (i == 0 || !(s[i - 1].is_alphanumeric() || s[i - 1] == '_'))
            && matches!(s.get(i + 1), Some('"') | Some('#'))
        {
            let mut j = i + 1;
            let mut hashes = 0;
            while j < n && s[j] == '#' {
                hashes += 1;
                j += 1;
            }
            if j >= n || s[j] != '"' {
                i += 1;
                continue;
            }
            let body = j + 1;
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat('#').take(hashes))
                .collect();
            let mut k = body;
            while k < n && !starts(k, &close) {
                k += 1;
            }
            wipe(&mut out, body, k);
            i = k + close.chars().count();
        } else if s[i] == '"' {
            let mut j = i + 1;
            while j < n && s[j] != '"' {
                j += if s[j] == '\\' { 2 } else { 1 };
            }
            wipe(&mut out, i + 1, j);
            i = j + 1;
        } else if s[i] == '\'' {
            if s.get(i + 1) == Some(&'\\') {
                let mut j = i + 2;
                while j < n && s[j] != '\'' {
                    j += 1;
                }
                wipe(&mut out, i + 1, j);
                i = j + 1;
            } else if s.get(i + 2) == Some(&'\'') {
                wipe(&mut out, i + 1, i + 2);
                i += 3;
            } else {
                i += 1; // a lifetime
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The code with `#[cfg(test)]` modules blanked too.
fn without_test_modules(mut code: Vec<char>) -> Vec<char> {
    let text: String = code.iter().collect();
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let byte_to_char = |b: usize| chars.partition_point(|(i, _)| *i < b);
    let mut from = 0;
    while let Some(p) = text[from..].find("#[cfg(test)]") {
        let at = from + p;
        let rest = &text[at + "#[cfg(test)]".len()..];
        let trimmed = rest.trim_start();
        let after_pub = trimmed
            .strip_prefix("pub ")
            .map(str::trim_start)
            .unwrap_or(trimmed);
        let semi = rest.find(';').unwrap_or(usize::MAX);
        let brace = rest.find('{').filter(|b| *b < semi);
        if let (true, Some(brace)) = (after_pub.starts_with("mod "), brace) {
            let open = byte_to_char(at + "#[cfg(test)]".len() + brace);
            let mut depth = 0;
            let mut k = open;
            while k < code.len() {
                match code[k] {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                k += 1;
            }
            for c in code.iter_mut().take(k + 1).skip(byte_to_char(at)) {
                if *c != '\n' {
                    *c = ' ';
                }
            }
        }
        from = at + 1;
    }
    code
}

fn rs_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rs_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

fn top_module(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy()
        .to_string();
    first.strip_suffix(".rs").unwrap_or(&first).to_string()
}

/// Items re-exported at the crate root, and the module that owns them.
fn root_item_owner(name: &str) -> &str {
    match name {
        "Error" | "Result" => "error",
        "ContactLaw" | "HertzLaw" => "contact_law",
        other => other,
    }
}

/// (from, to) → the places (file:line) of `crate::to` paths in module `from`.
fn imports() -> BTreeMap<(String, String), Vec<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rs_files(&src, &mut files);
    let mut edges: BTreeMap<(String, String), Vec<String>> = BTreeMap::new();
    for file in files {
        let from = top_module(&src, &file);
        if from == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let code: String = without_test_modules(blank(&text)).into_iter().collect();
        for (ln, line) in code.lines().enumerate() {
            let mut rest = line;
            while let Some(p) = rest.find("crate::") {
                let before = rest[..p].chars().next_back();
                let tail = &rest[p + "crate::".len()..];
                rest = tail;
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                    continue; // e.g. `mycrate::`
                }
                let name: String = tail
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                let to = root_item_owner(&name).to_string();
                if to != from && !to.is_empty() {
                    let rel = file.strip_prefix(&src).unwrap().display().to_string();
                    edges
                        .entry((from.clone(), to))
                        .or_default()
                        .push(format!("src/{rel}:{}", ln + 1));
                }
            }
        }
    }
    edges
}

#[test]
fn every_module_is_on_a_floor() {
    let layers = layers();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rs_files(&src, &mut files);
    let modules: BTreeSet<String> = files
        .iter()
        .map(|f| top_module(&src, f))
        .filter(|m| m != "lib")
        .collect();
    let missing: Vec<_> = modules
        .iter()
        .filter(|m| !layers.floor.contains_key(*m) && !layers.any.contains(*m))
        .collect();
    assert!(
        missing.is_empty(),
        "modules missing from crates/ehl-bearing/layers.txt: {missing:?}"
    );
    // the lint sees imports at all: the equilibrium uses the contact law
    assert!(imports().contains_key(&("bearing".to_string(), "contact_law".to_string())));
}

#[test]
fn no_module_imports_a_higher_floor() {
    let layers = layers();
    let allowed: BTreeMap<(String, String), &str> = ALLOWED
        .iter()
        .map(|(a, b, why)| ((a.to_string(), b.to_string()), *why))
        .collect();
    let mut new = Vec::new();
    let mut seen = BTreeSet::new();
    for ((from, to), places) in imports() {
        if layers.any.contains(&from) || layers.any.contains(&to) {
            continue;
        }
        let (Some(&f), Some(&t)) = (layers.floor.get(&from), layers.floor.get(&to)) else {
            continue; // not a module of the crate (e.g. a macro path); every module is checked above
        };
        if t >= f {
            if allowed.contains_key(&(from.clone(), to.clone())) {
                seen.insert((from.clone(), to.clone()));
            } else {
                new.push(format!(
                    "{from} (floor {f}) imports {to} (floor {t}) at {}",
                    places.join(", ")
                ));
            }
        }
    }
    assert!(
        new.is_empty(),
        "imports running back up (see docs/architecture.md; move the item down instead):\n{}",
        new.join("\n")
    );
    let stale: Vec<_> = allowed.keys().filter(|k| !seen.contains(*k)).collect();
    assert!(
        stale.is_empty(),
        "allowed imports that no longer occur, remove them from ALLOWED: {stale:?}"
    );
}
