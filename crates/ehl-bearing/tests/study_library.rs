//! Studies through the library (`ehl_bearing::study`) behind the in-memory store: shards give the
//! same outputs as one run, point records read back into the same value, another study's points
//! are refused before any work, and outputs need every point.

use ehl_bearing::io::parse_study;
use ehl_bearing::study::{
    finish_study, merge_points, run_study, MemoryStore, PointRecord, PointStore, RunOptions, Shard,
    StoreError, Study, StudyError, StudyEvent,
};
use std::path::Path;
use std::sync::Mutex;

fn study(method: &str, extra: &str) -> Study {
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let text = format!(
        "case = \"7006.toml\"\nmethod = \"{method}\"\ninner_speeds_rpm = [3000, 4000, 5000]\nload_scales = [0.5, 1.0, 2.0]\n{extra}"
    );
    parse_study(&text, "test.toml", examples).unwrap()
}

fn run(s: &Study, store: &MemoryStore, shard: Shard) -> ehl_bearing::study::StudyRun {
    run_study(
        s,
        store,
        &RunOptions {
            shard,
            overwrite: false,
            point_time_limit_s: None,
            ..RunOptions::default()
        },
        &|_| {},
    )
    .unwrap()
}

#[test]
fn shards_in_memory_give_the_outputs_of_one_run() {
    let s = study("synthetic", "");
    let one = MemoryStore::default();
    let r = run(&s, &one, Shard::ALL);
    assert_eq!((r.points, r.computed, r.loaded), (9, 9, 0));
    finish_study(&s, &one).unwrap();
    let shared = MemoryStore::default();
    let separate: Vec<MemoryStore> = (0..3).map(|_| MemoryStore::default()).collect();
    for i in 1..=3 {
        let shard = Shard::new(i, 3).unwrap();
        assert_eq!(run(&s, &shared, shard).computed, 3);
        run(&s, &separate[i - 1], shard);
    }
    finish_study(&s, &shared).unwrap();
    let merged = MemoryStore::default();
    let sources: Vec<&dyn PointStore> = separate.iter().map(|x| x as &dyn PointStore).collect();
    assert_eq!(merge_points(&s, &merged, &sources).unwrap(), 9);
    finish_study(&s, &merged).unwrap();
    let files = |m: &MemoryStore| {
        (
            m.points.lock().unwrap().clone(),
            m.outputs.lock().unwrap().clone(),
        )
    };
    assert_eq!(files(&one), files(&shared));
    assert_eq!(files(&one), files(&merged));
    let (_, outputs) = files(&one);
    for name in ["results.csv", "points.csv", "trends.json"] {
        assert!(outputs.contains_key(name), "{name}");
    }
    // Resuming loads everything.
    let again = run(&s, &one, Shard::ALL);
    assert_eq!((again.computed, again.loaded), (0, 9));
}

#[test]
fn point_records_read_back_into_the_same_value() {
    let s = study("synthetic", "");
    let store = MemoryStore::default();
    run(&s, &store, Shard::new(1, 9).unwrap());
    let points = store.points.lock().unwrap().clone();
    assert_eq!(points.len(), 1);
    for text in points.values() {
        let r = PointRecord::from_json(text).unwrap();
        assert_eq!(&r.to_json(), text);
        assert_eq!(PointRecord::from_json(&r.to_json()).unwrap(), r);
        assert!(r.result.as_ref().unwrap().converged);
        assert_eq!(r.spec.method, s.method);
        assert_eq!(r.rows().len(), 22);
    }
}

#[test]
fn another_studys_points_are_refused_before_any_work() {
    let a = study("hertz", "");
    let store = MemoryStore::default();
    run(&a, &store, Shard::new(1, 3).unwrap());
    let before = store.points.lock().unwrap().clone();
    let b = study("hertz", "[method_options]\nsamples = 11\n");
    let started = Mutex::new(0);
    let e = run_study(&b, &store, &RunOptions::default(), &|ev| {
        if let StudyEvent::PointStarted(_) = ev {
            *started.lock().unwrap() += 1;
        }
    })
    .unwrap_err();
    let StudyError::ForeignPoints {
        count, difference, ..
    } = &e
    else {
        panic!("{e}")
    };
    assert_eq!(*count, 3);
    assert!(difference.starts_with("method"), "{difference}");
    assert_eq!(*started.lock().unwrap(), 0);
    assert_eq!(*store.points.lock().unwrap(), before);
    // With overwrite they are recomputed.
    let r = run_study(
        &b,
        &store,
        &RunOptions {
            shard: Shard::ALL,
            overwrite: true,
            point_time_limit_s: None,
            ..RunOptions::default()
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!(r.computed, 9);
}

#[test]
fn outputs_need_every_point_and_unreadable_points_are_redone() {
    let s = study("hertz", "");
    let store = MemoryStore::default();
    run(&s, &store, Shard::new(2, 3).unwrap());
    let e = finish_study(&s, &store).unwrap_err();
    assert!(
        matches!(
            e,
            StudyError::Incomplete {
                missing: 6,
                total: 9,
                ..
            }
        ),
        "{e}"
    );
    // A truncated point file is recomputed.
    let stem = s.points()[1].file_stem();
    let text = store.load_point(&stem).unwrap().unwrap();
    store.save_point(&stem, &text[..text.len() / 3]).unwrap();
    let r = run(&s, &store, Shard::ALL);
    assert_eq!((r.redone, r.computed, r.loaded), (1, 7, 2));
    assert_eq!(store.load_point(&stem).unwrap().unwrap(), text);
    finish_study(&s, &store).unwrap();
}

/// Points computed concurrently (`points_in_flight`) give the files of points computed one after
/// the other, every point reports its start, loop events and end once, and the run's counts are
/// the same.
#[test]
fn concurrent_points_give_the_files_of_sequential_ones() {
    let s = study("synthetic", "");
    let go = |in_flight: usize| {
        let store = MemoryStore::default();
        let events = Mutex::new(Vec::new());
        let r = run_study(
            &s,
            &store,
            &RunOptions {
                points_in_flight: in_flight,
                ..RunOptions::default()
            },
            &|ev| {
                let tag = match ev {
                    StudyEvent::PointStarted(p) => Some((p.index, "started")),
                    StudyEvent::PointDone { point, .. } => Some((point.index, "done")),
                    StudyEvent::Loop(p, _) => Some((p.index, "loop")),
                    StudyEvent::Planned { .. } => None,
                };
                events.lock().unwrap().extend(tag);
            },
        )
        .unwrap();
        let mut ev = events.into_inner().unwrap();
        ev.sort();
        ev.dedup();
        let points = store.points.lock().unwrap().clone();
        (r.points, r.computed, r.failed.len(), points, ev)
    };
    let sequential = go(1);
    assert_eq!(sequential.0, 9);
    assert_eq!(sequential.4.len(), 9 * 3, "{:?}", sequential.4);
    assert_eq!(go(3), sequential);
    assert_eq!(go(100), sequential);
}

/// A store that cannot write point files (a full disk): every write fails.
struct FullStore;

impl PointStore for FullStore {
    fn load_point(&self, _: &str) -> Result<Option<String>, StoreError> {
        Ok(None)
    }
    fn save_point(&self, stem: &str, _: &str) -> Result<(), StoreError> {
        Err(StoreError {
            action: "writing".into(),
            location: stem.into(),
            message: "no space left on device".into(),
        })
    }
    fn write_output(&self, name: &str, _: &[u8]) -> Result<(), StoreError> {
        self.save_point(name, "")
    }
    fn point_location(&self, stem: &str) -> String {
        stem.into()
    }
}

/// A store error ends the run with that error, and no point is started after it: one after the
/// other, only the first point runs; with `in_flight` at once, at most one point per worker.
#[test]
fn a_store_error_stops_the_run() {
    let s = study("synthetic", "");
    for in_flight in [1, 3] {
        let started = Mutex::new(0);
        let e = run_study(
            &s,
            &FullStore,
            &RunOptions {
                points_in_flight: in_flight,
                ..RunOptions::default()
            },
            &|ev| {
                if let StudyEvent::PointStarted(_) = ev {
                    *started.lock().unwrap() += 1;
                }
            },
        )
        .unwrap_err();
        assert!(matches!(e, StudyError::Store(_)), "{e}");
        assert!(e.to_string().contains("no space left"), "{e}");
        // Every write fails, so each worker stops after its first point.
        let n = *started.lock().unwrap();
        assert!((1..=in_flight).contains(&n), "{n} points started");
    }
}

/// Point names stay short and distinct for every valid value: positional text up to 20
/// characters (the names of existing studies are unchanged), exponent form beyond (1e-300 gave
/// a 310-byte name, "File name too long").
#[test]
fn point_names_are_short_and_unique_for_every_valid_value() {
    use ehl_bearing::study::StudyPoint;
    let name = |n: f64, s: f64| {
        StudyPoint {
            index: 0,
            inner_speed_rpm: n,
            load_scale: s,
        }
        .file_stem()
    };
    assert_eq!(name(3000.0, 0.5), "n3000rpm_s0.5");
    assert_eq!(name(5000.0, 1.0), "n5000rpm_s1");
    assert_eq!(name(1e-300, 1e-300), "n1e-300rpm_s1e-300");
    assert_eq!(name(3000.0, 0.1 + 0.2), "n3000rpm_s0.30000000000000004");
    let values = [
        1e-300,
        1e-300 * (1.0 + f64::EPSILON),
        1e-7,
        1.0000000000000002e-7,
        0.1,
        0.1 + 0.2,
        0.3,
        1.0,
        100.0,
        1e6,
        123456.789012345,
        f64::MIN_POSITIVE,
    ];
    let mut names = std::collections::BTreeSet::new();
    for &v in &values {
        let stem = name(v, v);
        assert!(stem.len() < 60, "{stem}");
        names.insert(stem);
    }
    assert_eq!(names.len(), values.len(), "{names:?}");
}

/// A point file that is a FIFO, a folder, a link to /dev/zero or a huge file is an error naming
/// the file, at once (a FIFO blocked the read forever, /dev/zero filled the memory).
#[cfg(unix)]
#[test]
fn point_files_that_are_not_regular_files_are_refused_at_once() {
    use ehl_bearing::io::FsStore;
    let dir = std::env::temp_dir().join(format!("ehl-store-kinds-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    let store = FsStore::create(&dir).unwrap();
    let points = dir.join("points");
    let fifo = points.join("fifo.json");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    std::fs::create_dir(points.join("folder.json")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", points.join("zero.json")).unwrap();
    let huge = std::fs::File::create(points.join("huge.json")).unwrap();
    huge.set_len(ehl_bearing::io::MAX_INPUT_BYTES + 1).unwrap();
    for (stem, what) in [
        ("fifo", "a FIFO"),
        ("folder", "a folder"),
        ("zero", "a device"),
        ("huge", "larger than 16 MiB"),
    ] {
        let e = store.load_point(stem).unwrap_err().to_string();
        assert!(
            e.contains(&format!("{stem}.json")) && e.contains(what) && e.contains("remove it"),
            "{e}"
        );
    }
    assert_eq!(store.load_point("absent").unwrap(), None);
    std::fs::write(points.join("ok.json"), "{}").unwrap();
    assert_eq!(store.load_point("ok").unwrap().as_deref(), Some("{}"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Finishing (merging) a study over another study's point files names them as another study's,
/// not as missing ("first missing: …n3000rpm_s0.5.json" although the file was there, computed
/// by another method).
#[test]
fn finishing_over_another_studys_points_names_them() {
    let hertz = study("hertz", "");
    let store = MemoryStore::default();
    run(&hertz, &store, Shard::ALL);
    let other = study("quasi-static", "");
    match finish_study(&other, &store) {
        Err(StudyError::ForeignPoints {
            count, difference, ..
        }) => {
            assert_eq!(count, 9);
            assert!(difference.contains("method"), "{difference}");
        }
        Err(e) => panic!("expected ForeignPoints, got {e}"),
        Ok(_) => panic!("expected ForeignPoints, got outputs"),
    }
}

/// A CSV text as a header and rows of cells (no quoted cells in the study files).
fn csv_table(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn cell(header: &[String], row: &[String], name: &str) -> String {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    row[i].clone()
}

fn opt_num(s: &str) -> Option<f64> {
    (!s.is_empty()).then(|| s.parse().unwrap())
}

/// A study whose case describes its oil and gives roughness carries the lubrication figures of
/// each point (the report in the point file, at the final equilibrium) in `results.csv` (per
/// contact) and `points.csv` (per point: κ, the smallest Λ and where, the largest thermal
/// reduction, the warnings); the same study with the oil given by its constants and no roughness
/// has none of these columns.
#[test]
fn lubricated_studies_carry_the_lubrication_figures() {
    use ehl_bearing::study::{POINTS_CSV_HEADER, POINTS_CSV_LUBRICATION_HEADER};
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let text = "case = \"7006_vg46.toml\"\nmethod = \"synthetic\"\ninner_speeds_rpm = [3000, 5000]\nload_scales = [0.5, 2.0]\n";
    let s = parse_study(text, "test.toml", examples).unwrap();
    let store = MemoryStore::default();
    run(&s, &store, Shard::ALL);
    let out = finish_study(&s, &store).unwrap();
    let outputs = store.outputs.lock().unwrap().clone();
    let results = String::from_utf8(outputs["results.csv"].clone()).unwrap();
    let points = String::from_utf8(outputs["points.csv"].clone()).unwrap();

    // results.csv: the five columns appended after the contact's, equal to the point file's.
    let (h, rows) = csv_table(&results);
    let tail: Vec<&str> = h[h.len() - 5..].iter().map(|x| x.as_str()).collect();
    assert_eq!(
        tail,
        [
            "central_film_m",
            "min_film_m",
            "lambda",
            "thermal_reduction",
            "min_film_thermal_m"
        ]
    );
    assert_eq!(rows.len(), out.rows.len());
    let mut checked = 0;
    for row in &rows {
        let rpm: f64 = cell(&h, row, "speed_rpm").parse().unwrap();
        let scale: f64 = cell(&h, row, "load_scale").parse().unwrap();
        let ball: usize = cell(&h, row, "ball").parse().unwrap();
        let race = cell(&h, row, "race");
        let rec = out
            .records
            .iter()
            .find(|r| r.spec.inner_speed_rpm == rpm && r.spec.load_scale == scale)
            .unwrap();
        let lub = rec.result.as_ref().unwrap().lubrication.as_ref().unwrap();
        let c = lub
            .contacts
            .iter()
            .find(|c| c.ball == ball && c.race == race)
            .unwrap();
        assert_eq!(opt_num(&cell(&h, row, "central_film_m")), c.central_film_m);
        assert_eq!(opt_num(&cell(&h, row, "min_film_m")), c.min_film_m);
        assert_eq!(opt_num(&cell(&h, row, "lambda")), c.lambda);
        assert_eq!(
            opt_num(&cell(&h, row, "thermal_reduction")),
            c.thermal_reduction
        );
        assert_eq!(
            opt_num(&cell(&h, row, "min_film_thermal_m")),
            c.min_film_thermal_m
        );
        // The seed's loaded contacts have every figure (oil described, roughness given).
        if c.load_n > 1.0 {
            assert!(c.lambda.is_some() && c.thermal_reduction.is_some());
            checked += 1;
        }
    }
    assert!(checked > 20, "{checked}");

    // points.csv: the lubrication columns after the usual ones.
    let (h, rows) = csv_table(&points);
    assert_eq!(
        h.join(","),
        format!("{POINTS_CSV_HEADER},{POINTS_CSV_LUBRICATION_HEADER}")
    );
    assert_eq!(rows.len(), 4);
    for (row, rec) in rows.iter().zip(&out.records) {
        let lub = rec.result.as_ref().unwrap().lubrication.as_ref().unwrap();
        let min_lambda = opt_num(&cell(&h, row, "min_lambda")).unwrap();
        assert_eq!(Some(min_lambda), lub.min_lambda);
        // The named contact has that Λ, and no contact has less.
        let ball: usize = cell(&h, row, "min_lambda_ball").parse().unwrap();
        let race = cell(&h, row, "min_lambda_race");
        let at = lub
            .contacts
            .iter()
            .find(|c| c.ball == ball && c.race == race)
            .unwrap();
        assert_eq!(at.lambda, Some(min_lambda));
        assert!(lub
            .contacts
            .iter()
            .all(|c| c.lambda.iter().all(|&l| l >= min_lambda)));
        let min_film = lub
            .contacts
            .iter()
            .filter_map(|c| c.min_film_m)
            .fold(f64::INFINITY, f64::min);
        assert_eq!(opt_num(&cell(&h, row, "min_film_m")), Some(min_film));
        assert_eq!(opt_num(&cell(&h, row, "kappa")), lub.kappa);
        assert_eq!(
            opt_num(&cell(&h, row, "kinematic_viscosity_mm2_s")),
            Some(lub.kinematic_viscosity_mm2_s)
        );
        assert_eq!(
            opt_num(&cell(&h, row, "max_thermal_reduction")),
            lub.max_thermal_reduction
        );
        assert_eq!(
            cell(&h, row, "lubrication_warnings"),
            lub.warnings.len().to_string()
        );
    }
    // The study's summary: the extremes over every point and contact, where they occur.
    let sum = out.lubrication_summary().unwrap();
    assert_eq!(sum.points, 4);
    let all: Vec<(f64, f64, &ehl_bearing::lubrication::ContactFilm)> = out
        .records
        .iter()
        .flat_map(|r| {
            let l = r.result.as_ref().unwrap().lubrication.as_ref().unwrap();
            l.contacts
                .iter()
                .map(move |c| (r.spec.inner_speed_rpm, r.spec.load_scale, c))
        })
        .collect();
    let lam = sum.min_lambda.as_ref().unwrap();
    assert!(all
        .iter()
        .all(|(_, _, c)| c.lambda.iter().all(|&l| l >= lam.value)));
    assert!(all.iter().any(|(n, s, c)| *n == lam.inner_speed_rpm
        && *s == lam.load_scale
        && c.ball == lam.ball
        && c.race == lam.race
        && c.lambda == Some(lam.value)));
    let hot = sum.max_thermal_reduction.as_ref().unwrap();
    assert!(all
        .iter()
        .all(|(_, _, c)| c.thermal_reduction.iter().all(|&t| t <= hot.value)));
    assert!(all.iter().any(|(n, s, c)| *n == hot.inner_speed_rpm
        && *s == hot.load_scale
        && c.ball == hot.ball
        && c.race == hot.race
        && c.thermal_reduction == Some(hot.value)));
    let warned = out
        .records
        .iter()
        .filter(|r| {
            !r.result
                .as_ref()
                .unwrap()
                .lubrication
                .as_ref()
                .unwrap()
                .warnings
                .is_empty()
        })
        .count();
    assert_eq!(sum.points_with_warnings, warned);
    // The thermal reduction grows with speed (VG 46 at 40 °C: η0·β·u²).
    let red = |i: usize| opt_num(&cell(&h, &rows[i], "max_thermal_reduction")).unwrap();
    let rpm = |i: usize| out.records[i].spec.inner_speed_rpm;
    let (slow, fast) = (
        (0..4).find(|&i| rpm(i) == 3000.0),
        (0..4).find(|&i| rpm(i) == 5000.0),
    );
    assert!(red(fast.unwrap()) > red(slow.unwrap()));

    // The seed case with constants and no roughness: no lubrication columns.
    let plain = study("synthetic", "");
    let store = MemoryStore::default();
    run(&plain, &store, Shard::new(1, 9).unwrap());
    let rec =
        PointRecord::from_json(store.points.lock().unwrap().values().next().unwrap()).unwrap();
    assert!(!rec.spec.has_lubrication());
    let plain_out = ehl_bearing::study::StudyOutputs {
        records: vec![rec.clone()],
        rows: Vec::new(),
        trends: Err(String::new()),
        trend_errors: vec![None],
        failed: Vec::new(),
    };
    assert!(plain_out.lubrication_summary().is_none());
    let csv = ehl_bearing::study::points_csv(std::slice::from_ref(&rec), &[None]);
    assert_eq!(csv.lines().next().unwrap(), POINTS_CSV_HEADER);
    let rows = rec.rows();
    assert!(rows.iter().all(|r| r.lubrication.is_none()));
    let header = ehl_bearing::study::results_csv(&rows);
    assert!(header
        .lines()
        .next()
        .unwrap()
        .ends_with(",outside_fit_range,method"));
}

/// The roughness and the oil description are part of a point's spec: the point files of a study
/// without them are another study's for the same study with them (recomputed, not reused without
/// their lubrication figures), and the spec without them is written as before (no new keys).
#[test]
fn roughness_and_oil_description_are_part_of_the_point_spec() {
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    let text = |case: &str| {
        format!("case = \"{case}\"\nmethod = \"synthetic\"\ninner_speeds_rpm = [3000]\nload_scales = [1.0]\n")
    };
    let described = parse_study(&text("7006_vg46.toml"), "a.toml", examples).unwrap();
    let p = described.points()[0];
    let spec = described.point_spec(&p);
    assert!(spec.oil.is_some() && spec.roughness.is_some());
    // The same case with the roughness removed: a different spec.
    let mut smooth = described.clone();
    smooth.case.roughness = None;
    let store = MemoryStore::default();
    run(&smooth, &store, Shard::ALL);
    let err = run_study(&described, &store, &RunOptions::default(), &|_| {}).unwrap_err();
    assert!(
        matches!(&err, StudyError::ForeignPoints { difference, .. } if difference.contains("roughness")),
        "{err}"
    );
    // The seed's spec (constants, no roughness) has neither key.
    let plain = study("synthetic", "");
    let json = serde_json::to_string(&plain.point_spec(&plain.points()[0])).unwrap();
    assert!(!json.contains("\"oil\"") && !json.contains("\"roughness\""));
}
