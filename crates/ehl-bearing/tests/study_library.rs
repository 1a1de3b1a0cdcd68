//! Studies through the library (`ehl_bearing::study`) behind the in-memory store: shards give the
//! same outputs as one run, point records read back into the same value, another study's points
//! are refused before any work, and outputs need every point.

use ehl_bearing::study::{
    finish_study, merge_points, parse_study, run_study, MemoryStore, PointRecord, PointStore,
    RunOptions, Shard, StoreError, Study, StudyError, StudyEvent,
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
