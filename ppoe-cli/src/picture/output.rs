//! Atomic output: every picture is written to a temporary file beside its destination and
//! renamed over it, so a reader never sees a half-written file and a failure leaves the
//! previous file in place.

use anyhow::Context;
use std::path::Path;

/// Writes a temporary file beside `path` with `write`, then renames it to `path` (see
/// [`crate::output::write_atomic_path`]: the command's one implementation).
pub fn atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    crate::output::write_atomic_path(path, write)
}

/// Writes `bytes` to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    atomically(path, |tmp| {
        std::fs::write(tmp, bytes).with_context(|| format!("cannot create {}", tmp.display()))
    })
}
