//! Winding runs: a job's result files — the program, `blocks.csv`,
//! `axes.csv`, the band, eye and path CSVs, each layer's `layer-NN/`
//! outputs, `summary.json` and the plots — and the line that says what was
//! done. A single-layer job writes its layer's outputs as its own; a
//! multi-layer job (and a `.wind` document) writes them per layer.
//!
//! A run that writes a program then checks it on its machine as `formcam
//! check --mandrel JOB` would, from the written text (the program read
//! back, each block timed by its own feed), with the job's mandrel, laminate
//! and free fibre taken from the planning already done: `check.json` is the
//! report, the line says `checked: clean` or the violations, and
//! [`RunOutput::violations`] their count. [`ProgramCheck::Off`] skips it.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use formcam_machine::AxisTrack;
use formcam_machine::BandPassed;
use formcam_machine::Machine;
use formcam_program::{
    Assembled, Check, MachineSource, MandrelCheckBuilder, Post, ProgramError, Stage, WindJob,
    Wound, WoundLayer, WoundProgram, nc, plan_each, plan_until_with, write_program,
};
use formcam_progress::{Phase, Progress, Silent, Step};
use formcam_results::names::{self, CHECK, EYE_SVG, PATH_SVG, SUMMARY};
use formcam_results::winding::{AXES, BAND, BLOCKS, EYE, PATH, PROGRAM_AXES};
use formcam_winding::Layer;
use formcam_winding::eye::EyeTrajectory;
use serde_json::{Map, Value, json};

use crate::{ResultFile, RunError, RunOutput};

/// Whether a winding run checks the program it wrote (`formcam check` on
/// its text, on the job's machine) before it reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ProgramCheck {
    /// The written program read back and checked: `check.json`, the line's
    /// verdict, [`RunOutput::violations`].
    #[default]
    On,
    /// No check (`formcam wind --no-check`).
    Off,
}

/// `formcam wind [path|eye|axes] JOB -o OUT`: the job at `job` run up to
/// `stage`; `out` is only named in the line (and in the check's report).
pub fn wind(job: &Path, out: &Path, stage: Stage) -> Result<RunOutput, RunError> {
    wind_with(job, out, stage, &Silent)
}

/// [`wind`] reporting to `progress` (the pipeline's phases, the post, the
/// files); [`RunError::Cancelled`] when it asks to stop.
pub fn wind_with(
    job: &Path,
    out: &Path,
    stage: Stage,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    wind_checked_with(job, out, stage, ProgramCheck::On, progress)
}

/// [`wind_with`], checking the written program or not (`check`).
pub fn wind_checked_with(
    job: &Path,
    out: &Path,
    stage: Stage,
    check: ProgramCheck,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let wj = read_job(job)?;
    let mut output = run(job, out, &wj, stage, check, t0, progress)?;
    output.inputs = job_inputs(job, &wj);
    Ok(output)
}

/// The job at `job` run as far as its tables reach (the demo's rule, see
/// [`WindJob::furthest_stage`]).
pub fn wind_furthest(job: &Path, out: &Path) -> Result<RunOutput, RunError> {
    wind_furthest_with(job, out, &Silent)
}

/// [`wind_furthest`] reporting to `progress`.
pub fn wind_furthest_with(
    job: &Path,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let text = read_job_text(job)?;
    furthest(job, &text, out, t0, progress)
}

/// [`wind_furthest_with`] for the job `text` the caller holds (an edited
/// job not yet saved): read as if it were the file at `job`, so the files
/// it names are found relative to `job`'s folder and the summary names
/// `job`; the file itself is not read.
pub fn wind_furthest_text_with(
    job: &Path,
    text: &str,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    furthest(job, text, out, Instant::now(), progress)
}

/// The job `text` (of the file at `job`) run as far as its tables reach.
fn furthest(
    job: &Path,
    text: &str,
    out: &Path,
    t0: Instant,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let wj = parse_job(job, text)?;
    let stage = wj.furthest_stage();
    let mut output = run(job, out, &wj, stage, ProgramCheck::On, t0, progress)?;
    output.inputs = job_inputs(job, &wj);
    Ok(output)
}

/// The files a winding job at `path` reads: itself, its machine file, the
/// mandrel's meridian table, the eye's curve and the post's template.
fn job_inputs(path: &Path, job: &WindJob) -> Vec<PathBuf> {
    let machine = job.machine.as_ref().and_then(|m| match &m.source {
        MachineSource::File(f) => Some(f.as_str()),
        MachineSource::Shipped(_) => None,
    });
    let template = match &job.post {
        Some(Post::Template { file, .. }) => Some(file.as_str()),
        _ => None,
    };
    let named = [
        machine,
        job.mandrel.file.as_deref(),
        job.eye.as_ref().and_then(|e| e.curve.as_deref()),
        template,
    ];
    std::iter::once(path.to_path_buf())
        .chain(named.into_iter().flatten().map(|f| job.base_dir.join(f)))
        .collect()
}

/// `formcam wind JOB.wind -o OUT`: a Cyclone/FiberPath `.wind` job on the
/// shipped X/A/B winder with its eye `eye_clearance` mm over the mandrel,
/// written for Marlin X/A/B; `allow` accepts failed checks (`slack` always).
pub fn wind_file(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
) -> Result<RunOutput, RunError> {
    wind_file_with(path, out, eye_clearance, allow, &Silent)
}

/// [`wind_file`] reporting to `progress`.
pub fn wind_file_with(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    wind_file_checked_with(path, out, eye_clearance, allow, ProgramCheck::On, progress)
}

/// [`wind_file_with`], checking the written program or not (`check`).
pub fn wind_file_checked_with(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
    check: ProgramCheck,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let text = formcam_files::read_text(path).map_err(|e| RunError::Read {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    let wj = WindJob::from_wind(&text, eye_clearance, allow)
        .map_err(|e| RunError::wind(path, e))?
        .named(path);
    let mut output = run(path, out, &wj, Stage::Program, check, t0, progress)?;
    output.inputs = vec![path.to_path_buf()];
    if let Some(w) = &wj.wind_file {
        // Before the check's verdict, which ends the line.
        let at = output.line.find("; checked").unwrap_or(output.line.len());
        output.line.insert_str(
            at,
            &format!(
                "; eye {:.1} mm from the axis ({:.1} mm over the mandrel)",
                w.eye_radius_mm, w.eye_clearance_mm
            ),
        );
    }
    Ok(output)
}

/// The job at `path`, read.
fn read_job(path: &Path) -> Result<WindJob, RunError> {
    parse_job(path, &read_job_text(path)?)
}

/// The text of the job file at `path`.
fn read_job_text(path: &Path) -> Result<String, RunError> {
    formcam_files::read_text(path).map_err(|e| RunError::Read {
        path: path.to_path_buf(),
        source: e.into(),
    })
}

/// The job `text` of the file at `path`: the files it names relative to
/// `path`'s folder, named by `path`.
fn parse_job(path: &Path, text: &str) -> Result<WindJob, RunError> {
    let base = path.parent().unwrap_or(Path::new(""));
    Ok(WindJob::from_toml(text, base)
        .map_err(|e| RunError::wind(path, e))?
        .named(path))
}

/// Plans `job` up to `stage`, lays out its files and checks the program
/// written (unless `check` is off).
fn run(
    path: &Path,
    out: &Path,
    job: &WindJob,
    stage: Stage,
    check: ProgramCheck,
    t0: Instant,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let at = |e: ProgramError| RunError::wind(path, e);
    // The check's free fibre takes each layer's circuit as it is planned
    // (a user template's program is not read back).
    let mut mandrel = match (check, stage, job.post()) {
        (ProgramCheck::On, Stage::Program, Post::Dialect(_)) => {
            Some(MandrelCheckBuilder::new(job).map_err(|e| check_error(path, e))?)
        }
        _ => None,
    };
    // A multi-layer job's layer files are made as each layer is planned,
    // which then drops its per-point data.
    let mut each = LayerFiles::default();
    let wound = if job.is_layered() {
        let m = job.machine.as_ref().map(|jm| &jm.machine);
        plan_each(job, stage, progress, &mut |i, l| {
            if let Some(b) = &mut mandrel {
                b.add(l).map_err(|e| Halt::Run(check_error(path, e)))?;
            }
            match m {
                Some(m) => each.add(m, i, l).map_err(Halt::Run),
                None => Ok(()),
            }
        })
        .map_err(|h| match h {
            Halt::Program(e) => at(e),
            Halt::Run(e) => e,
        })?
    } else {
        let wound = plan_until_with(job, stage, progress).map_err(at)?;
        if let Some(b) = &mut mandrel {
            for l in &wound.layers {
                b.add(l).map_err(|e| check_error(path, e))?;
            }
        }
        wound
    };
    let program = match &wound.program {
        Some(p) => {
            progress.checkpoint(Step::new(Phase::Post, 0, 1))?;
            let mut text = Vec::new();
            write_program(&wound, &mut text).map_err(at)?;
            progress.checkpoint(Step::new(Phase::Post, 1, 1))?;
            Some((p, text))
        }
        None => None,
    };
    let checked = match (&program, mandrel) {
        (Some((_, text)), Some(mandrel)) => check_program(path, out, job, &wound, text, mandrel)?,
        _ => None,
    };
    progress.checkpoint(Step::new(Phase::Files, 0, 1))?;
    let mut output = if job.is_layered() {
        layered(job, &wound, program, each)?
    } else {
        single(path, job, &wound, program)?
    };
    progress.checkpoint(Step::new(Phase::Files, 1, 1))?;
    let check_time = checked.as_ref().map_or(Duration::ZERO, |c| c.time);
    let _ = write!(
        output.line,
        ", {:.1} ms -> {}",
        t0.elapsed().saturating_sub(check_time).as_secs_f64() * 1e3,
        out.display()
    );
    if let Some(c) = checked {
        output.line.push_str(&c.verdict());
        output.violations = Some(c.report.violations.len());
        output.files.push(ResultFile::new(CHECK, c.json()?));
    } else if check == ProgramCheck::On
        && program_written(&output)
        && matches!(wound.post, Post::Template { .. })
    {
        output
            .line
            .push_str("; not checked: a user template's program cannot be read back");
    }
    if let Some(l) = wound.layers.first().and_then(WoundLayer::wound)
        && !job.is_layered()
    {
        for w in &l.layer.warnings {
            let _ = write!(output.line, "\n  warning: {w}");
        }
    }
    output.warnings = wound
        .warnings
        .iter()
        .map(|w| format!("{}: {w}", path.display()))
        .collect();
    Ok(output)
}

/// Whether a run's files hold a program.
fn program_written(output: &RunOutput) -> bool {
    output.files.iter().any(|f| names::is_program(&f.name))
}

/// The check of a written program: its report and how long it took.
struct Checked {
    report: formcam_sim::Report,
    time: Duration,
}

impl Checked {
    /// The line's end: `; checked: clean (T ms)`, or the number of
    /// violations and the first.
    fn verdict(&self) -> String {
        let ms = self.time.as_secs_f64() * 1e3;
        match self.report.violations.first() {
            None => format!("; checked: clean ({ms:.1} ms)"),
            Some(first) => {
                let k = self.report.violations.len();
                let s = if k == 1 { "" } else { "s" };
                format!("; checked: {k} violation{s} ({ms:.1} ms), first {first}")
            }
        }
    }

    /// `check.json`: the report as `formcam check -o` writes it.
    fn json(&self) -> Result<Vec<u8>, RunError> {
        let mut v = serde_json::to_vec_pretty(&self.report)
            .map_err(|source| RunError::Summary { source })?;
        v.push(b'\n');
        Ok(v)
    }
}

/// Checks the program `text` written for `job` (the job file at `path`) on
/// its machine, as `formcam check OUT/program.<ext> --machine M --mandrel
/// JOB` does: read back in the dialect of its extension, each block timed
/// by its own feed, every axis's position, velocity, jump and acceleration
/// limits, the collisions of the machine's solids (mesh files relative to
/// the machine file), the bed and the mandrel grown by the laminate, and
/// the free fibre (`mandrel`: the job's laminate and fibre, from this
/// planning). `None` for a user template's program (no reader knows its
/// text).
fn check_program(
    path: &Path,
    out: &Path,
    job: &WindJob,
    wound: &WoundProgram,
    text: &[u8],
    mandrel: MandrelCheckBuilder,
) -> Result<Option<Checked>, RunError> {
    let (Some(m), Some(jm), Post::Dialect(_)) = (&wound.machine, &job.machine, &wound.post) else {
        return Ok(None);
    };
    let t = Instant::now();
    let program = out.join(names::program(wound.post.extension()));
    let (machine, mesh_dir) = match &jm.source {
        MachineSource::Shipped(n) => (n.clone(), None),
        MachineSource::File(f) => {
            let file = job.base_dir.join(f);
            (
                file.display().to_string(),
                file.parent().map(Path::to_path_buf),
            )
        }
    };
    let fail = |source| check_error(path, source);
    let mandrel = mandrel
        .finish(job, wound)
        .map_err(|e| RunError::wind(path, e))?;
    let text = String::from_utf8_lossy(text);
    let report = formcam_sim::check_text_with(
        &program,
        &text,
        m,
        &machine,
        mesh_dir.as_deref(),
        Some(&mandrel),
    )
    .map_err(fail)?;
    Ok(Some(Checked {
        report,
        time: t.elapsed(),
    }))
}

/// The check of the program written for the job file `path` failed.
fn check_error(path: &Path, source: formcam_sim::SimError) -> RunError {
    RunError::Check {
        path: path.to_path_buf(),
        source: Box::new(source),
    }
}

/// A single-layer job: the layer's outputs are the job's.
fn single(
    path: &Path,
    job: &WindJob,
    wound: &WoundProgram,
    program: Option<(&Assembled, Vec<u8>)>,
) -> Result<RunOutput, RunError> {
    let Some(l) = wound.layers.first().and_then(WoundLayer::wound) else {
        return Ok(RunOutput::default());
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let layer = &l.layer;
    let mut summary = layer_summary(&job.title, l.mandrel.kind(), layer);
    if let Some(w) = summary.get_mut("warnings").and_then(Value::as_array_mut) {
        w.extend(wound.warnings.iter().map(|s| json!(s)));
    }
    let title = format!("{name}: {} mandrel, one pass", l.mandrel.kind());
    let mut files = vec![
        ResultFile::new(PATH.file, path_csv(layer)),
        ResultFile::new(
            PATH_SVG,
            formcam_plot::layer_svg(&title, &l.mandrel, layer)?,
        ),
    ];
    let mut more = String::new();
    if let Some(t) = &l.eye {
        add_eye_summary(&mut summary, t);
        files.push(ResultFile::new(EYE.file, eye_csv(t)));
        files.push(ResultFile::new(
            EYE_SVG,
            formcam_plot::eye_svg(&format!("{name}: payout eye over one circuit"), t)?,
        ));
        more = eye_line(t);
    }
    if let (Some(m), Some(track), Some(jm)) = (&wound.machine, &l.track, &job.machine) {
        files.push(ResultFile::new(AXES.file, axes_csv(m, l, track)));
        let passed = l.band_passed(m);
        if !m.roles.band_path.is_empty() {
            files.push(ResultFile::new(BAND.file, band_csv(m, l, &passed)));
        }
        add_axes_summary(&mut summary, m, &jm.source, track, passed.last());
        let mut program_line = String::new();
        if let Some((p, text)) = program {
            let (pf, fields, line) = program_files(m, p, wound, text);
            files.extend(pf);
            if let Some(obj) = summary.as_object_mut() {
                obj.extend(fields);
            }
            program_line = line;
        }
        more.push_str(&axes_line(m, track));
        more.push_str(&program_line);
    }
    files.push(ResultFile::new(SUMMARY, pretty(&summary)?));
    let line = format!(
        "{}: {} path, mu {:.5}, alpha at equator {:.3} deg, {} circuits (pattern {} skip {}), dwell \
         {:.2} deg, fibre {:.1} m{more}",
        job.title,
        json_name(&layer.pass.method),
        layer.pass.mu.unwrap_or(layer.pass.mu_max_abs),
        layer.report.alpha_equator_rad.to_degrees(),
        layer.pattern.circuits,
        layer.pattern.pattern_number,
        layer.pattern.skip_index,
        layer.report.dwell_deg,
        layer.report.fibre_length_mm / 1000.0,
    );
    Ok(RunOutput {
        files,
        line,
        ..RunOutput::default()
    })
}

/// Why planning a multi-layer job stopped: the plan, or a layer's files.
enum Halt {
    Program(ProgramError),
    Run(RunError),
}

impl From<ProgramError> for Halt {
    fn from(e: ProgramError) -> Self {
        Self::Program(e)
    }
}

/// A multi-layer job's per-layer files (`layer-NN/`), made as each layer is
/// planned, and each layer's axes summary: limits kept, the largest IK
/// residual.
#[derive(Default)]
struct LayerFiles {
    files: Vec<ResultFile>,
    axes: Vec<(bool, f64)>,
}

impl LayerFiles {
    /// Layer `i` (0-based), planned on `m`: its files and its axes summary.
    fn add(&mut self, m: &Machine, i: usize, l: &WoundLayer) -> Result<(), RunError> {
        let Some(w) = l.wound() else {
            self.axes.push((true, 0.0));
            return Ok(());
        };
        let files = &mut self.files;
        let title = format!("{}: {} mandrel, one pass", l.label, w.mandrel.kind());
        files.push(ResultFile::new(
            names::in_layer(i + 1, PATH.file),
            path_csv(&w.layer),
        ));
        files.push(ResultFile::new(
            names::in_layer(i + 1, PATH_SVG),
            formcam_plot::layer_svg(&title, &w.mandrel, &w.layer)?,
        ));
        if let Some(t) = &w.eye {
            files.push(ResultFile::new(
                names::in_layer(i + 1, EYE.file),
                eye_csv(t),
            ));
            files.push(ResultFile::new(
                names::in_layer(i + 1, EYE_SVG),
                formcam_plot::eye_svg(&format!("{}: payout eye over one circuit", l.label), t)?,
            ));
        }
        let axes = match &w.track {
            Some(track) => {
                files.push(ResultFile::new(
                    names::in_layer(i + 1, AXES.file),
                    axes_csv(m, w, track),
                ));
                (track.limits_ok(), track.max_residual_mm())
            }
            None => (true, 0.0),
        };
        if !m.roles.band_path.is_empty() {
            let passed = w.band_passed(m);
            files.push(ResultFile::new(
                names::in_layer(i + 1, BAND.file),
                band_csv(m, w, &passed),
            ));
        }
        self.axes.push(axes);
        Ok(())
    }
}

/// A multi-layer job: each layer's outputs in `layer-NN/` (made as the
/// layers were planned), the program's axes over time in `axes.csv`.
fn layered(
    job: &WindJob,
    wound: &WoundProgram,
    program: Option<(&Assembled, Vec<u8>)>,
    each: LayerFiles,
) -> Result<RunOutput, RunError> {
    let (Some(m), Some(jm), Some((p, text))) = (&wound.machine, &job.machine, program) else {
        return Ok(RunOutput::default());
    };
    let mut files = each.files;
    let mut per_layer = Vec::with_capacity(wound.layers.len());
    for (i, ((l, b), &(limits_ok, residual))) in wound
        .layers
        .iter()
        .zip(&wound.blocks)
        .zip(&each.axes)
        .enumerate()
    {
        let Some(w) = l.wound() else {
            per_layer
                .push(json!({ "layer": i + 1, "kind": l.kind, "blocks": 1, "time_s": b.times[0] }));
            continue;
        };
        per_layer.push(json!({
            "layer": i + 1,
            "kind": l.kind,
            "mandrel_growth_mm": w.grown,
            "alpha_equator_deg": w.layer.report.alpha_equator_rad.to_degrees(),
            "circuits": w.layer.pattern.circuits,
            "blocks": b.blocks.len(),
            "time_s": b.times[0],
            "thickness_mm": w.thickness,
            "fibre_length_mm": w.layer.report.fibre_length_mm,
            "one_way": l.one_way,
            "limits_ok": limits_ok,
            "max_ik_residual_mm": residual,
        }));
    }
    let fibre = wound.fibre_length_mm();
    let mut summary = Map::new();
    summary.insert("job".into(), json!(job.title));
    summary.insert("machine".into(), json!(m.name));
    insert_source(&mut summary, &jm.source);
    summary.insert(
        "axes".into(),
        json!(m.axes.iter().map(|a| a.name.clone()).collect::<Vec<_>>()),
    );
    summary.insert("fibre_length_mm".into(), json!(fibre));
    summary.insert("per_layer".into(), json!(per_layer));
    summary.insert("warnings".into(), json!(wound.warnings));
    if let Some(w) = &job.wind_file {
        summary.insert("schema_version".into(), json!(w.schema_version));
        summary.insert("eye_radius_mm".into(), json!(w.eye_radius_mm));
        summary.insert("eye_clearance_mm".into(), json!(w.eye_clearance_mm));
    }
    let (pf, fields, program_line) = program_files(m, p, wound, text);
    summary.extend(fields);
    files.extend(pf);
    let (axes, _) = program_axes(m, p);
    files.push(ResultFile::new(PROGRAM_AXES.file, axes));
    files.push(ResultFile::new(SUMMARY, pretty(&Value::Object(summary))?));
    let line = format!(
        "{}: {} on {}, fibre {:.1} m{program_line}",
        job.title,
        wound
            .layers
            .iter()
            .map(|l| l.kind.name())
            .collect::<Vec<_>>()
            .join(" + "),
        m.name,
        fibre / 1000.0,
    );
    Ok(RunOutput {
        files,
        line,
        ..RunOutput::default()
    })
}

/// The program's files (`program.<ext>`, `blocks.csv`), its summary fields
/// and its part of the line.
fn program_files(
    m: &Machine,
    p: &Assembled,
    wound: &WoundProgram,
    text: Vec<u8>,
) -> (Vec<ResultFile>, Map<String, Value>, String) {
    let ext = wound.post.extension();
    let count = p.blocks.len();
    let (_, axis_ranges) = program_axes(m, p);
    let mut summary = Map::new();
    summary.insert("blocks".into(), json!(count));
    summary.insert("layers".into(), json!(p.layers));
    summary.insert("program_time_s".into(), json!(p.time_s));
    summary.insert("program_time_pairwise_s".into(), json!(p.time_pairwise_s));
    summary.insert("program_time_global_s".into(), json!(p.time_global_s));
    summary.insert(
        "program_time_preliminary_s".into(),
        json!(p.time_preliminary_s),
    );
    summary.insert("program_file".into(), json!(names::program(ext)));
    summary.insert("axis_ranges".into(), axis_ranges);
    summary.insert(
        "checks_accepted".into(),
        json!(p.accepted.iter().map(|c| c.name()).collect::<Vec<_>>()),
    );
    summary.insert(
        "checks_violated".into(),
        json!(
            p.violated
                .iter()
                .map(|v| json!({ "check": v.check.name(), "layer": v.layer, "detail": v.detail }))
                .collect::<Vec<_>>()
        ),
    );
    let line = format!(
        "; {} layers, {count} blocks, {:.2} s (pairwise {:.2} s, global {:.2} s) -> program.{ext}",
        p.layers, p.time_s, p.time_pairwise_s, p.time_global_s
    );
    let files = vec![
        ResultFile::new(names::program(ext), text),
        ResultFile::new(BLOCKS.file, blocks_csv(m, p)),
    ];
    (files, summary, line)
}

/// How the summary records the machine: its shipped name or its file as the
/// job wrote it.
fn insert_source(summary: &mut Map<String, Value>, source: &MachineSource) {
    match source {
        MachineSource::Shipped(n) => summary.insert("machine_shipped".into(), json!(n)),
        MachineSource::File(f) => summary.insert("machine_file".into(), json!(f)),
    };
}

fn pretty(v: &Value) -> Result<Vec<u8>, RunError> {
    serde_json::to_vec_pretty(v).map_err(|source| RunError::Summary { source })
}

/// A serialisable kind's name (`geodesic`).
fn json_name<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_value(v)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_default()
}

fn path_csv(layer: &Layer) -> Vec<u8> {
    let mut s = String::with_capacity(layer.points.len() * 120);
    s.push_str(&PATH.header());
    for (p, t) in layer.points.iter().zip(&layer.thickness) {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            p.s,
            p.z,
            p.r,
            p.v,
            p.alpha,
            p.c,
            p.mu,
            p.alpha.to_degrees(),
            t
        );
    }
    s.into_bytes()
}

fn layer_summary(job: &str, kind: &str, layer: &Layer) -> Value {
    let mu = layer.pass.mu.unwrap_or(layer.pass.mu_max_abs);
    json!({
        "job": job,
        "mandrel": kind,
        "method": layer.pass.method,
        "mu": mu,
        "mu_max_abs": layer.pass.mu_max_abs,
        "turn_angle_pass_rad": layer.report.turn_angle_pass_rad,
        "turn_angle_circuit_rad": layer.report.turn_angle_circuit_rad,
        "alpha_equator_rad": layer.report.alpha_equator_rad,
        "circuits": layer.pattern.circuits,
        "pattern_number": layer.pattern.pattern_number,
        "skip_index": layer.pattern.skip_index,
        "dwell_deg": layer.report.dwell_deg,
        "fibre_length_mm": layer.report.fibre_length_mm,
        "pass": layer.pass,
        "pattern": layer.pattern,
        "report": layer.report,
        "warnings": layer.warnings,
    })
}

fn eye_line(t: &EyeTrajectory) -> String {
    format!(
        "; eye {}: u in [{:.4}, {:.4}], rms {:.4}, constraints {}",
        json_name(&t.mode),
        t.stats.u_min,
        t.stats.u_max,
        t.stats.u_rms_dev,
        if t.constraints_ok { "ok" } else { "VIOLATED" }
    )
}

fn axes_line(m: &Machine, track: &AxisTrack) -> String {
    let issues = if track.issues.is_empty() {
        String::new()
    } else {
        format!(
            ", issues: {}",
            track
                .issues
                .iter()
                .map(|i| format!("{} {}", i.kind, i.axis.as_deref().unwrap_or("")))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    format!(
        "; axes {} on {} ({}): limits {}, IK residual {:.2e} mm{issues}",
        m.axes
            .iter()
            .map(|a| a.name.as_str())
            .collect::<Vec<_>>()
            .join(","),
        m.name,
        if track.closed_form {
            "closed form"
        } else {
            "solver"
        },
        if track.limits_ok() { "ok" } else { "VIOLATED" },
        track.max_residual_mm(),
    )
}

fn add_eye_summary(summary: &mut Value, t: &EyeTrajectory) {
    if let Some(obj) = summary.as_object_mut() {
        obj.insert("eye_mode".into(), json!(t.mode));
        obj.insert("u_min".into(), json!(t.stats.u_min));
        obj.insert("u_max".into(), json!(t.stats.u_max));
        obj.insert("u_rms_dev".into(), json!(t.stats.u_rms_dev));
        obj.insert("constraints_ok".into(), json!(t.constraints_ok));
        obj.insert("violations".into(), json!(t.violations));
        obj.insert("eye".into(), json!(t));
    }
}

fn axes_csv(m: &Machine, w: &Wound, track: &AxisTrack) -> Vec<u8> {
    let mut s = String::with_capacity(w.targets.len() * 16 * (m.axes.len() + 1));
    s.push_str(&AXES.header_with(&axis_names(m), false));
    for (t, q) in w.targets.iter().zip(track.rows()) {
        let _ = write!(s, "{}", t.x);
        for (a, v) in q.iter().enumerate() {
            let _ = write!(s, ",{}", nc(m, a, *v));
        }
        s.push('\n');
    }
    s.into_bytes()
}

/// The machine's axes' names in its order, for the headers.
fn axis_names(m: &Machine) -> Vec<&str> {
    m.axes.iter().map(|a| a.name.as_str()).collect()
}

fn band_csv(m: &Machine, w: &Wound, passed: &BandPassed) -> Vec<u8> {
    let points: Vec<&str> = m
        .roles
        .band_path
        .iter()
        .map(|&k| m.points[k].name.as_str())
        .collect();
    let mut s = BAND.header_with(&points, false);
    for (t, row) in w.targets.iter().zip(passed.rows()) {
        let _ = write!(s, "{}", t.x);
        for v in row {
            let _ = write!(s, ",{v}");
        }
        s.push('\n');
    }
    s.into_bytes()
}

fn add_axes_summary(
    summary: &mut Value,
    m: &Machine,
    source: &MachineSource,
    t: &AxisTrack,
    passed: Option<&[f64]>,
) {
    let issues: Vec<Value> = t
        .issues
        .iter()
        .map(|i| {
            json!({
                "kind": i.kind,
                "axis": i.axis,
                "x": i.x,
                "count": i.count,
                "worst": i.worst,
            })
        })
        .collect();
    let range: Vec<Value> = m
        .axes
        .iter()
        .enumerate()
        .map(|(a, ax)| {
            let lo = t.rows().map(|q| nc(m, a, q[a])).fold(f64::INFINITY, f64::min);
            let hi = t.rows().map(|q| nc(m, a, q[a])).fold(f64::NEG_INFINITY, f64::max);
            json!({ "axis": ax.name, "min": lo, "max": hi, "unit": if ax.is_rotary() { "deg" } else { "mm" } })
        })
        .collect();
    if let Some(obj) = summary.as_object_mut() {
        obj.insert("machine".into(), json!(m.name));
        insert_source(obj, source);
        obj.insert(
            "axes".into(),
            json!(m.axes.iter().map(|a| a.name.clone()).collect::<Vec<_>>()),
        );
        obj.insert("limits_ok".into(), json!(t.limits_ok()));
        obj.insert("max_ik_residual_mm".into(), json!(t.max_residual_mm()));
        obj.insert(
            "max_ik_orientation_residual".into(),
            json!(t.residual_orientation.iter().copied().fold(0.0, f64::max)),
        );
        obj.insert(
            "ik_method".into(),
            json!(if t.closed_form {
                "closed-form"
            } else {
                "solver"
            }),
        );
        obj.insert("ik_issues".into(), json!(issues));
        obj.insert("axis_ranges".into(), json!(range));
        if let Some(p) = passed {
            let names: Map<String, Value> = m
                .roles
                .band_path
                .iter()
                .zip(p)
                .map(|(&k, v)| (m.points[k].name.clone(), json!(v)))
                .collect();
            obj.insert("band_passed_per_circuit_mm".into(), json!(names));
        }
    }
}

fn eye_csv(t: &EyeTrajectory) -> Vec<u8> {
    let mut s = String::with_capacity(t.points.len() * 200);
    s.push_str(&EYE.header());
    for p in &t.points {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            p.x, p.z, p.r, p.v, p.alpha, p.l, p.eye_z, p.eye_r, p.eye_v, p.lambda, p.u, p.margin
        );
    }
    s.into_bytes()
}

/// `blocks.csv`: every block of the program with its time, the axes at its
/// end (NC units), its layer, least time and `mu`.
fn blocks_csv(m: &Machine, p: &Assembled) -> Vec<u8> {
    let mut csv = BLOCKS.header_with(&axis_names(m), false);
    for (n, b) in p.blocks.iter().enumerate() {
        let _ = write!(csv, "{},{}", n + 1, b.t);
        for v in &b.target {
            let _ = write!(csv, ",{v}");
        }
        let _ = writeln!(csv, ",{},{},{}", b.layer, b.t_star, b.t_star / b.t);
    }
    csv.into_bytes()
}

/// The axes over the whole program (`t` in s since its start, then each axis in
/// NC units, at its start and at every block's end) and their ranges over every
/// block as summary JSON.
fn program_axes(m: &Machine, p: &Assembled) -> (Vec<u8>, Value) {
    let program = &p.program;
    let mut csv = String::with_capacity(program.blocks.len() * 16 * (m.axes.len() + 1));
    csv.push_str(&PROGRAM_AXES.header_with(&axis_names(m), false));
    let mut lo = vec![f64::INFINITY; m.axes.len()];
    let mut hi = vec![f64::NEG_INFINITY; m.axes.len()];
    let mut t = 0.0;
    for b in &program.blocks {
        if let formcam_nc::Feed::InverseTime(dt) = b.feed {
            t += dt;
        }
        let _ = write!(csv, "{t}");
        for (a, v) in b.target.iter().enumerate() {
            let _ = write!(csv, ",{v}");
            if a < lo.len() {
                lo[a] = lo[a].min(*v);
                hi[a] = hi[a].max(*v);
            }
        }
        csv.push('\n');
    }
    let ranges = m
        .axes
        .iter()
        .enumerate()
        .map(|(a, ax)| {
            json!({
                "axis": ax.name,
                "min": lo[a],
                "max": hi[a],
                "unit": if ax.is_rotary() { "deg" } else { "mm" },
            })
        })
        .collect();
    (csv.into_bytes(), Value::Array(ranges))
}
