//! `formcam wind ...` and the demo.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use formcam_winding::job::{MandrelSpec, WindingSpec};
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

/// Plans the layer of a job; errors name the job file and the field.
fn plan(job_path: &Path) -> Result<(formcam_winding::job::Mandrel, Layer), CliError> {
    let job = read_job(job_path)?;
    let here = |e: formcam_winding::WindingError| CliError(format!("{}: {e}", job_path.display()));
    let mspec = job
        .mandrel
        .ok_or_else(|| CliError(format!("{}: [mandrel]: missing table", job_path.display())))?;
    let wspec = job
        .winding
        .ok_or_else(|| CliError(format!("{}: [winding]: missing table", job_path.display())))?;
    let dir = job_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mandrel = mspec
        .build(|name| {
            let p: PathBuf = dir.join(name);
            fs::read_to_string(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
        })
        .map_err(here)?;
    let spec = wspec.layer_spec(&mandrel).map_err(here)?;
    let layer = plan_layer(&mandrel, &spec).map_err(here)?;
    Ok((mandrel, layer))
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

fn summary_json(job: &Path, kind: &str, layer: &Layer) -> Result<Vec<u8>, CliError> {
    let mu = layer.pass.mu.unwrap_or(layer.pass.mu_max_abs);
    let v = json!({
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
    });
    serde_json::to_vec_pretty(&v).map_err(|e| CliError(format!("summary.json: {e}")))
}

/// `formcam wind path JOB -o OUT`; returns a one-line summary.
pub fn run_path(job: &Path, out: &Path) -> Result<String, CliError> {
    let t0 = Instant::now();
    let (mandrel, layer) = plan(job)?;
    let title = format!(
        "{}: {} mandrel, one pass",
        job.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        mandrel.kind()
    );
    let files = [
        ("path.csv", path_csv(&layer)),
        ("summary.json", summary_json(job, mandrel.kind(), &layer)?),
        (
            "path.svg",
            crate::plot::layer_svg(&title, &mandrel, &layer)?,
        ),
    ];
    write_all(out, &files)?;
    let mut line = format!(
        "{}: {} path, mu {:.5}, alpha at equator {:.3} deg, {} circuits (pattern {} skip {}), dwell {:.2} deg, \
         fibre {:.1} m, {:.1} ms -> {}",
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
        let line = run_path(job, &out.join(&name))?;
        println!("{line}");
    }
    println!("{} jobs written under {}", jobs.len(), out.display());
    Ok(())
}
