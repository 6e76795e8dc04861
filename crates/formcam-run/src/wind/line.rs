//! The parts of the printed line: the eye's and the axes' figures.

use formcam_machine::{AxisTrack, Machine};
use formcam_program::{Assembled, WindJob, WoundProgram};
use formcam_winding::Layer;
use formcam_winding::eye::EyeTrajectory;

use super::summary::json_name;

pub(super) fn eye_line(t: &EyeTrajectory) -> String {
    format!(
        "; eye {}: u in [{:.4}, {:.4}], rms {:.4}, constraints {}",
        json_name(&t.mode),
        t.stats.u_min,
        t.stats.u_max,
        t.stats.u_rms_dev,
        if t.constraints_ok { "ok" } else { "VIOLATED" }
    )
}

pub(super) fn axes_line(m: &Machine, track: &AxisTrack) -> String {
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

/// The program's part: its layers, blocks, times and file (`program.<ext>`).
pub(super) fn program_line(p: &Assembled, ext: &str) -> String {
    let count = p.blocks.len();
    format!(
        "; {} layers, {count} blocks, {:.2} s (pairwise {:.2} s, global {:.2} s) -> program.{ext}",
        p.layers, p.time_s, p.time_pairwise_s, p.time_global_s
    )
}

/// A multi-layer job's line: its layers' kinds, the machine, the fibre
/// (`fibre` mm) and the program's part.
pub(super) fn layered_line(
    job: &WindJob,
    wound: &WoundProgram,
    m: &Machine,
    fibre: f64,
    program_line: &str,
) -> String {
    format!(
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
    )
}

/// A single-layer job's line: the path's figures, then the eye's, the
/// axes' and the program's parts (`more`).
pub(super) fn single_line(title: &str, layer: &Layer, more: &str) -> String {
    format!(
        "{}: {} path, mu {:.5}, alpha at equator {:.3} deg, {} circuits (pattern {} skip {}), dwell \
         {:.2} deg, fibre {:.1} m{more}",
        title,
        json_name(&layer.pass.method),
        layer.pass.mu.unwrap_or(layer.pass.mu_max_abs),
        layer.report.alpha_equator_rad.to_degrees(),
        layer.pattern.circuits,
        layer.pattern.pattern_number,
        layer.pattern.skip_index,
        layer.report.dwell_deg,
        layer.report.fibre_length_mm / 1000.0,
    )
}
