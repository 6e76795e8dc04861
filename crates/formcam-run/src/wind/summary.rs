//! `summary.json`: its keys for a layer, the eye, the axes, the program and
//! a multi-layer job.

use formcam_machine::{AxisTrack, Machine};
use formcam_program::{Assembled, MachineSource, WindJob, WoundProgram, nc};
use formcam_results::names;
use formcam_winding::Layer;
use formcam_winding::eye::EyeTrajectory;
use serde_json::{Map, Value, json};

use crate::RunError;

/// How the summary records the machine: its shipped name or its file as the
/// job wrote it.
fn insert_source(summary: &mut Map<String, Value>, source: &MachineSource) {
    match source {
        MachineSource::Shipped(n) => summary.insert("machine_shipped".into(), json!(n)),
        MachineSource::File(f) => summary.insert("machine_file".into(), json!(f)),
    };
}

pub(super) fn pretty(v: &Value) -> Result<Vec<u8>, RunError> {
    serde_json::to_vec_pretty(v).map_err(|source| RunError::Summary { source })
}

/// A serialisable kind's name (`geodesic`).
pub(super) fn json_name<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_value(v)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_default()
}

/// A layer's summary; `job` the job file as the result records it.
pub(super) fn layer_summary(job: &str, kind: &str, layer: &Layer) -> Value {
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

pub(super) fn add_eye_summary(summary: &mut Value, t: &EyeTrajectory) {
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

pub(super) fn add_axes_summary(
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

/// The program's summary fields: its blocks, layers, times, file, the axes'
/// ranges over every block (`axis_ranges`) and the checks.
pub(super) fn program_summary(p: &Assembled, ext: &str, axis_ranges: Value) -> Map<String, Value> {
    let count = p.blocks.len();
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
    summary
}

/// A multi-layer job's summary: the job (`path`, the file as the result
/// records it), its machine, the fibre, each layer's figures (`axes`: each
/// layer's limits kept and largest IK residual) and, for a `.wind`
/// document, its eye.
pub(super) fn layered_summary(
    path: &str,
    job: &WindJob,
    m: &Machine,
    source: &MachineSource,
    wound: &WoundProgram,
    axes: &[(bool, f64)],
    fibre: f64,
) -> Map<String, Value> {
    let per_layer = per_layer(wound, axes);
    let mut summary = Map::new();
    summary.insert("job".into(), json!(path));
    summary.insert("machine".into(), json!(m.name));
    insert_source(&mut summary, source);
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
    summary
}

/// Each layer's figures in the summary's `per_layer`.
fn per_layer(wound: &WoundProgram, axes: &[(bool, f64)]) -> Vec<Value> {
    let mut per_layer = Vec::with_capacity(wound.layers.len());
    for (i, ((l, b), &(limits_ok, residual))) in
        wound.layers.iter().zip(&wound.blocks).zip(axes).enumerate()
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
    per_layer
}
