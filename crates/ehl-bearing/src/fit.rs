//! Levenberg–Marquardt fit of Q = K·δ^d + ΔF (placeholder: being written).

use thiserror::Error;

/// Errors of the fit.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    /// Invalid input.
    #[error("invalid fit input: {0}")]
    Invalid(String),
}
