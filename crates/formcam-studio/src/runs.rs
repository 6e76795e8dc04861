//! The run queue: one worker thread runs the jobs the page sends, one at a
//! time, each into a run folder of its own under `DIR/runs/`. A run's
//! progress and its cancel go through a `formcam_progress::Hook`; a new
//! run cancels the one before. A run folder is written whole, once the run
//! is done, through `formcam_files::write_folder`: a failed or cancelled
//! run leaves nothing.

use std::collections::HashSet;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::thread;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

use formcam_progress::{Hook, Step};
use formcam_run::{RunError, RunOutput, run_job_text_with};
use serde::Serialize;

use crate::studio::UNSAVED;
use crate::{JobKind, StudioError};

/// The folder of `DIR` the runs are written into.
pub const RUNS_FOLDER: &str = "runs";

/// What a run folder says of its run: the job file, its kind, the line.
pub const RUN_FILE: &str = "run.json";

/// Where a run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RunState {
    /// No run yet.
    Idle,
    /// Waiting for the run before it to stop, or running.
    Running,
    /// Done: its folder is written.
    Done,
    /// Stopped by an error (`error` says which); no folder.
    Failed,
    /// Cancelled; no folder.
    Cancelled,
}

/// The latest run as `/api/studio/status` answers it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunStatus {
    /// The run's name (its folder's under `DIR/runs/`).
    pub run: Option<String>,
    /// The job file it runs (`None`: a job not saved).
    pub job: Option<String>,
    /// Where it is.
    pub state: RunState,
    /// The phase it reported last (`path`, `eye`, ..., `files`).
    pub phase: Option<&'static str>,
    /// Items of that phase done.
    pub done: u64,
    /// Items of that phase in all.
    pub total: u64,
    /// Seconds since it started (until it ended, once it has).
    pub elapsed_s: f64,
    /// The run's line, once done.
    pub line: Option<String>,
    /// Why it failed.
    pub error: Option<String>,
}

impl RunStatus {
    fn idle() -> Self {
        Self {
            run: None,
            job: None,
            state: RunState::Idle,
            phase: None,
            done: 0,
            total: 0,
            elapsed_s: 0.0,
            line: None,
            error: None,
        }
    }
}

/// A run of `/api/studio/runs`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunEntry {
    /// Its name (the folder's).
    pub name: String,
    /// The job file it ran (`None`: not saved, or not said).
    pub job: Option<String>,
    /// The job's kind, where known.
    pub kind: Option<JobKind>,
    /// Where it is.
    pub state: RunState,
    /// The run's line, once done.
    pub line: Option<String>,
}

/// What `run.json` in a run folder holds.
#[derive(Debug, Serialize, serde::Deserialize)]
struct RunRecord {
    job: Option<String>,
    kind: JobKind,
    line: String,
}

/// A job to run: its text as edited, the file it stands for.
#[derive(Debug, Clone)]
pub struct RunOrder {
    /// The job file in `DIR` (`None`: not saved).
    pub file: Option<String>,
    /// Its kind.
    pub kind: JobKind,
    /// Its text.
    pub text: String,
}

/// One run handed to the worker.
struct Queued {
    name: String,
    order: RunOrder,
    flag: Arc<AtomicBool>,
}

/// The latest run: its status, its cancel flag, when it started.
struct Latest {
    status: RunStatus,
    flag: Arc<AtomicBool>,
    started: Option<Instant>,
    /// Run names handed out (their folders may not exist yet).
    taken: HashSet<String>,
}

/// What the worker and the server share.
struct Shared {
    dir: PathBuf,
    latest: Mutex<Latest>,
}

impl Shared {
    fn latest(&self) -> MutexGuard<'_, Latest> {
        // A status is plain data: one a panic left half-set is still read.
        self.latest.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Updates the status if `name` is still the latest run.
    fn update(&self, name: &str, f: impl FnOnce(&mut Latest)) {
        let mut l = self.latest();
        if l.status.run.as_deref() == Some(name) {
            f(&mut l);
        }
    }
}

/// The run queue of a studio folder.
pub struct Runs {
    shared: Arc<Shared>,
    queue: Mutex<Sender<Queued>>,
}

impl std::fmt::Debug for Runs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Runs")
            .field("dir", &self.shared.dir)
            .finish_non_exhaustive()
    }
}

impl Runs {
    /// The queue of the folder `dir` (absolute), its worker started.
    ///
    /// # Errors
    ///
    /// [`StudioError::Worker`] when the system has no thread to give.
    pub fn start(dir: &Path) -> Result<Self, StudioError> {
        let shared = Arc::new(Shared {
            dir: dir.to_path_buf(),
            latest: Mutex::new(Latest {
                status: RunStatus::idle(),
                flag: Arc::new(AtomicBool::new(false)),
                started: None,
                taken: HashSet::new(),
            }),
        });
        let (tx, rx) = channel();
        let worker = Arc::clone(&shared);
        thread::Builder::new()
            .name("formcam-studio-runs".into())
            .spawn(move || work(&worker, &rx))
            .map_err(|source| StudioError::Worker { source })?;
        Ok(Self {
            shared,
            queue: Mutex::new(tx),
        })
    }

    /// Starts `order`: the running run (if any) is cancelled, the new one
    /// queued behind it. Returns the new run's name.
    ///
    /// # Errors
    ///
    /// [`StudioError::Worker`] when the worker is gone.
    pub fn run(&self, order: RunOrder) -> Result<String, StudioError> {
        let stem = order
            .file
            .as_deref()
            .and_then(|f| Path::new(f).file_stem())
            .map_or_else(|| "job".to_string(), |s| s.to_string_lossy().into_owned());
        let flag = Arc::new(AtomicBool::new(false));
        let name = {
            let mut l = self.shared.latest();
            l.flag.store(true, Ordering::Relaxed);
            let name = free_name(
                &self.shared.dir,
                &run_stamp(SystemTime::now()),
                &stem,
                |n| l.taken.contains(n),
            );
            l.taken.insert(name.clone());
            l.flag = Arc::clone(&flag);
            l.started = Some(Instant::now());
            l.status = RunStatus {
                run: Some(name.clone()),
                job: order.file.clone(),
                state: RunState::Running,
                ..RunStatus::idle()
            };
            name
        };
        let queued = Queued {
            name: name.clone(),
            order,
            flag,
        };
        let sent = self
            .queue
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .send(queued);
        if sent.is_err() {
            self.shared.update(&name, |l| {
                l.status.state = RunState::Failed;
                l.status.error = Some("the studio's run worker has stopped".into());
            });
            return Err(StudioError::Worker {
                source: std::io::Error::other("the run worker has stopped"),
            });
        }
        Ok(name)
    }

    /// Asks the latest run to stop; returns the status.
    pub fn cancel(&self) -> RunStatus {
        self.shared.latest().flag.store(true, Ordering::Relaxed);
        self.status()
    }

    /// The latest run's status.
    pub fn status(&self) -> RunStatus {
        let l = self.shared.latest();
        let mut s = l.status.clone();
        if s.state == RunState::Running
            && let Some(t) = l.started
        {
            s.elapsed_s = t.elapsed().as_secs_f64();
        }
        s
    }

    /// The runs: the folders under `DIR/runs/` and the latest run while it
    /// has none (running, failed or cancelled), newest first.
    pub fn list(&self) -> Vec<RunEntry> {
        let mut entries = folders(&self.shared.dir.join(RUNS_FOLDER));
        let s = self.status();
        if let Some(name) = &s.run
            && s.state != RunState::Done
            && !entries.iter().any(|e| &e.name == name)
        {
            entries.push(RunEntry {
                name: name.clone(),
                job: s.job.clone(),
                kind: None,
                state: s.state,
                line: None,
            });
        }
        entries.sort_by(|a, b| b.name.cmp(&a.name));
        entries
    }

    /// Whether the run `name` is the latest and not done (its folder, if
    /// one is there, is not its own yet).
    pub fn is_pending(&self, name: &str) -> bool {
        let l = self.shared.latest();
        l.status.run.as_deref() == Some(name) && l.status.state != RunState::Done
    }
}

/// The run folders under `runs`, each as its `run.json` describes it.
fn folders(runs: &Path) -> Vec<RunEntry> {
    let Ok(read) = std::fs::read_dir(runs) else {
        return Vec::new();
    };
    read.filter_map(Result::ok)
        .filter(|e| e.path().is_dir())
        .filter_map(|e| {
            let name = e.file_name().to_str()?.to_string();
            if name.starts_with('.') {
                return None;
            }
            let record = formcam_files::read_text(&e.path().join(RUN_FILE))
                .ok()
                .and_then(|t| serde_json::from_str::<RunRecord>(&t).ok());
            Some(RunEntry {
                name,
                job: record.as_ref().and_then(|r| r.job.clone()),
                kind: record.as_ref().map(|r| r.kind),
                state: RunState::Done,
                line: record.map(|r| r.line),
            })
        })
        .collect()
}

/// The worker: each queued run in turn until the queue is dropped.
fn work(shared: &Shared, queue: &Receiver<Queued>) {
    while let Ok(q) = queue.recv() {
        if q.flag.load(Ordering::Relaxed) {
            shared.update(&q.name, |l| finish(l, RunState::Cancelled, None, None));
            continue;
        }
        shared.update(&q.name, |l| l.started = Some(Instant::now()));
        let ran = catch_unwind(AssertUnwindSafe(|| run_one(shared, &q)));
        let (state, line, error) = match ran {
            Ok(Ok(line)) => (RunState::Done, Some(line), None),
            Ok(Err(Ended::Cancelled)) => (RunState::Cancelled, None, None),
            Ok(Err(Ended::Failed(message))) => (RunState::Failed, None, Some(message)),
            Err(_) => (
                RunState::Failed,
                None,
                Some("the run stopped unexpectedly".into()),
            ),
        };
        shared.update(&q.name, |l| finish(l, state, line, error));
    }
}

/// The status of a run that ended.
fn finish(l: &mut Latest, state: RunState, line: Option<String>, error: Option<String>) {
    l.status.state = state;
    l.status.line = line;
    l.status.error = error;
    l.status.elapsed_s = l.started.map_or(0.0, |t| t.elapsed().as_secs_f64());
}

/// How a run ended without its folder.
enum Ended {
    Cancelled,
    Failed(String),
}

/// Runs `q` and writes its folder; its line.
fn run_one(shared: &Shared, q: &Queued) -> Result<String, Ended> {
    let out = shared.dir.join(RUNS_FOLDER).join(&q.name);
    // The job stands where its file is (or would be): the files it names
    // are found beside it, and the summary names it by its full path.
    let job = shared.dir.join(q.order.file.as_deref().unwrap_or(UNSAVED));
    let hook = Hook::with_flag(Arc::clone(&q.flag), |step: Step| {
        shared.update(&q.name, |l| {
            l.status.phase = Some(step.phase.name());
            l.status.done = step.done;
            l.status.total = step.total;
        });
    });
    let output =
        run_job_text_with(&job, &q.order.text, q.order.kind, &out, &hook).map_err(|e| match e {
            e if e.is_cancelled() => Ended::Cancelled,
            e => Ended::Failed(e.to_string()),
        })?;
    if q.flag.load(Ordering::Relaxed) {
        return Err(Ended::Cancelled);
    }
    write_run(&out, q, output)
}

/// The run folder: the result's files (the job's text as it ran among
/// them, as every result keeps it: `job.toml`), `run.json`.
fn write_run(out: &Path, q: &Queued, output: RunOutput) -> Result<String, Ended> {
    let record = RunRecord {
        job: q.order.file.clone(),
        kind: q.order.kind,
        line: output.line.clone(),
    };
    let record = serde_json::to_vec_pretty(&record)
        .map_err(|e| Ended::Failed(RunError::Summary { source: e }.to_string()))?;
    let mut files: Vec<(String, Vec<u8>)> = output
        .files
        .into_iter()
        .filter(|f| f.name != RUN_FILE)
        .map(|f| (f.name, f.bytes))
        .collect();
    files.push((RUN_FILE.into(), record));
    formcam_files::write_folder(out, &files, &output.inputs)
        .map_err(|e| Ended::Failed(e.to_string()))?;
    Ok(output.line)
}

/// `<stamp>-<stem>`, or with `-2`, `-3`, ... where that name is `taken` or
/// a folder of `DIR/runs/` already.
fn free_name(dir: &Path, stamp: &str, stem: &str, taken: impl Fn(&str) -> bool) -> String {
    let runs = dir.join(RUNS_FOLDER);
    let base = format!("{stamp}-{stem}");
    let free = |n: &str| !taken(n) && !runs.join(n).exists();
    if free(&base) {
        return base;
    }
    (2u64..)
        .map(|k| format!("{base}-{k}"))
        .find(|n| free(n))
        .unwrap_or(base)
}

/// `YYYYMMDD-HHMMSS` of `t`, UTC.
fn run_stamp(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let days = i64::try_from(secs / 86_400).unwrap_or(0);
    let rest = secs % 86_400;
    let (y, m, d) = civil_from_days(days);
    format!(
        "{y:04}{m:02}{d:02}-{:02}{:02}{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

/// The proleptic Gregorian date of `days` since 1970-01-01 (H. Hinnant's
/// `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    (
        y,
        u32::try_from(m).unwrap_or(1),
        u32::try_from(d).unwrap_or(1),
    )
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use std::time::Duration;

    #[test]
    fn stamps_are_utc_dates_and_times() {
        assert_eq!(run_stamp(UNIX_EPOCH), "19700101-000000");
        // 2000-02-29 23:59:59 UTC, a leap day.
        let t = UNIX_EPOCH + Duration::from_secs(951_868_799);
        assert_eq!(run_stamp(t), "20000229-235959");
        // 2026-12-02 13:50:44 UTC.
        let t = UNIX_EPOCH + Duration::from_secs(1_796_219_444);
        assert_eq!(run_stamp(t), "20261202-135044");
    }

    #[test]
    fn a_taken_name_gets_the_next_number() {
        let dir = std::env::temp_dir().join(format!("formcam-studio-names-{}", std::process::id()));
        let runs = dir.join(RUNS_FOLDER);
        std::fs::create_dir_all(runs.join("20260101-000000-a")).unwrap();
        let n = free_name(&dir, "20260101-000000", "a", |n| n.ends_with("-a-2"));
        assert_eq!(n, "20260101-000000-a-3");
        assert_eq!(
            free_name(&dir, "20260101-000000", "b", |_| false),
            "20260101-000000-b"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
