//! Atomic output: every picture is written to a temporary file beside its destination and
//! renamed over it, so a reader never sees a half-written file and a failure leaves the
//! previous file in place.

use anyhow::Context;
use std::path::{Path, PathBuf};

/// A temporary path in the same directory as `path` (so the rename stays on one file
/// system), keeping its extension (the PNG encoder picks the format from it).
pub fn temp_sibling(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let ext = path
        .extension()
        .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
    path.with_file_name(format!(".{name}.{}.tmp{ext}", std::process::id()))
}

/// Writes the temporary file with `write`, then renames it to `path`; the temporary file
/// is removed on any failure.
pub fn atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let tmp = temp_sibling(path);
    let result = write(&tmp).and_then(|()| {
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot rename onto {}", path.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.with_context(|| format!("cannot write {}", path.display()))
}

/// Writes `bytes` to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    atomically(path, |tmp| {
        std::fs::write(tmp, bytes).with_context(|| format!("cannot create {}", tmp.display()))
    })
}
