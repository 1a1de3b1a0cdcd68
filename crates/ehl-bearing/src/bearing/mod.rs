//! Angular-contact ball bearing: geometry, kinematics, quasi-static 5-DOF equilibrium, stiffness.

use thiserror::Error;

/// Errors of the bearing model.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BearingError {
    /// Invalid geometry.
    #[error("invalid bearing: {0}")]
    Invalid(String),
}
