//! Progress events as typed records: the dicts of the Python package's progress callbacks and the
//! JSON texts of the C interface's progress callback.

use crate::characterize::{IterationSummary, Progress};
use crate::study::StudyEvent;
use serde::Serialize;

/// An event of the coupled loop ([`Progress`]): `{"event": "iteration_started", "iteration",
/// "contacts"}`, `{"event": "contact_done", "iteration"}`, `{"event": "iteration_done",
/// "record"}` (the iteration's record with its `seconds`, as [`IterationSummary`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum ProgressEvent {
    /// An iteration starts (0: the load prediction).
    IterationStarted {
        /// Iteration number.
        iteration: usize,
        /// Contacts to characterize.
        contacts: usize,
    },
    /// One contact was characterized.
    ContactDone {
        /// Iteration number.
        iteration: usize,
    },
    /// An iteration finished.
    IterationDone {
        /// Its record, with its wall-clock time.
        record: IterationSummary,
    },
}

impl From<&Progress> for ProgressEvent {
    fn from(p: &Progress) -> Self {
        match *p {
            Progress::IterationStarted {
                iteration,
                contacts,
            } => ProgressEvent::IterationStarted {
                iteration,
                contacts,
            },
            Progress::ContactDone { iteration } => ProgressEvent::ContactDone { iteration },
            Progress::IterationDone(r) => ProgressEvent::IterationDone {
                record: IterationSummary {
                    record: r,
                    seconds: Some(r.seconds),
                },
            },
        }
    }
}

/// An event of the loop at one speed of a coefficients run: the [`ProgressEvent`]'s keys and
/// `speed_index`, the speed's index in the list given.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpeedProgressEvent {
    /// The loop's event.
    #[serde(flatten)]
    pub event: ProgressEvent,
    /// Index of the speed.
    pub speed_index: usize,
}

impl SpeedProgressEvent {
    /// The event `p` at speed `speed_index`.
    pub fn new(speed_index: usize, p: &Progress) -> Self {
        SpeedProgressEvent {
            event: p.into(),
            speed_index,
        }
    }
}

/// An event of a study run ([`StudyEvent`]): `planned` (`points`, `to_compute`, `redone`),
/// `point_started` (`index`, `inner_speed_rpm`, `load_scale`), `loop` (`index`, `progress`: the
/// point's [`ProgressEvent`]), `point_done` (`index`, `converged`, `error`, `seconds`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum StudyEventReport {
    /// The run's plan.
    Planned {
        /// Points of the shard.
        points: usize,
        /// Points to compute in this run.
        to_compute: usize,
        /// Unreadable point files that will be recomputed.
        redone: usize,
    },
    /// A point starts.
    PointStarted {
        /// Point index.
        index: usize,
        /// Inner-ring speed, rpm.
        inner_speed_rpm: f64,
        /// Load scale.
        load_scale: f64,
    },
    /// An event of a point's loop.
    Loop {
        /// Point index.
        index: usize,
        /// The loop's event.
        progress: ProgressEvent,
    },
    /// A point finished.
    PointDone {
        /// Point index.
        index: usize,
        /// Whether its loop converged.
        converged: bool,
        /// Its error, if it failed.
        error: Option<String>,
        /// Wall-clock time, s.
        seconds: f64,
    },
}

impl From<&StudyEvent> for StudyEventReport {
    fn from(e: &StudyEvent) -> Self {
        match e {
            StudyEvent::Planned {
                points,
                to_compute,
                redone,
            } => StudyEventReport::Planned {
                points: *points,
                to_compute: *to_compute,
                redone: *redone,
            },
            StudyEvent::PointStarted(p) => StudyEventReport::PointStarted {
                index: p.index,
                inner_speed_rpm: p.inner_speed_rpm,
                load_scale: p.load_scale,
            },
            StudyEvent::Loop(p, l) => StudyEventReport::Loop {
                index: p.index,
                progress: l.into(),
            },
            StudyEvent::PointDone {
                point,
                converged,
                error,
                seconds,
            } => StudyEventReport::PointDone {
                index: point.index,
                converged: *converged,
                error: error.clone(),
                seconds: *seconds,
            },
        }
    }
}
