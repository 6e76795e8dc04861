//! The HTTP server: on 127.0.0.1 only, GET only, the page, the result
//! folder's files and the JSON the page draws.

use std::io::Cursor;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread;

use serde::Serialize;
use tiny_http::{Header, Method, Request, Response};

use crate::ViewError;
use crate::correction::CorrectionBody;
use crate::dressing::DressingView;
use crate::folder::{ResultKind, RunFolder, read_summary};
use crate::overlay::{Overlay, Shown};
use crate::page::Page;
use crate::plots::WindingPlots;
use crate::request::{MAX_HEADER_BYTES, Refusal, Target, file_under};
use crate::scene::{MachineScene, MandrelScene};
use crate::timeline::{Timeline, TimelineHead};

/// Samples of `/api/timeline` when the query names none.
pub const DEFAULT_SAMPLES: usize = 2000;

/// The most samples of `/api/timeline`.
pub const MAX_SAMPLES: usize = 100_000;

/// Threads answering requests.
const WORKERS: usize = 4;

/// How to start a view.
#[derive(Debug, Clone, Default)]
pub struct ViewOptions {
    /// The port on 127.0.0.1 (0: any free one).
    pub port: u16,
    /// The machine file, instead of the one the result names.
    pub machine: Option<PathBuf>,
}

/// What the server answers from: the result read once.
#[derive(Debug)]
pub struct View {
    root: PathBuf,
    summary: Vec<u8>,
    machine: Vec<u8>,
    mandrel: Option<Vec<u8>>,
    program: Option<String>,
    timeline: Option<Timeline>,
    overlay: Option<Overlay>,
    page: Page,
    kind: ResultKind,
    /// A winding result's plots (`/api/plots`).
    plots: Option<Vec<u8>>,
    /// A dressing result (`/api/dressing`).
    dressing: Option<(DressingView, Vec<u8>)>,
    /// A correction result (`/api/correction`).
    correction: Option<Vec<u8>>,
}

impl View {
    /// Reads the result folder `root` for the page `page`.
    ///
    /// # Errors
    ///
    /// [`ViewError`] naming the file and the field.
    pub fn open(root: &Path, machine: Option<&Path>, page: Page) -> Result<Self, ViewError> {
        let kind = ResultKind::of(root)?;
        if kind != ResultKind::Winding {
            return Self::open_2d(root, kind, page);
        }
        let folder = RunFolder::open(root, machine)?;
        let real = root.canonicalize().map_err(|_| ViewError::NoFolder {
            path: root.to_path_buf(),
        })?;
        let scene = MachineScene::of(&folder.machine);
        let mandrel = match &folder.path_table {
            Some((path, text)) => Some(json(&MandrelScene::from_path_table(
                folder.machine.roles.mandrel,
                text,
                path,
            )?)),
            None => None,
        };
        let timeline = match &folder.program {
            Some(p) => Some(Timeline::from_program(
                folder.machine.clone(),
                &p.text,
                p.dialect,
                &p.path,
            )?),
            None => None,
        };
        let overlay = match &timeline {
            Some(tl) => Some(Overlay::open(&real, &folder.summary, tl)?),
            None => None,
        };
        let plots = json(&WindingPlots::read(
            root,
            timeline.as_ref().map(Timeline::sim),
        )?);
        Ok(Self {
            kind,
            plots: Some(plots),
            dressing: None,
            correction: None,
            root: real,
            summary: json(&folder.summary),
            machine: json(&scene),
            mandrel,
            program: folder.program.map(|p| p.text),
            timeline,
            overlay,
            page,
        })
    }

    /// A dressing or correction result: its summary or report, the view of
    /// its kind.
    fn open_2d(root: &Path, kind: ResultKind, page: Page) -> Result<Self, ViewError> {
        let real = root.canonicalize().map_err(|_| ViewError::NoFolder {
            path: root.to_path_buf(),
        })?;
        let (summary, dressing, correction) = if kind == ResultKind::Dressing {
            let s = read_summary(&root.join("summary.json"))?;
            let d = DressingView::read(root, &s)?;
            let body = json(d.body());
            (json(&s), Some((d, body)), None)
        } else {
            let r = read_summary(&root.join("report.json"))?;
            let c = CorrectionBody::read(root, r.clone())?;
            (json(&r), None, Some(json(&c)))
        };
        Ok(Self {
            root: real,
            summary,
            machine: Vec::new(),
            mandrel: None,
            program: None,
            timeline: None,
            overlay: None,
            page,
            kind,
            plots: None,
            dressing,
            correction,
        })
    }

    /// What the folder holds.
    pub fn kind(&self) -> ResultKind {
        self.kind
    }

    /// The timeline of the result's program, if it has one.
    pub fn timeline(&self) -> Option<&Timeline> {
        self.timeline.as_ref()
    }

    /// The answer to a GET of `url`: status, content type, body.
    pub fn answer(&self, url: &str) -> (u16, &'static str, Vec<u8>) {
        match self.route(url) {
            Ok((kind, body)) => (200, kind, body),
            Err(r) => (r.status(), TEXT, format!("{r}\n").into_bytes()),
        }
    }

    fn route(&self, url: &str) -> Result<(&'static str, Vec<u8>), Refusal> {
        let target = Target::parse(url)?;
        let seg: Vec<&str> = target.segments.iter().map(String::as_str).collect();
        match seg.as_slice() {
            ["api", "result"] => Ok((JSON, self.summary.clone())),
            ["api", "kind"] => Ok((JSON, json(&serde_json::json!({ "kind": self.kind })))),
            [
                "api",
                "machine" | "mandrel" | "program" | "timeline" | "sample" | "blocks",
            ] if self.kind != ResultKind::Winding => Err(Refusal::NotFound),
            ["api", "plots"] => self
                .plots
                .clone()
                .map(|b| (JSON, b))
                .ok_or(Refusal::NotFound),
            ["api", "dressing"] => self
                .dressing
                .as_ref()
                .map(|(_, b)| (JSON, b.clone()))
                .ok_or(Refusal::NotFound),
            ["api", "dressing", "sample"] => {
                let (d, _) = self.dressing.as_ref().ok_or(Refusal::NotFound)?;
                let t = target
                    .param("t")
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|t| t.is_finite())
                    .ok_or(Refusal::Path)?;
                Ok((JSON, json(&d.sample(t))))
            }
            ["api", "correction"] => self
                .correction
                .clone()
                .map(|b| (JSON, b))
                .ok_or(Refusal::NotFound),
            ["api", "machine"] => Ok((JSON, self.machine.clone())),
            ["api", "mandrel"] => self
                .mandrel
                .clone()
                .map(|b| (JSON, b))
                .ok_or(Refusal::NotFound),
            ["api", "program"] => self
                .program
                .clone()
                .map(|t| (TEXT, t.into_bytes()))
                .ok_or(Refusal::NotFound),
            ["api", "timeline"] => {
                let tl = self.timeline.as_ref().ok_or(Refusal::NotFound)?;
                let n = match target.param("samples") {
                    None => DEFAULT_SAMPLES,
                    Some(s) => s.parse::<usize>().map_err(|_| Refusal::Path)?,
                };
                let n = n.clamp(2, MAX_SAMPLES);
                Ok((
                    JSON,
                    json(&TimelineBody {
                        head: tl.head(),
                        samples: tl.samples(n).into_iter().map(|s| self.shown(s)).collect(),
                    }),
                ))
            }
            ["api", "sample"] => {
                let tl = self.timeline.as_ref().ok_or(Refusal::NotFound)?;
                let t = target
                    .param("t")
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|t| t.is_finite())
                    .ok_or(Refusal::Path)?;
                Ok((JSON, json(&self.shown(tl.sample(t)))))
            }
            ["api", "blocks"] => {
                let tl = self.timeline.as_ref().ok_or(Refusal::NotFound)?;
                let spans: Vec<(f64, f64)> = (0..tl.lines().len())
                    .filter_map(|b| tl.block_span(b))
                    .collect();
                Ok((
                    JSON,
                    json(&BlocksBody {
                        starts: spans.iter().map(|s| s.0).collect(),
                        ends: spans.iter().map(|s| s.1).collect(),
                        lines: &tl.lines(),
                    }),
                ))
            }
            ["api", "violations"] => self.overlay_json(|o| Some(json(&o.violations))),
            ["api", "eye"] => self.overlay_json(|o| Some(json(&o.eye))),
            ["api", "band"] => self.overlay_json(|o| o.band.as_ref().map(json)),
            ["api", ..] => Err(Refusal::NotFound),
            ["files", rest @ ..] if !rest.is_empty() => {
                let path = file_under(&self.root, &target.segments[1..])?;
                let body = formcam_files::read_bytes(&path).map_err(|_| Refusal::NotFound)?;
                Ok((content_type(&path), body))
            }
            [] => self.page_file("index.html"),
            // Browsers ask for an icon the page does not have: an empty one.
            ["favicon.ico"] if self.page.get("favicon.ico").is_none() => Ok((ICON, Vec::new())),
            _ => self.page_file(&seg.join("/")),
        }
    }

    /// A sample with what the overlays add to it.
    fn shown(&self, s: crate::timeline::Sample) -> Shown {
        match &self.overlay {
            Some(o) => o.shown(s),
            None => Shown {
                sample: s,
                laid: None,
            },
        }
    }

    /// An overlay's JSON, or 404 when the result has none.
    fn overlay_json(
        &self,
        body: impl Fn(&Overlay) -> Option<Vec<u8>>,
    ) -> Result<(&'static str, Vec<u8>), Refusal> {
        self.overlay
            .as_ref()
            .and_then(body)
            .map(|b| (JSON, b))
            .ok_or(Refusal::NotFound)
    }

    fn page_file(&self, name: &str) -> Result<(&'static str, Vec<u8>), Refusal> {
        let body = self.page.get(name).ok_or(Refusal::NotFound)?;
        Ok((content_type(Path::new(name)), body.to_vec()))
    }
}

/// `/api/timeline`: what the arrays mean, then the samples.
#[derive(Serialize)]
struct TimelineBody {
    #[serde(flatten)]
    head: TimelineHead,
    samples: Vec<Shown>,
}

/// `/api/blocks`: per block its start, end (s) and program line.
#[derive(Serialize)]
struct BlocksBody<'a> {
    starts: Vec<f64>,
    ends: Vec<f64>,
    lines: &'a [usize],
}

const JSON: &str = "application/json";
const TEXT: &str = "text/plain; charset=utf-8";
const ICON: &str = "image/x-icon";

fn json<T: Serialize>(v: &T) -> Vec<u8> {
    // Our own plain data (numbers, strings) always serialises.
    serde_json::to_vec(v).unwrap_or_default()
}

fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "js" | "mjs" => "text/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "json" => JSON,
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "ico" => ICON,
        "csv" => "text/csv; charset=utf-8",
        _ => TEXT,
    }
}

/// A view listening on 127.0.0.1.
pub struct ViewServer {
    server: Arc<tiny_http::Server>,
    view: Arc<View>,
    addr: SocketAddr,
}

impl ViewServer {
    /// Reads the result folder and listens on `127.0.0.1:port`.
    ///
    /// # Errors
    ///
    /// The result's [`ViewError`], or [`ViewError::Bind`].
    pub fn bind(root: &Path, options: &ViewOptions, page: Page) -> Result<Self, ViewError> {
        let view = View::open(root, options.machine.as_deref(), page)?;
        let bind = |e: Box<dyn std::error::Error + Send + Sync>| ViewError::Bind {
            port: options.port,
            source: std::io::Error::other(e),
        };
        let server = tiny_http::Server::http(("127.0.0.1", options.port)).map_err(bind)?;
        let addr = server
            .server_addr()
            .to_ip()
            .ok_or_else(|| bind("not an IP address".into()))?;
        Ok(Self {
            server: Arc::new(server),
            view: Arc::new(view),
            addr,
        })
    }

    /// `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Answers requests until the process ends.
    pub fn serve(self) {
        let workers: Vec<_> = (1..WORKERS)
            .map(|_| {
                let (server, view) = (Arc::clone(&self.server), Arc::clone(&self.view));
                thread::spawn(move || work(&server, &view))
            })
            .collect();
        work(&self.server, &self.view);
        for w in workers {
            let _ = w.join();
        }
    }

    /// Answers requests on background threads (tests, embedding).
    pub fn spawn(self) -> thread::JoinHandle<()> {
        thread::spawn(move || self.serve())
    }
}

fn work(server: &tiny_http::Server, view: &View) {
    while let Ok(request) = server.recv() {
        // A client gone before its answer is no error of the server.
        let _ = respond(view, request);
    }
}

fn respond(view: &View, request: Request) -> std::io::Result<()> {
    let header_bytes: usize = request
        .headers()
        .iter()
        .map(|h| h.field.as_str().as_str().len() + h.value.as_str().len() + 4)
        .sum();
    let refused = if *request.method() != Method::Get {
        Some(Refusal::Method)
    } else if header_bytes > MAX_HEADER_BYTES {
        Some(Refusal::HeadersTooLarge)
    } else if request.body_length().is_some_and(|n| n > 0) {
        Some(Refusal::Body)
    } else {
        None
    };
    let (status, kind, body) = match refused {
        Some(r) => (r.status(), TEXT, format!("{r}\n").into_bytes()),
        None => view.answer(request.url()),
    };
    let mut response = Response::new(
        status.into(),
        Vec::new(),
        Cursor::new(body.clone()),
        Some(body.len()),
        None,
    );
    for (k, v) in [
        ("Content-Type", kind),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
    ] {
        if let Ok(h) = Header::from_bytes(k.as_bytes(), v.as_bytes()) {
            response.add_header(h);
        }
    }
    if refused == Some(Refusal::Method)
        && let Ok(h) = Header::from_bytes(&b"Allow"[..], &b"GET"[..])
    {
        response.add_header(h);
    }
    request.respond(response)
}
