//! Every byte the command writes goes through here: files are written atomically where the
//! path allows it (a temporary file in the same directory, renamed over the final name
//! once complete), written through where it does not, and standard output tolerates a
//! reader that went away.
//!
//! Atomic: an interrupted run (Ctrl-C, a full disk, an error half-way through a GIF) never
//! leaves a truncated file under the final name, and the previous good file stays until
//! the new one is complete. A killed run may leave its hidden temporary file
//! (`.ppoe-tmp-<random>-<name>`, made by the `tempfile` crate) behind; nothing else reads
//! it.
//!
//! What the path is decides how ([`Target`]): a new path or a regular file is replaced
//! atomically; a symbolic link to a regular file (or to nothing yet) keeps the link, and
//! the file it points to is replaced atomically; anything else that exists — a device such
//! as `/dev/null`, a FIFO, `/dev/stdout` — is opened and written through, never renamed
//! over (renaming a temporary file over `/dev/null` would replace the system's device).
//!
//! Standard output: when the reader closes the pipe (`ppoe demo | head`), further output
//! is dropped silently and the command carries on (the files it writes are its product);
//! `table` and `eval`, whose product *is* standard output, stop early and exit 0. Any other
//! write error (a full disk behind `> file`) is an error naming standard output.

use anyhow::bail;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// Set once a write to standard output found the pipe closed.
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);
/// The first standard-output error other than a closed pipe, reported by `main` at exit
/// (the `println!` of this module cannot return it).
static STDOUT_ERROR: Mutex<Option<String>> = Mutex::new(None);

/// `true` once the reader of standard output went away.
pub fn stdout_closed() -> bool {
    STDOUT_CLOSED.load(Ordering::Relaxed)
}

/// Writes `bytes` to standard output and flushes.
///
/// # Errors
/// A write error other than a closed pipe, as a sentence naming standard output. A closed
/// pipe is not an error: the bytes are dropped and [`stdout_closed`] turns `true`.
pub fn print(bytes: &[u8]) -> anyhow::Result<()> {
    if stdout_closed() {
        return Ok(());
    }
    let mut out = io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            STDOUT_CLOSED.store(true, Ordering::Relaxed);
            Ok(())
        }
        Err(e) => bail!("cannot write to standard output: {}", io_sentence(&e)),
    }
}

/// [`print()`] for this module's `println!`: an error is kept for [`take_stdout_error`].
pub fn print_fmt(args: std::fmt::Arguments<'_>) {
    let mut text = args.to_string();
    text.push('\n');
    if let Err(e) = print(text.as_bytes()) {
        let mut slot = STDOUT_ERROR.lock().unwrap_or_else(|p| p.into_inner());
        slot.get_or_insert_with(|| e.to_string());
    }
}

/// The first standard-output error met by the `println!` of this module, if any.
pub fn take_stdout_error() -> Option<String> {
    STDOUT_ERROR
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .take()
}

/// `println!` through [`print()`]: a closed pipe is not a panic. Modules that log progress
/// lines (`use crate::output::println;`) shadow the standard macro with this one.
macro_rules! println {
    ($($arg:tt)*) => {
        $crate::output::print_fmt(format_args!($($arg)*))
    };
}
pub(crate) use println;

/// An I/O error as a sentence ("No such file or directory"), without the `(os error N)`
/// suffix and never as a debug value.
pub fn io_sentence(e: &io::Error) -> String {
    let text = e.to_string();
    match text.find(" (os error") {
        Some(i) => text[..i].to_string(),
        None => text,
    }
}

/// A new hidden temporary file next to `path` (in its directory, so the rename is atomic),
/// named `.ppoe-tmp-<random>-<name>` to keep `path`'s extension (the PNG writer picks the
/// format from it); removed when dropped unless persisted. Created with the mode a plain
/// `File::create` gives (0o666 less the umask), not tempfile's private 0o600, so outputs
/// keep the permissions they had.
fn temp_file(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut suffix = std::ffi::OsString::from("-");
    suffix.push(name);
    let mut builder = tempfile::Builder::new();
    builder.prefix(".ppoe-tmp-").suffix(&suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir)
}

/// How a file at a path is written.
#[derive(Debug, PartialEq, Eq)]
enum Target {
    /// Atomically: a temporary file next to this path (the path given, or the file a
    /// symbolic link points to), renamed over it.
    Replace(PathBuf),
    /// Through the path as given: it exists and is not a regular file (a device, a FIFO, a
    /// socket, or a link to one), so it is opened for writing, neither created nor
    /// truncated nor replaced.
    Through,
}

/// A symbolic link's own target, relative targets taken from the link's directory.
fn link_target(link: &Path) -> io::Result<PathBuf> {
    let t = std::fs::read_link(link)?;
    Ok(match link.parent() {
        Some(dir) if t.is_relative() => dir.join(t),
        _ => t,
    })
}

/// The path a chain of symbolic links that ends in nothing (yet) points to: the file to
/// create there, atomically.
fn dangling_target(path: &Path) -> anyhow::Result<PathBuf> {
    let sentence =
        |e: io::Error| anyhow::anyhow!("cannot write {}: {}", path.display(), io_sentence(&e));
    let mut p = path.to_path_buf();
    // As many links as Linux follows.
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => p = link_target(&p).map_err(sentence)?,
            Ok(_) => bail!(
                "cannot write {}: it changed while being looked at",
                path.display()
            ),
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(p),
            Err(e) => return Err(sentence(e)),
        }
    }
    bail!(
        "cannot write {}: too many levels of symbolic links",
        path.display()
    )
}

/// How `path` is written (see [`Target`]).
///
/// # Errors
/// `path` is a directory (or a link to one), or cannot be looked at.
fn target(path: &Path) -> anyhow::Result<Target> {
    let sentence =
        |e: io::Error| anyhow::anyhow!("cannot write {}: {}", path.display(), io_sentence(&e));
    // Followed by the kernel first: `/dev/stdout` → `/proc/self/fd/1` → `pipe:[…]` is a
    // link only the kernel can follow.
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => bail!("cannot write {}: it is a directory", path.display()),
        Ok(m) if !m.is_file() => Ok(Target::Through),
        Ok(_)
            if std::fs::symlink_metadata(path)
                .map_err(sentence)?
                .is_symlink() =>
        {
            std::fs::canonicalize(path)
                .map(Target::Replace)
                .map_err(sentence)
        }
        Ok(_) => Ok(Target::Replace(path.to_path_buf())),
        Err(e) if e.kind() == io::ErrorKind::NotFound => match std::fs::symlink_metadata(path) {
            Ok(_) => dangling_target(path).map(Target::Replace),
            Err(_) => Ok(Target::Replace(path.to_path_buf())),
        },
        Err(e) => Err(sentence(e)),
    }
}

/// Opens `path` (a [`Target::Through`]) for writing as it is.
fn open_through(path: &Path) -> io::Result<std::fs::File> {
    std::fs::OpenOptions::new().write(true).open(path)
}

/// Calls `write(temp)` to fill a temporary file next to `real`, then renames it to
/// `real` (tempfile's `persist`); errors name `shown`, the path as given. On any error the
/// temporary file is removed (dropped) and `real` is left as it was.
fn replace(
    real: &Path,
    shown: &Path,
    write: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let sentence =
        |e: io::Error| anyhow::anyhow!("cannot write {}: {}", shown.display(), io_sentence(&e));
    let temp = temp_file(real).map_err(sentence)?;
    write(temp.path())?;
    // Data on disk before the rename makes the new name visible (the writer may have
    // written through its own handle of the path).
    std::fs::File::open(temp.path())
        .and_then(|f| f.sync_all())
        .map_err(sentence)?;
    temp.persist(real).map_err(|e| sentence(e.error))?;
    Ok(())
}

/// Writes `path` with `write(file)`, for writers that take a path (the picture encoders,
/// which pick the format from its extension): atomically, or for a [`Target::Through`]
/// into a temporary file next to `path` whose bytes are then copied through.
///
/// # Errors
/// The writer's error, or a failure to write, rename or copy, each naming `path`; the
/// temporary file is removed and a replaced `path` is left as it was.
pub fn write_atomic_path(
    path: &Path,
    write: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let real = match target(path)? {
        Target::Replace(real) => return replace(&real, path, write),
        Target::Through => path,
    };
    let sentence =
        |e: io::Error| anyhow::anyhow!("cannot write {}: {}", real.display(), io_sentence(&e));
    // Dropped (removed) at the end, whatever happens.
    let temp = temp_file(path).map_err(sentence)?;
    write(temp.path())?;
    let mut from = std::fs::File::open(temp.path()).map_err(sentence)?;
    let mut to = open_through(real).map_err(sentence)?;
    io::copy(&mut from, &mut to).map_err(sentence)?;
    to.flush().map_err(sentence)
}

/// Writes `path` atomically through a buffered writer given to `write` (or through it, see
/// [`Target`]).
///
/// # Errors
/// As [`write_atomic_with`].
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> anyhow::Result<()> {
    write_atomic_with(path, |w| write(w).map_err(anyhow::Error::from))
}

/// Writes `path` through a buffered writer given to `write`, for writers whose own errors
/// are not I/O errors (a frame that cannot be made half-way through a page): atomically,
/// or for a [`Target::Through`] straight into it.
///
/// # Errors
/// As [`write_atomic_path`]; I/O errors as sentences naming `path`.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let sentence =
        |e: io::Error| anyhow::anyhow!("cannot write {}: {}", path.display(), io_sentence(&e));
    let fill = |file: std::fs::File| {
        let mut w = io::BufWriter::new(file);
        write(&mut w).map_err(|e| match e.downcast::<io::Error>() {
            Ok(io) => sentence(io),
            Err(e) => e,
        })?;
        w.flush().map_err(sentence)
    };
    match target(path)? {
        Target::Replace(real) => replace(&real, path, |temp| {
            fill(std::fs::File::create(temp).map_err(sentence)?)
        }),
        Target::Through => fill(open_through(path).map_err(sentence)?),
    }
}

/// Checks, before any computation, that the file `path` can be written: as
/// [`check_targets`] in its directory (the one of the file a link points to), or nothing
/// to check for a path written through.
///
/// # Errors
/// As [`check_targets`].
pub fn check_file(path: &Path) -> anyhow::Result<()> {
    let Target::Replace(real) = target(path)? else {
        return Ok(());
    };
    let dir = real.parent().filter(|d| !d.as_os_str().is_empty());
    let Some(name) = real.file_name() else {
        bail!("cannot write {}: not a file name", path.display());
    };
    check_targets(
        dir.unwrap_or(Path::new(".")),
        &[name.to_string_lossy().into_owned()],
    )
}

/// Checks, before any computation, that the files `names` can be written in `dir`:
/// creates `dir` if needed, checks that it is a directory, that no target is a directory,
/// and that a file can be created there (and in the directory of each file a link
/// points to).
///
/// # Errors
/// A sentence naming the directory or the file.
pub fn check_targets(dir: &Path, names: &[String]) -> anyhow::Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!("the output directory {} is not a directory", dir.display());
    }
    std::fs::create_dir_all(dir).map_err(|e| {
        anyhow::anyhow!(
            "cannot create the output directory {}: {}",
            dir.display(),
            io_sentence(&e)
        )
    })?;
    let mut dirs = vec![dir.to_path_buf()];
    for name in names {
        // A link elsewhere is replaced in its target's directory, which must take the
        // temporary file too; a path written through needs none.
        if let Target::Replace(real) = target(&dir.join(name))? {
            match real.parent() {
                Some(d) if !d.as_os_str().is_empty() && !dirs.iter().any(|x| x == d) => {
                    dirs.push(d.to_path_buf())
                }
                _ => {}
            }
        }
    }
    dirs.iter().try_for_each(|d| probe(d))
}

/// Creates and removes a temporary file in `dir`.
fn probe(dir: &Path) -> anyhow::Result<()> {
    // Removed when dropped.
    temp_file(&dir.join("probe")).map_err(|e| {
        anyhow::anyhow!(
            "cannot write into the output directory {}: {}",
            dir.display(),
            io_sentence(&e)
        )
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("ppoe-output-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_failed_write_keeps_the_previous_file_and_no_temporary() {
        let d = dir("keep");
        let p = d.join("a.obj");
        write_atomic(&p, |w| w.write_all(b"good")).unwrap();
        let r = write_atomic(&p, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("interrupted"))
        });
        assert!(r.unwrap_err().to_string().contains("a.obj"));
        assert_eq!(std::fs::read(&p).unwrap(), b"good");
        let names: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }

    #[test]
    fn temporary_keeps_the_extension_and_the_directory() {
        let d = dir("extension");
        let t = temp_file(&d.join("ppoe-render-0.png")).unwrap();
        assert_eq!(t.path().extension().unwrap(), "png");
        assert_eq!(t.path().parent().unwrap(), d);
        let name = t.path().file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            name.starts_with(".ppoe-tmp-") && name.ends_with("-ppoe-render-0.png"),
            "{name}"
        );
        #[cfg(unix)]
        {
            // Not tempfile's 0o600: what File::create gives under this umask.
            use std::os::unix::fs::PermissionsExt;
            let plain = d.join("plain");
            std::fs::File::create(&plain).unwrap();
            let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode();
            assert_eq!(mode(t.path()), mode(&plain));
        }
    }

    #[test]
    fn io_errors_are_sentences() {
        let e = io::Error::from_raw_os_error(2);
        assert_eq!(io_sentence(&e), "No such file or directory");
    }
}
