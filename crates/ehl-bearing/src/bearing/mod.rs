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
    /// Other invalid input.
    #[error("invalid bearing input: {0}")]
    Invalid(String),
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
    pub(crate) fn invalid(field: &'static str, value: f64, expected: impl Into<String>) -> Self {
        BearingError::InvalidField {
            field,
            value,
            expected: expected.into(),
        }
    }
}
