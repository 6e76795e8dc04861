//! The HTTP server: on 127.0.0.1 only, GET only, the page, the result
//! folder's files and the JSON the page draws.

use std::net::{Ipv4Addr, SocketAddr, TcpListener};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread;
use std::time::Duration;

use axum::Router;
use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{HeaderValue, Method, StatusCode, header};
use axum::response::Response;
use formcam_results::names;
use formcam_results::winding::PATH;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use serde::Serialize;
use ts_rs::TS;

use crate::ViewError;
use crate::correction::CorrectionBody;
use crate::dressing::DressingView;
use crate::folder::{ResultKind, RunFolder, read_path_table, read_summary, read_text};
use crate::mesh::DrawnMesh;
use crate::overlay::{Overlay, Shown};
use crate::page::Page;
use crate::pathview::PathView;
use crate::plots::WindingPlots;
use crate::request::{MAX_HEADER_BYTES, MAX_URL_BYTES, Refusal, Target, file_under, loopback_host};
use crate::scene::{MachineScene, MandrelScene};
use crate::timeline::{Timeline, TimelineHead};

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
    page: Page,
    content: Content,
}

/// What a result holds for the page, by its kind.
#[derive(Debug)]
enum Content {
    /// A winding result with its program: the machine playing it.
    Winding(Box<Played>),
    /// A winding result without a program: the path, band and eye
    /// (`/api/path`) in the same scene.
    Path(Scene, Vec<u8>),
    /// A dressing result (`/api/dressing`).
    Dressing(Box<DressingView>, Vec<u8>),
    /// A correction result (`/api/correction`).
    Correction(Vec<u8>),
}

/// What the 3-D views of a winding result share.
#[derive(Debug)]
struct Scene {
    /// `/api/machine`.
    machine: Vec<u8>,
    /// The machine's meshes drawn (`/api/mesh/N`), binary.
    meshes: Vec<Vec<u8>>,
    /// `/api/mandrel`, when the result has a path table.
    mandrel: Option<Vec<u8>>,
    /// The winding plots (`/api/plots`).
    plots: Vec<u8>,
}

/// A winding program played on its machine.
#[derive(Debug)]
struct Played {
    scene: Scene,
    program: Option<String>,
    timeline: Option<Timeline>,
    overlay: Option<Overlay>,
}

impl View {
    /// Reads the result folder `root` for the page `page`.
    ///
    /// # Errors
    ///
    /// [`ViewError`] naming the file and the field.
    pub fn open(root: &Path, machine: Option<&Path>, page: Page) -> Result<Self, ViewError> {
        let kind = ResultKind::of(root)?;
        let real = root.canonicalize().map_err(|_| ViewError::NoFolder {
            path: root.to_path_buf(),
        })?;
        let (summary, content) = match kind {
            ResultKind::Winding => Self::played(root, &real, machine)?,
            ResultKind::Path => Self::path(root, machine)?,
            ResultKind::Dressing => {
                let s = read_summary(&root.join(names::SUMMARY))?;
                let d = DressingView::read(root, &s)?;
                let body = json(d.body());
                (json(&s), Content::Dressing(Box::new(d), body))
            }
            ResultKind::Correction => {
                let r = read_summary(&root.join(names::REPORT))?;
                let c = CorrectionBody::read(root, r.clone())?;
                (json(&r), Content::Correction(json(&c)))
            }
        };
        Ok(Self {
            root: real,
            summary,
            page,
            content,
        })
    }

    /// A winding result with its program: the machine, the mandrel, the
    /// program's timeline, its overlays and the plots.
    fn played(
        root: &Path,
        real: &Path,
        machine: Option<&Path>,
    ) -> Result<(Vec<u8>, Content), ViewError> {
        let folder = RunFolder::open(root, machine)?;
        let (scene, meshes) = MachineScene::read(&folder.machine, folder.machine_dir());
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
            // The folder's `check.json` holds for the machine it names only.
            Some(tl) => Some(Overlay::open(real, &folder, tl, machine.is_none())?),
            None => None,
        };
        let plots = json(&WindingPlots::read(
            root,
            timeline.as_ref().map(Timeline::sim),
        )?);
        let played = Played {
            scene: Scene {
                machine: json(&scene),
                meshes: meshes.iter().map(DrawnMesh::to_bytes).collect(),
                mandrel,
                plots,
            },
            program: folder.program.map(|p| p.text),
            timeline,
            overlay,
        };
        Ok((json(&folder.summary), Content::Winding(Box::new(played))))
    }

    /// A winding result without a program: the mandrel with its path (the
    /// folder's path table), the band and eye of `/api/path`, the machine
    /// the result names (if any) and the winding plots, no timeline.
    fn path(root: &Path, machine: Option<&Path>) -> Result<(Vec<u8>, Content), ViewError> {
        let summary = read_summary(&root.join(names::SUMMARY))?;
        // Without a path table: the error of reading `path.csv`.
        let table = match read_path_table(root)? {
            Some(t) => t,
            None => {
                let p = root.join(PATH.file);
                let text = read_text(&p)?;
                (p, text)
            }
        };
        let view = PathView::read(root, &summary, machine, (&table.0, &table.1))?;
        let mandrel = MandrelScene::from_path_table(view.scene.mandrel, &table.1, &table.0)?;
        let scene = Scene {
            machine: json(&view.scene),
            meshes: view.meshes.iter().map(DrawnMesh::to_bytes).collect(),
            mandrel: Some(json(&mandrel)),
            plots: json(&WindingPlots::read(root, None)?),
        };
        Ok((json(&summary), Content::Path(scene, json(&view.body))))
    }

    /// What the folder holds.
    pub fn kind(&self) -> ResultKind {
        match &self.content {
            Content::Winding(_) => ResultKind::Winding,
            Content::Path(..) => ResultKind::Path,
            Content::Dressing(..) => ResultKind::Dressing,
            Content::Correction(_) => ResultKind::Correction,
        }
    }

    /// The program played, for a winding result with one.
    fn played_program(&self) -> Option<&Played> {
        match &self.content {
            Content::Winding(p) => Some(p),
            _ => None,
        }
    }

    /// The 3-D scene of a winding result, with or without its program.
    fn scene(&self) -> Option<&Scene> {
        match &self.content {
            Content::Winding(p) => Some(&p.scene),
            Content::Path(scene, _) => Some(scene),
            _ => None,
        }
    }

    /// The timeline of the result's program, if it has one.
    pub fn timeline(&self) -> Option<&Timeline> {
        self.played_program()?.timeline.as_ref()
    }

    /// The overlays of the result's program, if it has one.
    fn overlay(&self) -> Option<&Overlay> {
        self.played_program()?.overlay.as_ref()
    }

    /// How many meshes `/api/mesh/N` serves (N from 0).
    pub(crate) fn mesh_count(&self) -> usize {
        self.scene().map_or(0, |s| s.meshes.len())
    }

    /// The band's laying table (see [`crate::Band::laid`]), with a band.
    pub(crate) fn band_laid(&self) -> Option<crate::report::LaidTable> {
        self.overlay()?.band.as_ref().map(crate::Band::laid_table)
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
            ["api", "kind"] => Ok((JSON, json(&KindBody { kind: self.kind() }))),
            ["api", "path"] => match &self.content {
                Content::Path(_, body) => Ok((JSON, body.clone())),
                _ => Err(Refusal::NotFound),
            },
            // Which of `violations`, `eye` and `band` the result has: the
            // page asks only for those.
            ["api", "overlays"] => Ok((
                JSON,
                json(&OverlaysBody {
                    band: self.overlay().is_some_and(|o| o.band.is_some()),
                    eye: self.overlay().is_some(),
                    violations: self.overlay().is_some(),
                }),
            )),
            ["api", "plots"] => self
                .scene()
                .map(|s| (JSON, s.plots.clone()))
                .ok_or(Refusal::NotFound),
            ["api", "dressing"] => match &self.content {
                Content::Dressing(_, body) => Ok((JSON, body.clone())),
                _ => Err(Refusal::NotFound),
            },
            ["api", "dressing", "sample"] => match &self.content {
                Content::Dressing(d, _) => Ok((JSON, json(&d.sample(time_param(&target)?)))),
                _ => Err(Refusal::NotFound),
            },
            ["api", "correction"] => match &self.content {
                Content::Correction(body) => Ok((JSON, body.clone())),
                _ => Err(Refusal::NotFound),
            },
            ["api", "machine"] => self
                .scene()
                .map(|s| (JSON, s.machine.clone()))
                .ok_or(Refusal::NotFound),
            // The meshes the machine names, by their index in `/api/machine`.
            ["api", "mesh", n] => n
                .parse::<usize>()
                .ok()
                .and_then(|n| self.scene()?.meshes.get(n))
                .map(|b| (BINARY, b.clone()))
                .ok_or(Refusal::NotFound),
            ["api", "mandrel"] => self
                .scene()
                .and_then(|s| s.mandrel.clone())
                .map(|b| (JSON, b))
                .ok_or(Refusal::NotFound),
            ["api", "program"] => self
                .played_program()
                .and_then(|p| p.program.clone())
                .map(|t| (TEXT, t.into_bytes()))
                .ok_or(Refusal::NotFound),
            ["api", "timeline"] => self.timeline_answer(&target),
            ["api", "sample"] => {
                let tl = self.timeline().ok_or(Refusal::NotFound)?;
                Ok((JSON, json(&self.shown(tl.sample(time_param(&target)?)))))
            }
            ["api", "blocks"] => self.blocks_answer(),
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

    /// `/api/timeline?samples=N`: the timeline's head and `N` samples
    /// (clamped to 2..=`MAX_SAMPLES`, `DEFAULT_SAMPLES` when not given).
    fn timeline_answer(&self, target: &Target) -> Result<(&'static str, Vec<u8>), Refusal> {
        let tl = self.timeline().ok_or(Refusal::NotFound)?;
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

    /// `/api/blocks`: each block's start and end time and its line.
    fn blocks_answer(&self) -> Result<(&'static str, Vec<u8>), Refusal> {
        let tl = self.timeline().ok_or(Refusal::NotFound)?;
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

    /// A sample with what the overlays add to it.
    fn shown(&self, s: crate::timeline::Sample) -> Shown {
        match self.overlay() {
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
        self.overlay()
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
#[derive(Serialize, TS)]
pub(crate) struct TimelineBody {
    /// What the samples' arrays mean.
    #[serde(flatten)]
    head: TimelineHead,
    /// The samples at equal steps from the start to the end.
    samples: Vec<Shown>,
}

/// `/api/blocks`: per block its start, end (s) and program line.
#[derive(Serialize, TS)]
pub(crate) struct BlocksBody<'a> {
    /// Per block: its start, s.
    starts: Vec<f64>,
    /// Per block: its end, s.
    ends: Vec<f64>,
    /// Per block: its line in the program text (1-based).
    lines: &'a [usize],
}

/// `/api/kind`: what the result folder holds.
#[derive(Serialize, TS)]
pub(crate) struct KindBody {
    /// The result's kind.
    kind: ResultKind,
}

/// `/api/overlays`: which of `/api/violations`, `/api/eye` and `/api/band`
/// the result has (the page asks only for those); the fields in the order
/// of their names, as a JSON map writes them.
#[derive(Serialize, TS)]
pub(crate) struct OverlaysBody {
    /// Whether `/api/band` answers (a result with its circuit tables).
    band: bool,
    /// Whether `/api/eye` answers (a result with a program).
    eye: bool,
    /// Whether `/api/violations` answers (a result with a program).
    violations: bool,
}

const JSON: &str = "application/json";
const TEXT: &str = "text/plain; charset=utf-8";
const ICON: &str = "image/x-icon";
const BINARY: &str = "application/octet-stream";

fn json<T: Serialize>(v: &T) -> Vec<u8> {
    // Our own plain data (numbers, strings) always serialises.
    serde_json::to_vec(v).unwrap_or_default()
}

/// The query's time `t` in seconds: a finite number, or the request is
/// refused.
fn time_param(target: &Target) -> Result<f64, Refusal> {
    target
        .param("t")
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|t| t.is_finite())
        .ok_or(Refusal::Path)
}

/// The content type of a file served, by its extension (plain text for
/// any other).
pub fn content_type(path: &Path) -> &'static str {
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

/// A socket listening on 127.0.0.1, non-blocking, for [`serve_router`].
#[derive(Debug)]
pub struct Local {
    listener: TcpListener,
    addr: SocketAddr,
}

impl Local {
    /// Listens on `127.0.0.1:port` (0: any free port).
    ///
    /// # Errors
    ///
    /// The system's, when the port cannot be listened on.
    pub fn bind(port: u16) -> std::io::Result<Self> {
        let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, port))?;
        let addr = listener.local_addr()?;
        listener.set_nonblocking(true)?;
        Ok(Self { listener, addr })
    }

    /// `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Answers requests with `app` until the process ends (see
    /// [`serve_router`]).
    pub fn serve(self, app: Router) {
        serve_router(self.listener, app);
    }

    /// [`Local::serve`] on a background thread (tests, embedding).
    pub fn spawn(self, app: Router) -> thread::JoinHandle<()> {
        thread::spawn(move || self.serve(app))
    }
}

/// A view listening on 127.0.0.1.
pub struct ViewServer {
    local: Local,
    view: Arc<View>,
}

impl ViewServer {
    /// Reads the result folder and listens on `127.0.0.1:port`.
    ///
    /// # Errors
    ///
    /// The result's [`ViewError`], or [`ViewError::Bind`].
    pub fn bind(root: &Path, options: &ViewOptions, page: Page) -> Result<Self, ViewError> {
        let view = View::open(root, options.machine.as_deref(), page)?;
        let local = Local::bind(options.port).map_err(|source| ViewError::Bind {
            port: options.port,
            source,
        })?;
        Ok(Self {
            local,
            view: Arc::new(view),
        })
    }

    /// `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        self.local.url()
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.local.addr()
    }

    /// Answers requests until the process ends: every connection served
    /// on its own (at most [`MAX_CONNECTIONS`] at once), HTTP/1.1 with
    /// kept-alive connections. Returns at once only where the system
    /// cannot start the server's runtime (no threads or descriptors left).
    pub fn serve(self) {
        self.local
            .serve(Router::new().fallback(answer).with_state(self.view));
    }

    /// Answers requests on a background thread (tests, embedding).
    pub fn spawn(self) -> thread::JoinHandle<()> {
        thread::spawn(move || self.serve())
    }
}

/// The most connections answered at once; more are closed unanswered.
pub const MAX_CONNECTIONS: usize = 64;

/// How long a connection waits for a request's head (a kept connection
/// for its next request) before it is closed.
const IDLE: Duration = Duration::from_secs(60);

/// Answers requests on `listener` with `app` until the process ends, on
/// the loop [`ViewServer::serve`] runs: a current-thread runtime, every
/// connection a task of its own (at most [`MAX_CONNECTIONS`] at once),
/// HTTP/1.1 with kept-alive connections closed after a minute without a
/// request head. `listener` must be non-blocking. What a request may be
/// (its head's size, its method, its body) is the router's to refuse:
/// [`head_refusal`], [`refused`]. Returns at once only where the system
/// cannot start the runtime.
pub fn serve_router(listener: TcpListener, app: Router) {
    let Ok(runtime) = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    else {
        return;
    };
    runtime.block_on(accept(listener, app));
}

/// Accepts connections on `listener` and serves each as a task of its own.
async fn accept(listener: TcpListener, app: Router) {
    let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
        return;
    };
    let live = Arc::new(AtomicUsize::new(0));
    loop {
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            Err(_) => {
                // Out of descriptors or the like: try again in a moment.
                tokio::time::sleep(Duration::from_millis(20)).await;
                continue;
            }
        };
        if live.load(Ordering::Acquire) >= MAX_CONNECTIONS {
            continue;
        }
        let _ = stream.set_nodelay(true);
        let held = Live::hold(&live);
        let service = TowerToHyperService::new(app.clone());
        tokio::spawn(async move {
            let _held = held;
            // A client gone before its answer is no error of the server.
            let _ = http1::Builder::new()
                .title_case_headers(true)
                .timer(TokioTimer::new())
                .header_read_timeout(IDLE)
                .serve_connection(TokioIo::new(stream), service)
                .await;
        });
    }
}

/// One connection counted as live until dropped.
struct Live(Arc<AtomicUsize>);

impl Live {
    fn hold(count: &Arc<AtomicUsize>) -> Self {
        count.fetch_add(1, Ordering::AcqRel);
        Self(Arc::clone(count))
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Every request: refused by [`refusal`], or [`View::answer`]ed (on a
/// blocking thread, since an answer may compute a timeline).
async fn answer(State(view): State<Arc<View>>, request: Request) -> Response {
    if let Some(r) = refusal(&request) {
        return refused(r);
    }
    let url = request.uri().to_string();
    match tokio::task::spawn_blocking(move || view.answer(&url)).await {
        Ok((status, kind, body)) => reply(status, kind, body),
        Err(_) => reply(500, TEXT, b"the answer failed\n".to_vec()),
    }
}

/// The answer to a refused request: its status and reason, `Allow: GET`
/// for a method refused, and the connection closed (the request's rest is
/// not read).
pub fn refused(r: Refusal) -> Response {
    let mut response = reply(r.status(), TEXT, format!("{r}\n").into_bytes());
    let headers = response.headers_mut();
    if r == Refusal::Method {
        headers.insert(header::ALLOW, HeaderValue::from_static("GET"));
    }
    headers.insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}

/// Why `request` is refused before it is answered, in the order a reader
/// of its head meets the reasons: the URL, the headers, the method, a body.
fn refusal(request: &Request) -> Option<Refusal> {
    if let Some(r) = head_refusal(request) {
        Some(r)
    } else if request.method() != Method::GET {
        Some(Refusal::Method)
    } else if has_body(request) {
        Some(Refusal::Body)
    } else {
        None
    }
}

/// Why any request is refused by its head alone: a URL longer than
/// [`MAX_URL_BYTES`], headers longer than [`MAX_HEADER_BYTES`], a `Host`
/// that is not this machine's loopback ([`loopback_host`]).
pub fn head_refusal(request: &Request) -> Option<Refusal> {
    let header_bytes: usize = request
        .headers()
        .iter()
        .map(|(name, value)| name.as_str().len() + value.len() + 4)
        .sum();
    if request.uri().to_string().len() > MAX_URL_BYTES {
        Some(Refusal::UrlTooLong)
    } else if header_bytes > MAX_HEADER_BYTES {
        Some(Refusal::HeadersTooLarge)
    } else if !loopback_host(request.headers().get(header::HOST).map(|v| v.as_bytes())) {
        Some(Refusal::Host)
    } else {
        None
    }
}

/// Whether `request` says it has a body (a length other than 0, or a
/// transfer encoding).
pub fn has_body(request: &Request) -> bool {
    let headers = request.headers();
    let length = headers
        .get(header::CONTENT_LENGTH)
        .is_some_and(|v| v.as_bytes() != b"0");
    length || headers.contains_key(header::TRANSFER_ENCODING)
}

/// An answer whole, with its length (hyper writes `Content-Length` for a
/// body of known size) and the headers every answer has: its type,
/// `Cache-Control: no-store`, `X-Content-Type-Options: nosniff`.
pub fn reply(status: u16, kind: &'static str, body: Vec<u8>) -> Response {
    let mut response = Response::new(Body::from(body));
    *response.status_mut() =
        StatusCode::from_u16(status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let headers = response.headers_mut();
    headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(kind));
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    headers.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    response
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    fn request(method: &str, url: &str, headers: &[(&str, &str)]) -> Request {
        let mut r = axum::http::Request::builder().method(method).uri(url);
        for (k, v) in headers {
            r = r.header(*k, *v);
        }
        r.body(Body::empty()).unwrap()
    }

    #[test]
    fn refusals_come_in_the_order_a_head_is_read() {
        let long = format!("/{}", "a".repeat(MAX_URL_BYTES));
        let big = "b".repeat(MAX_HEADER_BYTES);
        assert_eq!(refusal(&request("GET", "/api/result", &[])), None);
        assert_eq!(
            refusal(&request("GET", "/api/result", &[("content-length", "0")])),
            None
        );
        assert_eq!(
            refusal(&request("POST", &long, &[("x-big", &big)])),
            Some(Refusal::UrlTooLong)
        );
        assert_eq!(
            refusal(&request("POST", "/", &[("x-big", &big)])),
            Some(Refusal::HeadersTooLarge)
        );
        assert_eq!(
            refusal(&request("POST", "/", &[("content-length", "5")])),
            Some(Refusal::Method)
        );
        assert_eq!(
            refusal(&request("GET", "/", &[("content-length", "5")])),
            Some(Refusal::Body)
        );
        assert_eq!(
            refusal(&request("GET", "/", &[("transfer-encoding", "chunked")])),
            Some(Refusal::Body)
        );
    }

    #[test]
    fn every_answer_says_its_type_and_is_not_stored() {
        let r = reply(404, TEXT, b"not found\n".to_vec());
        assert_eq!(r.status(), StatusCode::NOT_FOUND);
        let h = r.headers();
        assert_eq!(h[header::CONTENT_TYPE], TEXT);
        assert_eq!(h[header::CACHE_CONTROL], "no-store");
        assert_eq!(h[header::X_CONTENT_TYPE_OPTIONS], "nosniff");
    }
}
