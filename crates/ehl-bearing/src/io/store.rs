//! The file-system [`PointStore`]: `DIR/points/<stem>.json` and `DIR/<output>`, every file
//! written atomically (a temporary file in the same folder, synced, then renamed).

use crate::study::{PointStore, StoreError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A study's output folder on disk.
#[derive(Debug, Clone)]
pub struct FsStore {
    dir: PathBuf,
}

fn err(action: &str, path: &Path, e: impl ToString) -> StoreError {
    StoreError {
        action: action.into(),
        location: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Write `bytes` to `path` atomically: a temporary file in the same folder (named after the
/// process, so concurrent writers never share one), synced, then renamed over `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| err("writing", path, "not a file name"))?;
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp).map_err(|e| err("creating", &tmp, e))?;
        f.write_all(bytes).map_err(|e| err("writing", &tmp, e))?;
        f.sync_all().map_err(|e| err("syncing", &tmp, e))?;
        std::fs::rename(&tmp, path).map_err(|e| err("renaming into", path, e))
    })();
    if result.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    result
}

impl FsStore {
    /// The store in folder `dir`: creates `dir/points` if needed and removes temporary files
    /// that an interrupted run of this process id could have left (other processes' temporaries
    /// are left alone: they may be writing).
    pub fn create(dir: &Path) -> Result<Self, StoreError> {
        let points = dir.join("points");
        if dir.exists() && !dir.is_dir() {
            return Err(err(
                "using",
                dir,
                "exists and is not a folder: give a folder for -o",
            ));
        }
        std::fs::create_dir_all(&points).map_err(|e| err("creating", &points, e))?;
        // Refuse an unwritable folder now, not after the first point's computation.
        let probe = points.join(format!(".probe-{}", std::process::id()));
        std::fs::write(&probe, b"").map_err(|e| err("writing into", &points, e))?;
        std::fs::remove_file(&probe).map_err(|e| err("removing", &probe, e))?;
        Ok(FsStore {
            dir: dir.to_path_buf(),
        })
    }

    /// Open an existing store (for merging and status); errors if `dir/points` is missing.
    pub fn open(dir: &Path) -> Result<Self, StoreError> {
        let points = dir.join("points");
        if !points.is_dir() {
            return Err(err(
                "opening",
                &points,
                "no points folder: not the output folder of a study",
            ));
        }
        Ok(FsStore {
            dir: dir.to_path_buf(),
        })
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Path of the point file `stem`.
    pub fn point_path(&self, stem: &str) -> PathBuf {
        self.dir.join("points").join(format!("{stem}.json"))
    }

    /// Stems of the point files present (sorted).
    pub fn stems(&self) -> Result<Vec<String>, StoreError> {
        let points = self.dir.join("points");
        let mut out = Vec::new();
        for entry in std::fs::read_dir(&points).map_err(|e| err("reading", &points, e))? {
            let entry = entry.map_err(|e| err("reading", &points, e))?;
            let name = entry.file_name().to_string_lossy().to_string();
            if let Some(stem) = name.strip_suffix(".json") {
                if !name.starts_with('.') {
                    out.push(stem.to_string());
                }
            }
        }
        out.sort();
        Ok(out)
    }
}

/// What a file that is not a regular file is, for messages.
fn file_kind(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a folder"
    } else {
        "not a regular file"
    }
}

/// Why [`read_own_file`] did not return a file's text.
#[derive(Debug)]
pub enum OwnFileError {
    /// The file could not be read (permissions, I/O).
    Io(std::io::Error),
    /// The path is not a regular file (a folder, FIFO, device or a link to one).
    NotRegular {
        /// What it is instead.
        kind: &'static str,
    },
    /// The file is larger than any this program writes.
    TooLarge {
        /// Its size, bytes.
        bytes: u64,
        /// The limit, MiB.
        limit_mib: u64,
    },
}

impl OwnFileError {
    /// What the path is instead of a file this program could have written (None for an I/O
    /// error).
    pub fn foreign(&self) -> Option<String> {
        match self {
            OwnFileError::Io(_) => None,
            OwnFileError::NotRegular { kind } => Some(format!("not a regular file ({kind})")),
            OwnFileError::TooLarge { bytes, limit_mib } => {
                Some(format!("{bytes} bytes, larger than {limit_mib} MiB"))
            }
        }
    }
}

impl std::fmt::Display for OwnFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OwnFileError::Io(e) => write!(f, "{e}"),
            other => write!(
                f,
                "{}: not a file of this program",
                other.foreign().unwrap_or_default()
            ),
        }
    }
}

/// The text of a file this program writes into its output folders (point files, progress
/// markers, trend files; a few kB to MB); `None` when there is none. A folder, FIFO, device or a
/// link to one (reading a FIFO would block forever, `/dev/zero` would fill the memory) or a file
/// above [`MAX_INPUT_BYTES`](super::MAX_INPUT_BYTES) is refused before any read; invalid UTF-8
/// is replaced (the JSON parser then names the fault).
pub fn read_own_file(path: &Path) -> Result<Option<String>, OwnFileError> {
    use std::io::Read;
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(OwnFileError::Io(e)),
    };
    if !meta.is_file() {
        return Err(OwnFileError::NotRegular {
            kind: file_kind(&meta.file_type()),
        });
    }
    let limit = super::MAX_INPUT_BYTES;
    let too_large = |bytes: u64| OwnFileError::TooLarge {
        bytes,
        limit_mib: limit >> 20,
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
        .map_err(OwnFileError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(Some(String::from_utf8_lossy(&bytes).into_owned()))
}

impl PointStore for FsStore {
    /// The point file's text; `None` when there is none. A point file is a regular file this
    /// program wrote (a few kB): a folder, FIFO, device or a link to one (reading a FIFO would
    /// block forever, `/dev/zero` would fill the memory) or a file above
    /// [`MAX_INPUT_BYTES`](super::MAX_INPUT_BYTES) is an error naming it, before any read.
    fn load_point(&self, stem: &str) -> Result<Option<String>, StoreError> {
        let path = self.point_path(stem);
        match read_own_file(&path) {
            Ok(text) => Ok(text),
            Err(OwnFileError::Io(e)) => Err(err("reading", &path, e)),
            Err(foreign) => Err(err(
                "reading",
                &path,
                format!(
                    "{}: not a point file of this program; remove it to recompute the point",
                    foreign.foreign().unwrap_or_default()
                ),
            )),
        }
    }

    fn save_point(&self, stem: &str, text: &str) -> Result<(), StoreError> {
        write_atomic(&self.point_path(stem), text.as_bytes())
    }

    fn write_output(&self, name: &str, bytes: &[u8]) -> Result<(), StoreError> {
        write_atomic(&self.dir.join(name), bytes)
    }

    fn point_location(&self, stem: &str) -> String {
        self.point_path(stem).display().to_string()
    }
}
