//! `formcam report`: a result's read-only views as one self-contained HTML
//! file — the page `formcam view` serves, its script and style inlined, and
//! the answers of [`View::answer`] for every URL the page asks for, inlined
//! as data the page's transport (`viewer/src/api.ts`) looks up instead of
//! fetching. What the page asks with a free parameter (`/api/sample?t=T`)
//! it computes from inlined tables ([`SampleTables`]): the axes, block, line
//! and band laid exactly as the server does, the poses and key points
//! interpolated between knots placed so that the interpolation stays within
//! [`KNOT_TOLERANCE_MM`] of forward kinematics.

use std::path::{Path, PathBuf};

use formcam_machine::{JointKind, Machine};
use formcam_results::names;
use nalgebra::UnitQuaternion;
use serde::Serialize;
use serde_json::{Map, Value};
use ts_rs::TS;

use crate::ViewError;
use crate::folder::{ResultKind, read_summary};
use crate::page::Page;
use crate::server::View;
use crate::timeline::Timeline;

/// How far the poses' and key points' interpolation between knots may stray
/// from forward kinematics, mm (checked at each knot interval's middle and
/// quarters).
pub const KNOT_TOLERANCE_MM: f64 = 1e-3;

/// How far a link's orientation may stray, rad (checked likewise).
pub const KNOT_TOLERANCE_RAD: f64 = 1e-6;

/// The most values (varying pose and point coordinates, all knots) a
/// report holds, about 21 MB; a program that needs more gets as many knots
/// as fit at equal time steps, for drawing only (the axes, block, line and
/// band laid stay exact).
pub const MAX_KNOT_VALUES: usize = 2_000_000;

/// Halvings of a block at most when placing knots (4096 intervals).
const MAX_DEPTH: u32 = 12;

/// A report: the HTML and what the result read (an output must be none of them).
#[derive(Debug, Clone)]
pub struct Report {
    /// The whole page, one file.
    pub html: Vec<u8>,
    /// The files the result names as its inputs (never to be overwritten).
    pub inputs: Vec<PathBuf>,
    /// The result's kind.
    pub kind: ResultKind,
    /// Knots of the pose interpolation (0 without a program).
    pub knots: usize,
    /// The largest distance between interpolated and computed poses or key
    /// points found at the knot intervals' middles, mm.
    pub worst_mm: f64,
    /// Whether the knots were thinned to fit [`MAX_KNOT_VALUES`] (drawing only).
    pub thinned: bool,
}

/// The report of the result folder `root`, to be written to `out` (which is
/// only checked: it may not lie inside the result folder); `machine`
/// replaces the machine the result names, as `formcam view --machine` does.
///
/// # Errors
///
/// [`ViewError::ReportInResult`] for an output inside `root`, the result's
/// read errors as `formcam view` gives them, [`ViewError::PageNotBuilt`]
/// when `page` lacks the scripts its `index.html` names.
pub fn report(
    root: &Path,
    out: &Path,
    machine: Option<&Path>,
    page: &Page,
) -> Result<Report, ViewError> {
    guard_output(root, out)?;
    let view = View::open(root, machine, Page::none())?;
    let kind = view.kind();
    let mut entries: Vec<Entry> = urls(kind, view.mesh_count())
        .iter()
        .map(|url| Entry::answer(&view, url))
        .collect();
    let mut knots = 0;
    let mut worst_mm = 0.0;
    let mut thinned = false;
    if let Some(tl) = view.timeline() {
        let tables = SampleTables::of(tl, &view);
        knots = tables.knots.count;
        worst_mm = tables.knots.worst_mm;
        thinned = tables.knots.thinned;
        entries.push(Entry::json(SAMPLE_TABLES, serde_json::to_vec(&tables)));
    }
    let html = page_html(page, &title(root, &view), &entries)?;
    Ok(Report {
        html: html.into_bytes(),
        inputs: inputs(root, kind)
            .into_iter()
            .chain(machine.map(Path::to_path_buf))
            .collect(),
        kind,
        knots,
        worst_mm,
        thinned,
    })
}

/// The samples of the inlined `/api/timeline` (its head is what the page
/// needs; it computes the samples from [`SampleTables`]).
pub const TIMELINE_HEAD: usize = 2;

/// The key under which the sample tables are inlined.
const SAMPLE_TABLES: &str = "report:samples";

/// The URLs the page asks for, per kind of result.
fn urls(kind: ResultKind, meshes: usize) -> Vec<String> {
    let mut u = vec!["/api/kind".to_owned(), "/api/result".to_owned()];
    u.extend((0..meshes).map(|n| format!("/api/mesh/{n}")));
    match kind {
        ResultKind::Path => {
            for r in ["machine", "mandrel", "path", "plots"] {
                u.push(format!("/api/{r}"));
            }
        }
        ResultKind::Winding => {
            for r in [
                "machine",
                "mandrel",
                "blocks",
                "program",
                "overlays",
                "violations",
                "eye",
                "band",
                "plots",
            ] {
                u.push(format!("/api/{r}"));
            }
            // The timeline's head: the page computes the samples it asks for.
            u.push(format!("/api/timeline?samples={TIMELINE_HEAD}"));
        }
        ResultKind::Dressing => u.push("/api/dressing".to_owned()),
        ResultKind::Correction => u.push("/api/correction".to_owned()),
    }
    u
}

/// An output inside the result folder is refused: the folder is the
/// result's, replaced whole by the next run.
fn guard_output(root: &Path, out: &Path) -> Result<(), ViewError> {
    let folder = formcam_files::resolve(root).map_err(|_| ViewError::NoFolder {
        path: root.to_path_buf(),
    })?;
    let target = formcam_files::resolve(out).unwrap_or_else(|_| out.to_path_buf());
    if target.starts_with(&folder) {
        return Err(ViewError::ReportInResult {
            output: out.to_path_buf(),
            folder: root.to_path_buf(),
        });
    }
    Ok(())
}

/// The files the result's summary or report names (the job, its machine
/// file, the measurements, the program): absolute, as formcam records
/// them; a relative name (a result written before it did) as the run was
/// given it.
fn inputs(root: &Path, kind: ResultKind) -> Vec<PathBuf> {
    let name = if kind == ResultKind::Correction {
        names::REPORT
    } else {
        names::SUMMARY
    };
    let Ok(s) = read_summary(&root.join(name)) else {
        return Vec::new();
    };
    let text = |k: &str| s.get(k).and_then(Value::as_str).map(PathBuf::from);
    let mut out: Vec<PathBuf> = ["job", "measurements", "program"]
        .iter()
        .filter_map(|k| text(k))
        .collect();
    if let Some(m) = text("machine_file") {
        let base = text("job")
            .and_then(|j| j.parent().map(Path::to_path_buf))
            .unwrap_or_default();
        out.push(base.join(m));
    }
    out
}

/// The page's title: the report of which result.
fn title(root: &Path, view: &View) -> String {
    let summary: Map<String, Value> = match view.answer("/api/result") {
        (200, _, body) => serde_json::from_slice(&body).unwrap_or_default(),
        _ => Map::new(),
    };
    let job = summary
        .get("job")
        .and_then(Value::as_str)
        .and_then(|j| Path::new(j).file_name())
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| root.display().to_string());
    format!("formcam report: {job}")
}

/// One inlined answer.
struct Entry {
    url: String,
    status: u16,
    content: &'static str,
    body: Vec<u8>,
}

impl Entry {
    fn answer(view: &View, url: &str) -> Self {
        let (status, content, body) = view.answer(url);
        Self {
            url: url.to_owned(),
            status,
            content,
            body,
        }
    }

    fn json(url: &str, body: Result<Vec<u8>, serde_json::Error>) -> Self {
        Self {
            url: url.to_owned(),
            status: 200,
            content: "application/json",
            body: body.unwrap_or_default(),
        }
    }

    /// The answer as a `<script type="application/json">` element: a JSON
    /// body as it is, text as a JSON string, anything else in base64.
    fn element(&self) -> String {
        let (encoding, data) = if self.content.starts_with("application/json")
            && serde_json::from_slice::<serde::de::IgnoredAny>(&self.body).is_ok()
        {
            ("json", String::from_utf8_lossy(&self.body).into_owned())
        } else if let Ok(text) = std::str::from_utf8(&self.body) {
            ("text", serde_json::Value::from(text).to_string())
        } else {
            ("base64", format!("\"{}\"", base64(&self.body)))
        };
        format!(
            "<script type=\"application/json\" data-formcam-url=\"{}\" data-status=\"{}\" data-content-type=\"{}\" data-encoding=\"{encoding}\">{}</script>\n",
            attr(&self.url),
            self.status,
            attr(self.content),
            script_json(&data)
        )
    }
}

/// The built page with its scripts and styles inlined, the title set and
/// the answers added at the end of the body.
fn page_html(page: &Page, title: &str, entries: &[Entry]) -> Result<String, ViewError> {
    let index = page.get("index.html").ok_or(ViewError::PageNotBuilt)?;
    let index = String::from_utf8_lossy(index);
    let mut html = String::with_capacity(index.len());
    let mut rest = index.as_ref();
    while let Some(at) = rest.find('<') {
        html.push_str(&rest[..at]);
        rest = &rest[at..];
        let end = rest.find('>').map_or(rest.len(), |e| e + 1);
        let tag = &rest[..end];
        rest = &rest[end..];
        if tag.starts_with("<script") && attribute(tag, "src").is_some() {
            let src = attribute(tag, "src").unwrap_or_default();
            let js = asset(page, &src)?;
            // The element's end tag follows.
            if let Some(close) = rest.find("</script>") {
                rest = &rest[close + "</script>".len()..];
            }
            html.push_str("<script type=\"module\">");
            html.push_str(&script_text(&js));
            html.push_str("</script>");
        } else if tag.starts_with("<link") && attribute(tag, "rel").as_deref() == Some("stylesheet")
        {
            let href = attribute(tag, "href").unwrap_or_default();
            let css = asset(page, &href)?;
            html.push_str("<style>");
            html.push_str(&css.replace("</style", "<\\/style"));
            html.push_str("</style>");
        } else if tag.starts_with("<link")
            && attribute(tag, "rel").as_deref() == Some("modulepreload")
        {
            // One script, inlined: nothing to preload.
        } else if tag.starts_with("<title") {
            if let Some(close) = rest.find("</title>") {
                rest = &rest[close + "</title>".len()..];
            }
            html.push_str("<title>");
            html.push_str(&text_html(title));
            html.push_str("</title>");
        } else if tag == "</body>" {
            for e in entries {
                html.push_str(&e.element());
            }
            html.push_str(tag);
        } else {
            html.push_str(tag);
        }
    }
    html.push_str(rest);
    Ok(html)
}

/// A page file named by `src` (`/assets/x.js`), as text.
fn asset(page: &Page, src: &str) -> Result<String, ViewError> {
    let name = src.trim_start_matches("./").trim_start_matches('/');
    page.get(name)
        .map(|b| String::from_utf8_lossy(b).into_owned())
        .ok_or(ViewError::PageNotBuilt)
}

/// The value of `name="..."` in a start tag.
fn attribute(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let at = tag.find(&key)? + key.len();
    let len = tag[at..].find('"')?;
    Some(tag[at..at + len].to_owned())
}

/// Script text that cannot end its element early: `</script` and `<!--`
/// written with an escaped character (the same text in a JavaScript string,
/// regular expression or comment).
fn script_text(js: &str) -> String {
    js.replace("</script", "<\\/script")
        .replace("</SCRIPT", "<\\/SCRIPT")
        .replace("<!--", "<\\!--")
}

/// JSON inside a script element: every `<` (only ever inside a JSON string)
/// as `\u003c`.
fn script_json(json: &str) -> String {
    json.replace('<', "\\u003c")
}

fn attr(s: &str) -> String {
    text_html(s).replace('"', "&quot;")
}

fn text_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Standard base64 with padding.
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ABC[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Little-endian `f64`s in base64.
fn floats(v: &[f64]) -> String {
    let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    base64(&bytes)
}

/// What the page needs to answer `/api/sample?t=T` itself.
#[derive(Debug, Clone, Serialize, TS)]
pub struct SampleTables {
    /// The program's axes at every block boundary (the simulator's points).
    pub axes: AxisTable,
    /// Every link's pose and key point at the knots.
    pub knots: Knots,
    /// How many band points are laid at a spindle angle (absent without a band).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[ts(optional)]
    pub band: Option<LaidTable>,
}

/// The axes at block boundaries: block `i` runs from `starts[i]` to
/// `starts[i + 1]`, the axes linear from row `i` to row `i + 1`.
#[derive(Debug, Clone, Serialize, TS)]
pub struct AxisTable {
    /// Axes per row.
    pub width: usize,
    /// Boundaries (blocks + 1).
    pub rows: usize,
    /// Block starts and the end, s (base64, little-endian f64).
    pub starts: String,
    /// Rows of axis values, NC units (base64, little-endian f64).
    pub values: String,
}

/// The poses at knots: linear (translations, key points) and spherical
/// (orientations) interpolation between them.
#[derive(Debug, Clone, Serialize, TS)]
pub struct Knots {
    /// Knots.
    pub count: usize,
    /// The first knot's row whole (poses then key points): the values of
    /// every column that never changes.
    pub first: Vec<f64>,
    /// The columns that change (indices into a row), stored per knot in `values`.
    pub columns: Vec<usize>,
    /// Links (7 values each: `x, y, z, qx, qy, qz, qw`).
    pub links: usize,
    /// Key points (3 values each).
    pub points: usize,
    /// Knot times, s, never decreasing (base64, little-endian f64).
    pub t: String,
    /// Per knot the changing columns of its row (base64, little-endian f64).
    pub values: String,
    /// Whether the knots were thinned to fit [`MAX_KNOT_VALUES`].
    pub thinned: bool,
    /// The largest position error found at the intervals' middles, mm.
    pub worst_mm: f64,
    /// The largest orientation error found there, rad.
    pub worst_rad: f64,
}

/// The band's laying table (the server's `Band::laid`).
#[derive(Debug, Clone, Serialize, TS)]
pub struct LaidTable {
    /// The spindle axis (an index into the axes).
    pub spindle: usize,
    /// Per point: the spindle angle it is laid at, times its layer's direction.
    pub keys: Vec<f64>,
    /// Per layer: first point, end, direction.
    pub spans: Vec<(usize, usize, f64)>,
    /// The rounding allowed on the written angles, degrees.
    pub slack_deg: f64,
}

impl SampleTables {
    /// The tables of `tl` (and the band of `view`).
    pub fn of(tl: &Timeline, view: &View) -> Self {
        let sim = tl.sim();
        let n = sim.len();
        let width = sim.axes().len();
        let mut starts = Vec::with_capacity(n + 1);
        let mut values = Vec::with_capacity((n + 1) * width);
        for b in sim.blocks() {
            starts.push(b.start_s);
            values.extend_from_slice(b.from);
            if b.index + 1 == n {
                starts.push(tl.duration_s());
                values.extend_from_slice(b.to);
            }
        }
        let axes = AxisTable {
            width,
            rows: starts.len(),
            starts: floats(&starts),
            values: floats(&values),
        };
        Self {
            axes,
            knots: Knots::of(tl),
            band: view.band_laid(),
        }
    }
}

/// Poses then key points, flat, at the axis values `axes` (NC units).
fn pose_row(machine: &Machine, axes: &[f64]) -> Vec<f64> {
    let q: Vec<f64> = machine
        .axes
        .iter()
        .zip(axes)
        .map(|(a, v)| {
            if a.kind == JointKind::Revolute {
                v.to_radians()
            } else {
                *v
            }
        })
        .collect();
    let links = machine.poses(&q);
    let mut row = Vec::with_capacity(links.len() * 7 + machine.points.len() * 3);
    for p in &links {
        let v = p.translation.vector;
        let r = p.rotation.quaternion();
        row.extend_from_slice(&[v.x, v.y, v.z, r.i, r.j, r.k, r.w]);
    }
    for p in &machine.points {
        let w = links[p.link] * p.position;
        row.extend_from_slice(&[w.x, w.y, w.z]);
    }
    row
}

/// The row between `a` and `b` at `f` in [0, 1]: positions linear,
/// orientations by spherical interpolation (as the page computes it).
pub fn interpolate(a: &[f64], b: &[f64], f: f64, links: usize) -> Vec<f64> {
    let mut out: Vec<f64> = a.iter().zip(b).map(|(x, y)| x + f * (y - x)).collect();
    for l in 0..links {
        let k = 7 * l;
        let qa = quat(&a[k + 3..k + 7]);
        let qb = quat(&b[k + 3..k + 7]);
        let q = slerp(qa, qb, f);
        out[k + 3..k + 7].copy_from_slice(&q);
    }
    out
}

fn quat(v: &[f64]) -> [f64; 4] {
    [v[0], v[1], v[2], v[3]]
}

/// Spherical interpolation of unit quaternions `[x, y, z, w]` along the
/// shorter arc (the same formula as the page's).
fn slerp(a: [f64; 4], b: [f64; 4], f: f64) -> [f64; 4] {
    let mut dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    let mut b = b;
    if dot < 0.0 {
        dot = -dot;
        b = b.map(|x| -x);
    }
    let (wa, wb) = if dot > 0.999_999_999 {
        (1.0 - f, f)
    } else {
        let th = dot.min(1.0).acos();
        let s = th.sin();
        (((1.0 - f) * th).sin() / s, (f * th).sin() / s)
    };
    let q = [
        wa * a[0] + wb * b[0],
        wa * a[1] + wb * b[1],
        wa * a[2] + wb * b[2],
        wa * a[3] + wb * b[3],
    ];
    let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / norm)
}

/// The largest position (mm) and orientation (rad) difference of two rows.
fn row_error(a: &[f64], b: &[f64], links: usize) -> (f64, f64) {
    let mut mm: f64 = 0.0;
    let mut rad: f64 = 0.0;
    for l in 0..links {
        let k = 7 * l;
        mm = mm.max(dist(&a[k..k + 3], &b[k..k + 3]));
        let qa = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            a[k + 6],
            a[k + 3],
            a[k + 4],
            a[k + 5],
        ));
        let qb = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            b[k + 6],
            b[k + 3],
            b[k + 4],
            b[k + 5],
        ));
        rad = rad.max(qa.angle_to(&qb));
    }
    for k in (7 * links..a.len()).step_by(3) {
        mm = mm.max(dist(&a[k..k + 3], &b[k..k + 3]));
    }
    (mm, rad)
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Knots being placed.
struct Placer<'a> {
    machine: &'a Machine,
    links: usize,
    t: Vec<f64>,
    values: Vec<f64>,
    worst_mm: f64,
    worst_rad: f64,
}

impl Placer<'_> {
    fn push(&mut self, t: f64, row: &[f64]) {
        self.t.push(t);
        self.values.extend_from_slice(row);
    }

    /// Knots inside the interval from `(fa, ra)` to `(fb, rb)` of a block
    /// (fractions of it), then the knot at its end.
    #[allow(clippy::too_many_arguments)]
    fn fill(
        &mut self,
        block: (f64, f64, &[f64], &[f64]),
        fa: f64,
        ra: &[f64],
        fb: f64,
        rb: &[f64],
        depth: u32,
    ) {
        let (s, e, from, to) = block;
        let row_at = |f: f64| {
            let at: Vec<f64> = from.iter().zip(to).map(|(p, q)| p + f * (q - p)).collect();
            pose_row(self.machine, &at)
        };
        let fm = 0.5 * (fa + fb);
        let rm = row_at(fm);
        // The middle and the quarters: an error that changes sign in the
        // interval is zero at its middle.
        let (mut mm, mut rad) = row_error(&interpolate(ra, rb, 0.5, self.links), &rm, self.links);
        for q in [0.25, 0.75] {
            let (m, r) = row_error(
                &interpolate(ra, rb, q, self.links),
                &row_at(fa + q * (fb - fa)),
                self.links,
            );
            mm = mm.max(m);
            rad = rad.max(r);
        }
        if depth >= MAX_DEPTH || (mm <= KNOT_TOLERANCE_MM && rad <= KNOT_TOLERANCE_RAD) {
            self.worst_mm = self.worst_mm.max(mm);
            self.worst_rad = self.worst_rad.max(rad);
            self.push(s + fb * (e - s), rb);
            return;
        }
        self.fill(block, fa, ra, fm, &rm, depth + 1);
        self.fill(block, fm, &rm, fb, rb, depth + 1);
    }
}

impl Knots {
    /// Knots at every block boundary and, within a block, wherever the
    /// interpolation would stray from forward kinematics by more than the
    /// tolerances; beyond [`MAX_KNOT_VALUES`], as many as fit at equal time steps.
    pub fn of(tl: &Timeline) -> Self {
        let machine = tl.machine();
        let p = placed(tl);
        let knots = p.finish(machine.links.len(), machine.points.len(), false);
        if knots.count * knots.columns.len() > MAX_KNOT_VALUES {
            let n = MAX_KNOT_VALUES / knots.columns.len().max(1);
            return Self::thinned(tl, n.max(2));
        }
        knots
    }
}

/// The knots of [`Knots::of`] before thinning: every block boundary and
/// the halvings the tolerances ask for.
fn placed(tl: &Timeline) -> Placer<'_> {
    {
        let machine = tl.machine();
        let sim = tl.sim();
        let links = machine.links.len();
        let mut p = Placer {
            machine,
            links,
            t: Vec::new(),
            values: Vec::new(),
            worst_mm: 0.0,
            worst_rad: 0.0,
        };
        let blocks: Vec<_> = sim.blocks().collect();
        let mut row = blocks
            .first()
            .map(|b| pose_row(machine, b.from))
            .unwrap_or_default();
        p.push(0.0, &row);
        for (k, b) in blocks.iter().enumerate() {
            let end = blocks.get(k + 1).map_or(tl.duration_s(), |n| n.start_s);
            let next = pose_row(machine, b.to);
            if b.from == b.to || end <= b.start_s {
                p.push(end, &next);
            } else {
                p.fill((b.start_s, end, b.from, b.to), 0.0, &row, 1.0, &next, 0);
            }
            row = next;
        }
        p
    }
}

impl Knots {
    /// `n` knots at equal time steps (drawing only).
    fn thinned(tl: &Timeline, n: usize) -> Self {
        let machine = tl.machine();
        let links = machine.links.len();
        let mut p = Placer {
            machine,
            links,
            t: Vec::new(),
            values: Vec::new(),
            worst_mm: 0.0,
            worst_rad: 0.0,
        };
        let d = tl.duration_s();
        let at = |i: usize| d * i as f64 / (n - 1) as f64;
        let row = |t: f64| pose_row(machine, &tl.sim().sample(t));
        let mut before = row(0.0);
        p.push(0.0, &before);
        for i in 1..n {
            let (ta, tb) = (at(i - 1), at(i));
            let next = row(tb);
            let (mm, rad) = row_error(
                &interpolate(&before, &next, 0.5, links),
                &row(0.5 * (ta + tb)),
                links,
            );
            p.worst_mm = p.worst_mm.max(mm);
            p.worst_rad = p.worst_rad.max(rad);
            p.push(tb, &next);
            before = next;
        }
        p.finish(links, machine.points.len(), true)
    }
}

impl Placer<'_> {
    /// The knots, each row cut to the columns that change.
    fn finish(self, links: usize, points: usize, thinned: bool) -> Knots {
        let stride = 7 * links + 3 * points;
        let first = self.values[..stride.min(self.values.len())].to_vec();
        let columns: Vec<usize> = (0..first.len())
            .filter(|&c| {
                self.values
                    .chunks_exact(stride)
                    .any(|row| row[c].to_bits() != first[c].to_bits())
            })
            .collect();
        let values: Vec<f64> = self
            .values
            .chunks_exact(stride)
            .flat_map(|row| columns.iter().map(|&c| row[c]))
            .collect();
        Knots {
            count: self.t.len(),
            first,
            columns,
            links,
            points,
            t: floats(&self.t),
            values: floats(&values),
            thinned,
            worst_mm: self.worst_mm,
            worst_rad: self.worst_rad,
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn base64_matches_the_standard_alphabet_and_padding() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(base64(&[0xff, 0xfe, 0x00]), "//4A");
    }

    #[test]
    fn slerp_is_exact_for_a_rotation_about_one_axis() {
        let axis = nalgebra::Vector3::z_axis();
        let a = UnitQuaternion::from_axis_angle(&axis, 0.3);
        let b = UnitQuaternion::from_axis_angle(&axis, 2.9);
        let c = UnitQuaternion::from_axis_angle(&axis, 0.3 + 0.25 * 2.6);
        let v = |q: UnitQuaternion<f64>| [q.i, q.j, q.k, q.w];
        let s = slerp(v(a), v(b), 0.25);
        for (x, y) in s.iter().zip(v(c)) {
            assert!((x - y).abs() < 1e-12, "{s:?} {c:?}");
        }
    }

    /// A program of the placement arm (every joint turning at once) on
    /// its timeline.
    fn arm_timeline() -> Timeline {
        use formcam_nc::{Block, Feed, Program, write};
        let m = formcam_machine::shipped::shipped("placement-arm")
            .unwrap()
            .machine()
            .unwrap();
        let axes = formcam_sim::program_axes(&m);
        let w = axes.len();
        let mut p = Program::new("ARM", axes);
        p.blocks.push(Block::rapid(vec![0.0; w]));
        for i in 1..12 {
            let v = f64::from(i);
            let target: Vec<f64> = (0..w).map(|k| 3.0 * v * (1.0 + k as f64 * 0.3)).collect();
            p.blocks.push(Block::linear(target, Feed::InverseTime(0.5)));
        }
        let mut text = String::new();
        write(&p, formcam_nc::Dialect::Cldata, &mut text).unwrap();
        Timeline::from_program(m, &text, formcam_nc::Dialect::Cldata, Path::new("arm.cls")).unwrap()
    }

    #[test]
    fn knots_keep_the_poses_within_the_tolerance_of_forward_kinematics() {
        let tl = arm_timeline();
        let machine = tl.machine();
        let links = machine.links.len();
        let stride = 7 * links + 3 * machine.points.len();
        let p = placed(&tl);
        // Within the tolerance where the placement looked (no block halved
        // to the limit).
        assert!(p.worst_mm <= KNOT_TOLERANCE_MM, "{}", p.worst_mm);
        // More knots than block boundaries: the arm's joints turn together.
        assert!(p.t.len() > tl.sim().len() + 1, "{}", p.t.len());
        let rows: Vec<&[f64]> = p.values.chunks_exact(stride).collect();
        let mut worst: f64 = 0.0;
        for k in 0..p.t.len() - 1 {
            let (ta, tb) = (p.t[k], p.t[k + 1]);
            if tb <= ta {
                continue;
            }
            // Between the points the placement checked.
            for f in [0.125, 0.375, 0.625, 0.875] {
                let t = ta + f * (tb - ta);
                let exact = pose_row(machine, &tl.sim().sample(t));
                let (mm, rad) =
                    row_error(&interpolate(rows[k], rows[k + 1], f, links), &exact, links);
                worst = worst.max(mm);
                assert!(mm <= 2.0 * KNOT_TOLERANCE_MM, "{mm} mm at {t} s");
                assert!(rad <= 2.0 * KNOT_TOLERANCE_RAD, "{rad} rad at {t} s");
            }
        }
        assert!(worst > 0.0, "nothing compared");
        // At a knot the row is forward kinematics itself.
        for (k, &t) in p.t.iter().enumerate().step_by(7) {
            let exact = pose_row(machine, &tl.sim().sample(t));
            let (mm, _) = row_error(rows[k], &exact, links);
            assert!(mm < 1e-9, "{mm} mm at knot {k}");
        }
        // Cut to the changing columns and back: the same rows.
        let knots = p.finish(links, machine.points.len(), false);
        assert!(knots.columns.len() < stride && !knots.columns.is_empty());
        assert!(knots.worst_mm <= KNOT_TOLERANCE_MM);
    }

    #[test]
    fn script_text_cannot_close_its_element() {
        let js = "let a = '</script>'; /* <!-- */";
        let t = script_text(js);
        assert!(!t.contains("</script"));
        assert!(!t.contains("<!--"));
        assert_eq!(
            script_json("{\"a\":\"</script>\"}"),
            "{\"a\":\"\\u003c/script>\"}"
        );
    }

    #[test]
    fn the_page_is_inlined_with_its_answers() {
        let index = "<html><head><title>formcam view</title>\
            <script type=\"module\" crossorigin src=\"/assets/a.js\"></script>\
            <link rel=\"stylesheet\" crossorigin href=\"/assets/a.css\"></head>\
            <body><div id=\"app\"></div></body></html>";
        let page = Page::from_files(vec![
            ("index.html".into(), index.as_bytes().to_vec()),
            ("assets/a.js".into(), b"console.log('</script>')".to_vec()),
            ("assets/a.css".into(), b"body{color:red}".to_vec()),
        ]);
        let entries = [
            Entry::json("/api/kind", Ok(b"{\"kind\":\"winding\"}".to_vec())),
            Entry {
                url: "/api/program".into(),
                status: 200,
                content: "text/plain; charset=utf-8",
                body: b"N1 G1 X1 ; <x>\n".to_vec(),
            },
            Entry {
                url: "/api/band".into(),
                status: 404,
                content: "text/plain; charset=utf-8",
                body: b"not found\n".to_vec(),
            },
        ];
        let html = page_html(&page, "formcam report: a & b", &entries).unwrap();
        assert!(!html.contains("src="), "{html}");
        assert!(!html.contains("href="), "{html}");
        assert!(
            html.contains("<title>formcam report: a &amp; b</title>"),
            "{html}"
        );
        assert!(html.contains("<style>body{color:red}</style>"), "{html}");
        assert!(html.contains("console.log('<\\/script>')"), "{html}");
        assert!(html.contains("data-formcam-url=\"/api/kind\""), "{html}");
        assert!(html.contains("data-encoding=\"json\">{\"kind\":\"winding\"}</script>"));
        assert!(html.contains("data-encoding=\"text\">\"N1 G1 X1 ; \\u003cx>\\n\"</script>"));
        assert!(html.contains("data-status=\"404\""), "{html}");
        assert!(html.ends_with("</body></html>"), "{html}");
        // A page without its script is no page.
        let broken = Page::from_files(vec![("index.html".into(), index.as_bytes().to_vec())]);
        assert!(matches!(
            page_html(&broken, "t", &entries),
            Err(ViewError::PageNotBuilt)
        ));
    }
}
