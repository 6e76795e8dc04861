//! The CSV tables of a winding run (`path.csv`, `eye.csv`, `axes.csv`,
//! `band.csv`, `blocks.csv`, the program's axes), their headers and file
//! names from formcam-results.

use std::fmt::Write as _;

use formcam_machine::{AxisTrack, BandPassed, Machine};
use formcam_program::{Assembled, Wound, nc};
use formcam_results::winding::{AXES, BAND, BLOCKS, EYE, PATH, PROGRAM_AXES};
use formcam_winding::Layer;
use formcam_winding::eye::EyeTrajectory;
use serde_json::{Value, json};

pub(super) fn path_csv(layer: &Layer) -> Vec<u8> {
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

pub(super) fn eye_csv(t: &EyeTrajectory) -> Vec<u8> {
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

pub(super) fn axes_csv(m: &Machine, w: &Wound, track: &AxisTrack) -> Vec<u8> {
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

pub(super) fn band_csv(m: &Machine, w: &Wound, passed: &BandPassed) -> Vec<u8> {
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

/// `blocks.csv`: every block of the program with its time, the axes at its
/// end (NC units), its layer, least time and `mu`.
pub(super) fn blocks_csv(m: &Machine, p: &Assembled) -> Vec<u8> {
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
pub(super) fn program_axes(m: &Machine, p: &Assembled) -> (Vec<u8>, Value) {
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
