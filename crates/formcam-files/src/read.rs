//! Reading an input file: regular files only, with a size cap.
//!
//! Every file formcam reads (job files, meridian and eye-curve tables,
//! templates, machine files, measurements, programs, axes tables, `.wind`
//! documents, contours) is read by [`read_text`] or [`read_bytes`]. A path
//! that names something other than a regular file (a folder, a FIFO, a device
//! such as `/dev/zero`) is refused before it is opened, and at most the cap
//! is read, so an endless input stops at once instead of filling the memory.
//!
//! The cap is one process-wide setting ([`max_input_bytes`],
//! [`set_max_input_bytes`]), [`DEFAULT_MAX_INPUT_BYTES`] unless changed: the
//! command line sets it once from `--max-input-mb`, so every reader below it
//! keeps its one-argument form.

use std::fs::{self, File, Metadata};
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The default cap on one input: 256 MiB, far above any real job, table,
/// report or program.
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 256 * MIB;

/// Bytes per MiB.
const MIB: u64 = 1024 * 1024;

/// The cap in force (bytes).
static MAX_INPUT_BYTES: AtomicU64 = AtomicU64::new(DEFAULT_MAX_INPUT_BYTES);

/// The largest input read, in bytes.
pub fn max_input_bytes() -> u64 {
    MAX_INPUT_BYTES.load(Ordering::Relaxed)
}

/// Sets the largest input read, in bytes, for the whole process (the command
/// line's `--max-input-mb`).
pub fn set_max_input_bytes(bytes: u64) {
    MAX_INPUT_BYTES.store(bytes, Ordering::Relaxed);
}

/// What a path names when it is not a regular file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A folder.
    Folder,
    /// A named pipe.
    Fifo,
    /// A character device (`/dev/zero`, `/dev/urandom`, a terminal).
    CharDevice,
    /// A block device.
    BlockDevice,
    /// A Unix socket.
    Socket,
    /// Anything else that is not a regular file.
    Other,
}

impl FileKind {
    /// What `meta` describes, or `None` for a regular file.
    fn of(meta: &Metadata) -> Option<Self> {
        let t = meta.file_type();
        if t.is_file() {
            return None;
        }
        if t.is_dir() {
            return Some(Self::Folder);
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if t.is_fifo() {
                return Some(Self::Fifo);
            }
            if t.is_char_device() {
                return Some(Self::CharDevice);
            }
            if t.is_block_device() {
                return Some(Self::BlockDevice);
            }
            if t.is_socket() {
                return Some(Self::Socket);
            }
        }
        Some(Self::Other)
    }
}

impl std::fmt::Display for FileKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Folder => "a folder",
            Self::Fifo => "a named pipe",
            Self::CharDevice => "a character device",
            Self::BlockDevice => "a block device",
            Self::Socket => "a socket",
            Self::Other => "not a regular file",
        })
    }
}

/// Why an input could not be read.
///
/// The message says why without the path: every caller's message leads
/// with the path already (`job.toml: cannot read: ...`); [`ReadError::path`]
/// gives it. It converts into an [`io::Error`] (an I/O failure as it was),
/// so readers that keep an `io::Error` take it unchanged.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// Opening or reading failed.
    #[error("{source}")]
    Io {
        /// The input.
        path: PathBuf,
        /// The reason.
        source: io::Error,
    },
    /// The path names no regular file.
    #[error("{kind}, not a regular file; give a file")]
    NotAFile {
        /// The input.
        path: PathBuf,
        /// What it names.
        kind: FileKind,
    },
    /// The input is larger than the cap.
    #[error(
        "larger than {} MiB, the most read of one input; raise it with --max-input-mb",
        mib(*cap)
    )]
    TooLarge {
        /// The input.
        path: PathBuf,
        /// The cap in force, bytes.
        cap: u64,
    },
    /// A text input that is not UTF-8.
    #[error("not UTF-8 text (byte {offset} is not valid UTF-8)")]
    NotUtf8 {
        /// The input.
        path: PathBuf,
        /// The offset of the first invalid byte.
        offset: usize,
    },
}

impl ReadError {
    /// The input that could not be read.
    pub fn path(&self) -> &Path {
        match self {
            Self::Io { path, .. }
            | Self::NotAFile { path, .. }
            | Self::TooLarge { path, .. }
            | Self::NotUtf8 { path, .. } => path,
        }
    }
}

impl From<ReadError> for io::Error {
    fn from(e: ReadError) -> Self {
        match e {
            ReadError::Io { source, .. } => source,
            e @ ReadError::NotAFile { .. } => io::Error::new(io::ErrorKind::InvalidInput, e),
            e @ ReadError::TooLarge { .. } => io::Error::new(io::ErrorKind::FileTooLarge, e),
            e @ ReadError::NotUtf8 { .. } => io::Error::new(io::ErrorKind::InvalidData, e),
        }
    }
}

/// A cap in MiB as written in messages (`0.5`, `256`).
fn mib(bytes: u64) -> String {
    let m = bytes as f64 / MIB as f64;
    if m.fract() == 0.0 {
        format!("{m}")
    } else {
        format!("{m:.3}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_owned()
    }
}

/// The bytes of the regular file at `path`, at most [`max_input_bytes`].
///
/// # Errors
///
/// [`ReadError::NotAFile`] for a folder, FIFO, device or socket (checked
/// before opening, so a FIFO never blocks), [`ReadError::TooLarge`] past
/// the cap, [`ReadError::Io`] when it cannot be opened or read.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, ReadError> {
    read_bytes_capped(path, max_input_bytes())
}

/// The text of the regular file at `path`, at most [`max_input_bytes`].
///
/// # Errors
///
/// Those of [`read_bytes`], and [`ReadError::NotUtf8`].
pub fn read_text(path: &Path) -> Result<String, ReadError> {
    read_text_capped(path, max_input_bytes())
}

/// [`read_text`] with the cap `cap` (bytes).
///
/// # Errors
///
/// Those of [`read_text`].
pub fn read_text_capped(path: &Path, cap: u64) -> Result<String, ReadError> {
    let bytes = read_bytes_capped(path, cap)?;
    String::from_utf8(bytes).map_err(|e| ReadError::NotUtf8 {
        path: path.to_path_buf(),
        offset: e.utf8_error().valid_up_to(),
    })
}

/// [`read_bytes`] with the cap `cap` (bytes).
///
/// # Errors
///
/// Those of [`read_bytes`].
pub fn read_bytes_capped(path: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
    let io = |source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    };
    // 1. What the path names, before opening it (opening a FIFO waits for a
    // writer).
    let regular = |meta: &Metadata| match FileKind::of(meta) {
        Some(kind) => Err(ReadError::NotAFile {
            path: path.to_path_buf(),
            kind,
        }),
        None => Ok(meta.len()),
    };
    regular(&fs::metadata(path).map_err(io)?)?;
    // 2. The file opened is what was checked (it may have been swapped).
    let file = File::open(path).map_err(io)?;
    let len = regular(&file.metadata().map_err(io)?)?;
    let too_large = || ReadError::TooLarge {
        path: path.to_path_buf(),
        cap,
    };
    if len > cap {
        return Err(too_large());
    }
    // 3. At most one byte past the cap: a file that grows stops there.
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    file.take(cap.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > cap {
        return Err(too_large());
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    /// A fresh scratch folder for one test.
    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("formcam-files-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_regular_file_is_read_whole() {
        let p = scratch("whole").join("a.txt");
        fs::write(&p, "z,r\n0,1\n").unwrap();
        assert_eq!(read_text(&p).unwrap(), "z,r\n0,1\n");
        assert_eq!(read_bytes(&p).unwrap(), b"z,r\n0,1\n");
    }

    #[test]
    fn a_file_at_the_cap_is_read_and_one_byte_more_is_refused() {
        let d = scratch("cap");
        let at = d.join("at.txt");
        let over = d.join("over.txt");
        fs::write(&at, "x".repeat(100)).unwrap();
        fs::write(&over, "x".repeat(101)).unwrap();
        assert_eq!(read_text_capped(&at, 100).unwrap().len(), 100);
        let e = read_text_capped(&over, 100).unwrap_err();
        assert!(matches!(e, ReadError::TooLarge { cap: 100, .. }), "{e:?}");
        assert_eq!(e.path(), over);
    }

    #[test]
    fn the_cap_message_says_the_cap_and_how_to_raise_it() {
        let e = ReadError::TooLarge {
            path: PathBuf::from("a"),
            cap: 512 * 1024,
        };
        assert_eq!(
            e.to_string(),
            "larger than 0.5 MiB, the most read of one input; raise it with --max-input-mb"
        );
        let e = ReadError::TooLarge {
            path: PathBuf::from("a"),
            cap: DEFAULT_MAX_INPUT_BYTES,
        };
        assert!(e.to_string().starts_with("larger than 256 MiB"), "{e}");
    }

    #[test]
    fn a_folder_is_refused() {
        let d = scratch("folder");
        let e = read_text(&d).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::NotAFile {
                    kind: FileKind::Folder,
                    ..
                }
            ),
            "{e:?}"
        );
        assert_eq!(e.to_string(), "a folder, not a regular file; give a file");
    }

    #[cfg(unix)]
    #[test]
    fn dev_zero_is_refused_without_reading() {
        let e = read_bytes(Path::new("/dev/zero")).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::NotAFile {
                    kind: FileKind::CharDevice,
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_waiting_for_a_writer() {
        let p = scratch("fifo").join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&p).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", p.display());
        let e = read_text(&p).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::NotAFile {
                    kind: FileKind::Fifo,
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn a_missing_file_keeps_the_io_error() {
        let p = scratch("missing").join("nope.toml");
        let e = read_text(&p).unwrap_err();
        let want = fs::read_to_string(&p).unwrap_err().to_string();
        assert_eq!(e.to_string(), want);
        assert_eq!(io::Error::from(e).kind(), io::ErrorKind::NotFound);
    }

    #[test]
    fn invalid_utf8_names_the_byte() {
        let p = scratch("utf8").join("a.csv");
        fs::write(&p, b"z,r\n\xff").unwrap();
        let e = read_text(&p).unwrap_err();
        assert!(matches!(e, ReadError::NotUtf8 { offset: 4, .. }), "{e:?}");
        assert_eq!(read_bytes(&p).unwrap().len(), 5);
    }
}
