//! `formcam wind ...` and the demo.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use formcam_machine::{AxisTrack, IkMethod, MachineKind, solve};
use formcam_machine::{Machine, Target, band_passed, placement_targets, winder_targets};
use formcam_winding::eye::{EyeSpec, EyeTrajectory, eye_trajectory};
use formcam_winding::job::{EyeJob, LayerKind, Mandrel, MandrelSpec, WindingSpec};
use formcam_winding::{Circuit, Layer, plan_layer};
use serde::Deserialize;
use serde_json::json;

use crate::CliError;
use crate::checks::{Check, ChecksJob};
use crate::output::write_all;
use crate::program::{MotionJob, PostJob, nc};

/// A winding job file: a table it does not know (a misspelt `[motoin]`) is an
/// error.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Job {
    mandrel: Option<MandrelSpec>,
    winding: Option<WindingSpec>,
    eye: Option<EyeJob>,
    machine: Option<MachineJob>,
    /// Multi-layer jobs: one table per layer, in winding order.
    layer: Option<Vec<WindingSpec>>,
    motion: Option<MotionJob>,
    post: Option<PostJob>,
    /// Failed checks the job accepts.
    checks: Option<ChecksJob>,
}

fn read_job(path: &Path) -> Result<Job, CliError> {
    let text = fs::read_to_string(path)
        .map_err(|e| CliError(format!("{}: cannot read the job file: {e}", path.display())))?;
    parse_job(path, &text)
}

/// A winding job from the text of `path`.
fn parse_job(path: &Path, text: &str) -> Result<Job, CliError> {
    toml::from_str(text).map_err(|e| {
        let (line, col) = e.span().map_or((0, 0), |s| line_col(text, s.start));
        let msg = e.message().replace('\n', " ");
        CliError(format!("{}:{line}:{col}: {msg}", path.display()))
    })
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// The `[machine]` table of a job.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MachineJob {
    /// The machine file, relative to the job's folder or the current one.
    file: String,
    /// `auto` (default), `solver` or `closed-form`.
    ik: Option<String>,
}

/// A job read and planned.
struct Planned {
    mandrel: Mandrel,
    layer: Layer,
    eye: Option<EyeSpec>,
    machine: Option<(PathBuf, IkMethod)>,
    motion: MotionJob,
    post: PostJob,
    checks: Vec<Check>,
    /// Implausible values, one line each naming the field.
    warnings: Vec<String>,
}

/// The machine file and IK method a job's `[machine]` names.
fn machine_of(
    job_path: &Path,
    dir: &Path,
    mj: &MachineJob,
) -> Result<(PathBuf, IkMethod), CliError> {
    let method = match mj.ik.as_deref() {
        None | Some("auto") => IkMethod::Auto,
        Some("solver") => IkMethod::Solver,
        Some("closed-form") => IkMethod::ClosedForm,
        Some(other) => {
            return Err(CliError(format!(
                "{}: machine.ik: \"{other}\" is not one of auto, solver, closed-form",
                job_path.display()
            )));
        }
    };
    let near = dir.join(&mj.file);
    let file = if near.exists() {
        near
    } else {
        PathBuf::from(&mj.file)
    };
    if !file.exists() {
        return Err(CliError(format!(
            "{}: machine.file: \"{}\" not found (looked in the job's folder and the current one)",
            job_path.display(),
            mj.file
        )));
    }
    Ok((file, method))
}

/// What the machine must reach over a circuit of `layer`: the eye trajectory's
/// points (winders) or the path with the roller's radius (placement heads).
fn targets_for(
    m: &Machine,
    mandrel: &Mandrel,
    layer: &Layer,
    traj: Option<&EyeTrajectory>,
    eye: Option<&EyeSpec>,
) -> Vec<Target> {
    match traj {
        Some(t) => winder_targets(mandrel, t),
        None => {
            let circuit = Circuit::new(mandrel, layer);
            let n = eye.map_or(2000, |e| e.samples - 1);
            let path: Vec<_> = circuit
                .points(n)
                .iter()
                .map(|p| (p.x, p.z, p.r, p.v, p.alpha))
                .collect();
            placement_targets(mandrel, &path, m.roles.roller_radius)
        }
    }
}

/// Plans the layer of a job; errors name the job file and the field.
fn plan(job_path: &Path, job: Job) -> Result<Planned, CliError> {
    let here = |e: formcam_winding::WindingError| CliError(format!("{}: {e}", job_path.display()));
    let mspec = job
        .mandrel
        .ok_or_else(|| CliError(format!("{}: [mandrel]: missing table", job_path.display())))?;
    let wspec = job
        .winding
        .ok_or_else(|| CliError(format!("{}: [winding]: missing table", job_path.display())))?;
    let dir = job_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let read = |name: &str| {
        let p: PathBuf = dir.join(name);
        fs::read_to_string(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let mandrel = mspec.build(read).map_err(here)?;
    let spec = wspec.layer_spec(&mandrel).map_err(here)?;
    let mut warnings = mspec.warnings();
    warnings.extend(wspec.warnings(&mandrel));
    let eye = job.eye.map(|e| e.spec(read)).transpose().map_err(here)?;
    let machine = job
        .machine
        .map(|mj| machine_of(job_path, &dir, &mj))
        .transpose()?;
    let layer = plan_layer(&mandrel, &spec).map_err(here)?;
    Ok(Planned {
        mandrel,
        layer,
        eye,
        machine,
        motion: job.motion.unwrap_or_default(),
        post: job.post.unwrap_or_default(),
        checks: job.checks.unwrap_or_default().allow,
        warnings,
    })
}

/// Prints implausible values on stderr, one line each naming the job.
fn warn(job: &Path, warnings: &[String]) {
    for w in warnings {
        eprintln!("formcam: warning: {}: {w}", job.display());
    }
}

fn path_csv(layer: &Layer) -> Vec<u8> {
    let mut s = String::with_capacity(layer.points.len() * 120);
    s.push_str("s,z,r,v,alpha,c,mu,alpha_deg,thickness\n");
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

fn summary_value(job: &Path, kind: &str, layer: &Layer) -> serde_json::Value {
    let mu = layer.pass.mu.unwrap_or(layer.pass.mu_max_abs);
    json!({
        "job": job.display().to_string(),
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

/// How far a `wind` command goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// The path, the pattern and the layer report.
    Path,
    /// ... and the payout eye's trajectory.
    Eye,
    /// ... and the machine's axes.
    Axes,
    /// ... and the NC program (blocks, times, post-processor).
    Program,
}

/// `formcam wind [path|eye|axes] JOB -o OUT`; returns a one-line summary.
pub fn run(job: &Path, out: &Path, stage: Stage) -> Result<String, CliError> {
    run_job(job, read_job(job)?, out, stage)
}

/// [`run`] for a job already read from `job`.
fn run_job(job: &Path, table: Job, out: &Path, stage: Stage) -> Result<String, CliError> {
    if table.layer.is_some() {
        return if stage == Stage::Program {
            run_layers(job, table, out)
        } else {
            Err(CliError(format!(
                "{}: [[layer]]: a multi-layer job runs as a whole program (`formcam wind JOB -o \
                 OUT`); path, eye and axes take one [winding]",
                job.display()
            )))
        };
    }
    let t0 = Instant::now();
    let Planned {
        mandrel,
        layer,
        eye,
        machine,
        motion,
        post,
        checks,
        warnings,
    } = plan(job, table)?;
    warn(job, &warnings);
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let title = format!("{name}: {} mandrel, one pass", mandrel.kind());
    let mut summary = summary_value(job, mandrel.kind(), &layer);
    if let Some(w) = summary.get_mut("warnings").and_then(|w| w.as_array_mut()) {
        w.extend(warnings.iter().map(|s| json!(s)));
    }
    let mut files: Vec<(String, Vec<u8>)> = vec![
        ("path.csv".to_string(), path_csv(&layer)),
        (
            "path.svg".to_string(),
            formcam_plot::layer_svg(&title, &mandrel, &layer)?,
        ),
    ];
    let mut eye_line = String::new();
    let mut program_line = String::new();
    let machine = if stage >= Stage::Axes {
        let (file, method) = machine
            .ok_or_else(|| CliError(format!("{}: [machine]: missing table", job.display())))?;
        Some((crate::machine::load(&file)?, file, method))
    } else {
        None
    };
    let placement = machine
        .as_ref()
        .is_some_and(|(m, _, _)| m.roles.kind == MachineKind::Placement);
    let mut traj = None;
    if stage >= Stage::Eye && !placement {
        let spec = eye
            .as_ref()
            .ok_or_else(|| CliError(format!("{}: [eye]: missing table", job.display())))?;
        let t = eye_trajectory(&mandrel, &layer, spec)
            .map_err(|e| CliError(format!("{}: {e}", job.display())))?;
        add_eye_summary(&mut summary, &t);
        files.push(("eye.csv".to_string(), eye_csv(&t)));
        files.push((
            "eye.svg".to_string(),
            formcam_plot::eye_svg(&format!("{name}: payout eye over one circuit"), &t)?,
        ));
        eye_line = format!(
            "; eye {}: u in [{:.4}, {:.4}], rms {:.4}, constraints {}",
            serde_json::to_value(t.mode)
                .ok()
                .and_then(|v| v.as_str().map(String::from))
                .unwrap_or_default(),
            t.stats.u_min,
            t.stats.u_max,
            t.stats.u_rms_dev,
            if t.constraints_ok { "ok" } else { "VIOLATED" }
        );
        traj = Some(t);
    }
    if let Some((m, file, method)) = &machine {
        let targets = targets_for(m, &mandrel, &layer, traj.as_ref(), eye.as_ref());
        let track = solve(m, &targets, *method)
            .map_err(|e| CliError(format!("{}: {}: {e}", job.display(), file.display())))?;
        let passed = band_passed(m, &targets, &track);
        files.push(("axes.csv".to_string(), axes_csv(m, &targets, &track)));
        if !m.roles.band_path.is_empty() {
            files.push(("band.csv".to_string(), band_csv(m, &targets, &passed)));
        }
        add_axes_summary(&mut summary, m, file, &track, passed.last());
        if stage == Stage::Program {
            let stem = job
                .file_stem()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let mut layer_blocks = crate::program::layer_blocks(
                job,
                "layer 1",
                m,
                &targets,
                &track,
                &motion,
                layer.pattern.circuits,
            )?;
            if let Some(t) = &traj {
                layer_blocks
                    .violated
                    .extend(crate::checks::eye_violations("layer 1", &t.violations));
            }
            crate::checks::enforce(job, &checks, &layer_blocks.violated)?;
            let built =
                crate::program::write_program(job, &stem, m, &[layer_blocks], &motion, &post)?;
            crate::checks::enforce(job, &checks, &built.violated)?;
            files.extend(built.files);
            if let Some(obj) = summary.as_object_mut() {
                obj.extend(built.summary);
            }
            program_line = built.line;
        }
        let _ = write!(
            eye_line,
            "; axes {} on {} ({}): limits {}, IK residual {:.2e} mm{}",
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
            if track.issues.is_empty() {
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
            }
        );
    }
    let json =
        serde_json::to_vec_pretty(&summary).map_err(|e| CliError(format!("summary.json: {e}")))?;
    files.push(("summary.json".to_string(), json));
    write_all(out, &files)?;
    let mut line = format!(
        "{}: {} path, mu {:.5}, alpha at equator {:.3} deg, {} circuits (pattern {} skip {}), dwell {:.2} deg, \
         fibre {:.1} m{eye_line}{program_line}, {:.1} ms -> {}",
        job.display(),
        serde_json::to_value(layer.pass.method)
            .ok()
            .and_then(|v| v.as_str().map(String::from))
            .unwrap_or_default(),
        layer.pass.mu.unwrap_or(layer.pass.mu_max_abs),
        layer.report.alpha_equator_rad.to_degrees(),
        layer.pattern.circuits,
        layer.pattern.pattern_number,
        layer.pattern.skip_index,
        layer.report.dwell_deg,
        layer.report.fibre_length_mm / 1000.0,
        t0.elapsed().as_secs_f64() * 1e3,
        out.display()
    );
    for w in &layer.warnings {
        let _ = write!(line, "\n  warning: {w}");
    }
    Ok(line)
}

fn add_eye_summary(summary: &mut serde_json::Value, t: &EyeTrajectory) {
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

/// A multi-layer job (`[[layer]]`): each layer planned on the mandrel grown by
/// the layers before it, its circuits cut into blocks and timed, and all of them
/// written as one program.
fn run_layers(job_path: &Path, job: Job, out: &Path) -> Result<String, CliError> {
    let at = |msg: String| CliError(format!("{}: {msg}", job_path.display()));
    if job.winding.is_some() {
        return Err(at("[winding] and [[layer]]: give one of them".into()));
    }
    let mspec = job
        .mandrel
        .ok_or_else(|| at("[mandrel]: missing table".into()))?;
    let dir = job_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let (file, method) = job
        .machine
        .as_ref()
        .map(|mj| machine_of(job_path, &dir, mj))
        .transpose()?
        .ok_or_else(|| at("[machine]: missing table (a program needs a machine)".into()))?;
    let m = crate::machine::load(&file)?;
    if job.layer.as_ref().is_some_and(Vec::is_empty) {
        return Err(at("[[layer]]: no layers".into()));
    }
    run_layered(
        job_path,
        Layered {
            mandrel: mspec,
            layers: job.layer.unwrap_or_default(),
            eye: job.eye,
            machine: (m, file, method),
            motion: job.motion.unwrap_or_default(),
            post: job.post.unwrap_or_default(),
            checks: job.checks.unwrap_or_default().allow,
            warnings: Vec::new(),
            summary: serde_json::Map::new(),
        },
        out,
    )
}

/// `formcam wind JOB.wind -o OUT [--eye-clearance MM]`: a Cyclone/FiberPath job
/// on the X/A/B winder with its eye `eye_clearance` mm over the mandrel, written
/// for Marlin X/A/B.
///
/// The format knows no eye: FiberPath's machines lay the band where `X` says
/// and take up a little slack at the turn-arounds with their tensioner, so the
/// eye's `slack` check is accepted (and reported); `allow` accepts more.
pub fn run_wind_file(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
) -> Result<String, CliError> {
    let imported = crate::windfile::read(path, eye_clearance)?;
    let label = PathBuf::from("machines/winder-xab.toml (built in)");
    let m = crate::machine::parse(&label, &crate::windfile::machine_text(imported.eye_radius)?)?;
    let mut summary = serde_json::Map::new();
    summary.insert("schema_version".into(), json!(imported.schema_version));
    summary.insert("eye_radius_mm".into(), json!(imported.eye_radius));
    summary.insert("eye_clearance_mm".into(), json!(imported.eye_clearance));
    let line = run_layered(
        path,
        Layered {
            mandrel: imported.mandrel,
            layers: imported.layers,
            eye: Some(imported.eye),
            machine: (m, label, IkMethod::Auto),
            motion: MotionJob::default(),
            post: PostJob {
                dialect: Some("marlin-xab".into()),
                template: None,
            },
            checks: [Check::Slack].iter().chain(allow).copied().collect(),
            warnings: imported.warnings,
            summary,
        },
        out,
    )?;
    Ok(format!(
        "{line}; eye {:.1} mm from the axis ({:.1} mm over the mandrel)",
        imported.eye_radius, imported.eye_clearance
    ))
}

/// Output files: name and contents.
type Files = Vec<(String, Vec<u8>)>;

/// A multi-layer job, read from TOML or imported.
struct Layered {
    mandrel: MandrelSpec,
    layers: Vec<WindingSpec>,
    eye: Option<EyeJob>,
    machine: (Machine, PathBuf, IkMethod),
    motion: MotionJob,
    post: PostJob,
    /// Failed checks the job accepts.
    checks: Vec<Check>,
    /// Warnings found while reading the job.
    warnings: Vec<String>,
    /// Summary fields of the job's reader.
    summary: serde_json::Map<String, serde_json::Value>,
}

fn run_layered(job_path: &Path, job: Layered, out: &Path) -> Result<String, CliError> {
    let t0 = Instant::now();
    let at = |msg: String| CliError(format!("{}: {msg}", job_path.display()));
    let dir = job_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let read = |name: &str| {
        let p: PathBuf = dir.join(name);
        fs::read_to_string(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let Layered {
        mandrel: mspec,
        layers,
        eye,
        machine: (m, file, method),
        motion,
        post,
        checks,
        mut warnings,
        summary: read_summary,
    } = job;
    warnings.extend(mspec.warnings());
    let eye = eye
        .map(|e| e.spec(read))
        .transpose()
        .map_err(|e| at(e.to_string()))?;
    let tau = motion.tau_s.unwrap_or(0.004);
    // 1. Plan every layer in order: each on the mandrel grown by those before.
    enum LayerPlan {
        Skip(f64),
        Wind {
            mandrel: Box<Mandrel>,
            z_shift: f64,
            layer: Box<Layer>,
            grown: f64,
            thickness: f64,
        },
    }
    let mut grown = 0.0;
    let mut plans = Vec::with_capacity(layers.len());
    for (i, w) in layers.iter().enumerate() {
        // Errors name the layer: `layer[2].band_width`.
        let field = |e: formcam_winding::WindingError| {
            at(e.to_string()
                .replacen("winding.", &format!("layer[{}].", i + 1), 1))
        };
        if w.kind == Some(LayerKind::Skip) {
            let turn = w.mandrel_rotation_deg.ok_or_else(|| {
                at(format!(
                    "layer[{}].mandrel_rotation_deg: missing: how far the mandrel turns, degrees",
                    i + 1
                ))
            })?;
            plans.push(LayerPlan::Skip(turn));
            continue;
        }
        let mandrel = mspec
            .grown(grown)
            .and_then(|g| g.build(read))
            .map_err(field)?;
        // A hoop layer on a vessel covers its cylinder: planned on that cylinder,
        // its targets moved to where the cylinder starts.
        let (mandrel, z_shift) = match (&mandrel, w.kind) {
            (Mandrel::Vessel(v), Some(LayerKind::Hoop)) => {
                let (z1, z2) = v.cylinder_range();
                let cyl = formcam_geom::Cylinder::new(v.radius(), z2 - z1)
                    .map_err(|e| field(e.into()))?;
                (Mandrel::Cylinder(cyl), z1)
            }
            _ => (mandrel, 0.0),
        };
        let spec = w.layer_spec(&mandrel).map_err(field)?;
        warnings.extend(
            w.warnings(&mandrel)
                .into_iter()
                .map(|s| s.replacen("winding.", &format!("layer[{}].", i + 1), 1)),
        );
        let layer = plan_layer(&mandrel, &spec).map_err(field)?;
        // The layer's thickness where the mandrel is widest (one ply of the two
        // for a one-way hoop).
        let plies = if w.one_way == Some(true) { 0.5 } else { 1.0 };
        let thickness = plies
            * layer
                .points
                .iter()
                .zip(&layer.thickness)
                .max_by(|a, b| a.0.r.total_cmp(&b.0.r))
                .map_or(spec.band_thickness, |(_, t)| *t);
        plans.push(LayerPlan::Wind {
            mandrel: Box::new(mandrel),
            z_shift,
            layer: Box::new(layer),
            grown,
            thickness,
        });
        grown += thickness;
    }
    if m.roles.kind != MachineKind::Placement && eye.is_none() {
        return Err(at("[eye]: missing table".into()));
    }
    warn(job_path, &warnings);
    // 2. Eye, axes and blocks of every winding layer, one thread per layer.
    let kind_of = |i: usize| layers[i].kind.unwrap_or_default().to_string();
    let wind = |i: usize, mandrel: &Mandrel, z_shift: f64, layer: &Layer| {
        let label = format!("layer {} ({})", i + 1, kind_of(i));
        let traj = match (&eye, m.roles.kind) {
            (Some(spec), MachineKind::Winder) => {
                Some(eye_trajectory(mandrel, layer, spec).map_err(|e| {
                    at(e.to_string()
                        .replacen("winding.", &format!("layer[{}].", i + 1), 1))
                })?)
            }
            _ => None,
        };
        let mut targets = targets_for(&m, mandrel, layer, traj.as_ref(), eye.as_ref());
        for t in &mut targets {
            t.point.z += z_shift;
            t.path_point.z += z_shift;
        }
        if layers[i].one_way == Some(true) {
            // A terminal hoop: the outgoing pass only.
            let pass = layer.pass_path.length();
            targets.retain(|t| t.x <= pass + 1e-9);
        }
        let track = solve(&m, &targets, method)
            .map_err(|e| at(format!("{label}: {}: {e}", file.display())))?;
        let mut b = crate::program::layer_blocks(
            job_path,
            &label,
            &m,
            &targets,
            &track,
            &motion,
            layer.pattern.circuits,
        )?;
        // The layer's own outputs, as a single-layer job writes them.
        let title = format!("{label}: {} mandrel, one pass", mandrel.kind());
        let mut own: Files = vec![
            ("path.csv".into(), path_csv(layer)),
            (
                "path.svg".into(),
                formcam_plot::layer_svg(&title, mandrel, layer)?,
            ),
        ];
        if let Some(t) = &traj {
            b.violated
                .extend(crate::checks::eye_violations(&label, &t.violations));
            own.push(("eye.csv".into(), eye_csv(t)));
            own.push((
                "eye.svg".into(),
                formcam_plot::eye_svg(&format!("{label}: payout eye over one circuit"), t)?,
            ));
        }
        own.push(("axes.csv".into(), axes_csv(&m, &targets, &track)));
        if !m.roles.band_path.is_empty() {
            let passed = band_passed(&m, &targets, &track);
            own.push(("band.csv".into(), band_csv(&m, &targets, &passed)));
        }
        Ok::<_, CliError>((b, track.limits_ok(), track.max_residual_mm(), own))
    };
    let wound: Vec<Option<Result<_, CliError>>> = std::thread::scope(|s| {
        let handles: Vec<_> = plans
            .iter()
            .enumerate()
            .map(|(i, p)| match p {
                LayerPlan::Wind {
                    mandrel,
                    z_shift,
                    layer,
                    ..
                } => {
                    let wind = &wind;
                    Some(s.spawn(move || wind(i, mandrel, *z_shift, layer)))
                }
                LayerPlan::Skip(_) => None,
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.map(|h| {
                    h.join()
                        .unwrap_or_else(|_| Err(at("a layer's worker thread failed".into())))
                })
            })
            .collect()
    });
    // 3. In order: the layers' blocks (a skip starts where the layer before ends).
    let mut fibre = 0.0;
    let mut blocks: Vec<crate::program::LayerBlocks> = Vec::new();
    let mut per_layer = Vec::new();
    let mut layer_files: Vec<(String, Files)> = Vec::new();
    // Skip layers before the first winding layer turn the mandrel from where
    // that layer starts (else from the machine's home).
    let first_start: Vec<f64> = wound
        .iter()
        .flatten()
        .find_map(|r| r.as_ref().ok().map(|(b, ..)| b.start.clone()))
        .unwrap_or_else(|| {
            m.axes
                .iter()
                .enumerate()
                .map(|(a, ax)| nc(&m, a, ax.home))
                .collect()
        });
    for (i, (plan, result)) in plans.iter().zip(wound).enumerate() {
        let kind = kind_of(i);
        let label = format!("layer {} ({kind})", i + 1);
        match (plan, result) {
            (LayerPlan::Skip(turn), _) => {
                let from = blocks
                    .last()
                    .and_then(|b| b.blocks.last())
                    .map_or_else(|| first_start.clone(), |b| b.0.clone());
                let b = crate::program::skip_blocks(job_path, &label, &m, &from, *turn, tau)?;
                per_layer.push(
                    json!({ "layer": i + 1, "kind": kind, "blocks": 1, "time_s": b.times[0] }),
                );
                blocks.push(b);
            }
            (
                LayerPlan::Wind {
                    layer,
                    grown,
                    thickness,
                    ..
                },
                Some(result),
            ) => {
                let (b, limits_ok, residual, own) = result?;
                layer_files.push((format!("layer-{:02}", i + 1), own));
                per_layer.push(json!({
                    "layer": i + 1,
                    "kind": kind,
                    "mandrel_growth_mm": grown,
                    "alpha_equator_deg": layer.report.alpha_equator_rad.to_degrees(),
                    "circuits": layer.pattern.circuits,
                    "blocks": b.blocks.len(),
                    "time_s": b.times[0],
                    "thickness_mm": thickness,
                    "fibre_length_mm": layer.report.fibre_length_mm,
                    "one_way": layers[i].one_way.unwrap_or(false),
                    "limits_ok": limits_ok,
                    "max_ik_residual_mm": residual,
                }));
                fibre += layer.report.fibre_length_mm;
                blocks.push(b);
            }
            (LayerPlan::Wind { .. }, None) => {
                return Err(at(format!("layer[{}]: not computed", i + 1)));
            }
        }
    }
    let stem = job_path
        .file_stem()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let violated: Vec<_> = blocks.iter().flat_map(|b| b.violated.clone()).collect();
    crate::checks::enforce(job_path, &checks, &violated)?;
    let built = crate::program::write_program(job_path, &stem, &m, &blocks, &motion, &post)?;
    crate::checks::enforce(job_path, &checks, &built.violated)?;
    let mut summary = serde_json::Map::new();
    summary.insert("job".into(), json!(job_path.display().to_string()));
    summary.insert("machine".into(), json!(m.name));
    summary.insert("machine_file".into(), json!(file.display().to_string()));
    summary.insert(
        "axes".into(),
        json!(m.axes.iter().map(|a| a.name.clone()).collect::<Vec<_>>()),
    );
    summary.insert("fibre_length_mm".into(), json!(fibre));
    summary.insert("per_layer".into(), json!(per_layer));
    summary.insert("warnings".into(), json!(warnings));
    summary.extend(read_summary);
    summary.extend(built.summary);
    let json =
        serde_json::to_vec_pretty(&summary).map_err(|e| CliError(format!("summary.json: {e}")))?;
    let mut files = built.files;
    files.push(("axes.csv".to_string(), built.program_axes));
    files.push(("summary.json".to_string(), json));
    for (dir, own) in &layer_files {
        write_all(&out.join(dir), own)?;
    }
    write_all(out, &files)?;
    Ok(format!(
        "{}: {} on {}, fibre {:.1} m{}, {:.1} ms -> {}",
        job_path.display(),
        layers
            .iter()
            .map(|l| l.kind.unwrap_or_default().to_string())
            .collect::<Vec<_>>()
            .join(" + "),
        m.name,
        fibre / 1000.0,
        built.line,
        t0.elapsed().as_secs_f64() * 1e3,
        out.display()
    ))
}

fn axes_csv(m: &Machine, targets: &[Target], track: &AxisTrack) -> Vec<u8> {
    let mut s = String::with_capacity(targets.len() * 16 * (m.axes.len() + 1));
    s.push('x');
    for a in &m.axes {
        let _ = write!(s, ",{}", a.name);
    }
    s.push('\n');
    for (t, q) in targets.iter().zip(track.rows()) {
        let _ = write!(s, "{}", t.x);
        for (a, v) in q.iter().enumerate() {
            let _ = write!(s, ",{}", nc(m, a, *v));
        }
        s.push('\n');
    }
    s.into_bytes()
}

fn band_csv(m: &Machine, targets: &[Target], passed: &[Vec<f64>]) -> Vec<u8> {
    let mut s = String::from("x");
    for &k in &m.roles.band_path {
        let _ = write!(s, ",{}", m.points[k].name);
    }
    s.push('\n');
    for (t, row) in targets.iter().zip(passed) {
        let _ = write!(s, "{}", t.x);
        for v in row {
            let _ = write!(s, ",{v}");
        }
        s.push('\n');
    }
    s.into_bytes()
}

fn add_axes_summary(
    summary: &mut serde_json::Value,
    m: &Machine,
    file: &Path,
    t: &AxisTrack,
    passed: Option<&Vec<f64>>,
) {
    let issues: Vec<serde_json::Value> = t
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
    let range: Vec<serde_json::Value> = m
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
        obj.insert("machine_file".into(), json!(file.display().to_string()));
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
            let names: serde_json::Map<String, serde_json::Value> = m
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
    s.push_str("x,z,r,v,alpha,l,eye_z,eye_r,eye_v,lambda,u,margin\n");
    for p in &t.points {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            p.x, p.z, p.r, p.v, p.alpha, p.l, p.eye_z, p.eye_r, p.eye_v, p.lambda, p.u, p.margin
        );
    }
    s.into_bytes()
}

/// Runs every `*.toml` job in `examples` into `out/<name>/`.
pub fn run_demo(examples: &Path, out: &Path) -> Result<(), CliError> {
    let mut jobs: Vec<PathBuf> = fs::read_dir(examples)
        .map_err(|e| {
            CliError(format!(
                "{}: cannot list the examples: {e}",
                examples.display()
            ))
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml" || x == "wind"))
        .collect();
    jobs.sort();
    if jobs.is_empty() {
        return Err(CliError(format!(
            "{}: no *.toml or *.wind jobs found",
            examples.display()
        )));
    }
    for job in &jobs {
        let name = job
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if job.extension().is_some_and(|x| x == "wind") {
            println!(
                "{}",
                run_wind_file(
                    job,
                    &out.join(&name),
                    crate::windfile::EYE_CLEARANCE_MM,
                    &[]
                )?
            );
            continue;
        }
        let text = fs::read_to_string(job)
            .map_err(|e| CliError(format!("{}: cannot read the job file: {e}", job.display())))?;
        if let Ok(table) = text.parse::<toml::Table>() {
            let dir = out.join(&name);
            if crate::correct::is_scenario(&table) {
                println!("{}", crate::correct::simulate_text(job, &text, &dir)?);
                continue;
            }
            if crate::correct::is_job(&table) {
                println!("{}", crate::correct::run_job_text(job, &text, &dir)?);
                continue;
            }
            if crate::dress::is_job(&table) {
                println!("{}", crate::dress::run_text(job, &text, &dir)?);
                continue;
            }
        }
        let j = parse_job(job, &text)?;
        let stage = if j.machine.is_some() && (j.post.is_some() || j.layer.is_some()) {
            Stage::Program
        } else if j.machine.is_some() {
            Stage::Axes
        } else if j.eye.is_some() {
            Stage::Eye
        } else {
            Stage::Path
        };
        let line = run_job(job, j, &out.join(&name), stage)?;
        println!("{line}");
    }
    println!("{} jobs written under {}", jobs.len(), out.display());
    Ok(())
}
