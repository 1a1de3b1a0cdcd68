//! Where a study keeps its point files and outputs: the [`PointStore`] interface, with an
//! in-memory implementation for tests ([`MemoryStore`]); the file-system store is
//! [`crate::io::FsStore`].

use std::collections::BTreeMap;
use std::sync::Mutex;
use thiserror::Error;

/// A storage failure: what was being done, where, and the system's message.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{action} {location}: {message}")]
pub struct StoreError {
    /// What was being done, e.g. `writing`.
    pub action: String,
    /// The file or key, e.g. `out/points/n3000rpm_s1.json`.
    pub location: String,
    /// The system's message.
    pub message: String,
}

/// Storage of a study: one text file per finished point (by the point's file stem) and the
/// output files built from them. Every write is atomic: a reader, or a resumed or concurrent run
/// of another shard, never sees a partial file. Implementations must allow concurrent writes of
/// different points from several processes (the cluster route writes every shard into one
/// folder).
pub trait PointStore: Sync {
    /// The text of the point file `stem`, or None if there is none.
    fn load_point(&self, stem: &str) -> Result<Option<String>, StoreError>;
    /// Store the point file `stem` atomically (replacing an older one).
    fn save_point(&self, stem: &str, text: &str) -> Result<(), StoreError>;
    /// Write the output file `name` (e.g. `results.csv`) atomically.
    fn write_output(&self, name: &str, bytes: &[u8]) -> Result<(), StoreError>;
    /// Human-readable location of the point file `stem`, for messages.
    fn point_location(&self, stem: &str) -> String;
}

/// A store in memory (tests, and callers that keep results themselves).
#[derive(Debug, Default)]
pub struct MemoryStore {
    /// Point files by stem.
    pub points: Mutex<BTreeMap<String, String>>,
    /// Output files by name.
    pub outputs: Mutex<BTreeMap<String, Vec<u8>>>,
}

fn poisoned(location: &str) -> StoreError {
    StoreError {
        action: "locking".into(),
        location: location.into(),
        message: "a thread panicked while holding the store".into(),
    }
}

impl PointStore for MemoryStore {
    fn load_point(&self, stem: &str) -> Result<Option<String>, StoreError> {
        let m = self.points.lock().map_err(|_| poisoned(stem))?;
        Ok(m.get(stem).cloned())
    }

    fn save_point(&self, stem: &str, text: &str) -> Result<(), StoreError> {
        let mut m = self.points.lock().map_err(|_| poisoned(stem))?;
        m.insert(stem.to_string(), text.to_string());
        Ok(())
    }

    fn write_output(&self, name: &str, bytes: &[u8]) -> Result<(), StoreError> {
        let mut m = self.outputs.lock().map_err(|_| poisoned(name))?;
        m.insert(name.to_string(), bytes.to_vec());
        Ok(())
    }

    fn point_location(&self, stem: &str) -> String {
        format!("memory:{stem}")
    }
}
