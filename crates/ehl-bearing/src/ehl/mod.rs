//! Elastohydrodynamic point contact (placeholder: the solver is being written).

use thiserror::Error;

/// Errors of the EHL solver.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EhlError {
    /// Invalid input.
    #[error("invalid EHL input: {0}")]
    Invalid(String),
}
