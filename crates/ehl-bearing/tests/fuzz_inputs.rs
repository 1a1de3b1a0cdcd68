//! Structure-aware fuzzing of the input files on stable Rust (docs/robustness.md).
//!
//! Case files, contact files and study files are generated from the examples by mutations
//! (right keys with wild values: 0, negative, NaN, ±inf, huge, tiny, wrong types; missing,
//! duplicated and unknown keys and tables; random bytes; byte mutations of the valid files;
//! small perturbations of valid values) and driven through the path the command line takes:
//! parse and validate, the plausibility checks, then a bounded run of the cheap stages (dry
//! equilibrium; the coupled loop with the hertz method for one valid case in five; the EHL
//! solver's first start on a 17² grid with a cycle and a time budget). Each input must end in a clear error or a result without NaN, never a
//! panic; a watchdog aborts the run, naming the input, if one takes longer than `HANG_S`.
//!
//! The generator is a SplitMix64 of our own, seeded per input by (seed, index): any input is
//! reproducible from its index alone, whatever the thread count (`FUZZ_ONE=index` reruns one
//! and prints it). Not `proptest`: its runner is sequential, shrinks (slow at 10⁶ inputs) and
//! does not address an input by index; not `rand`: one function of ten lines does.
//!
//! Default run: a fixed-seed slice (`fuzz_slice`, 3000 inputs, a few seconds). The full run:
//!
//! ```text
//! FUZZ_CASES=1000000 cargo test -p ehl-bearing --test fuzz_inputs -- --ignored --nocapture
//! ```
//!
//! (`FUZZ_SEED`, `FUZZ_THREADS` optional; prints the outcome table of docs/robustness.md.)

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::characterize::{characterize_bearing, CharacterizeSettings};
use ehl_bearing::ehl::{solve_steady_starts, EhlSettings, StartStrategy};
use ehl_bearing::io::parse_study;
use ehl_bearing::io::{contact::parse_contact_file, parse_case};
use ehl_bearing::method::Method;
use ehl_bearing::plausibility::{check_case, check_contact};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};
use toml::{Table, Value};

/// An input running longer than this is a hang (typical inputs take well under 100 ms).
const HANG_S: u64 = 60;
/// Wall-time budget of the EHL solve of one input.
const EHL_BUDGET_S: f64 = 5.0;

mod splitmix;
use splitmix::Rng;

const STRINGS: [&str; 14] = [
    "",
    "nan",
    "roelands",
    "barus",
    "outer",
    "quasi-static",
    "hertz",
    "harmonic",
    "7006.toml",
    "/dev/zero",
    "/",
    "does-not-exist.toml",
    "é\u{0}\u{202e}",
    "1e3",
];

const JUNK_KEYS: [&str; 6] = [
    "unknown_key",
    "ball_diameter_m",
    "force_axial_N",
    "grid",
    "",
    "bearing",
];

/// A wild value for a key whose valid value is `orig`.
fn wild(rng: &mut Rng, orig: Option<&Value>) -> Value {
    let base = match orig {
        Some(Value::Float(f)) => *f,
        Some(Value::Integer(i)) => *i as f64,
        _ => 1.0,
    };
    match rng.below(20) {
        0 => Value::Float(0.0),
        1 => Value::Integer(0),
        2 => Value::Float(-base.abs().max(1.0)),
        3 => Value::Float(f64::NAN),
        4 => Value::Float(f64::INFINITY),
        5 => Value::Float(f64::NEG_INFINITY),
        6 => Value::Float(1e300),
        7 => Value::Float(1e-300),
        8 => Value::Float(f64::MAX),
        9 => Value::Integer(i64::MAX),
        10 => Value::Integer(i64::MIN),
        11 => Value::Integer(-1),
        12 => Value::String(rng.pick(&STRINGS).to_string()),
        13 => Value::Boolean(rng.chance(0.5)),
        14 => Value::Array(vec![Value::Float(base), Value::String("x".into())]),
        15 => {
            let mut t = Table::new();
            t.insert("x".into(), Value::Integer(1));
            Value::Table(t)
        }
        16 => {
            let e = rng.unit() * 24.0 - 12.0;
            let s = if rng.chance(0.8) { 1.0 } else { -1.0 };
            Value::Float(s * 10f64.powf(e))
        }
        17 => Value::Integer((rng.next() % 4097) as i64),
        _ => near(rng, orig),
    }
}

/// A valid-looking perturbation: the value times a factor from 0.1 to 10 (integers stay
/// integers).
fn near(rng: &mut Rng, orig: Option<&Value>) -> Value {
    let f = 10f64.powf(rng.unit() * 2.0 - 1.0);
    match orig {
        Some(Value::Float(x)) => Value::Float(x * f),
        Some(Value::Integer(i)) => Value::Integer(((*i as f64) * f).round() as i64),
        Some(v) => v.clone(),
        None => Value::Float(f),
    }
}

/// Paths (table, key) of the leaves of a document.
fn leaves(t: &Table) -> Vec<(Option<String>, String)> {
    let mut out = Vec::new();
    for (k, v) in t {
        match v {
            Value::Table(sub) => {
                for k2 in sub.keys() {
                    out.push((Some(k.clone()), k2.clone()));
                }
            }
            _ => out.push((None, k.clone())),
        }
    }
    out
}

fn slot<'a>(t: &'a mut Table, table: &Option<String>) -> Option<&'a mut Table> {
    match table {
        None => Some(t),
        Some(name) => match t.get_mut(name) {
            Some(Value::Table(sub)) => Some(sub),
            _ => None,
        },
    }
}

/// What a generated input is, for the outcome table.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Kind {
    Case,
    Contact,
    Study,
}

/// How the input was made.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Mutation {
    WildValues,
    Removed,
    Unknown,
    Duplicated,
    RandomBytes,
    ByteFlips,
    NearValid,
    MethodOptions,
}

/// A mutated document: the text and, for a single-key value mutation, the key.
fn mutate(rng: &mut Rng, base: &Table, kind: Kind) -> (String, Mutation, Option<String>) {
    let mut t = base.clone();
    let text_of = |t: &Table| toml::to_string(t).unwrap_or_default();
    let m = match rng.below(16) {
        0..=4 => Mutation::WildValues,
        5 | 6 => Mutation::Removed,
        7 => Mutation::Unknown,
        8 => Mutation::Duplicated,
        9 => Mutation::RandomBytes,
        10 | 11 => Mutation::ByteFlips,
        12 if kind != Kind::Contact => Mutation::MethodOptions,
        _ => Mutation::NearValid,
    };
    let mut key = None;
    match m {
        Mutation::WildValues | Mutation::NearValid => {
            let n = if rng.chance(0.7) { 1 } else { 1 + rng.below(3) };
            let paths = leaves(&t);
            for _ in 0..n {
                let (table, k) = rng.pick(&paths).clone();
                if let Some(s) = slot(&mut t, &table) {
                    let orig = s.get(&k).cloned();
                    let v = if m == Mutation::NearValid {
                        near(rng, orig.as_ref())
                    } else {
                        wild(rng, orig.as_ref())
                    };
                    s.insert(k.clone(), v);
                }
                if n == 1 {
                    key = Some(k);
                }
            }
        }
        Mutation::Removed => {
            if rng.chance(0.3) {
                let tables: Vec<String> = t
                    .iter()
                    .filter(|(_, v)| v.is_table())
                    .map(|(k, _)| k.clone())
                    .collect();
                if !tables.is_empty() {
                    let k = rng.pick(&tables).clone();
                    t.remove(&k);
                }
            } else {
                let paths = leaves(&t);
                let (table, k) = rng.pick(&paths).clone();
                if let Some(s) = slot(&mut t, &table) {
                    s.remove(&k);
                }
            }
        }
        Mutation::Unknown => {
            let k = rng.pick(&JUNK_KEYS).to_string();
            let v = wild(rng, None);
            let tables: Vec<Option<String>> = std::iter::once(None)
                .chain(
                    t.iter()
                        .filter(|(_, v)| v.is_table())
                        .map(|(k, _)| Some(k.clone())),
                )
                .collect();
            let table = rng.pick(&tables).clone();
            if rng.chance(0.2) {
                let mut sub = Table::new();
                sub.insert(k, v);
                t.insert("unknown_table".into(), Value::Table(sub));
            } else if let Some(s) = slot(&mut t, &table) {
                s.insert(k, v);
            }
        }
        Mutation::Duplicated => {
            let text = text_of(&t);
            let lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return (text, m, None);
            }
            let i = rng.below(lines.len());
            let mut out: Vec<&str> = lines.clone();
            out.insert((i + 1 + rng.below(3)).min(out.len()), lines[i]);
            return (out.join("\n") + "\n", m, None);
        }
        Mutation::RandomBytes => {
            let n = rng.below(300);
            let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
            return (String::from_utf8_lossy(&bytes).into_owned(), m, None);
        }
        Mutation::ByteFlips => {
            let mut bytes = text_of(&t).into_bytes();
            for _ in 0..1 + rng.below(8) {
                if bytes.is_empty() {
                    break;
                }
                let i = rng.below(bytes.len());
                match rng.below(3) {
                    0 => bytes[i] = rng.next() as u8,
                    1 => {
                        bytes.remove(i);
                    }
                    _ => bytes.insert(i, *rng.pick(b"=[]\"'.#0123456789-+eE\n ")),
                }
            }
            return (String::from_utf8_lossy(&bytes).into_owned(), m, None);
        }
        Mutation::MethodOptions => {
            let name = rng.pick(&["quasi-static", "harmonic", "hertz", "synthetic", "x"]);
            t.insert("method".into(), Value::String(name.to_string()));
            let mut o = Table::new();
            for _ in 0..1 + rng.below(2) {
                let k = rng.pick(&[
                    "grid",
                    "amplitude",
                    "points",
                    "samples",
                    "frequency_fraction",
                    "steps_per_period",
                    "settling_periods",
                    "mass_kg",
                    "inlet",
                ]);
                let v = if rng.chance(0.5) {
                    Value::Integer(*rng.pick(&[17, 33, 129, 257, 1025, 2049, 0, 18]))
                } else {
                    wild(rng, Some(&Value::Float(0.2)))
                };
                o.insert(k.to_string(), v);
            }
            t.insert("method_options".into(), Value::Table(o));
        }
    }
    (text_of(&t), m, key)
}

/// How one input ended.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Outcome {
    /// Refused by the parser/validation with a message.
    Rejected,
    /// Valid but refused by the plausibility checks.
    Implausible,
    /// Ran: converged (equilibrium, loop, EHL) with finite results.
    Converged,
    /// Ran: the solver reported that it did not converge (an error or `converged: false`).
    NotConverged,
    /// Ran into its wall-time budget (reported with its residual history).
    TimeLimit,
    /// A result with NaN or infinite numbers: a finding.
    NonFinite,
    /// A panic: a finding.
    Panic,
}

struct Bases {
    case: Table,
    contact: Table,
    study: Table,
    high_speed: Table,
    dir: PathBuf,
}

fn bases() -> Bases {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let read = |f: &str| -> Table {
        toml::from_str(&std::fs::read_to_string(ex.join(f)).expect("example")).expect("toml")
    };
    Bases {
        case: read("7006.toml"),
        contact: read("contact_7006_inner.toml"),
        study: read("study_7006.toml"),
        high_speed: read("218_high_speed.toml"),
        dir: ex,
    }
}

fn finite_all(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Drive one text through the command line's path for its kind. Returns the outcome and the
/// message of a refusal.
fn run_input(kind: Kind, text: &str, dir: &Path, with_loop: bool) -> (Outcome, String) {
    match kind {
        Kind::Case => run_case(text, with_loop),
        Kind::Contact => run_contact(text),
        Kind::Study => match parse_study(text, "fuzz", dir) {
            Err(e) => (Outcome::Rejected, e.to_string()),
            Ok(study) => {
                let mut out = (Outcome::Converged, String::new());
                for p in study.points().iter().take(2) {
                    let case = study.point_case(p);
                    if let Err(e) = check_case(&case) {
                        return (Outcome::Implausible, e.to_string());
                    }
                    match dry(&case) {
                        (Outcome::Converged, _) => {}
                        other => out = other,
                    }
                }
                out
            }
        },
    }
}

/// The dry equilibrium of a valid case, its numbers checked.
fn dry(case: &ehl_bearing::case::Case) -> (Outcome, String) {
    let laws = match ContactLaws::hertz(&case.bearing) {
        Ok(l) => l,
        Err(e) => return (Outcome::Rejected, e.to_string()),
    };
    match solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings) {
        Err(e) => (Outcome::NotConverged, e.to_string()),
        Ok(eq) => {
            let mut nums: Vec<f64> = eq.displacement.to_vec();
            nums.extend(eq.reaction);
            nums.extend(eq.stiffness.iter().flatten());
            for b in &eq.balls {
                nums.extend([b.inner.load, b.outer.load, b.inner.max_pressure]);
            }
            if finite_all(&nums) {
                (Outcome::Converged, String::new())
            } else {
                (Outcome::NonFinite, format!("{:?}", eq.displacement))
            }
        }
    }
}

fn run_case(text: &str, with_loop: bool) -> (Outcome, String) {
    let case = match parse_case(text, "fuzz") {
        Ok(c) => c,
        Err(e) => return (Outcome::Rejected, e.to_string()),
    };
    if let Err(e) = check_case(&case) {
        return (Outcome::Implausible, e.to_string());
    }
    let r = dry(&case);
    if r.0 != Outcome::Converged || !with_loop {
        return r;
    }
    // The coupled loop with the dry reference method: equilibrium, fit and loop, cheap.
    let hertz = Method::parse("hertz", None).expect("hertz");
    let settings = CharacterizeSettings {
        max_iterations: 3,
        predict_loads: false,
        ..Default::default()
    };
    match characterize_bearing(&case, &hertz, &settings) {
        Err(e) => (Outcome::NotConverged, e.to_string()),
        Ok(c) => {
            let nums: Vec<f64> = c
                .contacts
                .iter()
                .flat_map(|r| [r.characterized.k, r.characterized.d, r.state.load])
                .chain(c.equilibrium.displacement)
                .collect();
            if !finite_all(&nums) {
                (Outcome::NonFinite, "characterization".into())
            } else if c.converged {
                (Outcome::Converged, String::new())
            } else {
                (Outcome::NotConverged, "loop not converged".into())
            }
        }
    }
}

fn run_contact(text: &str) -> (Outcome, String) {
    let file = match parse_contact_file(text) {
        Ok(f) => f,
        Err(e) => return (Outcome::Rejected, e.to_string()),
    };
    if let Err(e) = check_contact(&file.contact) {
        return (Outcome::Implausible, e.to_string());
    }
    let s = EhlSettings {
        grid: 17,
        coarsest: 9,
        max_cycles: 8,
        ..Default::default()
    };
    let deadline = ehl_bearing::budget::Deadline::after_seconds(EHL_BUDGET_S);
    // One start (the solver's first, with its cycle limit): the ladder of fallbacks is
    // exercised by the property tests of tests/ehl_edges.rs.
    match solve_steady_starts(&file.contact, &s, &[StartStrategy::Given], deadline) {
        Err(ehl_bearing::ehl::EhlError::TimeLimit { .. }) => {
            (Outcome::TimeLimit, "time limit".into())
        }
        Err(e) => (Outcome::NotConverged, e.to_string()),
        Ok(sol) => {
            let nums = [
                sol.h_central,
                sol.h_min,
                sol.p_max,
                sol.approach,
                sol.residual,
            ];
            if !finite_all(&nums) || !finite_all(&sol.fields.p) {
                (Outcome::NonFinite, format!("{nums:?}"))
            } else if sol.converged {
                (Outcome::Converged, String::new())
            } else {
                (Outcome::NotConverged, "not converged".into())
            }
        }
    }
}

/// Generate input `index` of the run with `seed`.
/// Input `index`: its kind, mutation, mutated key (single-key mutations), text, and whether a
/// valid case also runs the coupled loop (one in five, for the rate of the full run).
#[allow(clippy::type_complexity)]
fn generate(b: &Bases, seed: u64, index: u64) -> (Kind, Mutation, Option<String>, String, bool) {
    let mut rng = Rng::new(seed, index);
    let kind = match rng.below(10) {
        0..=4 => Kind::Case,
        5..=7 => Kind::Contact,
        _ => Kind::Study,
    };
    let base = match kind {
        Kind::Case if rng.chance(0.2) => &b.high_speed,
        Kind::Case => &b.case,
        Kind::Contact => &b.contact,
        Kind::Study => &b.study,
    };
    let (text, m, key) = mutate(&mut rng, base, kind);
    (kind, m, key, text, rng.chance(0.2))
}

#[derive(Default)]
struct Tally {
    counts: BTreeMap<(String, String), usize>,
    outcomes: BTreeMap<String, usize>,
    seconds: BTreeMap<String, f64>,
    named: usize,
    named_of: usize,
    findings: Vec<String>,
    unnamed_examples: Vec<String>,
}

/// Run `cases` inputs from `seed` on `threads` threads; a watchdog aborts on a hang.
fn fuzz(seed: u64, cases: u64, threads: usize) -> Tally {
    let b = bases();
    let next = AtomicU64::new(0);
    let done = AtomicUsize::new(0);
    let tally = Mutex::new(Tally::default());
    // Per worker: start time (ms since t0, 0 = idle) and the index it runs.
    let t0 = Instant::now();
    let slots: Vec<(AtomicU64, AtomicU64)> = (0..threads)
        .map(|_| (AtomicU64::new(0), AtomicU64::new(0)))
        .collect();
    let finished = std::sync::atomic::AtomicBool::new(false);
    std::thread::scope(|scope| {
        scope.spawn(|| {
            let mut last_report = Instant::now();
            while !finished.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(200));
                let now = t0.elapsed().as_millis() as u64 + 1;
                for (start, idx) in &slots {
                    let s = start.load(Ordering::Relaxed);
                    if s > 0 && now - s > HANG_S * 1000 {
                        let i = idx.load(Ordering::Relaxed);
                        let (kind, m, _, text, _) = generate(&b, seed, i);
                        eprintln!(
                            "HANG: input {i} (seed {seed}, {kind:?}, {m:?}) ran more than {HANG_S} s:\n{text}"
                        );
                        std::process::abort();
                    }
                }
                if last_report.elapsed() > Duration::from_secs(60) {
                    last_report = Instant::now();
                    let d = done.load(Ordering::Relaxed);
                    eprintln!(
                        "fuzz: {d} of {cases} inputs, {:.0} s, {:.0}/s",
                        t0.elapsed().as_secs_f64(),
                        d as f64 / t0.elapsed().as_secs_f64()
                    );
                }
            }
        });
        let workers: Vec<_> = slots
            .iter()
            .map(|(start, idx)| {
                let (b, next, done, tally) = (&b, &next, &done, &tally);
                scope.spawn(move || loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= cases {
                        break;
                    }
                    idx.store(i, Ordering::Relaxed);
                    start.store(t0.elapsed().as_millis() as u64 + 1, Ordering::Relaxed);
                    let (kind, m, key, text, with_loop) = generate(b, seed, i);
                    let ti = Instant::now();
                    let r = std::panic::catch_unwind(|| run_input(kind, &text, &b.dir, with_loop));
                    let spent = ti.elapsed().as_secs_f64();
                    start.store(0, Ordering::Relaxed);
                    let (outcome, msg) = r.unwrap_or((Outcome::Panic, "panic".into()));
                    let mut t = tally.lock().unwrap_or_else(|p| p.into_inner());
                    *t.counts
                        .entry((format!("{kind:?}"), format!("{m:?}")))
                        .or_default() += 1;
                    *t.outcomes
                        .entry(format!("{kind:?} {outcome:?}"))
                        .or_default() += 1;
                    *t.seconds
                        .entry(format!("{kind:?} {outcome:?}"))
                        .or_default() += spent;
                    if matches!(outcome, Outcome::Panic | Outcome::NonFinite) {
                        t.findings.push(format!(
                            "input {i} ({kind:?}, {m:?}): {outcome:?} {msg}\n{text}"
                        ));
                    }
                    if matches!(outcome, Outcome::Rejected | Outcome::Implausible) {
                        assert!(!msg.trim().is_empty(), "input {i}: empty error message");
                        if let Some(k) = key {
                            t.named_of += 1;
                            if msg.contains(&k) {
                                t.named += 1;
                            } else if t.unnamed_examples.len() < 5 {
                                t.unnamed_examples.push(format!("{k}: {msg}"));
                            }
                        }
                    }
                    drop(t);
                    done.fetch_add(1, Ordering::Relaxed);
                })
            })
            .collect();
        for w in workers {
            let _ = w.join();
        }
        finished.store(true, Ordering::Relaxed);
    });
    let t = tally.into_inner().unwrap_or_else(|p| p.into_inner());
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "fuzz: seed {seed}, {cases} inputs on {threads} threads in {secs:.1} s ({:.0} inputs/s)",
        cases as f64 / secs
    );
    println!("\n| input | outcome | count | mean time ms |\n|---|---|---|---|");
    for (k, n) in &t.outcomes {
        let (kind, o) = k.split_once(' ').unwrap_or((k, ""));
        let ms = 1e3 * t.seconds.get(k).copied().unwrap_or(0.0) / *n as f64;
        println!("| {kind} | {o} | {n} | {ms:.2} |");
    }
    println!("\n| input | mutation | count |\n|---|---|---|");
    for ((k, m), n) in &t.counts {
        println!("| {k} | {m} | {n} |");
    }
    println!(
        "\nsingle-key mutations refused with the key named in the message: {} of {}",
        t.named, t.named_of
    );
    for e in &t.unnamed_examples {
        println!("  not named: {e}");
    }
    t
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn threads() -> usize {
    env_u64(
        "FUZZ_THREADS",
        std::thread::available_parallelism().map_or(2, |n| n.get()) as u64,
    ) as usize
}

/// CI's slice: a fixed seed, a few thousand inputs.
#[test]
fn fuzz_slice() {
    let t = fuzz(15, 3000, threads());
    assert!(
        t.findings.is_empty(),
        "findings:\n{}",
        t.findings.join("\n\n")
    );
    // The slice reaches every stage: refusals, plausibility refusals and converged runs.
    let count = |s: &str| t.outcomes.get(s).copied().unwrap_or(0);
    assert!(count("Case Rejected") > 100 && count("Case Converged") > 50);
    assert!(count("Contact Converged") + count("Contact NotConverged") > 20);
    assert!(count("Case Implausible") + count("Contact Implausible") > 0);
    assert!(count("Study Rejected") > 20 && count("Study Converged") > 10);
}

/// The full run (docs/robustness.md): `FUZZ_CASES=1000000 cargo test -p ehl-bearing --test
/// fuzz_inputs -- --ignored --nocapture`.
#[test]
#[ignore]
fn fuzz_many() {
    let t = fuzz(
        env_u64("FUZZ_SEED", 15),
        env_u64("FUZZ_CASES", 1_000_000),
        threads(),
    );
    assert!(
        t.findings.is_empty(),
        "findings:\n{}",
        t.findings.join("\n\n")
    );
}

/// Rerun and print one input: `FUZZ_ONE=index [FUZZ_SEED=s] cargo test -p ehl-bearing --test
/// fuzz_inputs fuzz_one -- --ignored --nocapture`.
#[test]
#[ignore]
fn fuzz_one() {
    let b = bases();
    let i = env_u64("FUZZ_ONE", 0);
    let (kind, m, key, text, with_loop) = generate(&b, env_u64("FUZZ_SEED", 15), i);
    println!("input {i}: {kind:?}, {m:?}, key {key:?}\n{text}\n---");
    println!("{:?}", run_input(kind, &text, &b.dir, with_loop));
}
