//! A dressing job (`[wheel]`, `[dresser]`, `[process]`) to its files: the
//! two programs, the CSVs of the profile, the dresser's path, the removal
//! rate and the contours, the plots, `summary.json` (its `job` the job
//! file's absolute path) and the job's text as it ran (`job.toml`).
//!
//! Every table names the wheel's axes as the programs do: `z` along the
//! wheel's axis, `x` radial (mm, the ball's centre at the origin).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use formcam_dress::{Contour, DressError, DressJob, Dressing, Point, dress_with as run_dressing};
use formcam_nc::Dialect;
use formcam_progress::{Phase, Progress, Silent, Step};
use formcam_results::dressing::{
    CONTOUR_FINAL, CONTOUR_INITIAL, CONTOUR_PASSES, DRESSER, MRR, PROFILE,
};
use formcam_results::names::{JOB, MRR_SVG, PROFILE_SVG, SUMMARY};
use serde_json::json;

use crate::files::recorded;
use crate::{ResultFile, RunError, RunOutput};

/// Whether a job's top-level table is a dressing job (it has `[wheel]`).
pub fn is_dress_job(table: &toml::Table) -> bool {
    table.contains_key("wheel")
}

/// Runs the dressing job in the file `job`.
pub fn dress(job: &Path) -> Result<RunOutput, RunError> {
    dress_with(job, &Silent)
}

/// [`dress`] reporting to `progress` (the simulation of forming, the
/// files); [`RunError::Cancelled`] when it asks to stop.
pub fn dress_with(job: &Path, progress: &dyn Progress) -> Result<RunOutput, RunError> {
    let text = formcam_files::read_text(job)
        .map_err(|e| dress_error(job, "", format!("cannot read the job file: {e}")))?;
    dress_text_with(job, &text, progress)
}

/// [`dress`] for a job already read from `job` (which places the files it
/// names and names the job in messages).
pub fn dress_text(job: &Path, text: &str) -> Result<RunOutput, RunError> {
    dress_text_with(job, text, &Silent)
}

/// [`dress_text`] reporting to `progress`.
pub fn dress_text_with(
    job: &Path,
    text: &str,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let parsed = DressJob::from_toml(text).map_err(|e| job_error(job, e))?;
    let warnings = parsed.warnings();
    let mut inputs = vec![job.to_path_buf()];
    let contour_file = parsed
        .process
        .initial_contour
        .as_ref()
        .map(|file| resolve(job, file));
    let initial = match &contour_file {
        Some(path) => {
            let contour = read_initial(path)?;
            inputs.push(path.clone());
            Some(contour)
        }
        None => None,
    };
    // A contour that cannot be dressed (below the profile, narrower than
    // the wheel) is named by its own file.
    let blame = |e: DressError| match (&e, &contour_file) {
        (DressError::Contour(_), Some(path)) => job_error(path, e),
        _ => job_error(job, e),
    };
    let spec = parsed.spec(initial).map_err(blame)?;
    let d = run_dressing(&spec, progress).map_err(blame)?;
    progress.checkpoint(Step::new(Phase::Files, 0, 1))?;
    let cls = d.nc(Dialect::Cldata).map_err(|e| job_error(job, e))?;
    let mpf = d
        .nc(Dialect::Sinumerik840d)
        .map_err(|e| job_error(job, e))?;
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut summary = summary(&recorded(job), &d);
    if let Some(obj) = summary.as_object_mut() {
        obj.insert("warnings".into(), json!(warnings));
    }
    let summary = serde_json::to_vec_pretty(&summary)
        .map_err(|e| dress_error(Path::new(SUMMARY), "", e.to_string()))?;
    let files = vec![
        ResultFile::new(PROFILE.file, profile_csv(&d)),
        ResultFile::new(DRESSER.file, dresser_csv(&d)),
        ResultFile::new(MRR.file, mrr_csv(&d)),
        ResultFile::new(CONTOUR_INITIAL.file, contour_csv(&d.forming.initial)),
        ResultFile::new(CONTOUR_FINAL.file, contour_csv(d.forming.final_contour())),
        ResultFile::new(CONTOUR_PASSES.file, contour_passes_csv(&d)),
        ResultFile::new("program.cls", cls),
        ResultFile::new("program.mpf", mpf),
        ResultFile::new(PROFILE_SVG, formcam_plot::profile_svg(&name, &d)?),
        ResultFile::new(MRR_SVG, formcam_plot::mrr_svg(&name, &d)?),
        ResultFile::new(SUMMARY, summary),
        ResultFile::new(JOB, text),
    ];
    let ratio = |r: Option<f64>| r.map_or("-".to_string(), |r| format!("{r:.2}"));
    let line = format!(
        "{}: {} points, {:.2} s of dressing, removal-rate spread {} -> {} with feed control, \
         {:.1} ms",
        job.display(),
        d.points(),
        d.dressing_time_s(),
        ratio(d.feed.ratio_uncontrolled),
        ratio(d.feed.ratio_controlled),
        t0.elapsed().as_secs_f64() * 1e3,
    );
    progress.checkpoint(Step::new(Phase::Files, 1, 1))?;
    Ok(RunOutput {
        files,
        line,
        warnings,
        inputs,
        violations: None,
    })
}

/// The error of a dressing run: the file, where in it (`:line` or
/// `:line:column`, or empty) and what is wrong.
fn dress_error(file: &Path, at: &str, message: String) -> RunError {
    RunError::Dress {
        file: file.to_path_buf(),
        at: at.to_string(),
        message,
    }
}

/// A dressing error of the job `job`: TOML errors with their line and column.
fn job_error(job: &Path, e: DressError) -> RunError {
    match e {
        DressError::Toml {
            line,
            column,
            message,
        } => dress_error(job, &format!(":{line}:{column}"), message),
        DressError::Cancelled(c) => RunError::Cancelled(c),
        e => dress_error(job, "", e.to_string()),
    }
}

/// A file named in a job: relative to the job's folder if it is there, else
/// to the current folder.
fn resolve(job: &Path, file: &str) -> PathBuf {
    let beside = job.parent().map(|p| p.join(file));
    match beside {
        Some(p) if p.exists() => p,
        _ => PathBuf::from(file),
    }
}

/// The contour of `process.initial_contour`; errors name the file and line.
fn read_initial(path: &Path) -> Result<Vec<Point>, RunError> {
    let text = formcam_files::read_text(path).map_err(|e| {
        dress_error(
            path,
            "",
            format!("process.initial_contour: cannot read: {e}"),
        )
    })?;
    formcam_dress::read_contour(&text).map_err(|e| match e {
        DressError::ContourLine { line, problem } => dress_error(
            path,
            &format!(":{line}"),
            format!("process.initial_contour: {problem}"),
        ),
        e => dress_error(path, "", e.to_string()),
    })
}

/// Points as `z,x` rows (the profile's `x` along the axis is the program's
/// `z`, its radial `y` the program's `x`).
fn zx_csv(points: &[Point]) -> Vec<u8> {
    let mut s = PROFILE.header();
    for p in points {
        let _ = writeln!(s, "{:.9},{:.9}", p.x, p.y);
    }
    s.into_bytes()
}

fn profile_csv(d: &Dressing) -> Vec<u8> {
    zx_csv(&d.profile.sample(d.step))
}

fn contour_csv(c: &Contour) -> Vec<u8> {
    zx_csv(c.points())
}

/// The contour after each pass, pass after pass: `z,x,pass` (1-based).
fn contour_passes_csv(d: &Dressing) -> Vec<u8> {
    let mut s = CONTOUR_PASSES.header();
    for (i, c) in d.forming.after_pass.iter().enumerate() {
        for p in c.points() {
            let _ = writeln!(s, "{:.9},{:.9},{}", p.x, p.y, i + 1);
        }
    }
    s.into_bytes()
}

fn dresser_csv(d: &Dressing) -> Vec<u8> {
    let mut s = DRESSER.header();
    for (i, pass) in d.passes.iter().enumerate() {
        for p in &pass.points {
            let _ = writeln!(
                s,
                "{:.9},{:.9},{},{},{:.9},{:.9}",
                p.reference.x,
                p.reference.y,
                i + 1,
                p.stage.name(),
                p.centre.x,
                p.centre.y
            );
        }
    }
    s.into_bytes()
}

fn mrr_csv(d: &Dressing) -> Vec<u8> {
    let vol = d.volume_factor();
    let mut s = MRR.header_with(&[], vol.is_some());
    let f = &d.feed;
    for (k, st) in d.forming.steps.iter().enumerate() {
        let r = d.passes.get(st.pass).map_or(0.0, |p| p.radius);
        let analogue = 0.5 * (r * st.cut_angle).powi(2);
        let _ = write!(
            s,
            "{:.9},{:.9},{:.6e},{:.6},{:.4},{},{},{:.9},{:.9},{:.4},{:.6},{:.6},{:.6e},{}",
            st.reference.x,
            st.reference.y,
            st.area,
            f.mrr[k],
            f.feed[k],
            st.pass + 1,
            st.stage.name(),
            st.length,
            st.area_per_mm(),
            f.required[k],
            f.mrr_uncontrolled[k],
            st.cut_angle,
            analogue,
            u8::from(st.steady)
        );
        if let Some(v) = vol {
            let _ = write!(s, ",{:.6},{:.6}", f.mrr[k] * v, f.mrr_uncontrolled[k] * v);
        }
        s.push('\n');
    }
    s.into_bytes()
}

/// The summary of `d`, the job file `job` as the result records it.
fn summary(job: &str, d: &Dressing) -> serde_json::Value {
    let f = &d.feed;
    let fs = &d.feed_spec;
    let (removed, between) = (d.forming.removed(), d.forming.area_between());
    let (dev_lo, dev_hi) = d.forming.deviation(&d.profile, d.step);
    let joints = d.profile.joints();
    let [cr, cl] = d.profile.contacts();
    let held = (0..f.feed.len()).filter(|&k| f.held(k)).count();
    let steady = d.forming.steps.iter().filter(|s| s.steady).count();
    // Steady steps whose rate is more than 5 % off the target: where the
    // feed is free (at neither limit and not held by the change limit), and
    // where the change limit holds it.
    let off = |k: usize| {
        let s = &d.forming.steps[k];
        s.steady
            && s.length > 0.0
            && (s.area / s.length * f.feed[k] / f.target - 1.0).abs() > 0.05
            && !f.at_bound(k, fs)
    };
    let off_free = (0..f.feed.len()).filter(|&k| off(k) && !f.held(k)).count();
    let off_held = (0..f.feed.len()).filter(|&k| off(k) && f.held(k)).count();
    let merged = d.forming.steps.len() - d.step_block.last().map_or(0, |b| b + 1);
    let fmin = f.feed.iter().copied().fold(f64::INFINITY, f64::min);
    let fmax = f.feed.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let passes: Vec<serde_json::Value> = d
        .passes
        .iter()
        .zip(1..)
        .map(|(p, i)| {
            let start = p.points.first().map(|q| q.reference).unwrap_or_default();
            json!({
                "pass": i,
                "side": p.side.name(),
                "corner_radius_mm": p.radius,
                "start_z_mm": start.x,
                "start_x_mm": start.y,
                "steps": p.points.len().saturating_sub(1),
            })
        })
        .collect();
    let mut v = json!({
        "job": job,
        "points": d.points(),
        "dressing_time_s": d.dressing_time_s(),
        "mrr_ratio_uncontrolled": f.ratio_uncontrolled,
        "mrr_ratio_controlled": f.ratio_controlled,
        "mrr_ratio_all_steps_uncontrolled": f.ratio_all_uncontrolled,
        "mrr_ratio_all_steps_controlled": f.ratio_all_controlled,
        "target_mrr_mm2_min": f.target,
        "target_given": f.target_given,
        "feed_uncontrolled_mm_min": f.feed_uncontrolled,
        "feed_used_min_mm_min": fmin,
        "feed_used_max_mm_min": fmax,
        "feed_change_max_mm_min": f.change_max,
        "feed_limits_mm_min": [fs.feed_min, fs.feed_max],
        "steps": d.forming.steps.len(),
        "steps_steady": steady,
        "steps_feed_held_by_change_limit": held,
        "steps_off_target_feed_free": off_free,
        "steps_off_target_feed_held": off_held,
        "steps_merged_below_resolution": merged,
        "step_mm": d.step,
        "chord_mm": d.forming.chord,
        "removed_area_mm2": removed,
        "area_between_contours_mm2": between,
        "area_identity_rel_error": (removed - between) / between,
        "final_deviation_min_mm": dev_lo,
        "final_deviation_max_mm": dev_hi,
        "scallop_bound_mm": d.scallop_bound(),
        "clearance_mm": d.profile.clearance(),
        "profile_height_mm": d.profile.height(),
        "contact_angles_deg": [cr.angle.to_degrees(), cl.angle.to_degrees()],
        "contact_gaps_mm": [cr.gap, cl.gap],
        "joint_gap_mm": joints.gap,
        "joint_angle_rad": joints.angle,
        "apex_angle_rad": joints.apex_angle,
        "passes": passes,
        "point_a_yo_mm": d.dresser.yo,
    });
    if let (Some(factor), Some(obj)) = (d.volume_factor(), v.as_object_mut()) {
        obj.insert("target_mrr_mm3_min".into(), json!(f.target * factor));
        obj.insert("wheel_circumference_mm".into(), json!(factor));
    }
    v
}
