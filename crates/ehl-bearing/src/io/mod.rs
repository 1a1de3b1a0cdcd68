//! Case files (TOML, engineering units in every key name) and machine-readable results (JSON, SI).
//!
//! Every invalid case gets an [`InputError`] naming the key (with its table), the value and the
//! valid range; unknown keys are rejected. Nothing here panics on user input.

pub mod case;
pub mod json;
pub mod store;

pub use case::{parse_case, read_case, Case};
pub use store::{write_atomic, FsStore};

use thiserror::Error;

/// Errors reading user input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum InputError {
    /// A field has an invalid value.
    #[error("{field} = {value}: expected {expected}")]
    Field {
        /// The key, with its table, e.g. `bearing.ball_diameter_mm`.
        field: String,
        /// The value given.
        value: String,
        /// The valid range.
        expected: String,
    },
    /// Two keys that exclude each other were both given.
    #[error("{first} and {second} are both given: give one or the other")]
    Conflict {
        /// One key.
        first: String,
        /// The other key.
        second: String,
    },
    /// A required key is missing.
    #[error("{field} is missing: {hint}")]
    Missing {
        /// The key.
        field: String,
        /// What to give.
        hint: String,
    },
    /// The file is not valid TOML for a case (syntax, wrong type, unknown key).
    #[error("{path}: {message}")]
    Syntax {
        /// File name (or `<input>`).
        path: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// The file could not be read.
    #[error("cannot read {path}: {message}")]
    Io {
        /// File name.
        path: String,
        /// The OS error.
        message: String,
    },
}

impl InputError {
    pub(crate) fn field(field: &str, value: impl ToString, expected: impl Into<String>) -> Self {
        InputError::Field {
            field: field.to_string(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }
}
