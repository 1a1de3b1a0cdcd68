//! Case files (TOML, engineering units in every key name); the results they produce are written
//! by [`crate::report`] (JSON and CSV, SI).
//!
//! Every invalid case gets an [`InputError`] naming the key (with its table), the value and the
//! valid range; unknown keys are rejected. Nothing here panics on user input.

pub mod case;
pub mod contact;
pub mod store;
pub mod study;

pub use case::{case_from_table, parse_case, read_case};
pub use store::{read_own_file, write_atomic, FsStore, OwnFileError};
pub use study::{parse_study, read_study};

use crate::case::InputError;

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
    deserialize(toml::Deserializer::new(text), origin)
}

/// [`from_toml`] for values already parsed (a table built by a program, e.g. from a Python
/// dict): the same checks and messages, without writing text.
pub(crate) fn from_toml_value<T: serde::de::DeserializeOwned>(
    value: toml::Value,
    origin: &str,
) -> Result<T, InputError> {
    deserialize(value, origin)
}

fn deserialize<'de, T: serde::de::DeserializeOwned, D: serde::Deserializer<'de>>(
    de: D,
    origin: &str,
) -> Result<T, InputError>
where
    D::Error: std::fmt::Display,
{
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
