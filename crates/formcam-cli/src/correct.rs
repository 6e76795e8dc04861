//! `formcam correct`: a mould's milling program corrected from CMM
//! measurements of the part; `formcam correct simulate`: the closed loop.

use std::fs;
use std::path::{Path, PathBuf};

use formcam_correct::simulate::{LoopResult, Scenario, Shape};
use formcam_correct::{
    CorrectError, Corrector, Grid, Interpolation, Measurements, NodeTable, Options, Placement,
    Tool, Totals, check_displacement, smooth,
};
use formcam_nc::{Dialect, NodeKind, ToolpathOptions, read_toolpath};
use plotters::prelude::*;
use serde_json::{Value, json};

use crate::CliError;
use crate::output::write_all;
use formcam_plot::{Series, panels_svg, svg_err, tick_label};

/// Options of `formcam correct`.
#[derive(Debug, clap::Args)]
pub struct CorrectArgs {
    /// A job file with a `[correct]` table holding these options (instead of
    /// --measurements and --program); -o then names the output folder.
    #[arg(conflicts_with_all = ["measurements", "program", "report"])]
    pub job: Option<PathBuf>,
    /// The CMM report: CSV (section, point, x_nom, y_nom, z_nom, x_act,
    /// y_act, z_act[, nx, ny, nz]) or DMIS (.dmi, .dms, .dmo) point features.
    #[arg(long)]
    pub measurements: Option<PathBuf>,
    /// The milling program (G-code: ISO, .mpf Sinumerik, .ngc LinuxCNC) or a
    /// node table (.csv: x, y, z).
    #[arg(long)]
    pub program: Option<PathBuf>,
    /// The corrected program (never the input itself).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Displacement = -gain x interpolated deviation; allowed (0, 2].
    #[arg(long, default_value_t = 1.0)]
    pub gain: f64,
    /// `point` (nodes on the surface) or `ball:R` (nodes at the centre of a
    /// ball-end tool of radius R mm).
    #[arg(long, default_value = "point")]
    pub tool: String,
    /// `bilinear` (Coons patches) or `bicubic` (C1 Hermite).
    #[arg(long, default_value = "bilinear")]
    pub interpolation: String,
    /// The report (JSON); an existing report there keeps its history.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Nodes up to this far beyond the measured area (mm) are corrected by
    /// extrapolation; 0 leaves every node outside unchanged.
    #[arg(long, default_value_t = 0.0)]
    pub margin: f64,
    /// The CMM's noise (standard deviation, mm): the deviations are smoothed
    /// to separate it from the warp; 0 takes them as measured.
    #[arg(long, default_value_t = 0.0)]
    pub noise: f64,
    /// Arcs (G2/G3) are written back as G1 chords within this distance, mm.
    #[arg(long, default_value_t = 0.001)]
    pub arc_tolerance: f64,
    /// Split straight feed moves longer than this (mm) into pieces, so the
    /// correction can bend them (default: moves are kept whole).
    #[arg(long)]
    pub max_segment: Option<f64>,
    /// The program's syntax: iso, sinumerik-840d, linuxcnc (default: from
    /// the extension).
    #[arg(long)]
    pub dialect: Option<String>,
    /// Resample every section to this many points (default: as measured when
    /// all sections have the same count, else the largest count).
    #[arg(long)]
    pub points_per_section: Option<usize>,
    /// The largest plausible deviation and node displacement, mm: a measured
    /// deviation or a displacement beyond it stops the run (a typing error in
    /// the report, or a part too far off to correct by re-milling).
    #[arg(long, default_value_t = DEFAULT_MAX_DEVIATION_MM)]
    pub max_deviation: f64,
}

/// The default of `--max-deviation`, mm.
const DEFAULT_MAX_DEVIATION_MM: f64 = 5.0;

fn read_text(path: &Path) -> Result<String, CliError> {
    fs::read_to_string(path).map_err(|e| CliError(format!("{}: cannot read: {e}", path.display())))
}

fn ext(path: &Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default()
}

/// Reads a CMM report, CSV or DMIS by its extension.
pub fn read_measurements(path: &Path) -> Result<Measurements, CliError> {
    let text = read_text(path)?;
    let m = match ext(path).as_str() {
        "dmi" | "dmis" | "dms" | "dmo" => Measurements::from_dmis(&text),
        _ => Measurements::from_csv(&text),
    };
    m.map_err(|e| CliError(format!("{}: {e}", path.display())))
}

/// Parses `point` or `ball:R`.
pub fn parse_tool(s: &str) -> Result<Tool, CliError> {
    if s == "point" {
        return Ok(Tool::Point);
    }
    if let Some(r) = s.strip_prefix("ball:") {
        let radius: f64 = r.trim().parse().map_err(|_| {
            CliError(format!(
                "--tool {s}: the radius `{r}` is not a number (e.g. ball:6)"
            ))
        })?;
        if !(radius.is_finite() && radius > 0.0) {
            return Err(CliError(format!(
                "--tool {s}: the ball radius must be > 0 mm"
            )));
        }
        return Ok(Tool::Ball { radius });
    }
    Err(CliError(format!(
        "--tool {s}: allowed `point` or `ball:R` (R in mm)"
    )))
}

/// Parses `bilinear` or `bicubic`.
pub fn parse_interpolation(s: &str) -> Result<Interpolation, CliError> {
    Interpolation::from_name(s)
        .ok_or_else(|| CliError(format!("--interpolation {s}: allowed bilinear, bicubic")))
}

/// A program read for correction: its nodes, which of them may move, and
/// how to write it back.
enum Source {
    Gcode(formcam_nc::Toolpath),
    Table(NodeTable),
}

impl Source {
    fn read(
        path: &Path,
        dialect: Option<&str>,
        arc_tolerance: f64,
        max_segment: Option<f64>,
    ) -> Result<Self, CliError> {
        let text = read_text(path)?;
        let at = |e: String| CliError(format!("{}: {e}", path.display()));
        if ext(path) == "csv" {
            return NodeTable::from_csv(&text)
                .map(Self::Table)
                .map_err(|e| at(e.to_string()));
        }
        if text.trim().is_empty() {
            return Err(at("the program is empty".into()));
        }
        let dialect = match dialect {
            Some(d) => Dialect::from_name(d).map_err(|e| CliError(format!("--dialect: {e}")))?,
            None => Dialect::from_extension(&ext(path)).unwrap_or(Dialect::Iso),
        };
        if let Some(m) = max_segment
            && !(m.is_finite() && m > 0.0)
        {
            return Err(CliError(format!("--max-segment {m}: must be > 0 mm")));
        }
        if !(arc_tolerance.is_finite() && arc_tolerance > 0.0) {
            return Err(CliError(format!(
                "--arc-tolerance {arc_tolerance}: must be > 0 mm"
            )));
        }
        let tp = read_toolpath(
            &text,
            &ToolpathOptions {
                dialect,
                arc_tolerance_mm: arc_tolerance,
                max_segment_mm: max_segment,
            },
        )
        .map_err(|e| at(e.to_string()))?;
        if tp.nodes.is_empty() {
            return Err(at("the program has no motion blocks".into()));
        }
        Ok(Self::Gcode(tp))
    }

    /// Node positions, and whether each may be corrected (feed moves; rapid
    /// moves are left alone).
    fn nodes(&self) -> (Vec<[f64; 3]>, Vec<bool>) {
        match self {
            Self::Gcode(tp) => (
                tp.nodes.iter().map(|n| n.position).collect(),
                tp.nodes.iter().map(|n| n.kind != NodeKind::Rapid).collect(),
            ),
            Self::Table(t) => (t.nodes.clone(), vec![true; t.nodes.len()]),
        }
    }

    /// Program line of node `k` (1-based), for the report.
    fn line_of(&self, k: usize) -> usize {
        match self {
            Self::Gcode(tp) => tp.nodes[k].line,
            Self::Table(_) => k + 1,
        }
    }

    fn write(&self, positions: &[[f64; 3]], header: &[String]) -> Result<String, CliError> {
        match self {
            Self::Gcode(tp) => tp
                .write(positions, header)
                .map_err(|e| CliError(e.to_string())),
            Self::Table(t) => Ok(t.write(positions)),
        }
    }
}

/// `1-3, 7, 9-12`.
fn ranges(lines: &[usize]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        let start = lines[k];
        let mut end = start;
        while k + 1 < lines.len() && lines[k + 1] <= end + 1 {
            k += 1;
            end = lines[k];
        }
        out.push(if end == start {
            start.to_string()
        } else {
            format!("{start}-{end}")
        });
        k += 1;
    }
    out.join(", ")
}

/// `path` made absolute through its folder (the file itself need not exist).
fn resolved(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = fs::canonicalize(path) {
        return Some(p);
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    Some(fs::canonicalize(dir).ok()?.join(path.file_name()?))
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (resolved(a), resolved(b)) {
        (Some(x), Some(y)) => x == y,
        _ => false,
    }
}

/// Runs `formcam correct` (a job file, or the options on the command line);
/// returns the one-line summary.
pub fn run(a: &CorrectArgs) -> Result<String, CliError> {
    let Some(job) = &a.job else {
        return run_args(a);
    };
    let out = a.output.clone().ok_or_else(|| {
        CliError(format!(
            "correct {}: give -o OUTDIR (the folder for the corrected program, report.json and the plots)",
            job.display()
        ))
    })?;
    let text = read_text(job)?;
    let table: toml::Table = toml::from_str(&text)
        .map_err(|e| CliError(format!("{}: {}", job.display(), e.message())))?;
    if !is_job(&table) {
        return Err(CliError(format!(
            "{}: no [correct] table (a correction job names measurements and program there; \
             see examples/correct-mould.toml)",
            job.display()
        )));
    }
    run_job_text(job, &text, &out)
}

/// Runs `formcam correct` with the options on the command line.
fn run_args(a: &CorrectArgs) -> Result<String, CliError> {
    let need = |p: &Option<PathBuf>, flag: &str| {
        p.clone()
            .ok_or_else(|| CliError(format!("correct: give {flag} (see formcam correct --help)")))
    };
    let meas_path = need(&a.measurements, "--measurements cmm.csv")?;
    let prog_path = need(&a.program, "--program mould.nc")?;
    let out_path = need(&a.output, "-o corrected.nc")?;
    // No output may land on an input or on another output.
    let mut outputs = vec![("-o", out_path.clone())];
    if let Some(r) = &a.report {
        outputs.push(("--report", r.clone()));
    }
    for (flag, o) in &outputs {
        for (what, input) in [("program", &prog_path), ("measurements", &meas_path)] {
            if same_file(o, input) {
                return Err(CliError(format!(
                    "{}: {flag} would overwrite the input {what}; give another {flag}",
                    o.display()
                )));
            }
        }
    }
    if let Some(r) = &a.report
        && same_file(r, &out_path)
    {
        return Err(CliError(format!(
            "{}: --report and -o are the same file; give another --report",
            r.display()
        )));
    }
    let options = Options {
        gain: a.gain,
        tool: parse_tool(&a.tool)?,
        interpolation: parse_interpolation(&a.interpolation)?,
        margin_mm: a.margin,
    };
    options
        .validate()
        .map_err(|e| CliError(format!("correct: {e}")))?;
    if !(a.noise.is_finite() && a.noise >= 0.0) {
        return Err(CliError(format!("--noise {}: must be >= 0 mm", a.noise)));
    }
    if !(a.max_deviation.is_finite() && a.max_deviation > 0.0) {
        return Err(CliError(format!(
            "--max-deviation {}: must be > 0 mm",
            a.max_deviation
        )));
    }
    let measurements = read_measurements(&meas_path)?;
    if let Err(CorrectError::Deviation {
        section,
        point,
        deviation_mm,
        ..
    }) = measurements.check_deviation(a.max_deviation)
    {
        return Err(CliError(format!(
            "{}: section `{section}`, point `{point}`: deviation {deviation_mm:.3} mm is beyond \
             --max-deviation {} mm (a typing error in the report? nothing written)",
            meas_path.display(),
            a.max_deviation
        )));
    }
    let mut grid = Grid::from_measurements(&measurements, a.points_per_section)
        .map_err(|e| CliError(format!("{}: {e}", meas_path.display())))?;
    let smoothing = smooth(&mut grid, a.noise);
    let source = Source::read(
        &prog_path,
        a.dialect.as_deref(),
        a.arc_tolerance,
        a.max_segment,
    )?;
    let (positions, movable) = source.nodes();
    let corrector =
        Corrector::new(&grid, options).map_err(|e| CliError(format!("correct: {e}")))?;
    let picked: Vec<[f64; 3]> = positions
        .iter()
        .zip(&movable)
        .filter(|(_, m)| **m)
        .map(|(p, _)| *p)
        .collect();
    let corrections = corrector.correct(&picked);
    if let Err(CorrectError::Displacement {
        node,
        displacement_mm,
        ..
    }) = check_displacement(&corrections, a.max_deviation)
    {
        // The program line of the `node`-th movable node.
        let k = movable
            .iter()
            .enumerate()
            .filter(|(_, m)| **m)
            .nth(node)
            .map_or(0, |(k, _)| k);
        return Err(CliError(format!(
            "{}: line {}: the node would move by {displacement_mm:.3} mm, beyond \
             --max-deviation {} mm (nothing written)",
            prog_path.display(),
            source.line_of(k),
            a.max_deviation
        )));
    }
    let mut new_positions = positions.clone();
    let mut outside_lines = Vec::new();
    let mut it = corrections.iter();
    for (k, p) in new_positions.iter_mut().enumerate() {
        if !movable[k] {
            continue;
        }
        let Some(c) = it.next() else { break };
        for (v, d) in p.iter_mut().zip(c.displacement) {
            *v += d;
        }
        if c.placement == Placement::Outside {
            outside_lines.push(source.line_of(k));
        }
    }
    outside_lines.dedup();
    let totals = Totals::of(&corrections);
    let mut header = Vec::new();
    if let Source::Gcode(tp) = &source {
        if tp.arcs_linearised > 0 {
            header.push(format!(
                "formcam correct: {} arc blocks G2/G3 linearised as G1 chords within {} mm",
                tp.arcs_linearised, a.arc_tolerance
            ));
        }
        if let Some(m) = a.max_segment
            && tp.moves_split > 0
        {
            header.push(format!(
                "formcam correct: {} G1 moves split into pieces of at most {m} mm",
                tp.moves_split
            ));
        }
    }
    let program = source.write(&new_positions, &header)?;

    let (max_deviation, rms_deviation) =
        (measurements.max_deviation(), measurements.rms_deviation());
    let name = |p: &Path| p.display().to_string();
    let entry = json!({
        "measurements": name(&meas_path),
        "program": name(&prog_path),
        "output": name(&out_path),
        "max_deviation_mm": max_deviation,
        "rms_deviation_mm": rms_deviation,
        "max_displacement_mm": totals.max_displacement_mm,
        "nodes_corrected": totals.corrected,
    });
    let report_path = a.report.clone();
    let mut history: Vec<Value> = Vec::new();
    if let Some(rp) = &report_path
        && rp.exists()
    {
        let old: Value = serde_json::from_str(&read_text(rp)?).map_err(|e| {
            CliError(format!(
                "{}: exists but is not a JSON report ({e}); give another --report",
                rp.display()
            ))
        })?;
        match old.get("history").and_then(Value::as_array) {
            Some(h) => history.extend(h.iter().cloned()),
            None => {
                return Err(CliError(format!(
                    "{}: exists but is not a formcam correct report (no `history`); give another --report",
                    rp.display()
                )));
            }
        }
    }
    let mut entry = entry;
    entry["iteration"] = json!(history.len() + 1);
    history.push(entry);
    let (arcs, split, flavor) = match &source {
        Source::Gcode(tp) => (
            tp.arcs_linearised,
            tp.moves_split,
            tp.dialect().name().to_string(),
        ),
        Source::Table(_) => (0, 0, "csv".into()),
    };
    let report = json!({
        "nodes": positions.len(),
        "nodes_feed": totals.nodes,
        "nodes_corrected": totals.corrected,
        "nodes_outside": totals.outside,
        "nodes_extrapolated": totals.extrapolated,
        "nodes_rapid_unchanged": movable.iter().filter(|m| !**m).count(),
        "nodes_unknown": totals.unknown,
        "outside_lines": ranges(&outside_lines),
        "max_deviation_mm": max_deviation,
        "rms_deviation_mm": rms_deviation,
        "max_displacement_mm": totals.max_displacement_mm,
        "rms_displacement_mm": totals.rms_displacement_mm,
        "interpolation": options.interpolation.name(),
        "gain": options.gain,
        "tool": match options.tool {
            Tool::Point => json!({"kind": "point"}),
            Tool::Ball { radius } => json!({"kind": "ball", "radius_mm": radius}),
        },
        "margin_mm": options.margin_mm,
        "sections": grid.nv,
        "points_per_section": grid.nu,
        "measured_points": measurements.len(),
        "resampled": grid.resampled,
        "sections_reordered": grid.reordered,
        "smoothing": if a.noise > 0.0 {
            json!({
                "noise_mm": smoothing.noise_mm,
                "lambda": smoothing.lambda,
                "removed_rms_mm": smoothing.removed_rms_mm,
                "saturated": smoothing.saturated,
            })
        } else {
            Value::Null
        },
        "program_syntax": flavor,
        "arcs_linearised": arcs,
        "arc_tolerance_mm": a.arc_tolerance,
        "moves_split": split,
        "max_segment_mm": a.max_segment,
        "measurements": name(&meas_path),
        "program": name(&prog_path),
        "output": name(&out_path),
        "history": history,
    });

    let deviations_svg = deviations_svg(&measurements, &grid)?;
    let displacement_svg = displacement_svg(&picked, &corrections, &grid)?;

    let dir = out_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let file = out_path
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .ok_or_else(|| CliError(format!("{}: not a file name", out_path.display())))?;
    let stem = out_path
        .file_stem()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| "corrected".into());
    let mut files: Vec<(String, Vec<u8>)> = vec![
        (file, program.into_bytes()),
        (format!("{stem}.deviations.svg"), deviations_svg),
        (format!("{stem}.displacement.svg"), displacement_svg),
    ];
    let mut report_json =
        serde_json::to_string_pretty(&report).map_err(|e| CliError(format!("report: {e}")))?;
    report_json.push('\n');
    match &report_path {
        Some(rp) => {
            write_all(dir, &files)?;
            let rdir = rp
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            let rname = rp
                .file_name()
                .map(|f| f.to_string_lossy().into_owned())
                .ok_or_else(|| CliError(format!("{}: not a file name", rp.display())))?;
            write_all(rdir, &[(rname, report_json.into_bytes())])?;
        }
        None => {
            files.push((format!("{stem}.report.json"), report_json.into_bytes()));
            write_all(dir, &files)?;
        }
    }
    Ok(format!(
        "{}: {} nodes, {} corrected, {} outside, max deviation {:.4} mm, max displacement {:.4} mm",
        out_path.display(),
        positions.len(),
        totals.corrected,
        totals.outside,
        max_deviation,
        totals.max_displacement_mm
    ))
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// The measured deviation along the surface normal, per section, against
/// the arc length along the section (a legend naming the sections, up to 16
/// sections; none beyond).
pub fn deviations_svg(m: &Measurements, grid: &Grid) -> Result<Vec<u8>, CliError> {
    let legend = m.sections.len() <= 16;
    let mut series: Vec<Series> = Vec::new();
    // The grid normal of the section's first point orients the sign.
    for (j, s) in m.sections.iter().enumerate() {
        let n0 = grid.normal_at(0, j.min(grid.nv - 1));
        let mut acc = 0.0;
        let mut pts = Vec::new();
        for (k, p) in s.points.iter().enumerate() {
            if k > 0 {
                let q = s.points[k - 1].nominal;
                acc += ((p.nominal[0] - q[0]).powi(2)
                    + (p.nominal[1] - q[1]).powi(2)
                    + (p.nominal[2] - q[2]).powi(2))
                .sqrt();
            }
            let d = p.deviation();
            let n = p.normal.unwrap_or(n0);
            pts.push((acc, d[0] * n[0] + d[1] * n[1] + d[2] * n[2]));
        }
        let label = if legend {
            format!("section {}", s.name)
        } else {
            String::new()
        };
        series.push((label, pts, PALETTE[j % PALETTE.len()]));
    }
    Ok(panels_svg(
        "deviations.svg",
        &format!(
            "Measured deviation per section (max {:.4} mm, rms {:.4} mm)",
            m.max_deviation(),
            m.rms_deviation()
        ),
        vec![(
            "length along the section, mm",
            "deviation along the normal, mm",
            series,
        )],
    )?)
}

/// The displacement of the nodes (along the surface normal, coloured) over
/// `x, y`, with the measured points; at most 20 000 nodes drawn.
pub fn displacement_svg(
    nodes: &[[f64; 3]],
    corrections: &[formcam_correct::NodeCorrection],
    grid: &Grid,
) -> Result<Vec<u8>, CliError> {
    let err = svg_err("displacement.svg");
    let step = nodes.len().div_ceil(20_000).max(1);
    let mut pts = Vec::new();
    for (k, (p, c)) in nodes.iter().zip(corrections).enumerate().step_by(step) {
        let _ = k;
        let (i, j) = (c.facet.0 as usize, c.facet.1 as usize);
        let n = grid.normal_at(i.min(grid.nu - 1), j.min(grid.nv - 1));
        let d = c.displacement;
        pts.push((
            p[0],
            p[1],
            d[0] * n[0] + d[1] * n[1] + d[2] * n[2],
            c.placement,
        ));
    }
    // The colour scale's half range: the largest displacement, at least
    // 1 um (a map of nothing moved is white, not noise).
    let lim = pts.iter().fold(1e-3f64, |m, p| m.max(p.2.abs()));
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in pts
        .iter()
        .map(|p| (p.0, p.1))
        .chain(grid.nominal.iter().map(|q| (q[0], q[1])))
    {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = 0.03 * (x1 - x0).max(y1 - y0).max(1e-9);
    let colour = |d: f64| {
        let f = (d / lim).clamp(-1.0, 1.0);
        if f >= 0.0 {
            RGBColor(255, (255.0 * (1.0 - f)) as u8, (255.0 * (1.0 - f)) as u8)
        } else {
            RGBColor((255.0 * (1.0 + f)) as u8, (255.0 * (1.0 + f)) as u8, 255)
        }
    };
    let grey = RGBColor(190, 190, 190);
    let (xr, yr) = ((x0 - pad, x1 + pad), (y0 - pad, y1 + pad));
    let (fx, fy, fbar) = (
        tick_label(xr.0, xr.1),
        tick_label(yr.0, yr.1),
        tick_label(-lim, lim),
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 800)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let root = root
            .titled(
                "Node displacement along the surface normal",
                ("sans-serif", 18),
            )
            .map_err(|e| err(e.to_string()))?;
        let (map, bar) = root.split_horizontally(880);
        let mut chart = ChartBuilder::on(&map)
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(60)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("x, mm")
            .y_desc("y, mm")
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .draw()
            .map_err(|e| err(e.to_string()))?;
        let (unchanged, moved): (Vec<_>, Vec<_>) = pts
            .iter()
            .partition(|p| matches!(p.3, Placement::Outside | Placement::Unknown));
        chart
            .draw_series(
                moved
                    .iter()
                    .map(|&&(x, y, d, _)| Circle::new((x, y), 2, colour(d).filled())),
            )
            .map_err(|e| err(e.to_string()))?;
        if !unchanged.is_empty() {
            chart
                .draw_series(
                    unchanged
                        .iter()
                        .map(|p| Circle::new((p.0, p.1), 2, grey.filled())),
                )
                .map_err(|e| err(e.to_string()))?
                .label("node left unchanged (outside the measured area)")
                .legend(move |(x, y)| Circle::new((x + 10, y), 3, grey.filled()));
        }
        chart
            .draw_series(
                grid.nominal
                    .iter()
                    .map(|q| Circle::new((q[0], q[1]), 2, BLACK.filled())),
            )
            .map_err(|e| err(e.to_string()))?
            .label("measured point")
            .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        // The colour bar: the displacement each colour stands for.
        let mut scale = ChartBuilder::on(&bar)
            .margin_top(10)
            .margin_bottom(45)
            .margin_right(5)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, -lim..lim)
            .map_err(|e| err(e.to_string()))?;
        scale
            .configure_mesh()
            .disable_x_mesh()
            .disable_x_axis()
            .disable_y_mesh()
            .y_desc("displacement, mm")
            .y_label_formatter(&fbar)
            .draw()
            .map_err(|e| err(e.to_string()))?;
        let steps = 100;
        scale
            .draw_series((0..steps).map(|k| {
                let a = -lim + 2.0 * lim * k as f64 / steps as f64;
                let b = -lim + 2.0 * lim * (k + 1) as f64 / steps as f64;
                Rectangle::new([(0.0, a), (1.0, b)], colour(0.5 * (a + b)).filled())
            }))
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg.into_bytes())
}

/// A correction job file: `[correct]` with the options of the command line
/// (`measurements`, `program`, paths relative to the job's folder; `tool`,
/// `interpolation`, `gain`, `margin_mm`, `noise_mm`, `arc_tolerance_mm`,
/// `dialect`, `points_per_section`, `max_segment_mm`, `max_deviation_mm`).
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct JobFile {
    correct: JobTable,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct JobTable {
    measurements: PathBuf,
    program: PathBuf,
    #[serde(default = "default_tool")]
    tool: String,
    #[serde(default = "default_interpolation")]
    interpolation: String,
    #[serde(default = "default_gain")]
    gain: f64,
    #[serde(default)]
    margin_mm: f64,
    #[serde(default)]
    noise_mm: f64,
    #[serde(default = "default_arc_tolerance")]
    arc_tolerance_mm: f64,
    dialect: Option<String>,
    points_per_section: Option<usize>,
    max_segment_mm: Option<f64>,
    #[serde(default = "default_max_deviation")]
    max_deviation_mm: f64,
}

fn default_max_deviation() -> f64 {
    DEFAULT_MAX_DEVIATION_MM
}

fn default_tool() -> String {
    "point".into()
}

fn default_arc_tolerance() -> f64 {
    0.001
}

/// Whether a TOML table is a correction job (it has `[correct]`).
pub fn is_job(table: &toml::Table) -> bool {
    table.contains_key("correct")
}

/// Runs a correction job file into `out` (`corrected.<ext>`, `report.json`,
/// the plots).
pub fn run_job_text(path: &Path, text: &str, out: &Path) -> Result<String, CliError> {
    let f: JobFile = toml::from_str(text)
        .map_err(|e| CliError(format!("{}: {}", path.display(), e.message())))?;
    let j = f.correct;
    let base = path.parent().unwrap_or(Path::new("."));
    let program = base.join(&j.program);
    let name = format!(
        "corrected.{}",
        program
            .extension()
            .map_or("nc".into(), |e| e.to_string_lossy().into_owned())
    );
    let args = CorrectArgs {
        job: None,
        measurements: Some(base.join(&j.measurements)),
        program: Some(program),
        output: Some(out.join(name)),
        gain: j.gain,
        tool: j.tool,
        interpolation: j.interpolation,
        report: Some(out.join("report.json")),
        margin: j.margin_mm,
        noise: j.noise_mm,
        arc_tolerance: j.arc_tolerance_mm,
        dialect: j.dialect,
        points_per_section: j.points_per_section,
        max_segment: j.max_segment_mm,
        max_deviation: j.max_deviation_mm,
    };
    // A fresh report per demo run: the history is for runs on real parts.
    let _ = fs::remove_file(out.join("report.json"));
    run(&args)
}

/// A closed-loop scenario file.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    surface: SurfaceTable,
    program: ProgramTable,
    warp: WarpTable,
    cmm: CmmTable,
    #[serde(rename = "loop")]
    rounds: LoopTable,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SurfaceTable {
    kind: String,
    length: f64,
    width: f64,
    radius_x: Option<f64>,
    radius_y: Option<f64>,
    radius_start: Option<f64>,
    radius_end: Option<f64>,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ProgramTable {
    tool: String,
    step: f64,
    step_over: f64,
    feed: f64,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct WarpTable {
    amplitude: f64,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct CmmTable {
    sections: usize,
    points: usize,
    #[serde(default)]
    noise: f64,
    #[serde(default)]
    seed: u64,
}

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct LoopTable {
    iterations: usize,
    #[serde(default = "default_interpolation")]
    interpolation: String,
    #[serde(default = "default_gain")]
    gain: f64,
    #[serde(default)]
    margin_mm: f64,
    #[serde(default)]
    smoothing: bool,
    #[serde(default)]
    section_study: Vec<usize>,
}

fn default_interpolation() -> String {
    "bilinear".into()
}

fn default_gain() -> f64 {
    1.0
}

/// Whether a TOML table is a correction scenario (it has `[surface]` and `[warp]`).
pub fn is_scenario(table: &toml::Table) -> bool {
    table.contains_key("surface") && table.contains_key("warp")
}

fn scenario_of(path: &Path, text: &str) -> Result<(Scenario, Vec<usize>), CliError> {
    let at = |m: String| CliError(format!("{}: {m}", path.display()));
    let f: ScenarioFile = toml::from_str(text).map_err(|e| at(e.message().to_string()))?;
    let need = |v: Option<f64>, name: &str| {
        v.ok_or_else(|| {
            at(format!(
                "surface.{name}: missing for surface.kind = \"{}\"",
                f.surface.kind
            ))
        })
    };
    let shape = match f.surface.kind.as_str() {
        "panel" => Shape::Panel {
            radius_x: need(f.surface.radius_x, "radius_x")?,
            radius_y: need(f.surface.radius_y, "radius_y")?,
        },
        "nose-cone" => Shape::NoseCone {
            radius_start: need(f.surface.radius_start, "radius_start")?,
            radius_end: need(f.surface.radius_end, "radius_end")?,
        },
        other => {
            return Err(at(format!(
                "surface.kind = \"{other}\": allowed panel, nose-cone"
            )));
        }
    };
    let tool = parse_tool(&f.program.tool).map_err(|e| at(format!("program.tool: {}", e.0)))?;
    let interpolation = parse_interpolation(&f.rounds.interpolation)
        .map_err(|e| at(format!("loop.interpolation: {}", e.0)))?;
    let s = Scenario {
        shape,
        length: f.surface.length,
        width: f.surface.width,
        tool,
        step_over: f.program.step_over,
        step: f.program.step,
        feed: f.program.feed,
        warp_amplitude: f.warp.amplitude,
        sections: f.cmm.sections,
        points: f.cmm.points,
        noise: f.cmm.noise,
        smoothing: f.rounds.smoothing,
        seed: f.cmm.seed,
        iterations: f.rounds.iterations,
        options: Options {
            gain: f.rounds.gain,
            tool,
            interpolation,
            margin_mm: f.rounds.margin_mm,
        },
    };
    s.validate().map_err(|e| at(e.to_string()))?;
    Ok((s, f.rounds.section_study))
}

/// The measurements as the CMM CSV report (with normals).
fn cmm_csv(m: &Measurements) -> String {
    let mut out = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act,nx,ny,nz\n");
    for s in &m.sections {
        for p in &s.points {
            let n = p.normal.unwrap_or([0.0, 0.0, 1.0]);
            out.push_str(&format!(
                "{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.6},{:.6},{:.6}\n",
                s.name,
                p.point,
                p.nominal[0],
                p.nominal[1],
                p.nominal[2],
                p.actual[0],
                p.actual[1],
                p.actual[2],
                n[0],
                n[1],
                n[2]
            ));
        }
    }
    out
}

/// Runs `formcam correct simulate`; returns the one-line summary.
pub fn simulate(path: &Path, out: &Path) -> Result<String, CliError> {
    let text = read_text(path)?;
    simulate_text(path, &text, out)
}

/// Runs a scenario already read (the demo passes the text it read).
pub fn simulate_text(path: &Path, text: &str, out: &Path) -> Result<String, CliError> {
    let (scenario, study) = scenario_of(path, text)?;
    let at = |e: formcam_correct::CorrectError| CliError(format!("{}: {e}", path.display()));
    let result = scenario.run().map_err(at)?;
    let rows = if study.is_empty() {
        Vec::new()
    } else {
        scenario.spacing_study(&study).map_err(at)?
    };
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    let mut rounds = Vec::new();
    for (k, r) in result.rounds.iter().enumerate() {
        files.push((format!("program-{k}.nc"), r.program.clone().into_bytes()));
        files.push((
            format!("cmm-{k}.csv"),
            cmm_csv(&r.measurements).into_bytes(),
        ));
        rounds.push(json!({
            "iteration": k,
            "measured_max_mm": r.measured_max_mm,
            "measured_rms_mm": r.measured_rms_mm,
            "true_max_mm": r.true_max_mm,
            "true_rms_mm": r.true_rms_mm,
        }));
    }
    let (Some(first), Some(last)) = (result.rounds.first(), result.rounds.last()) else {
        return Err(CliError(format!(
            "{}: the loop ran no round",
            path.display()
        )));
    };
    let grid_of = |m: &Measurements| {
        Grid::from_measurements(m, None).map_err(|e| CliError(format!("{}: {e}", path.display())))
    };
    files.push((
        "deviations-before.svg".into(),
        deviations_svg(&first.measurements, &grid_of(&first.measurements)?)?,
    ));
    files.push((
        "deviations-after.svg".into(),
        deviations_svg(&last.measurements, &grid_of(&last.measurements)?)?,
    ));
    files.push(("convergence.svg".into(), convergence_svg(&result)?));
    let study_json: Vec<Value> = rows
        .iter()
        .map(|r| {
            json!({
                "sections": r.sections,
                "points_per_section": r.points,
                "section_spacing_mm": r.spacing_mm,
                "interpolation": r.interpolation.name(),
                "true_max_mm": r.true_max_mm,
                "true_rms_mm": r.true_rms_mm,
            })
        })
        .collect();
    let report = json!({
        "scenario": path.display().to_string(),
        "iterations": scenario.iterations,
        "interpolation": scenario.options.interpolation.name(),
        "sections": scenario.sections,
        "points_per_section": scenario.points,
        "noise_mm": scenario.noise,
        "warp_amplitude_mm": scenario.warp_amplitude,
        "rounds": rounds,
        "max_deviation_before_mm": first.true_max_mm,
        "max_deviation_after_mm": last.true_max_mm,
        "rms_deviation_after_mm": last.true_rms_mm,
        "section_study": study_json,
    });
    let mut report_json =
        serde_json::to_string_pretty(&report).map_err(|e| CliError(format!("report: {e}")))?;
    report_json.push('\n');
    files.push(("report.json".into(), report_json.into_bytes()));
    write_all(out, &files)?;
    Ok(format!(
        "{}: {} rounds, true max deviation {:.4} mm -> {:.4} mm (rms {:.4} mm), measured {:.4} mm -> {:.4} mm",
        out.display(),
        result.rounds.len() - 1,
        first.true_max_mm,
        last.true_max_mm,
        last.true_rms_mm,
        first.measured_max_mm,
        last.measured_max_mm,
    ))
}

/// A named, coloured line of a plot.
type Line = (&'static str, Vec<(f64, f64)>, RGBColor);
/// Max and RMS deviation per round, log scale.
fn convergence_svg(r: &LoopResult) -> Result<Vec<u8>, CliError> {
    let err = svg_err("convergence.svg");
    let n = r.rounds.len();
    let lines: [Line; 4] = [
        (
            "true max |deviation| (check grid)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.true_max_mm))
                .collect(),
            PALETTE[3],
        ),
        (
            "true rms deviation (check grid)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.true_rms_mm))
                .collect(),
            PALETTE[0],
        ),
        (
            "measured max |deviation| (CMM)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.measured_max_mm))
                .collect(),
            PALETTE[1],
        ),
        (
            "measured rms deviation (CMM)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.measured_rms_mm))
                .collect(),
            PALETTE[2],
        ),
    ];
    let (lo, hi) = lines
        .iter()
        .flat_map(|l| l.1.iter().map(|p| p.1))
        .filter(|v| *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let (lo, hi) = if lo.is_finite() {
        (lo / 2.0, hi * 2.0)
    } else {
        (1e-4, 1.0)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Closed loop: deviation of the part per round",
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.2..(n as f64 - 0.8), (lo..hi).log_scale())
            .map_err(|e| err(e.to_string()))?;
        // Rounds are whole numbers: at most one label per round, no minor
        // lines between them.
        let round = |v: &f64| format!("{v:.0}");
        chart
            .configure_mesh()
            .x_desc("round (0: nominal program)")
            .y_desc("deviation, mm")
            .x_labels(n.max(1))
            .x_max_light_lines(1)
            .x_label_formatter(&round)
            .draw()
            .map_err(|e| err(e.to_string()))?;
        for (name, pts, color) in lines {
            let pts: Vec<(f64, f64)> = pts.into_iter().map(|(x, y)| (x, y.max(lo))).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| err(e.to_string()))?
                .label(name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
                .map_err(|e| err(e.to_string()))?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg.into_bytes())
}
