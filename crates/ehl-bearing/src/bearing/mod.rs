//! Angular-contact ball bearing: geometry, kinematics, quasi-static 5-DOF equilibrium, stiffness,
//! and the bearing as a force element.

mod dual;
pub mod equilibrium;
pub mod geometry;
pub mod hertz_law;
mod linalg;

pub use equilibrium::{
    cage_speed_of, solve_equilibrium, BallState, BearingModel, ContactLaws, ContactState, Control,
    DynamicForce, Equilibrium, EquilibriumSettings, ForceResult, Kinematics, OperatingPoint,
    RaceControl, DOF_NAMES,
};
pub use geometry::{Bearing, BearingGeometry, Race};
pub use hertz_law::OperatingAngleHertzLaw;
pub(crate) use linalg::solve as linalg_solve;

use thiserror::Error;

/// Errors of the bearing model.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BearingError {
    /// A field has an invalid value (SI units).
    #[error("{field} = {value}: expected {expected}")]
    InvalidField {
        /// The field, e.g. `ball_diameter`.
        field: &'static str,
        /// The value given (SI).
        value: f64,
        /// The valid range.
        expected: String,
    },
    /// Contact laws for a number of contacts other than the bearing's.
    #[error(
        "invalid bearing input: contact laws given for {inner} inner and {outer} outer contacts, \
         bearing has {balls} balls"
    )]
    LawCount {
        /// Inner-raceway laws given.
        inner: usize,
        /// Outer-raceway laws given.
        outer: usize,
        /// Balls of the bearing.
        balls: usize,
    },
    /// A warm-start state for a number of balls other than the bearing's.
    #[error("invalid bearing input: warm-start state for {given} balls, bearing has {balls}")]
    WarmStartSize {
        /// Balls of the state.
        given: usize,
        /// Balls of the bearing.
        balls: usize,
    },
    /// A contact's Hertz constants could not be computed.
    #[error("invalid bearing input: {0}")]
    Hertz(#[from] crate::hertz::HertzError),
    /// The Hertz constant over the contact angle could not be represented by the series.
    #[error(
        "invalid bearing input: the Hertz constant of the {race:?} contact could not be \
         represented over the contact angle to {tolerance:e} (error {worst:.2e} with {terms} terms)"
    )]
    HertzSeries {
        /// The raceway.
        race: Race,
        /// Relative tolerance asked for.
        tolerance: f64,
        /// Largest relative error reached.
        worst: f64,
        /// Terms of the last series tried.
        terms: usize,
    },
    /// A force element's state used before its model was set.
    #[error("invalid bearing input: force element state without a model")]
    StateWithoutModel,
    /// A number of per-contact laws other than 2·Z.
    #[error(
        "invalid bearing input: {given} contact laws given, the bearing has {balls} balls (2·Z \
         laws needed)"
    )]
    ElementLawCount {
        /// Laws given.
        given: usize,
        /// Balls of the bearing.
        balls: usize,
    },
    /// A contact row whose raceway is neither inner nor outer.
    #[error("invalid bearing input: contact row of ball {ball}: race = {race:?}; expected \"inner\" or \"outer\"")]
    ContactRace {
        /// Ball index.
        ball: usize,
        /// The raceway given.
        race: String,
    },
    /// Laws by load from contacts of which none has a finite, positive load.
    #[error(
        "invalid bearing input: laws by load: no contact with a finite, positive \
         characterization load"
    )]
    NoLawLoad,
    /// A law of the laws by load that does not reach a load.
    #[error("invalid bearing input: laws by load: a law does not reach the load w = {load_n} N")]
    LawLoadUnreached {
        /// The load, N.
        load_n: f64,
    },
    /// A law of the laws by load whose stiffness at a load is not finite and positive.
    #[error(
        "invalid bearing input: laws by load: dQ/dδ = {stiffness_n_m} N/m at w = {load_n} N; \
         expected a finite, positive contact stiffness"
    )]
    LawStiffness {
        /// dQ/dδ, N/m.
        stiffness_n_m: f64,
        /// The load, N.
        load_n: f64,
    },
    /// The equilibrium Newton iteration did not converge.
    #[error("bearing equilibrium did not converge after {iterations} iterations: residual {residual:.3e} N (tolerance {tolerance:.3e} N); the load may be one the bearing cannot carry")]
    NotConverged {
        /// Iterations used.
        iterations: usize,
        /// Largest load residual, N (moments divided by d_m/2).
        residual: f64,
        /// Tolerance, N.
        tolerance: f64,
    },
    /// A ball's own equilibrium did not converge.
    #[error("equilibrium of ball {ball} did not converge: residual {residual:.3e} N")]
    BallNotConverged {
        /// Ball index.
        ball: usize,
        /// Residual, N.
        residual: f64,
    },
    /// The load needs a state the bearing cannot physically reach.
    #[error("load the bearing cannot carry: {reason}")]
    Overloaded {
        /// What went out of range.
        reason: String,
    },
}

impl BearingError {
    /// Whether the error is an input the bearing model refuses (laws or states of the wrong
    /// size, contacts it cannot describe, laws by load it cannot build) rather than a failed
    /// equilibrium or a field out of range ([`BearingError::InvalidField`]).
    pub fn is_refused_input(&self) -> bool {
        use BearingError::*;
        matches!(
            self,
            LawCount { .. }
                | WarmStartSize { .. }
                | Hertz(_)
                | HertzSeries { .. }
                | StateWithoutModel
                | ElementLawCount { .. }
                | ContactRace { .. }
                | NoLawLoad
                | LawLoadUnreached { .. }
                | LawStiffness { .. }
        )
    }
}

impl BearingError {
    pub(crate) fn invalid(field: &'static str, value: f64, expected: impl Into<String>) -> Self {
        BearingError::InvalidField {
            field,
            value,
            expected: expected.into(),
        }
    }
}
