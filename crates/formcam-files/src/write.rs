//! A run's output folder written whole, never over an input.
//!
//! Every output path is compared with every input of the run after
//! resolving `.`, `..` and symlinks ([`same_file`], [`resolve`]); a clash is
//! an error naming both, before anything is written.
//!
//! A folder ([`Writer::write_folder`]) is written into a fresh folder
//! beside the target, created exclusively (`.OUT.formcam-new-<pid>-<nanos>`),
//! its files and the folder synced, then swapped in: the old folder renamed
//! aside, the new one in, the old removed. A crash in between leaves both
//! whole; the next run into the target tidies up the leftovers it
//! recognises as its own. Each folder holds a marker, [`MARKER`], listing
//! the files formcam wrote there: a target holding anything else is refused,
//! naming one such file, and nothing foreign is ever deleted. One run at a
//! time writes a target: it claims it by the exclusive creation of
//! `.OUT.formcam-claim` beside it (removed at the end; a claim left by a
//! process of this host that is gone is taken over).
//!
//! Single files ([`Writer::write_files`], `correct -o x.nc`) are placed in
//! the order given, each through a new temporary file beside it renamed into
//! place; a failure removes the files this run had placed.
//!
//! No temporary name is ever opened if it exists: files are created with
//! `create_new` and folders with `create_dir`, so a symlink planted where a
//! temporary would go is never followed.

use std::ffi::OsString;
use std::fs;
use std::io::{self, Write as _};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{SystemTime, UNIX_EPOCH};

/// The file in each folder formcam wrote that lists the files it wrote.
pub const MARKER: &str = ".formcam-run";

/// The marker's first line.
const MARKER_HEAD: &str = "# formcam: the files of one run, written by formcam";

/// How many unique names are tried before giving up.
const ATTEMPTS: u32 = 64;

/// Why a run's files could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// An output that is one of the run's inputs.
    #[error("{}: would overwrite the input {}; give another output", output.display(), input.display())]
    Clash {
        /// The output, as it would be written.
        output: PathBuf,
        /// The input, as the run named it.
        input: PathBuf,
    },
    /// An output folder holding one of the run's inputs (the folder is
    /// replaced whole).
    #[error(
        "{}: the output folder holds the input {}, which a new run would remove; give another output folder",
        folder.display(),
        input.display()
    )]
    InputInFolder {
        /// The output folder.
        folder: PathBuf,
        /// The input inside it.
        input: PathBuf,
    },
    /// Two outputs of one run that are the same file.
    #[error("{}: written twice by one run (also as {})", first.display(), second.display())]
    Twice {
        /// One output.
        first: PathBuf,
        /// The other, the same file.
        second: PathBuf,
    },
    /// A file in the output folder that formcam did not write.
    #[error(
        "{}: the output folder holds {}, which formcam did not write; move it away or give another output folder",
        folder.display(),
        file.display()
    )]
    Foreign {
        /// The output folder.
        folder: PathBuf,
        /// The file formcam did not write.
        file: PathBuf,
    },
    /// A folder where an output file goes.
    #[error("{}: cannot write: a folder is in the way", path.display())]
    FolderInTheWay {
        /// The path.
        path: PathBuf,
    },
    /// An output folder that is a file.
    #[error("{}: is a file, not a folder; give an output folder", path.display())]
    NotFolder {
        /// The path.
        path: PathBuf,
    },
    /// Another run is writing the same target.
    #[error(
        "{}: another formcam run (process {pid}) is writing there; try again when it has finished (or remove {} if none is)",
        target.display(),
        claim.display()
    )]
    Busy {
        /// The target.
        target: PathBuf,
        /// The claim file.
        claim: PathBuf,
        /// The process holding the claim, as the claim says.
        pid: String,
    },
    /// An output name that is no plain relative file name.
    #[error("{name:?}: not a file name inside the output folder")]
    Name {
        /// The name.
        name: String,
    },
    /// An output path that names no file or folder.
    #[error("{}: not a file name", path.display())]
    NotFileName {
        /// The path.
        path: PathBuf,
    },
    /// The output folder could not be created.
    #[error("{}: cannot create the output folder: {source}", path.display())]
    Folder {
        /// The folder.
        path: PathBuf,
        /// The reason.
        source: io::Error,
    },
    /// A file or folder could not be written, synced or renamed.
    #[error("{}: cannot write: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The reason.
        source: io::Error,
    },
}

/// Where a [`Writer`] is in its work, for its test hook.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Point {
    /// The target is claimed (folders), nothing written yet.
    Claimed,
    /// This many files are complete (in the new folder, or placed).
    Wrote(usize),
    /// The old folder is renamed aside, the new one not yet in.
    SetAside,
}

/// A hook called at each [`Point`]; an error stops the writer there as a
/// failure of the file system would.
pub type Hook = Box<dyn Fn(Point) -> io::Result<()> + Send + Sync>;

/// Writes run folders and single files; [`Writer::default`] is what every
/// run uses, the hook and the fixed stamp are for tests.
#[derive(Default)]
pub struct Writer {
    hook: Option<Hook>,
    stamp: Option<String>,
}

impl std::fmt::Debug for Writer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Writer")
            .field("hook", &self.hook.is_some())
            .field("stamp", &self.stamp)
            .finish()
    }
}

/// [`Writer::write_folder`] with the default writer.
pub fn write_folder<S: AsRef<str>, B: AsRef<[u8]>>(
    target: &Path,
    files: &[(S, B)],
    inputs: &[PathBuf],
) -> Result<(), WriteError> {
    Writer::default().write_folder(target, files, inputs)
}

/// [`Writer::write_files`] with the default writer.
pub fn write_files<P: AsRef<Path>, B: AsRef<[u8]>>(
    files: &[(P, B)],
    inputs: &[PathBuf],
) -> Result<(), WriteError> {
    Writer::default().write_files(files, inputs)
}

impl Writer {
    /// A writer calling `hook` at each [`Point`] (tests: a failure injected
    /// between writes, a pause while the target is claimed).
    pub fn with_hook(hook: impl Fn(Point) -> io::Result<()> + Send + Sync + 'static) -> Self {
        Self {
            hook: Some(Box::new(hook)),
            stamp: None,
        }
    }

    /// The writer with its unique names built from `stamp` and a counter
    /// instead of the process id and the time (tests: a name known in
    /// advance).
    pub fn stamped(mut self, stamp: &str) -> Self {
        self.stamp = Some(stamp.to_owned());
        self
    }

    fn at(&self, point: Point, path: &Path) -> Result<(), WriteError> {
        match &self.hook {
            Some(h) => h(point).map_err(|source| io_error(path, source)),
            None => Ok(()),
        }
    }

    /// A name not used before by this process: `stamp-k` or `pid-nanos-k`.
    fn unique(&self, attempt: u32) -> String {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        match &self.stamp {
            Some(s) => format!("{s}-{attempt}"),
            None => {
                let nanos = SystemTime::now()
                    .duration_since(UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos());
                let k = COUNTER.fetch_add(1, Ordering::Relaxed);
                format!("{}-{nanos}-{k}", std::process::id())
            }
        }
    }

    /// Writes `files` (name inside the folder, which may hold `/`, and
    /// contents) as the folder `target`, whole: the folder then holds this
    /// run and nothing of the one before, or, on any error, the run before
    /// as it was. `inputs` are the files the run read.
    pub fn write_folder<S: AsRef<str>, B: AsRef<[u8]>>(
        &self,
        target: &Path,
        files: &[(S, B)],
        inputs: &[PathBuf],
    ) -> Result<(), WriteError> {
        let names = checked_names(files.iter().map(|(n, _)| n.as_ref()))?;
        let real = resolve(target).map_err(|source| io_error(target, source))?;
        let (parent, name) = match (real.parent(), real.file_name()) {
            (Some(p), Some(n)) => (p.to_path_buf(), n.to_os_string()),
            _ => {
                return Err(WriteError::NotFileName {
                    path: target.to_path_buf(),
                });
            }
        };
        guard_folder(target, &real, &names, inputs)?;
        fs::create_dir_all(&parent).map_err(|source| WriteError::Folder {
            path: target.to_path_buf(),
            source,
        })?;
        let _claim = Claim::take(target, &parent, &name)?;
        self.at(Point::Claimed, target)?;
        let aside = Aside { parent, name };
        aside.tidy(&real);
        check_owned(target, &real, &names)?;
        let fresh = self.fresh_folder(&aside, target)?;
        let filled = self.fill(&fresh, &names, files, target);
        let filled = filled.and_then(|()| sync_dir(&fresh).map_err(|e| io_error(target, e)));
        if let Err(e) = filled {
            remove_run(&fresh);
            return Err(e);
        }
        self.swap(&aside, &fresh, &real, target)
    }

    /// A new, empty folder beside the target, created exclusively.
    fn fresh_folder(&self, aside: &Aside, target: &Path) -> Result<PathBuf, WriteError> {
        for attempt in 0..ATTEMPTS {
            let p = aside.path("new", &self.unique(attempt));
            match fs::create_dir(&p) {
                Ok(()) => return Ok(p),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(source) => return Err(WriteError::Folder { path: p, source }),
            }
        }
        Err(io_error(
            target,
            io::Error::new(io::ErrorKind::AlreadyExists, "no free temporary name"),
        ))
    }

    /// The marker, then every file, each synced, into the fresh folder.
    fn fill<S: AsRef<str>, B: AsRef<[u8]>>(
        &self,
        fresh: &Path,
        names: &[PathBuf],
        files: &[(S, B)],
        target: &Path,
    ) -> Result<(), WriteError> {
        let mut listing = String::from(MARKER_HEAD);
        listing.push('\n');
        for (n, _) in files {
            listing.push_str(n.as_ref());
            listing.push('\n');
        }
        let shown = |n: &Path| target.join(n);
        create_file(&fresh.join(MARKER), listing.as_bytes())
            .map_err(|e| io_error(&shown(Path::new(MARKER)), e))?;
        for (k, (rel, (_, bytes))) in names.iter().zip(files).enumerate() {
            let path = fresh.join(rel);
            if let Some(dir) = path.parent() {
                fs::create_dir_all(dir).map_err(|e| io_error(&shown(rel), e))?;
            }
            create_file(&path, bytes.as_ref()).map_err(|e| io_error(&shown(rel), e))?;
            self.at(Point::Wrote(k + 1), &shown(rel))?;
        }
        let mut dirs: Vec<&Path> = names.iter().filter_map(|n| n.parent()).collect();
        dirs.sort();
        dirs.dedup();
        for d in dirs.into_iter().filter(|d| !d.as_os_str().is_empty()) {
            sync_dir(&fresh.join(d)).map_err(|e| io_error(&shown(d), e))?;
        }
        Ok(())
    }

    /// The old folder aside, the fresh one in, the old one removed.
    fn swap(
        &self,
        aside: &Aside,
        fresh: &Path,
        real: &Path,
        target: &Path,
    ) -> Result<(), WriteError> {
        let old = if fs::symlink_metadata(real).is_ok() {
            let old = (0..ATTEMPTS)
                .map(|a| aside.path("old", &self.unique(a)))
                .find(|p| fs::symlink_metadata(p).is_err());
            let Some(old) = old else {
                remove_run(fresh);
                return Err(io_error(
                    target,
                    io::Error::new(io::ErrorKind::AlreadyExists, "no free temporary name"),
                ));
            };
            if let Err(e) = fs::rename(real, &old) {
                remove_run(fresh);
                return Err(io_error(target, e));
            }
            Some(old)
        } else {
            None
        };
        let moved = self
            .at(Point::SetAside, target)
            .and_then(|()| fs::rename(fresh, real).map_err(|e| io_error(target, e)));
        if let Err(e) = moved {
            if let Some(old) = &old {
                let _ = fs::rename(old, real);
            }
            remove_run(fresh);
            return Err(e);
        }
        let _ = sync_dir(&aside.parent);
        if let Some(old) = old {
            remove_run(&old);
        }
        Ok(())
    }

    /// Places `files` (path, contents) in the order given, each through a
    /// new temporary file beside it renamed into place: side files first,
    /// the main file last. On an error the files placed so far by this run
    /// are removed. `inputs` are the files the run read.
    pub fn write_files<P: AsRef<Path>, B: AsRef<[u8]>>(
        &self,
        files: &[(P, B)],
        inputs: &[PathBuf],
    ) -> Result<(), WriteError> {
        let mut real = Vec::with_capacity(files.len());
        for (p, _) in files {
            let p = p.as_ref();
            let r = resolve(p).map_err(|e| io_error(p, e))?;
            if r.file_name().is_none() {
                return Err(WriteError::NotFileName {
                    path: p.to_path_buf(),
                });
            }
            for input in inputs {
                if same_file(p, input) {
                    return Err(WriteError::Clash {
                        output: p.to_path_buf(),
                        input: input.clone(),
                    });
                }
            }
            if let Some(k) = real.iter().position(|seen| *seen == r) {
                return Err(WriteError::Twice {
                    first: files[k].0.as_ref().to_path_buf(),
                    second: p.to_path_buf(),
                });
            }
            if fs::symlink_metadata(&r).is_ok_and(|m| m.is_dir()) {
                return Err(WriteError::FolderInTheWay {
                    path: p.to_path_buf(),
                });
            }
            real.push(r);
        }
        let mut placed: Vec<&Path> = Vec::new();
        for (k, ((shown, bytes), r)) in files.iter().zip(&real).enumerate() {
            let done = self.place(r, bytes.as_ref(), shown.as_ref());
            if done.is_ok() {
                placed.push(r);
            }
            if let Err(e) = done.and_then(|()| self.at(Point::Wrote(k + 1), shown.as_ref())) {
                for p in placed {
                    let _ = fs::remove_file(p);
                }
                return Err(e);
            }
        }
        Ok(())
    }

    /// One file through a new temporary file beside it.
    fn place(&self, real: &Path, bytes: &[u8], shown: &Path) -> Result<(), WriteError> {
        let dir = real.parent().unwrap_or(Path::new("/"));
        fs::create_dir_all(dir).map_err(|source| WriteError::Folder {
            path: shown.parent().unwrap_or(shown).to_path_buf(),
            source,
        })?;
        let file = real
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        for attempt in 0..ATTEMPTS {
            let tmp = dir.join(format!(".{file}.formcam-new-{}", self.unique(attempt)));
            match create_file(&tmp, bytes) {
                Ok(()) => {}
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => {
                    let _ = fs::remove_file(&tmp);
                    return Err(io_error(shown, e));
                }
            }
            if let Err(e) = fs::rename(&tmp, real) {
                let _ = fs::remove_file(&tmp);
                return Err(io_error(shown, e));
            }
            let _ = sync_dir(dir);
            return Ok(());
        }
        Err(io_error(
            shown,
            io::Error::new(io::ErrorKind::AlreadyExists, "no free temporary name"),
        ))
    }
}

fn io_error(path: &Path, source: io::Error) -> WriteError {
    WriteError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The names of a run's files as relative paths of plain components (no
/// `..`, no root, not the marker), each once.
fn checked_names<'a>(names: impl Iterator<Item = &'a str>) -> Result<Vec<PathBuf>, WriteError> {
    let mut out: Vec<PathBuf> = Vec::new();
    for n in names {
        let p = PathBuf::from(n);
        let plain = !n.is_empty()
            && !n.contains('\n')
            && p.components().all(|c| matches!(c, Component::Normal(_)))
            && p != Path::new(MARKER);
        if !plain || out.contains(&p) {
            return Err(WriteError::Name { name: n.to_owned() });
        }
        out.push(p);
    }
    Ok(out)
}

/// `path` made absolute, its deepest existing ancestor with its symlinks
/// resolved, the rest (which does not exist yet) taken as written, `..`
/// going up from a folder that will be created.
pub fn resolve(path: &Path) -> io::Result<PathBuf> {
    let abs = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()?.join(path)
    };
    let parts: Vec<Component<'_>> = abs.components().collect();
    for k in (1..=parts.len()).rev() {
        let head: PathBuf = parts[..k].iter().collect();
        if let Ok(mut out) = fs::canonicalize(&head) {
            for c in &parts[k..] {
                match c {
                    Component::Normal(n) => out.push(n),
                    Component::ParentDir => {
                        out.pop();
                    }
                    _ => {}
                }
            }
            return Ok(out);
        }
    }
    Ok(abs)
}

/// Whether `a` and `b` are the same file: the same device and inode where
/// both exist, else the same resolved path ([`resolve`]).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    match (resolve(a), resolve(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// No output of a folder run on an input, and no input inside the folder
/// (the folder is replaced whole).
fn guard_folder(
    target: &Path,
    real: &Path,
    names: &[PathBuf],
    inputs: &[PathBuf],
) -> Result<(), WriteError> {
    for input in inputs {
        for n in names {
            if same_file(&target.join(n), input) {
                return Err(WriteError::Clash {
                    output: target.join(n),
                    input: input.clone(),
                });
            }
        }
        let inside = resolve(input).is_ok_and(|r| r.starts_with(real));
        if inside || same_file(target, input) {
            return Err(WriteError::InputInFolder {
                folder: target.to_path_buf(),
                input: input.clone(),
            });
        }
    }
    Ok(())
}

/// The files formcam wrote in `folder` by its marker (`None` without one).
fn listed(folder: &Path) -> Option<Vec<PathBuf>> {
    let text = fs::read_to_string(folder.join(MARKER)).ok()?;
    let mut lines = text.lines();
    (lines.next()? == MARKER_HEAD).then(|| lines.map(PathBuf::from).collect())
}

/// The first entry of `folder` (relative) that is not its marker, a file it
/// lists or a folder: what formcam did not write. A folder standing where
/// the marker lists a file is returned too.
fn first_foreign(folder: &Path, listed: &[PathBuf]) -> Option<(PathBuf, bool)> {
    fn walk(root: &Path, rel: &Path, listed: &[PathBuf]) -> Option<(PathBuf, bool)> {
        let mut entries: Vec<_> = fs::read_dir(root.join(rel))
            .ok()?
            .filter_map(Result::ok)
            .map(|e| e.file_name())
            .collect();
        entries.sort();
        for name in entries {
            let r = rel.join(&name);
            let is_dir = fs::symlink_metadata(root.join(&r)).is_ok_and(|m| m.is_dir());
            let ours = listed.contains(&r);
            if is_dir {
                if ours {
                    return Some((r, true));
                }
                if let Some(f) = walk(root, &r, listed) {
                    return Some(f);
                }
            } else if !ours && r != Path::new(MARKER) {
                return Some((r, false));
            }
        }
        None
    }
    walk(folder, Path::new(""), listed)
}

/// The target holds only what formcam wrote there (or nothing).
fn check_owned(target: &Path, real: &Path, names: &[PathBuf]) -> Result<(), WriteError> {
    let Ok(meta) = fs::symlink_metadata(real) else {
        return Ok(());
    };
    if !meta.is_dir() {
        return Err(WriteError::NotFolder {
            path: target.to_path_buf(),
        });
    }
    let own = listed(real).unwrap_or_default();
    match first_foreign(real, &own) {
        Some((rel, true)) if names.contains(&rel) => Err(WriteError::FolderInTheWay {
            path: target.join(rel),
        }),
        Some((rel, _)) => Err(WriteError::Foreign {
            folder: target.to_path_buf(),
            file: target.join(rel),
        }),
        None => Ok(()),
    }
}

/// Removes a folder formcam wrote: the files its marker lists, the marker,
/// then every folder left empty. Anything else stays.
fn remove_run(folder: &Path) {
    fn empty_dirs(dir: &Path) {
        if let Ok(entries) = fs::read_dir(dir) {
            for e in entries.filter_map(Result::ok) {
                let p = e.path();
                if fs::symlink_metadata(&p).is_ok_and(|m| m.is_dir()) {
                    empty_dirs(&p);
                }
            }
        }
        let _ = fs::remove_dir(dir);
    }
    for f in listed(folder).unwrap_or_default() {
        let p = folder.join(f);
        if fs::symlink_metadata(&p).is_ok_and(|m| !m.is_dir()) {
            let _ = fs::remove_file(p);
        }
    }
    let _ = fs::remove_file(folder.join(MARKER));
    empty_dirs(folder);
}

/// The names beside a target: `.OUT.formcam-new-*`, `.OUT.formcam-old-*`.
struct Aside {
    parent: PathBuf,
    name: OsString,
}

impl Aside {
    fn prefix(&self, kind: &str) -> String {
        format!(".{}.formcam-{kind}-", self.name.to_string_lossy())
    }

    fn path(&self, kind: &str, unique: &str) -> PathBuf {
        self.parent.join(format!("{}{unique}", self.prefix(kind)))
    }

    /// The leftovers of runs cut off: an old folder set aside goes back
    /// when the target is missing; every other leftover that holds only
    /// what formcam wrote is removed. Foreign ones and symlinks stay.
    fn tidy(&self, real: &Path) {
        let (new, old) = (self.prefix("new"), self.prefix("old"));
        let Ok(entries) = fs::read_dir(&self.parent) else {
            return;
        };
        let mut left: Vec<(PathBuf, bool)> = entries
            .filter_map(Result::ok)
            .filter_map(|e| {
                let n = e.file_name().to_string_lossy().into_owned();
                let is_old = n.starts_with(&old);
                (is_old || n.starts_with(&new)).then(|| (e.path(), is_old))
            })
            .filter(|(p, _)| fs::symlink_metadata(p).is_ok_and(|m| m.is_dir()))
            .filter(|(p, _)| first_foreign(p, &listed(p).unwrap_or_default()).is_none())
            .collect();
        left.sort();
        for (p, is_old) in left {
            if is_old && fs::symlink_metadata(real).is_err() && fs::rename(&p, real).is_ok() {
                continue;
            }
            remove_run(&p);
        }
    }
}

/// The claim of a target by one run: `.OUT.formcam-claim` beside it,
/// created exclusively, holding the process id and the host; removed when
/// dropped.
struct Claim {
    path: PathBuf,
}

impl Claim {
    fn take(target: &Path, parent: &Path, name: &std::ffi::OsStr) -> Result<Self, WriteError> {
        let path = parent.join(format!(".{}.formcam-claim", name.to_string_lossy()));
        let me = format!("{} {}\n", std::process::id(), host());
        for _ in 0..2 {
            match create_file(&path, me.as_bytes()) {
                Ok(()) => return Ok(Self { path }),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {
                    let held = fs::read_to_string(&path).unwrap_or_default();
                    if stale(&held) {
                        let _ = fs::remove_file(&path);
                        continue;
                    }
                    return Err(WriteError::Busy {
                        target: target.to_path_buf(),
                        claim: path,
                        pid: held.split_whitespace().next().unwrap_or("?").to_owned(),
                    });
                }
                Err(source) => return Err(io_error(&path, source)),
            }
        }
        Err(WriteError::Busy {
            target: target.to_path_buf(),
            claim: path,
            pid: "?".into(),
        })
    }
}

impl Drop for Claim {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.path);
    }
}

/// This host's name (empty where it cannot be read).
fn host() -> String {
    ["/proc/sys/kernel/hostname", "/etc/hostname"]
        .iter()
        .find_map(|p| fs::read_to_string(p).ok())
        .map(|h| h.trim().to_owned())
        .unwrap_or_default()
}

/// Whether a claim's text names a process of this host that is gone (only
/// where `/proc` tells; elsewhere a claim is never stale).
fn stale(held: &str) -> bool {
    let mut words = held.split_whitespace();
    let (Some(pid), h) = (
        words.next().and_then(|p| p.parse::<u32>().ok()),
        words.next(),
    ) else {
        return false;
    };
    let proc_here = Path::new("/proc/self").exists();
    proc_here
        && pid != std::process::id()
        && h.unwrap_or("") == host()
        && !Path::new("/proc").join(pid.to_string()).exists()
}

/// A new file (never an existing one, never through a symlink) with
/// `bytes`, synced.
fn create_file(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut f = fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)?;
    f.write_all(bytes)?;
    f.sync_all()
}

/// Syncs a folder's entries (where the platform can).
fn sync_dir(dir: &Path) -> io::Result<()> {
    #[cfg(unix)]
    {
        fs::File::open(dir)?.sync_all()
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use std::sync::mpsc;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("formcam-files-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    fn run(tag: &str) -> Vec<(String, Vec<u8>)> {
        vec![
            (
                "summary.json".into(),
                format!("{{\"run\": \"{tag}\"}}").into_bytes(),
            ),
            (
                "layer-01/path.csv".into(),
                format!("z,r\n{tag}\n").into_bytes(),
            ),
        ]
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut n: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    }

    fn read(p: &Path) -> String {
        fs::read_to_string(p).unwrap()
    }

    /// The folder holds the run `tag` whole, and nothing else beside it.
    fn holds(dir: &Path, out: &Path, tag: &str) {
        assert_eq!(
            read(&out.join("summary.json")),
            format!("{{\"run\": \"{tag}\"}}")
        );
        assert_eq!(
            read(&out.join("layer-01/path.csv")),
            format!("z,r\n{tag}\n")
        );
        let listed = listed(out).unwrap();
        assert_eq!(listed.len(), 2);
        assert_eq!(
            names(dir),
            vec![out.file_name().unwrap().to_string_lossy().into_owned()]
        );
    }

    #[test]
    fn a_second_run_replaces_the_first_whole() {
        let dir = scratch("replace");
        let out = dir.join("out");
        write_folder(&out, &run("a"), &[]).unwrap();
        let mut first = run("a");
        first.push(("program.mpf".into(), b"M30\n".to_vec()));
        write_folder(&out, &first, &[]).unwrap();
        assert!(out.join("program.mpf").exists());
        write_folder(&out, &run("b"), &[]).unwrap();
        holds(&dir, &out, "b");
        assert!(!out.join("program.mpf").exists());
        assert_eq!(names(&out), vec![MARKER, "layer-01", "summary.json"]);
    }

    #[test]
    fn an_empty_folder_is_taken_and_a_file_is_no_folder() {
        let dir = scratch("empty");
        let out = dir.join("out");
        fs::create_dir(&out).unwrap();
        write_folder(&out, &run("a"), &[]).unwrap();
        holds(&dir, &out, "a");
        let file = dir.join("out.txt");
        fs::write(&file, "x").unwrap();
        let e = write_folder(&file, &run("a"), &[]).unwrap_err();
        assert!(matches!(e, WriteError::NotFolder { .. }), "{e}");
    }

    #[test]
    fn a_foreign_file_is_refused_and_kept() {
        let dir = scratch("foreign");
        let out = dir.join("out");
        write_folder(&out, &run("a"), &[]).unwrap();
        fs::write(out.join("layer-01/notes.txt"), "mine").unwrap();
        let e = write_folder(&out, &run("b"), &[]).unwrap_err();
        assert!(
            matches!(&e, WriteError::Foreign { file, .. } if file.ends_with("layer-01/notes.txt")),
            "{e}"
        );
        assert_eq!(read(&out.join("layer-01/notes.txt")), "mine");
        assert_eq!(read(&out.join("summary.json")), "{\"run\": \"a\"}");
        // A folder holding no marker holds nothing formcam wrote.
        let bare = dir.join("bare");
        fs::create_dir(&bare).unwrap();
        fs::write(bare.join("summary.json"), "theirs").unwrap();
        let e = write_folder(&bare, &run("b"), &[]).unwrap_err();
        assert!(matches!(e, WriteError::Foreign { .. }), "{e}");
        assert_eq!(read(&bare.join("summary.json")), "theirs");
    }

    #[test]
    fn outputs_never_land_on_inputs() {
        let dir = scratch("clash");
        let out = dir.join("out");
        fs::create_dir(&out).unwrap();
        // A job named summary.json inside the folder.
        let job = out.join("summary.json");
        fs::write(&job, "[mandrel]").unwrap();
        let e = write_folder(&out, &run("a"), std::slice::from_ref(&job)).unwrap_err();
        assert!(
            matches!(&e, WriteError::Clash { output, input } if output.ends_with("summary.json") && input == &job),
            "{e}"
        );
        assert_eq!(read(&job), "[mandrel]");
        // An input in the folder that no output names is still replaced with it.
        let curve = out.join("curve.csv");
        fs::write(&curve, "z,r").unwrap();
        let e = write_folder(&out, &run("a"), std::slice::from_ref(&curve)).unwrap_err();
        assert!(matches!(e, WriteError::InputInFolder { .. }), "{e}");
        // Through a symlink and `..` over a folder that does not exist.
        let input = dir.join("mould.nc");
        fs::write(&input, "G0").unwrap();
        let via = dir.join("missing/../mould.nc");
        let e = write_files(&[(&via, b"x")], std::slice::from_ref(&input)).unwrap_err();
        assert!(matches!(e, WriteError::Clash { .. }), "{e}");
        #[cfg(unix)]
        {
            let link = dir.join("link.nc");
            std::os::unix::fs::symlink(&input, &link).unwrap();
            let e = write_files(&[(&link, b"x")], std::slice::from_ref(&input)).unwrap_err();
            assert!(matches!(e, WriteError::Clash { .. }), "{e}");
            let hard = dir.join("hard.nc");
            fs::hard_link(&input, &hard).unwrap();
            let e = write_files(&[(&hard, b"x")], std::slice::from_ref(&input)).unwrap_err();
            assert!(matches!(e, WriteError::Clash { .. }), "{e}");
        }
        assert_eq!(read(&input), "G0");
        assert!(!dir.join("missing").exists());
    }

    #[test]
    fn resolving_goes_through_links_and_folders_to_come() {
        let dir = scratch("resolve");
        let real = fs::canonicalize(&dir).unwrap();
        assert_eq!(resolve(&dir.join("x/../a.nc")).unwrap(), real.join("a.nc"));
        assert_eq!(resolve(&dir.join("./x/y/../b")).unwrap(), real.join("x/b"));
        assert!(same_file(&dir.join("x/../a.nc"), &dir.join("a.nc")));
        assert!(!same_file(&dir.join("x/a.nc"), &dir.join("a.nc")));
    }

    #[test]
    fn names_must_stay_inside_the_folder() {
        let dir = scratch("names");
        for bad in ["../x", "/etc/x", "", MARKER, "a/../../b"] {
            let e = write_folder(&dir.join("out"), &[(bad, b"x")], &[]).unwrap_err();
            assert!(matches!(e, WriteError::Name { .. }), "{bad}: {e}");
        }
        let e = write_folder(&dir.join("out"), &[("a", b"x"), ("a", b"y")], &[]).unwrap_err();
        assert!(matches!(e, WriteError::Name { .. }), "{e}");
        assert!(!dir.join("out").exists());
    }

    #[test]
    fn a_failure_between_writes_leaves_the_old_run_whole() {
        let dir = scratch("fail");
        let out = dir.join("out");
        write_folder(&out, &run("a"), &[]).unwrap();
        for point in [
            Point::Claimed,
            Point::Wrote(1),
            Point::Wrote(2),
            Point::SetAside,
        ] {
            let w = Writer::with_hook(move |p| {
                if p == point {
                    Err(io::Error::other("injected"))
                } else {
                    Ok(())
                }
            });
            let e = w.write_folder(&out, &run("b"), &[]).unwrap_err();
            assert!(e.to_string().contains("injected"), "{e}");
            holds(&dir, &out, "a");
        }
        // Into a folder not there yet: still nothing.
        let w = Writer::with_hook(|p| {
            if p == Point::Wrote(1) {
                Err(io::Error::other("injected"))
            } else {
                Ok(())
            }
        });
        assert!(w.write_folder(&dir.join("new"), &run("b"), &[]).is_err());
        assert!(!dir.join("new").exists());
    }

    #[test]
    fn the_leftovers_of_a_crash_are_tidied_by_the_next_run() {
        let dir = scratch("crash");
        let out = dir.join("out");
        write_folder(&out, &run("a"), &[]).unwrap();
        // Killed after setting the old run aside: the old and a half new
        // folder beside the target, no target.
        let aside = Aside {
            parent: dir.clone(),
            name: "out".into(),
        };
        fs::rename(&out, aside.path("old", "1")).unwrap();
        let half = aside.path("new", "2");
        fs::create_dir(&half).unwrap();
        fs::write(half.join(MARKER), format!("{MARKER_HEAD}\nsummary.json\n")).unwrap();
        fs::write(half.join("summary.json"), "{").unwrap();
        // A folder of that pattern holding a foreign file stays.
        let theirs = aside.path("new", "3");
        fs::create_dir(&theirs).unwrap();
        fs::write(theirs.join("notes.txt"), "mine").unwrap();
        write_folder(&out, &run("b"), &[]).unwrap();
        assert_eq!(read(&out.join("summary.json")), "{\"run\": \"b\"}");
        let mut left = names(&dir);
        left.sort();
        assert_eq!(left, vec![".out.formcam-new-3".to_string(), "out".into()]);
        // A run that fails after tidying leaves the old run back in place.
        fs::rename(&out, aside.path("old", "4")).unwrap();
        let w = Writer::with_hook(|p| {
            if p == Point::Wrote(1) {
                Err(io::Error::other("injected"))
            } else {
                Ok(())
            }
        });
        assert!(w.write_folder(&out, &run("c"), &[]).is_err());
        assert_eq!(read(&out.join("summary.json")), "{\"run\": \"b\"}");
    }

    #[test]
    fn of_two_concurrent_runs_one_wins_and_the_folder_holds_it_whole() {
        let dir = scratch("concurrent");
        let out = dir.join("out");
        write_folder(&out, &run("old"), &[]).unwrap();
        let (claimed_tx, claimed_rx) = mpsc::channel::<()>();
        let (go_tx, go_rx) = mpsc::channel::<()>();
        let go_rx = std::sync::Mutex::new(go_rx);
        let claimed_tx = std::sync::Mutex::new(claimed_tx);
        let first = Writer::with_hook(move |p| {
            if p == Point::Claimed {
                let _ = claimed_tx.lock().unwrap().send(());
                let _ = go_rx.lock().unwrap().recv();
            }
            Ok(())
        });
        let out_a = out.clone();
        let a = std::thread::spawn(move || first.write_folder(&out_a, &run("a"), &[]));
        claimed_rx.recv().unwrap();
        let out_b = out.clone();
        let b = std::thread::spawn(move || write_folder(&out_b, &run("b"), &[]));
        let b = b.join().unwrap();
        go_tx.send(()).unwrap();
        let a = a.join().unwrap();
        assert!(a.is_ok(), "{a:?}");
        assert!(matches!(&b, Err(WriteError::Busy { .. })), "{b:?}");
        holds(&dir, &out, "a");
        // Free again once the winner is done.
        write_folder(&out, &run("c"), &[]).unwrap();
        holds(&dir, &out, "c");
    }

    #[test]
    fn a_claim_of_a_process_gone_is_taken_over() {
        let dir = scratch("stale");
        let out = dir.join("out");
        let claim = dir.join(".out.formcam-claim");
        fs::write(&claim, format!("{} {}\n", std::process::id(), host())).unwrap();
        let e = write_folder(&out, &run("a"), &[]).unwrap_err();
        assert!(matches!(e, WriteError::Busy { .. }), "{e}");
        if Path::new("/proc/self").exists() {
            // Process ids stay below 2^22 on Linux.
            fs::write(&claim, format!("4999999 {}\n", host())).unwrap();
            write_folder(&out, &run("a"), &[]).unwrap();
            holds(&dir, &out, "a");
        }
    }

    #[test]
    #[cfg(unix)]
    fn a_symlink_where_a_temporary_would_go_is_not_followed() {
        let dir = scratch("symlink");
        let victim = dir.join("victim.txt");
        fs::write(&victim, "keep").unwrap();
        let victim_dir = dir.join("victim-dir");
        fs::create_dir(&victim_dir).unwrap();
        std::os::unix::fs::symlink(&victim, dir.join(".prog.nc.formcam-new-t-0")).unwrap();
        std::os::unix::fs::symlink(&victim_dir, dir.join(".out.formcam-new-t-0")).unwrap();
        let prog = dir.join("prog.nc");
        Writer::default()
            .stamped("t")
            .write_files(&[(&prog, b"G1")], &[])
            .unwrap();
        assert_eq!(read(&prog), "G1");
        assert_eq!(read(&victim), "keep");
        let out = dir.join("out");
        Writer::default()
            .stamped("t")
            .write_folder(&out, &run("a"), &[])
            .unwrap();
        assert_eq!(read(&out.join("summary.json")), "{\"run\": \"a\"}");
        assert!(names(&victim_dir).is_empty());
        assert!(
            fs::symlink_metadata(dir.join(".out.formcam-new-t-0"))
                .unwrap()
                .is_symlink()
        );
    }

    #[test]
    fn single_files_side_files_first_and_all_or_none() {
        let dir = scratch("single");
        let side = dir.join("c.deviations.svg");
        let report = dir.join("sub/report.json");
        let prog = dir.join("c.nc");
        let files = [
            (&side, b"<svg/>".as_slice()),
            (&report, b"{}"),
            (&prog, b"G1"),
        ];
        let w = Writer::with_hook(|p| {
            if p == Point::Wrote(2) {
                Err(io::Error::other("injected"))
            } else {
                Ok(())
            }
        });
        assert!(w.write_files(&files, &[]).is_err());
        assert!(!side.exists() && !report.exists() && !prog.exists());
        write_files(&files, &[]).unwrap();
        assert_eq!(read(&report), "{}");
        assert_eq!(read(&prog), "G1");
        let e = write_files(&[(&prog, b"a"), (&dir.join("x/../c.nc"), b"b")], &[]).unwrap_err();
        assert!(matches!(e, WriteError::Twice { .. }), "{e}");
        fs::create_dir(dir.join("d.nc")).unwrap();
        let e = write_files(&[(&dir.join("d.nc"), b"a")], &[]).unwrap_err();
        assert!(e.to_string().contains("a folder is in the way"), "{e}");
        let mut left = names(&dir);
        left.retain(|n| n.starts_with('.'));
        assert!(left.is_empty(), "{left:?}");
    }
}
