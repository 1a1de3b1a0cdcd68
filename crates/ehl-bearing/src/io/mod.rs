//! Case files (TOML) and results (JSON, CSV).

use thiserror::Error;

/// Errors reading user input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum InputError {
    /// A field has an invalid value.
    #[error("{field} = {value}: {expected}")]
    Field {
        /// The field's key, with its table, e.g. `bearing.ball_diameter_mm`.
        field: String,
        /// The value given.
        value: String,
        /// The valid range.
        expected: String,
    },
}
