//! Wall-time budgets of the iterative solves.
//!
//! Every iterative solve has an iteration budget of its own (EHL multigrid cycles per start and
//! a fixed ladder of starts, transient cycles per step, Newton iterations of the equilibrium,
//! Levenberg–Marquardt iterations of the fit, iterations of the coupled loop). A [`Deadline`]
//! adds a wall-time budget where a user asks for one: the EHL solver checks it before every
//! multigrid cycle and between its starts, the transient solver before every cycle, the
//! coupled loop before every iteration; when it has passed, the solve ends with a typed error
//! carrying what it had reached (residual history, cycles).

use std::time::{Duration, Instant};

/// A point in time after which solves stop, with the budget it was made from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deadline {
    start: Instant,
    limit: Duration,
}

impl Deadline {
    /// A deadline `seconds` from now. `None` unless `seconds` is finite and > 0 (at most a year).
    pub fn after_seconds(seconds: f64) -> Option<Self> {
        if seconds.is_finite() && seconds > 0.0 && seconds <= 3.2e7 {
            Some(Deadline {
                start: Instant::now(),
                limit: Duration::from_secs_f64(seconds),
            })
        } else {
            None
        }
    }

    /// Whether the budget is spent.
    pub fn expired(&self) -> bool {
        self.start.elapsed() >= self.limit
    }

    /// The budget, s.
    pub fn limit_seconds(&self) -> f64 {
        self.limit.as_secs_f64()
    }

    /// Time since the deadline was made, s.
    pub fn elapsed_seconds(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// Whether an optional deadline has passed.
pub fn expired(d: &Option<Deadline>) -> bool {
    d.as_ref().is_some_and(Deadline::expired)
}
