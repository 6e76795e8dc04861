//! The HTTP server: on 127.0.0.1 only, GET only, the page, the result
//! folder's files and the JSON the page draws.

use std::io::{BufWriter, Write};
use std::net::{Ipv4Addr, SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread;
use std::time::Duration;

use serde::Serialize;

use crate::ViewError;
use crate::folder::RunFolder;
use crate::http::{self, Answer, Incoming};
use crate::page::Page;
use crate::request::{Refusal, Target, file_under};
use crate::scene::{MachineScene, MandrelScene};
use crate::timeline::{Sample, Timeline, TimelineHead};

/// Samples of `/api/timeline` when the query names none.
pub const DEFAULT_SAMPLES: usize = 2000;

/// The most samples of `/api/timeline`.
pub const MAX_SAMPLES: usize = 100_000;

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
    page: Page,
}

impl View {
    /// Reads the result folder `root` for the page `page`.
    ///
    /// # Errors
    ///
    /// [`ViewError`] naming the file and the field.
    pub fn open(root: &Path, machine: Option<&Path>, page: Page) -> Result<Self, ViewError> {
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
        Ok(Self {
            root: real,
            summary: json(&folder.summary),
            machine: json(&scene),
            mandrel,
            program: folder.program.map(|p| p.text),
            timeline,
            page,
        })
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
                        samples: tl.samples(n),
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
                Ok((JSON, json(&tl.sample(t))))
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
                        lines: tl.lines(),
                    }),
                ))
            }
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
    samples: Vec<Sample>,
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
    listener: TcpListener,
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
        let bind = |source| ViewError::Bind {
            port: options.port,
            source,
        };
        let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, options.port)).map_err(bind)?;
        let addr = listener.local_addr().map_err(bind)?;
        Ok(Self {
            listener,
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

    /// Answers requests until the process ends: every connection on a
    /// thread of its own (at most [`MAX_CONNECTIONS`] at once).
    pub fn serve(self) {
        let live = Arc::new(AtomicUsize::new(0));
        for stream in self.listener.incoming() {
            let Ok(stream) = stream else {
                // Out of descriptors or the like: try again in a moment.
                thread::sleep(Duration::from_millis(20));
                continue;
            };
            if live.load(Ordering::Acquire) >= MAX_CONNECTIONS {
                continue;
            }
            live.fetch_add(1, Ordering::AcqRel);
            let (view, held) = (Arc::clone(&self.view), Arc::clone(&live));
            let spawned = thread::Builder::new()
                .name("formcam-view connection".into())
                .spawn(move || {
                    // A client gone before its answer is no error of the server.
                    let _ = connection(&view, &stream);
                    held.fetch_sub(1, Ordering::AcqRel);
                });
            if spawned.is_err() {
                live.fetch_sub(1, Ordering::AcqRel);
            }
        }
    }

    /// Answers requests on a background thread (tests, embedding).
    pub fn spawn(self) -> thread::JoinHandle<()> {
        thread::spawn(move || self.serve())
    }
}

/// The most connections answered at once; more are closed unanswered.
pub const MAX_CONNECTIONS: usize = 64;

/// Answers the requests of one connection, one after another, until the
/// client closes it, asks to, idles past [`http::IDLE`] or is refused.
fn connection(view: &View, stream: &TcpStream) -> std::io::Result<()> {
    stream.set_read_timeout(Some(http::IDLE))?;
    stream.set_write_timeout(Some(http::IDLE))?;
    let _ = stream.set_nodelay(true);
    let mut requests = http::reader(stream)?;
    let mut out = BufWriter::new(stream);
    loop {
        let head = match http::read_head(&mut requests)? {
            Incoming::End => return Ok(()),
            Incoming::Refused(r) => {
                refuse(&mut out, r)?;
                http::close(stream, true);
                return Ok(());
            }
            Incoming::Head(head) => head,
        };
        let refused = if head.method != "GET" {
            Some(Refusal::Method)
        } else if head.body {
            Some(Refusal::Body)
        } else {
            None
        };
        if let Some(r) = refused {
            refuse(&mut out, r)?;
            http::close(stream, true);
            return Ok(());
        }
        let (status, kind, body) = view.answer(&head.target);
        http::write_answer(
            &mut out,
            &Answer {
                status,
                kind,
                body: &body,
                allow_get: false,
                close: head.close,
            },
        )?;
        if head.close {
            http::close(stream, false);
            return Ok(());
        }
    }
}

/// Answers a refused request (the connection closes after it).
fn refuse<W: Write>(out: &mut W, r: Refusal) -> std::io::Result<()> {
    http::write_answer(
        out,
        &Answer {
            status: r.status(),
            kind: TEXT,
            body: format!("{r}\n").as_bytes(),
            allow_get: r == Refusal::Method,
            close: true,
        },
    )
}
