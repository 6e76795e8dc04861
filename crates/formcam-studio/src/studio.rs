//! A studio: the folder `DIR` of job files, what each request of the page
//! asks of it (the job list, a job as form values, apply, run, cancel,
//! save, an example started) and the run folders shown as `formcam view`
//! shows a result. Reads and writes only in `DIR`: job files directly in
//! it by plain names, run folders under `DIR/runs/`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use formcam_view::request::{Refusal, Target};
use formcam_view::{Page, View, content_type};
use serde::Deserialize;
use serde_json::{Value, json};

use crate::runs::{RUNS_FOLDER, RunOrder, Runs};
use crate::{
    Applied, JobKind, StudioError, apply_job, examples, job_path, save_job, start_example,
    values_of,
};

/// The most bytes of a request's body (the JSON the page posts).
pub const MAX_BODY_BYTES: usize = 1024 * 1024;

/// The file name an unsaved job is checked and run under (in `DIR`).
pub(crate) const UNSAVED: &str = "job.toml";

/// A request's method, as the studio serves them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StudioMethod {
    /// Reading: the page, the job list, a job, the status, a run's view.
    Get,
    /// Acting: apply, run, cancel, save, start an example (a JSON body).
    Post,
}

/// An answer: status, content type, body and, for a redirect, where to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Answer {
    /// The HTTP status.
    pub status: u16,
    /// The content type.
    pub kind: &'static str,
    /// The body.
    pub body: Vec<u8>,
    /// `Location` of a redirect.
    pub location: Option<String>,
}

impl Answer {
    fn json(status: u16, v: &Value) -> Self {
        Self {
            status,
            kind: JSON,
            body: serde_json::to_vec(v).unwrap_or_default(),
            location: None,
        }
    }

    fn error(status: u16, message: impl std::fmt::Display) -> Self {
        Self::json(status, &json!({ "error": message.to_string() }))
    }

    fn refusal(r: Refusal) -> Self {
        Self::error(r.status(), r)
    }

    fn of(r: Result<Self, Self>) -> Self {
        r.unwrap_or_else(|e| e)
    }
}

const JSON: &str = "application/json";
const TEXT: &str = "text/plain; charset=utf-8";

/// The body of apply, run and save: the job's text as saved (or the
/// example's) and the form's values.
#[derive(Debug, Deserialize)]
struct Edit {
    file: Option<String>,
    kind: JobKind,
    text: String,
    values: Value,
}

/// The body of `/api/studio/example`.
#[derive(Debug, Deserialize)]
struct ExampleName {
    name: String,
}

/// A studio on a folder.
#[derive(Debug)]
pub struct Studio {
    /// The folder as given.
    folder: PathBuf,
    /// The folder, absolute.
    dir: PathBuf,
    /// The job file given (preselected on the page).
    job: Option<String>,
    page: Page,
    runs: Runs,
    /// The run folders opened for their view, by run name.
    views: Mutex<HashMap<String, Arc<View>>>,
}

impl Studio {
    /// A studio on `path`: a folder, or a job file (its folder, that job
    /// preselected); `page` is served at `/` and in each run's view.
    ///
    /// # Errors
    ///
    /// [`StudioError::NoFolder`] for a path that does not exist,
    /// [`StudioError::NotAJob`] for a file that is no job of a known kind,
    /// [`StudioError::Worker`] when the run worker cannot start.
    pub fn open(path: &Path, page: Page) -> Result<Self, StudioError> {
        let (folder, job) = if path.is_dir() {
            (path.to_path_buf(), None)
        } else if path.is_file() {
            (
                path.parent()
                    .filter(|p| !p.as_os_str().is_empty())
                    .unwrap_or(Path::new("."))
                    .to_path_buf(),
                Some(job_file_name(path)?),
            )
        } else {
            return Err(StudioError::NoFolder {
                path: path.to_path_buf(),
            });
        };
        let dir = folder.canonicalize().map_err(|_| StudioError::NoFolder {
            path: folder.clone(),
        })?;
        let runs = Runs::start(&dir)?;
        Ok(Self {
            folder,
            dir,
            job,
            page,
            runs,
            views: Mutex::new(HashMap::new()),
        })
    }

    /// The folder, absolute.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The run queue.
    pub fn runs(&self) -> &Runs {
        &self.runs
    }

    /// The answer to a request: `method`, `url` (path and query), `body`
    /// (JSON, for a POST).
    pub fn answer(&self, method: StudioMethod, url: &str, body: &[u8]) -> Answer {
        // `/runs/NAME/`, a run's view page, is read without its final `/`
        // (a plain path has no empty name).
        let path = url.split_once('?').map_or(url, |(p, _)| p);
        let run_page =
            path.starts_with("/runs/") && path.ends_with('/') && path.matches('/').count() == 3;
        let target = match Target::parse(if run_page {
            &path[..path.len() - 1]
        } else {
            url
        }) {
            Ok(t) => t,
            Err(r) => return Answer::refusal(r),
        };
        let seg: Vec<&str> = target.segments.iter().map(String::as_str).collect();
        match (method, seg.as_slice()) {
            (StudioMethod::Get, ["api", "kind"]) => Answer::json(200, &json!({"kind": "studio"})),
            (StudioMethod::Get, ["api", "studio"]) => Answer::json(200, &self.listing()),
            (StudioMethod::Get, ["api", "studio", "job"]) => Answer::of(
                target
                    .param_decoded("file")
                    .ok_or_else(|| Answer::error(400, "give the job file: ?file=NAME"))
                    .and_then(|f| self.job(&f)),
            ),
            (StudioMethod::Get, ["api", "studio", "status"]) => {
                Answer::json(200, &json!(self.runs.status()))
            }
            (StudioMethod::Get, ["api", "studio", "runs"]) => {
                Answer::json(200, &json!(self.runs.list()))
            }
            (StudioMethod::Post, ["api", "studio", "apply"]) => {
                Answer::of(parse::<Edit>(body).map(|e| self.apply(&e)))
            }
            (StudioMethod::Post, ["api", "studio", "run"]) => {
                Answer::of(parse::<Edit>(body).and_then(|e| self.run(&e)))
            }
            (StudioMethod::Post, ["api", "studio", "cancel"]) => {
                Answer::json(200, &json!(self.runs.cancel()))
            }
            (StudioMethod::Post, ["api", "studio", "save"]) => {
                Answer::of(parse::<Edit>(body).and_then(|e| self.save(&e)))
            }
            (StudioMethod::Post, ["api", "studio", "example"]) => {
                Answer::of(parse::<ExampleName>(body).and_then(|e| self.example(&e.name)))
            }
            (StudioMethod::Post, _) => Answer::error(404, "no such action"),
            (StudioMethod::Get, ["api", ..]) => Answer::refusal(Refusal::NotFound),
            // The view's page asks for its files relative to its folder.
            (StudioMethod::Get, ["runs", name]) if run_page => self.run_view(name, url),
            (StudioMethod::Get, ["runs", _]) => Answer {
                status: 308,
                kind: TEXT,
                body: Vec::new(),
                location: Some(format!("/runs/{}/", target_segment(url, 1))),
            },
            (StudioMethod::Get, ["runs", name, ..]) => self.run_view(name, url),
            (StudioMethod::Get, _) => self.page_file(&seg.join("/")),
        }
    }

    /// `/api/studio`: the folder, the job given, each kind's description,
    /// the job files and the examples.
    fn listing(&self) -> Value {
        let kinds: Vec<Value> = JobKind::EDITABLE
            .iter()
            .map(|k| json!({"kind": k, "schema": k.schema()}))
            .collect();
        let examples: Vec<Value> = examples()
            .iter()
            .map(|e| json!({"name": e.name, "kind": e.kind}))
            .collect();
        json!({
            "folder": self.folder.display().to_string(),
            "job": self.job,
            "kinds": kinds,
            "jobs": self.jobs(),
            "examples": examples,
        })
    }

    /// The job files directly in `DIR` whose kind is known, sorted.
    fn jobs(&self) -> Vec<Value> {
        let Ok(read) = std::fs::read_dir(&self.dir) else {
            return Vec::new();
        };
        let mut jobs: Vec<(String, JobKind)> = read
            .filter_map(Result::ok)
            .filter(|e| e.path().is_file())
            .filter_map(|e| {
                let name = e.file_name().to_str()?.to_string();
                job_path(Path::new(""), &name).ok()?;
                let text = formcam_files::read_text(&e.path()).ok()?;
                Some((name, JobKind::of_text(&text)?))
            })
            .collect();
        jobs.sort();
        jobs.into_iter()
            .map(|(file, kind)| json!({"file": file, "kind": kind}))
            .collect()
    }

    /// `/api/studio/job?file=NAME`: the job's text and its form values.
    fn job(&self, file: &str) -> Result<Answer, Answer> {
        let path = self.job_path(file)?;
        let text = formcam_files::read_text(&path).map_err(|e| Answer::error(404, e))?;
        let kind = JobKind::of_text(&text).ok_or_else(|| {
            Answer::error(
                422,
                StudioError::NotAJob {
                    path: PathBuf::from(file),
                },
            )
        })?;
        let values = values_of(&text).map_err(|e| Answer::error(422, e))?;
        Ok(Answer::json(
            200,
            &json!({"file": file, "kind": kind, "text": text, "values": values}),
        ))
    }

    /// The form's values applied to the text and checked (the job file's
    /// name checked first).
    fn edited(&self, e: &Edit) -> Result<Applied, Answer> {
        let file = match &e.file {
            Some(f) => {
                self.job_path(f)?;
                f.as_str()
            }
            None => UNSAVED,
        };
        Ok(apply_job(e.kind, &self.dir, file, &e.text, &e.values))
    }

    /// The edited text of a job that checks clean; else its errors (422).
    fn checked(&self, e: &Edit) -> Result<String, Answer> {
        let Applied { ok, text, errors } = self.edited(e)?;
        if ok {
            Ok(text)
        } else {
            Err(Answer::json(422, &json!({"ok": false, "errors": errors})))
        }
    }

    /// `/api/studio/apply`: the new text and every error at its field.
    fn apply(&self, e: &Edit) -> Answer {
        Answer::of(self.edited(e).map(|a| Answer::json(200, &json!(a))))
    }

    /// `/api/studio/run`: a job that checks clean starts (the running one
    /// cancelled); else its errors, and nothing runs.
    fn run(&self, e: &Edit) -> Result<Answer, Answer> {
        let text = self.checked(e)?;
        let name = self
            .runs
            .run(RunOrder {
                file: e.file.clone(),
                kind: e.kind,
                text,
            })
            .map_err(|err| Answer::error(500, err))?;
        Ok(Answer::json(200, &json!({"run": name})))
    }

    /// `/api/studio/save`: a job that checks clean written (the previous
    /// file kept as `.bak`); else its errors, and nothing is written.
    fn save(&self, e: &Edit) -> Result<Answer, Answer> {
        let file = e
            .file
            .as_deref()
            .ok_or_else(|| Answer::error(400, "give the job file's name to save it as"))?;
        let text = self.checked(e)?;
        save_job(&self.dir, file, &text).map_err(|err| Answer::error(400, err))?;
        Ok(Answer::json(
            200,
            &json!({"ok": true, "file": file, "text": text}),
        ))
    }

    /// `/api/studio/example`: the example's job and inputs written into
    /// `DIR`; the job as `/api/studio/job` answers it.
    fn example(&self, name: &str) -> Result<Answer, Answer> {
        let file = start_example(&self.dir, name).map_err(|err| Answer::error(400, err))?;
        self.job(&file)
    }

    /// The job file `file` in `DIR`: a plain `*.toml` name.
    fn job_path(&self, file: &str) -> Result<PathBuf, Answer> {
        job_path(&self.dir, file).map_err(|e| Answer::error(400, e))
    }

    /// `/runs/<name>/...`: the run folder's view (opened once, kept);
    /// 404 while the run has no folder of its own.
    fn run_view(&self, name: &str, url: &str) -> Answer {
        let view = match self.view_of(name) {
            Ok(v) => v,
            Err(a) => return a,
        };
        // The rest of the path, its query kept: `/runs/NAME/api/x?q` is
        // the view's `/api/x?q`.
        let prefix = format!("/runs/{}", target_segment(url, 1));
        let rest = url.strip_prefix(&prefix).unwrap_or("/");
        let (status, kind, body) = view.answer(rest);
        Answer {
            status,
            kind,
            body,
            location: None,
        }
    }

    /// The view of the run folder `name`, opened on first use.
    fn view_of(&self, name: &str) -> Result<Arc<View>, Answer> {
        let lock = || self.views.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(v) = lock().get(name) {
            return Ok(Arc::clone(v));
        }
        let folder = self.dir.join(RUNS_FOLDER).join(name);
        if self.runs.is_pending(name) || !folder.is_dir() {
            return Err(Answer::refusal(Refusal::NotFound));
        }
        let view = View::open(&folder, None, self.page.clone())
            .map(Arc::new)
            .map_err(|e| Answer::error(404, e))?;
        Ok(Arc::clone(lock().entry(name.to_string()).or_insert(view)))
    }

    /// A file of the page (`/` is `index.html`).
    fn page_file(&self, name: &str) -> Answer {
        match self.page.get(name) {
            Some(body) => Answer {
                status: 200,
                kind: content_type(Path::new(if name.is_empty() { "index.html" } else { name })),
                body: body.to_vec(),
                location: None,
            },
            None if name == "favicon.ico" => Answer {
                status: 200,
                kind: "image/x-icon",
                body: Vec::new(),
                location: None,
            },
            None => Answer::refusal(Refusal::NotFound),
        }
    }
}

/// The `k`-th segment of `url`'s path as sent (still percent-encoded).
fn target_segment(url: &str, k: usize) -> &str {
    let path = url.split_once('?').map_or(url, |(p, _)| p);
    path.split('/').nth(k + 1).unwrap_or("")
}

/// A request body as JSON of `T`.
fn parse<T: for<'de> Deserialize<'de>>(body: &[u8]) -> Result<T, Answer> {
    serde_json::from_slice(body).map_err(|e| Answer::error(400, format!("the request: {e}")))
}

/// The file name of the job file at `path`, if it is one of a known kind.
fn job_file_name(path: &Path) -> Result<String, StudioError> {
    let not = || StudioError::NotAJob {
        path: path.to_path_buf(),
    };
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .filter(|n| job_path(Path::new(""), n).is_ok())
        .ok_or_else(not)?;
    let text = formcam_files::read_text(path).map_err(|_| not())?;
    JobKind::of_text(&text).ok_or_else(not)?;
    Ok(name.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_taken_as_sent() {
        assert_eq!(target_segment("/runs/a%20b/api/x?y=1", 1), "a%20b");
        assert_eq!(target_segment("/runs/a", 1), "a");
        assert_eq!(target_segment("/runs", 1), "");
    }

    #[test]
    fn a_runs_page_is_its_view_and_its_name_alone_redirects_there() {
        #![allow(clippy::unwrap_used)]
        let dir = std::env::temp_dir().join(format!("formcam-studio-page-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let studio = Studio::open(&dir, Page::none()).unwrap();
        // No such run: the view's 404, not a refused path.
        for url in ["/runs/x/", "/runs/x/api/kind", "/runs/x/?t=1"] {
            assert_eq!(
                studio.answer(StudioMethod::Get, url, &[]).status,
                404,
                "{url}"
            );
        }
        let a = studio.answer(StudioMethod::Get, "/runs/x", &[]);
        assert_eq!(a.location.as_deref(), Some("/runs/x/"));
        // Nothing else ends in `/`.
        for url in ["/runs/x//", "/api/studio/", "/runs/"] {
            assert_eq!(
                studio.answer(StudioMethod::Get, url, &[]).status,
                400,
                "{url}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
