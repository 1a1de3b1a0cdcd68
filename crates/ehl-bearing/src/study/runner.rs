//! Running a study (all points or one shard), resuming it, and building its outputs from the
//! stored point files ([`run_study`], [`finish_study`], [`merge_points`]).
//!
//! Every finished point is one file, written atomically as soon as it is done; a rerun skips
//! every point whose file holds the same spec, so a study killed at any moment redoes only the
//! points in flight. The outputs (`results.csv`, `points.csv`, `trends.json`) are built from the
//! point files alone, in study order, so they are byte for byte the same whether the study ran
//! in one go, was resumed, or ran as shards (in one folder or merged from several).

use super::point::{points_csv, results_csv, PointRecord, ResultRow};
use super::spec::{Shard, Study, StudyPoint};
use super::store::{PointStore, StoreError};
use super::trends::{fit_trends, trend_reaction_error};
use crate::characterize::{characterize_bearing_with_progress, CharacterizeError, Progress};
use crate::force_element::TrendForceElement;
use crate::trends::TrendModel;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;
use thiserror::Error;

/// Errors of running, merging and finishing a study.
#[derive(Debug, Error)]
pub enum StudyError {
    /// Reading or writing the store failed.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// The store holds point files of a different study (another method, case or setting) under
    /// this study's point names; nothing was computed or overwritten.
    #[error("{count} point file(s) in the output hold results of a different study (first: {first}: {difference}); nothing was overwritten — use another output folder, or pass --overwrite to recompute them")]
    ForeignPoints {
        /// How many point files differ.
        count: usize,
        /// The first of them.
        first: String,
        /// What differs in it (the first differing part of the spec).
        difference: String,
    },
    /// Building the outputs needs every point, and some are missing.
    #[error("{missing} of {total} points are not finished (first missing: {first}); run the remaining shards first")]
    Incomplete {
        /// Points without a valid file.
        missing: usize,
        /// Points of the study.
        total: usize,
        /// The first missing point's file.
        first: String,
    },
}

/// Options of [`run_study`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// Which points to run (default: all).
    pub shard: Shard,
    /// Recompute point files that hold a different spec instead of refusing (default false).
    pub overwrite: bool,
    /// Wall-time budget of each point, s (default none): a point that runs out of it fails with
    /// the time-limit error and is not saved (a later run with a larger budget computes it).
    /// With a budget the points run one at a time, so that each budget covers a point that has
    /// the whole thread pool.
    pub point_time_limit_s: Option<f64>,
    /// Largest number of points computed at once (default 2; 0 is taken as 1). Their contacts share the
    /// current rayon pool, so a second point fills the threads that one point leaves idle (its
    /// serial equilibrium solves, the last contacts of an iteration); 1 runs the points one
    /// after the other. Results do not depend on it.
    pub points_in_flight: usize,
}

impl RunOptions {
    /// How many points run at once: `points_in_flight` (at least 1), or 1 with a per-point time
    /// limit.
    pub fn points_at_once(&self) -> usize {
        if self.point_time_limit_s.is_some() {
            1
        } else {
            self.points_in_flight.max(1)
        }
    }
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            shard: Shard::ALL,
            overwrite: false,
            point_time_limit_s: None,
            points_in_flight: 2,
        }
    }
}

/// Events of [`run_study`] for progress displays and logs (no effect on results).
#[derive(Debug, Clone, PartialEq)]
pub enum StudyEvent {
    /// The plan: `to_compute` of the shard's `points` points will be computed, the others were
    /// loaded; `redone` of those to compute had an unreadable (e.g. truncated) file.
    Planned {
        /// Points of the shard.
        points: usize,
        /// Points to compute.
        to_compute: usize,
        /// Unreadable point files that will be recomputed.
        redone: usize,
    },
    /// A point starts.
    PointStarted(StudyPoint),
    /// The characterization loop of a point progressed (points may run concurrently, see
    /// [`RunOptions::points_in_flight`]).
    Loop(StudyPoint, Progress),
    /// A point finished and its file was written.
    PointDone {
        /// The point.
        point: StudyPoint,
        /// Whether its loop converged.
        converged: bool,
        /// Its error, if it failed.
        error: Option<String>,
        /// Wall-clock time, s.
        seconds: f64,
    },
}

/// What [`run_study`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyRun {
    /// The shard that ran.
    pub shard: Shard,
    /// Points of the shard.
    pub points: usize,
    /// Points computed in this run.
    pub computed: usize,
    /// Points loaded from their files.
    pub loaded: usize,
    /// Points recomputed because their file was unreadable.
    pub redone: usize,
    /// Computed points whose loop did not converge (recorded with `converged: false`).
    pub not_converged: usize,
    /// Points that failed, with their errors (recorded in their files).
    pub failed: Vec<(StudyPoint, String)>,
    /// Wall-clock time, s.
    pub seconds: f64,
}

/// State of one point in the store.
enum Stored {
    /// A file with this study's spec.
    Done(Box<PointRecord>),
    /// No file.
    Missing,
    /// A file that does not parse (e.g. truncated by a crash).
    Unreadable,
    /// A file of a different study; the string says what differs.
    Foreign(String),
}

fn stored(study: &Study, store: &dyn PointStore, p: &StudyPoint) -> Result<Stored, StoreError> {
    let Some(text) = store.load_point(&p.file_stem())? else {
        return Ok(Stored::Missing);
    };
    let Ok(record) = PointRecord::from_json(&text) else {
        return Ok(Stored::Unreadable);
    };
    let spec = study.point_spec(p);
    if record.spec == spec {
        return Ok(Stored::Done(Box::new(record)));
    }
    Ok(Stored::Foreign(spec_difference(&record, &spec)))
}

/// The first top-level part of the spec that differs, in words (its JSON, shortened to 80
/// characters; `absent` for a part one spec does not have).
fn spec_difference(record: &PointRecord, spec: &super::point::PointSpec) -> String {
    fn short(s: String) -> String {
        if s.len() > 80 {
            format!("{}…", &s[..s.floor_char_boundary_compat(80)])
        } else {
            s
        }
    }
    fn text<T: serde::Serialize>(v: &T) -> String {
        short(serde_json::to_string(v).unwrap_or_default())
    }
    fn optional<T: serde::Serialize>(v: &Option<T>) -> String {
        v.as_ref().map_or_else(|| "absent".into(), text)
    }
    let (a, b) = (&record.spec, spec);
    macro_rules! first_difference {
        ($show:ident: $($part:ident),*) => {
            $(if a.$part != b.$part {
                return format!(
                    "{} is {} there, {} here",
                    stringify!($part),
                    $show(&a.$part),
                    $show(&b.$part)
                );
            })*
        };
    }
    first_difference!(text: inner_speed_rpm, load_scale, method, settings, bearing, lubricant,
        operating, equilibrium);
    first_difference!(optional: oil, roughness, ring_oils);
    "the spec differs".into()
}

trait FloorCharBoundary {
    fn floor_char_boundary_compat(&self, i: usize) -> usize;
}

impl FloorCharBoundary for str {
    fn floor_char_boundary_compat(&self, mut i: usize) -> usize {
        i = i.min(self.len());
        while !self.is_char_boundary(i) {
            i -= 1;
        }
        i
    }
}

/// Run the points of `options.shard` of `study` that are not finished in `store`, writing each
/// point's file as soon as it is done.
///
/// Before any work, every existing point file of the shard is checked: a file with this study's
/// spec is kept, an unreadable one (truncated by a crash) is recomputed, and a file of a
/// different study is an error ([`StudyError::ForeignPoints`]) unless `options.overwrite`. A
/// point that fails (e.g. a load the bearing cannot carry) is recorded with its error and the run
/// goes on; the failures are listed in the returned [`StudyRun`]. Contacts within a point run in
/// parallel on the current rayon pool; results do not depend on the number of threads.
pub fn run_study(
    study: &Study,
    store: &dyn PointStore,
    options: &RunOptions,
    events: &(dyn Fn(StudyEvent) + Sync),
) -> Result<StudyRun, StudyError> {
    let t0 = Instant::now();
    let points = study.shard_points(options.shard);
    // Plan: look at every point file first, so that a foreign folder is refused before any work.
    let mut todo = Vec::new();
    let (mut loaded, mut redone) = (0, 0);
    let mut foreign: Vec<(String, String)> = Vec::new();
    for p in &points {
        match stored(study, store, p)? {
            Stored::Done(_) => loaded += 1,
            Stored::Missing => todo.push(*p),
            Stored::Unreadable => {
                redone += 1;
                todo.push(*p);
            }
            Stored::Foreign(why) => {
                foreign.push((store.point_location(&p.file_stem()), why));
                todo.push(*p);
            }
        }
    }
    if !foreign.is_empty() && !options.overwrite {
        return Err(StudyError::ForeignPoints {
            count: foreign.len(),
            first: foreign[0].0.clone(),
            difference: foreign[0].1.clone(),
        });
    }
    events(StudyEvent::Planned {
        points: points.len(),
        to_compute: todo.len(),
        redone,
    });
    let mut run = StudyRun {
        shard: options.shard,
        points: points.len(),
        computed: 0,
        loaded,
        redone,
        not_converged: 0,
        failed: Vec::new(),
        seconds: 0.0,
    };
    let in_flight = options.points_at_once().min(todo.len().max(1));
    // `in_flight` workers take the next point of the plan until none is left (one worker: in
    // this thread, in plan order); each point's contacts run on the current pool. A store error
    // stops the workers from taking further points, as it stopped the one-by-one loop before.
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let slots: Vec<Mutex<Option<Result<Outcome, StudyError>>>> =
        todo.iter().map(|_| Mutex::new(None)).collect();
    let worker = || {
        while !stop.load(Ordering::Relaxed) {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(p) = todo.get(i) else { break };
            let out = compute_point(study, store, options, p, events);
            if out.is_err() {
                stop.store(true, Ordering::Relaxed);
            }
            *slots[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(out);
        }
    };
    if in_flight == 1 {
        worker();
    } else {
        rayon::scope(|sc| {
            for _ in 0..in_flight {
                sc.spawn(|_| worker());
            }
        });
    }
    // Outcomes in plan order; points not taken after a store error are empty.
    let outcomes: Vec<Option<Result<Outcome, StudyError>>> = slots
        .into_iter()
        .map(|m| m.into_inner().unwrap_or_else(|e| e.into_inner()))
        .collect();
    for (p, out) in todo.iter().zip(outcomes) {
        match out {
            Some(Err(e)) => return Err(e),
            Some(Ok(Outcome::OutOfTime(e))) => run.failed.push((*p, e)),
            Some(Ok(Outcome::Saved { error, converged })) => {
                run.computed += 1;
                if let Some(e) = error {
                    run.failed.push((*p, e));
                } else if !converged {
                    run.not_converged += 1;
                }
            }
            None => {}
        }
    }
    run.seconds = t0.elapsed().as_secs_f64();
    Ok(run)
}

/// What became of one computed point.
enum Outcome {
    /// Its file was written; the error if it failed, and whether its loop converged.
    Saved {
        error: Option<String>,
        converged: bool,
    },
    /// It ran out of its time budget (not saved); the message.
    OutOfTime(String),
}

/// Compute point `p`, write its file (unless it ran out of its time budget) and send its events.
fn compute_point(
    study: &Study,
    store: &dyn PointStore,
    options: &RunOptions,
    p: &StudyPoint,
    events: &(dyn Fn(StudyEvent) + Sync),
) -> Result<Outcome, StudyError> {
    let p = *p;
    events(StudyEvent::PointStarted(p));
    let tp = Instant::now();
    let deadline = options
        .point_time_limit_s
        .and_then(crate::budget::Deadline::after_seconds);
    let record = run_point_within(study, &p, deadline, &|e| events(StudyEvent::Loop(p, e)));
    if record.error.is_some() && deadline.is_some_and(|d| d.expired()) {
        // Out of its time budget: not a result of the point, so no point file.
        let e = format!(
            "{} (not saved: a run with a larger time limit computes it)",
            record.error.clone().unwrap_or_default()
        );
        events(StudyEvent::PointDone {
            point: p,
            converged: false,
            error: Some(e.clone()),
            seconds: tp.elapsed().as_secs_f64(),
        });
        return Ok(Outcome::OutOfTime(e));
    }
    store.save_point(&p.file_stem(), &record.to_json())?;
    events(StudyEvent::PointDone {
        point: p,
        converged: record.converged(),
        error: record.error.clone(),
        seconds: tp.elapsed().as_secs_f64(),
    });
    Ok(Outcome::Saved {
        error: record.error.clone(),
        converged: record.converged(),
    })
}

/// Characterize one point: its [`PointRecord`], reproducible bit for bit (no timings). A point
/// whose characterization fails is a record with the error, not an `Err`.
pub fn run_point(
    study: &Study,
    p: &StudyPoint,
    progress: &(dyn Fn(Progress) + Sync),
) -> PointRecord {
    run_point_within(study, p, None, progress)
}

/// [`run_point`] within the wall-time budget `deadline` (None: none): a point that runs out of
/// it is a record with the time-limit error.
pub fn run_point_within(
    study: &Study,
    p: &StudyPoint,
    deadline: Option<crate::budget::Deadline>,
    progress: &(dyn Fn(Progress) + Sync),
) -> PointRecord {
    let spec = study.point_spec(p);
    match characterize_bearing_with_progress(
        &study.point_case(p),
        &study.method,
        &study.settings,
        deadline,
        progress,
    ) {
        Ok(c) => PointRecord {
            spec,
            result: Some(c.report(false)),
            error: None,
        },
        Err(e) => PointRecord {
            spec,
            result: None,
            error: Some(e.to_string()),
        },
    }
}

/// The outputs of a study, built from its point files.
#[derive(Debug, Clone)]
pub struct StudyOutputs {
    /// Every point's record, in study order.
    pub records: Vec<PointRecord>,
    /// The rows of `results.csv` (points that did not fail).
    pub rows: Vec<ResultRow>,
    /// The trend model, or why it could not be fitted.
    pub trends: Result<TrendModel, String>,
    /// Per point, the trend force element's largest relative reaction error against the point's
    /// own equilibrium (None where there is no trend model or the point failed).
    pub trend_errors: Vec<Option<f64>>,
    /// Failed points: (point, error).
    pub failed: Vec<(StudyPoint, String)>,
}

impl StudyOutputs {
    /// Points whose loop did not converge (failed points not counted).
    pub fn not_converged(&self) -> usize {
        self.records
            .iter()
            .filter(|r| r.result.as_ref().is_some_and(|x| !x.converged))
            .count()
    }

    /// Largest trend reaction error over the points (0 if none).
    pub fn worst_trend_error(&self) -> f64 {
        self.trend_errors
            .iter()
            .flatten()
            .fold(0.0, |m, &x| m.max(x))
    }

    /// The lubrication figures over the study's points (None when its case describes no oil
    /// and gives no roughness or oil supply): the smallest Λ and the largest thermal and
    /// starvation reductions with where they occur, and how many points have warnings.
    pub fn lubrication_summary(&self) -> Option<LubricationSummary> {
        if !self.records.iter().any(|r| r.spec.has_lubrication()) {
            return None;
        }
        let mut s = LubricationSummary {
            min_lambda: None,
            max_thermal_reduction: None,
            max_starvation_reduction: None,
            points_with_warnings: 0,
            points: 0,
        };
        for r in &self.records {
            let Some(l) = r.result.as_ref().and_then(|x| x.lubrication.as_ref()) else {
                continue;
            };
            s.points += 1;
            if !l.warnings.is_empty() {
                s.points_with_warnings += 1;
            }
            let (rpm, scale) = (r.spec.inner_speed_rpm, r.spec.load_scale);
            for c in &l.contacts {
                let at = |value: f64| LubricationExtreme {
                    value,
                    inner_speed_rpm: rpm,
                    load_scale: scale,
                    ball: c.ball,
                    race: c.race.clone(),
                };
                match (c.lambda, &s.min_lambda) {
                    (Some(x), Some(m)) if x >= m.value => {}
                    (Some(x), _) => s.min_lambda = Some(at(x)),
                    (None, _) => {}
                }
                match (c.thermal_reduction, &s.max_thermal_reduction) {
                    (Some(x), Some(m)) if x <= m.value => {}
                    (Some(x), _) => s.max_thermal_reduction = Some(at(x)),
                    (None, _) => {}
                }
                match (
                    c.starvation.map(|v| v.reduction),
                    &s.max_starvation_reduction,
                ) {
                    (Some(x), Some(m)) if x <= m.value => {}
                    (Some(x), _) => s.max_starvation_reduction = Some(at(x)),
                    (None, _) => {}
                }
            }
        }
        Some(s)
    }
}

/// Where a lubrication figure of a study is at its extreme.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LubricationExtreme {
    /// The figure (Λ, or the thermal reduction as a fraction).
    pub value: f64,
    /// The point's inner-ring speed, rpm.
    pub inner_speed_rpm: f64,
    /// The point's load scale.
    pub load_scale: f64,
    /// Ball index.
    pub ball: usize,
    /// `inner` or `outer`.
    pub race: String,
}

/// The lubrication figures over a study's points ([`StudyOutputs::lubrication_summary`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LubricationSummary {
    /// The smallest Λ over every point and contact (None without roughness).
    pub min_lambda: Option<LubricationExtreme>,
    /// The largest thermal film reduction (None without a described oil).
    pub max_thermal_reduction: Option<LubricationExtreme>,
    /// The largest starvation reduction of the minimum film (None without an oil supply;
    /// absent from the JSON then).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_starvation_reduction: Option<LubricationExtreme>,
    /// Points whose report has warnings (Λ < 1.5, thermal reduction above 10 %, κ < 1).
    pub points_with_warnings: usize,
    /// Points with a report (the failed ones have none).
    pub points: usize,
}

/// Read every point of `study` from `store` (all must be finished, with this study's spec), fit
/// the trend curves, and write `results.csv`, `points.csv` and (if the trends could be fitted)
/// `trends.json` into the store. The files depend on the point files only.
pub fn finish_study(study: &Study, store: &dyn PointStore) -> Result<StudyOutputs, StudyError> {
    let points = study.points();
    let mut records = Vec::with_capacity(points.len());
    let mut missing = Vec::new();
    let mut foreign = Vec::new();
    for p in &points {
        let location = store.point_location(&p.file_stem());
        match stored(study, store, p)? {
            Stored::Done(r) => records.push(*r),
            Stored::Missing => missing.push(location),
            Stored::Unreadable => missing.push(format!(
                "{location} (unreadable: truncated or not a point file)"
            )),
            // A file computed by another study (e.g. another method) is there but is not this
            // study's point: say so, not "missing".
            Stored::Foreign(why) => foreign.push((location, why)),
        }
    }
    if let Some((first, difference)) = foreign.first() {
        return Err(StudyError::ForeignPoints {
            count: foreign.len(),
            first: first.clone(),
            difference: difference.clone(),
        });
    }
    if !missing.is_empty() {
        return Err(StudyError::Incomplete {
            missing: missing.len(),
            total: points.len(),
            first: missing[0].clone(),
        });
    }
    let rows: Vec<ResultRow> = records.iter().flat_map(|r| r.rows()).collect();
    let failed: Vec<(StudyPoint, String)> = points
        .iter()
        .zip(&records)
        .filter_map(|(p, r)| r.error.clone().map(|e| (*p, e)))
        .collect();
    store.write_output("results.csv", results_csv(&rows).as_bytes())?;
    let trends = fit_trends(study, &rows).map_err(|e: CharacterizeError| e.to_string());
    let mut trend_errors = vec![None; records.len()];
    if let Ok(model) = &trends {
        store.write_output("trends.json", (model.to_json() + "\n").as_bytes())?;
        if let Ok(element) = TrendForceElement::new(model.clone()) {
            for (i, r) in records.iter().enumerate() {
                if r.result.is_some() {
                    trend_errors[i] = trend_reaction_error(&element, r).ok();
                }
            }
        }
    }
    store.write_output("points.csv", points_csv(&records, &trend_errors).as_bytes())?;
    Ok(StudyOutputs {
        records,
        rows,
        trends,
        trend_errors,
        failed,
    })
}

/// Copy into `target` every point file of `study` found in `sources` (the output folders of
/// shards run apart) whose spec is this study's; a point already in `target` with this spec is
/// kept. Returns the number of point files copied. Files of other studies are not copied
/// (a source holding one is an error, as in [`run_study`]).
pub fn merge_points(
    study: &Study,
    target: &dyn PointStore,
    sources: &[&dyn PointStore],
) -> Result<usize, StudyError> {
    let mut copied = 0;
    for p in &study.points() {
        if let Stored::Done(_) = stored(study, target, p)? {
            continue;
        }
        for src in sources {
            match stored(study, *src, p)? {
                Stored::Done(r) => {
                    target.save_point(&p.file_stem(), &r.to_json())?;
                    copied += 1;
                    break;
                }
                Stored::Foreign(why) => {
                    return Err(StudyError::ForeignPoints {
                        count: 1,
                        first: src.point_location(&p.file_stem()),
                        difference: why,
                    })
                }
                Stored::Missing | Stored::Unreadable => {}
            }
        }
    }
    Ok(copied)
}
