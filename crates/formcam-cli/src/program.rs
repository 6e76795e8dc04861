//! The whole winding program: the axes cut into blocks, timed, and written by a
//! post-processor (`formcam wind JOB -o OUT`).

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use formcam_machine::Machine;
use formcam_machine::Target;
use formcam_machine::ik::AxisTrack;
use formcam_motion::{
    AxisLimits, Timing, Tolerance, check_timing, deltas, fit_blocks, global, pairwise,
    preliminary_times,
};
use formcam_nc::{AxisSpec, Block, Dialect, Feed, Program, Template, write, write_template};
use serde::Deserialize;
use serde_json::json;

use crate::CliError;

/// The `[motion]` table of a job.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionJob {
    /// Tolerance of the linear axes, mm (default 0.05).
    pub tolerance_mm: Option<f64>,
    /// Tolerance of the rotary axes, degrees (default 0.05).
    pub tolerance_deg: Option<f64>,
    /// Tolerance on the payout point's position, mm (none by default).
    pub position_tolerance_mm: Option<f64>,
    /// The controller's least block time, s (default 0.004).
    pub tau_s: Option<f64>,
    /// Which block times the program uses: `global` (default) or `pairwise`.
    pub times: Option<String>,
}

/// The `[post]` table of a job.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PostJob {
    /// `sinumerik-840d` (default), `iso`, `linuxcnc`, `marlin-xab` or `cldata`.
    pub dialect: Option<String>,
    /// A user post-processor template (TOML), relative to the job's folder.
    pub template: Option<String>,
}

/// What the program stage adds: files, summary fields and a line for the console.
pub struct Built {
    /// Output files.
    pub files: Vec<(String, Vec<u8>)>,
    /// Summary fields.
    pub summary: serde_json::Map<String, serde_json::Value>,
    /// A part of the console line.
    pub line: String,
}

fn positive(job: &Path, field: &str, v: f64) -> Result<f64, CliError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(CliError(format!(
            "{}: {field}: must be a finite number > 0, got {v}",
            job.display()
        )))
    }
}

/// NC units: mm, degrees for rotary axes.
fn nc(m: &Machine, a: usize, v: f64) -> f64 {
    if m.axes[a].is_rotary() {
        v.to_degrees()
    } else {
        v
    }
}

/// Builds the program of one circuit on `m`.
pub fn build(
    job: &Path,
    name: &str,
    m: &Machine,
    targets: &[Target],
    track: &AxisTrack,
    motion: &MotionJob,
    post: &PostJob,
) -> Result<Built, CliError> {
    let here = |msg: String| CliError(format!("{}: {msg}", job.display()));
    // A program must not drive an axis beyond its limits.
    if let Some(i) = track
        .issues
        .iter()
        .find(|i| i.kind == "limit" || i.kind == "unreachable")
    {
        return Err(here(format!(
            "machine: the program would {} at x = {:.3} mm ({} points, worst {:.4}); no program written",
            match (i.kind, &i.axis) {
                ("limit", Some(a)) => format!("drive axis {a} beyond its limit"),
                _ => "miss the eye (unreachable)".to_string(),
            },
            i.x,
            i.count,
            i.worst
        )));
    }
    let w = m.axes.len();
    let tol_mm = positive(
        job,
        "motion.tolerance_mm",
        motion.tolerance_mm.unwrap_or(0.05),
    )?;
    let tol_deg = positive(
        job,
        "motion.tolerance_deg",
        motion.tolerance_deg.unwrap_or(0.05),
    )?;
    let tau = positive(job, "motion.tau_s", motion.tau_s.unwrap_or(0.004))?;
    let position = motion
        .position_tolerance_mm
        .map(|p| positive(job, "motion.position_tolerance_mm", p))
        .transpose()?;
    let tol = Tolerance {
        axes: m
            .axes
            .iter()
            .map(|a| {
                if a.is_rotary() {
                    tol_deg.to_radians()
                } else {
                    tol_mm
                }
            })
            .collect(),
        position_mm: position,
    };
    let x: Vec<f64> = targets.iter().map(|t| t.x).collect();
    // The payout point's deviation where the axes move linearly.
    let payout = m.roles.payout;
    let wanted: Vec<_> = if position.is_some() {
        track.rows().map(|q| m.key_points(q)[payout]).collect()
    } else {
        Vec::new()
    };
    let deviation = |q: &[f64], k: usize| (m.key_points(q)[payout] - wanted[k]).norm();
    let ends = fit_blocks(
        &x,
        &track.values,
        w,
        &tol,
        position.map(|_| &deviation as &dyn Fn(&[f64], usize) -> f64),
    )
    .map_err(|e| here(format!("motion: {e}")))?;
    let limits: Vec<AxisLimits> = m
        .axes
        .iter()
        .map(|a| AxisLimits {
            v_max: a.v_max,
            dv_max: a.dv_max,
        })
        .collect();
    let d = deltas(&track.values, w, &ends);
    let limit_err = |e: formcam_motion::MotionError| here(format!("machine: {e}"));
    let t_star = preliminary_times(&d, &limits, tau).map_err(limit_err)?;
    let pw = pairwise(&d, &t_star, &limits).map_err(limit_err)?;
    let gl = global(&d, &t_star, &limits).map_err(limit_err)?;
    let chosen: &Timing = match motion.times.as_deref() {
        None | Some("global") => &gl,
        Some("pairwise") => &pw,
        Some(other) => {
            return Err(here(format!(
                "motion.times: \"{other}\" is not one of global, pairwise"
            )));
        }
    };
    if let Some(&(b, k, e)) = check_timing(&d, &chosen.times, &limits).first() {
        return Err(here(format!(
            "motion: block {} breaks the limits of axis {} by {e:.3e}; no program written",
            b + 1,
            m.axes[k].name
        )));
    }
    // The program: a rapid to the start, then one G1 block per block with its time.
    let axes: Vec<AxisSpec> = m
        .axes
        .iter()
        .map(|a| {
            if a.is_rotary() {
                AxisSpec::rotary(a.name.clone())
            } else {
                AxisSpec::linear(a.name.clone())
            }
        })
        .collect();
    let row = |i: usize| -> Vec<f64> {
        track
            .row(i)
            .iter()
            .enumerate()
            .map(|(a, v)| nc(m, a, *v))
            .collect()
    };
    let mut program = Program::new(name, axes);
    program.header_comments = vec![
        format!("formcam: {} on {}", job.display(), m.name),
        format!(
            "one circuit, {} blocks, {:.3} s ({} block times; pairwise {:.3} s, global {:.3} s)",
            ends.len() - 1,
            chosen.total,
            motion.times.as_deref().unwrap_or("global"),
            pw.total,
            gl.total
        ),
    ];
    program
        .blocks
        .push(Block::rapid(row(0)).with_comment("start of the circuit"));
    for (b, e) in ends.iter().skip(1).enumerate() {
        program
            .blocks
            .push(Block::linear(row(*e), Feed::InverseTime(chosen.times[b])));
    }
    let mut text = String::new();
    let ext = match (&post.template, &post.dialect) {
        (Some(_), Some(_)) => {
            return Err(here(
                "post: give either dialect or template, not both".into(),
            ));
        }
        (Some(t), None) => {
            let dir = job.parent().unwrap_or(Path::new("."));
            let p = dir.join(t);
            let src = fs::read_to_string(&p)
                .map_err(|e| here(format!("post.template: cannot read {}: {e}", p.display())))?;
            let tpl =
                Template::from_toml(&src).map_err(|e| CliError(format!("{}: {e}", p.display())))?;
            write_template(&program, &tpl, &mut text)
                .map_err(|e| CliError(format!("{}: {e}", p.display())))?;
            tpl.extension().to_string()
        }
        (None, d) => {
            let dialect = Dialect::from_name(d.as_deref().unwrap_or("sinumerik-840d"))
                .map_err(|e| here(format!("post.dialect: {e}")))?;
            write(&program, dialect, &mut text).map_err(|e| here(format!("post: {e}")))?;
            dialect.extension().to_string()
        }
    };
    let mut csv = String::from("block,t,t_star,mu");
    for a in &m.axes {
        let _ = write!(csv, ",{}", a.name);
    }
    csv.push('\n');
    for (b, e) in ends.iter().skip(1).enumerate() {
        let _ = write!(
            csv,
            "{},{},{},{}",
            b + 1,
            chosen.times[b],
            t_star[b],
            chosen.mu[b]
        );
        for v in row(*e) {
            let _ = write!(csv, ",{v}");
        }
        csv.push('\n');
    }
    let mut summary = serde_json::Map::new();
    summary.insert("blocks".into(), json!(ends.len() - 1));
    summary.insert("program_time_s".into(), json!(chosen.total));
    summary.insert("program_time_pairwise_s".into(), json!(pw.total));
    summary.insert("program_time_global_s".into(), json!(gl.total));
    summary.insert(
        "program_time_preliminary_s".into(),
        json!(t_star.iter().sum::<f64>()),
    );
    summary.insert("program_file".into(), json!(format!("program.{ext}")));
    let line = format!(
        "; {} blocks, {:.2} s per circuit (pairwise {:.2} s, global {:.2} s) -> program.{ext}",
        ends.len() - 1,
        chosen.total,
        pw.total,
        gl.total
    );
    Ok(Built {
        files: vec![
            (format!("program.{ext}"), text.into_bytes()),
            ("blocks.csv".to_string(), csv.into_bytes()),
        ],
        summary,
        line,
    })
}
