//! `formcam wind ...` and the demo.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use formcam_winding::eye::{EyeSpec, EyeTrajectory, eye_trajectory};
use formcam_winding::job::{EyeJob, Mandrel, MandrelSpec, WindingSpec};
use formcam_winding::{Layer, plan_layer};
use serde::Deserialize;
use serde_json::json;

use crate::CliError;
use crate::output::write_all;

/// A job file. Tables of other processes are kept for their commands.
#[derive(Debug, Deserialize)]
struct Job {
    mandrel: Option<MandrelSpec>,
    winding: Option<WindingSpec>,
    eye: Option<EyeJob>,
    #[serde(flatten)]
    _other: BTreeMap<String, toml::Value>,
}

fn read_job(path: &Path) -> Result<Job, CliError> {
    let text = fs::read_to_string(path)
        .map_err(|e| CliError(format!("{}: cannot read the job file: {e}", path.display())))?;
    toml::from_str(&text).map_err(|e| {
        let (line, col) = e.span().map_or((0, 0), |s| line_col(&text, s.start));
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

/// A job read and planned.
struct Planned {
    mandrel: Mandrel,
    layer: Layer,
    eye: Option<EyeSpec>,
}

/// Plans the layer of a job; errors name the job file and the field.
fn plan(job_path: &Path) -> Result<Planned, CliError> {
    let job = read_job(job_path)?;
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
    let eye = job.eye.map(|e| e.spec(read)).transpose().map_err(here)?;
    let layer = plan_layer(&mandrel, &spec).map_err(here)?;
    Ok(Planned {
        mandrel,
        layer,
        eye,
    })
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

/// `formcam wind path JOB -o OUT`; returns a one-line summary.
pub fn run_path(job: &Path, out: &Path) -> Result<String, CliError> {
    run(job, out, false)
}

/// `formcam wind eye JOB -o OUT`: the path outputs plus the eye trajectory.
pub fn run_eye(job: &Path, out: &Path) -> Result<String, CliError> {
    run(job, out, true)
}

fn run(job: &Path, out: &Path, with_eye: bool) -> Result<String, CliError> {
    let t0 = Instant::now();
    let Planned {
        mandrel,
        layer,
        eye,
    } = plan(job)?;
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let title = format!("{name}: {} mandrel, one pass", mandrel.kind());
    let mut summary = summary_value(job, mandrel.kind(), &layer);
    let mut files = vec![
        ("path.csv", path_csv(&layer)),
        (
            "path.svg",
            crate::plot::layer_svg(&title, &mandrel, &layer)?,
        ),
    ];
    let mut eye_line = String::new();
    if with_eye {
        let spec =
            eye.ok_or_else(|| CliError(format!("{}: [eye]: missing table", job.display())))?;
        let traj = eye_trajectory(&mandrel, &layer, &spec)
            .map_err(|e| CliError(format!("{}: {e}", job.display())))?;
        add_eye_summary(&mut summary, &traj);
        files.push(("eye.csv", eye_csv(&traj)));
        files.push((
            "eye.svg",
            crate::plot::eye_svg(&format!("{name}: payout eye over one circuit"), &traj)?,
        ));
        eye_line = format!(
            "; eye {}: u in [{:.4}, {:.4}], rms {:.4}, constraints {}",
            serde_json::to_value(traj.mode)
                .ok()
                .and_then(|v| v.as_str().map(String::from))
                .unwrap_or_default(),
            traj.stats.u_min,
            traj.stats.u_max,
            traj.stats.u_rms_dev,
            if traj.constraints_ok {
                "ok"
            } else {
                "VIOLATED"
            }
        );
    }
    let json =
        serde_json::to_vec_pretty(&summary).map_err(|e| CliError(format!("summary.json: {e}")))?;
    files.push(("summary.json", json));
    write_all(out, &files)?;
    let mut line = format!(
        "{}: {} path, mu {:.5}, alpha at equator {:.3} deg, {} circuits (pattern {} skip {}), dwell {:.2} deg, \
         fibre {:.1} m{eye_line}, {:.1} ms -> {}",
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
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    jobs.sort();
    if jobs.is_empty() {
        return Err(CliError(format!(
            "{}: no *.toml jobs found",
            examples.display()
        )));
    }
    for job in &jobs {
        let name = job
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let has_eye = read_job(job)?.eye.is_some();
        let line = run(job, &out.join(&name), has_eye)?;
        println!("{line}");
    }
    println!("{} jobs written under {}", jobs.len(), out.display());
    Ok(())
}
