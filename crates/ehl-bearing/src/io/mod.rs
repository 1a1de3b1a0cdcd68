//! Case files (TOML, engineering units in every key name); the results they produce are written
//! by [`crate::report`] (JSON and CSV, SI).
//!
//! Every invalid case gets an [`InputError`] naming the key (with its table), the value and the
//! valid range; unknown keys are rejected. Nothing here panics on user input.

pub mod case;
pub mod store;

pub use case::{parse_case, read_case, Case};
pub use store::{read_own_file, write_atomic, FsStore, OwnFileError};

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

/// Shortest round-trip text of `v` for names and messages: positional (`3000`, `0.5`) when at
/// most 20 characters, else exponent form (`1e-300`, `1e300`, where positional text runs to
/// 300 digits). Distinct values give distinct texts (only the exponent form has an `e`).
pub fn number_text(v: f64) -> String {
    let positional = format!("{v}");
    if positional.len() <= 20 {
        positional
    } else {
        format!("{v:e}")
    }
}

/// Largest input file read (case, contact, study, trend files are a few kB): 16 MiB.
pub const MAX_INPUT_BYTES: u64 = 16 << 20;

/// Reads a text input file of at most [`MAX_INPUT_BYTES`]: a larger file or an endless one
/// (e.g. `/dev/zero`) is an error after reading that much, instead of filling the memory.
pub fn read_text(path: &std::path::Path) -> Result<String, InputError> {
    use std::io::Read;
    let io = |message: String| InputError::Io {
        path: path.display().to_string(),
        message,
    };
    let file = std::fs::File::open(path).map_err(|e| io(e.to_string()))?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| io(e.to_string()))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(io(format!(
            "larger than {} MiB: not an input file of this program",
            MAX_INPUT_BYTES >> 20
        )));
    }
    String::from_utf8(bytes).map_err(|e| io(format!("not UTF-8 text: {e}")))
}

/// Deserializes TOML text, naming the key of a value of the wrong type or an unknown variant
/// (`in bearing.ball_count: …`), which the TOML parser's message alone does not always do.
pub(crate) fn from_toml<T: serde::de::DeserializeOwned>(
    text: &str,
    origin: &str,
) -> Result<T, InputError> {
    let de = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let message = e.into_inner().to_string().trim_end().to_string();
        InputError::Syntax {
            path: origin.to_string(),
            message: if path == "." || message.contains(&path) {
                message
            } else {
                format!("in `{path}`: {message}")
            },
        }
    })
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
