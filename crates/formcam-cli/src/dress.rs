//! `formcam dress JOB -o OUT`: the dressing program of a grinding wheel for
//! ball-screw nut raceways, with the simulation of forming and feed control.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use formcam_dress::{Contour, DressError, DressJob, Dressing, Point, Side, dress};
use formcam_nc::Dialect;
use plotters::prelude::*;
use serde_json::json;

use crate::CliError;
use crate::output::write_all;
use formcam_plot::{Panel, Series, panels_svg, range, svg_err};

/// Whether a job's top-level table is a dressing job (it has `[wheel]`).
pub fn is_job(table: &toml::Table) -> bool {
    table.contains_key("wheel")
}

/// Runs the dressing job `job`, writing its outputs into `out`; returns the
/// line to print.
pub fn run(job: &Path, out: &Path) -> Result<String, CliError> {
    let text = fs::read_to_string(job)
        .map_err(|e| CliError(format!("{}: cannot read the job file: {e}", job.display())))?;
    run_text(job, &text, out)
}

/// [`run`] for a job already read.
pub fn run_text(job: &Path, text: &str, out: &Path) -> Result<String, CliError> {
    let t0 = Instant::now();
    let err = |e: DressError| match e {
        DressError::Toml {
            line,
            column,
            message,
        } => CliError(format!("{}:{line}:{column}: {message}", job.display())),
        e => CliError(format!("{}: {e}", job.display())),
    };
    let parsed = DressJob::from_toml(text).map_err(err)?;
    let warnings = parsed.warnings();
    for w in &warnings {
        eprintln!("formcam: warning: {}: {w}", job.display());
    }
    let initial = match &parsed.process.initial_contour {
        Some(file) => Some(read_contour(&resolve(job, file))?),
        None => None,
    };
    let spec = parsed.spec(initial).map_err(err)?;
    let d = dress(&spec).map_err(err)?;
    let cls = d.nc(Dialect::Cldata).map_err(err)?;
    let mpf = d.nc(Dialect::Sinumerik840d).map_err(err)?;
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut summary = summary(&name, &d);
    if let Some(obj) = summary.as_object_mut() {
        obj.insert("warnings".into(), serde_json::json!(warnings));
    }
    let files: Vec<(&str, Vec<u8>)> = vec![
        ("profile.csv", profile_csv(&d)),
        ("dresser.csv", dresser_csv(&d)),
        ("mrr.csv", mrr_csv(&d)),
        ("contour_initial.csv", contour_csv(&d.forming.initial)),
        ("contour_final.csv", contour_csv(d.forming.final_contour())),
        ("program.cls", cls.into_bytes()),
        ("program.mpf", mpf.into_bytes()),
        ("profile.svg", profile_svg(&name, &d)?),
        ("mrr.svg", mrr_svg(&name, &d)?),
        (
            "summary.json",
            serde_json::to_vec_pretty(&summary)
                .map_err(|e| CliError(format!("summary.json: {e}")))?,
        ),
    ];
    write_all(out, &files)?;
    let ratio = |r: Option<f64>| r.map_or("-".to_string(), |r| format!("{r:.2}"));
    Ok(format!(
        "{}: {} points, {:.2} s of dressing, removal-rate spread {} -> {} with feed control, \
         {:.1} ms -> {}",
        job.display(),
        d.points(),
        d.dressing_time_s(),
        ratio(d.feed.ratio_uncontrolled),
        ratio(d.feed.ratio_controlled),
        t0.elapsed().as_secs_f64() * 1e3,
        out.display()
    ))
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

/// An `x,y` CSV (a header line is skipped).
fn read_contour(path: &Path) -> Result<Vec<Point>, CliError> {
    let text = fs::read_to_string(path).map_err(|e| {
        CliError(format!(
            "{}: process.initial_contour: cannot read: {e}",
            path.display()
        ))
    })?;
    let mut pts = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.split(',').map(str::trim).collect();
        let nums: Option<Vec<f64>> = cols.iter().map(|c| c.parse().ok()).collect();
        match nums {
            Some(v) if v.len() >= 2 => pts.push(Point::new(v[0], v[1])),
            None if i == 0 => {}
            _ => {
                return Err(CliError(format!(
                    "{}:{}: process.initial_contour: expected two numbers x,y (mm)",
                    path.display(),
                    i + 1
                )));
            }
        }
    }
    Ok(pts)
}

fn profile_csv(d: &Dressing) -> Vec<u8> {
    let mut s = String::from("x,y\n");
    for p in d.profile.sample(d.step) {
        let _ = writeln!(s, "{:.9},{:.9}", p.x, p.y);
    }
    s.into_bytes()
}

fn contour_csv(c: &Contour) -> Vec<u8> {
    let mut s = String::from("x,y\n");
    for p in c.points() {
        let _ = writeln!(s, "{:.9},{:.9}", p.x, p.y);
    }
    s.into_bytes()
}

fn dresser_csv(d: &Dressing) -> Vec<u8> {
    let mut s = String::from("z,x,pass,stage,corner_z,corner_x\n");
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
    let mut s = String::from(
        "z,x,area,mrr,feed,pass,stage,length,area_per_mm,feed_required,mrr_uncontrolled,\
         cut_angle,cut_analogue,steady",
    );
    if vol.is_some() {
        s.push_str(",mrr_volume,mrr_volume_uncontrolled");
    }
    s.push('\n');
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

fn summary(name: &str, d: &Dressing) -> serde_json::Value {
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
        "job": name,
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

/// The profile, the allowance, the dresser's paths (corner centre and point
/// A), the dresser at the start of the first pass and the ball, to scale.
fn profile_svg(title: &str, d: &Dressing) -> Result<Vec<u8>, CliError> {
    let err = svg_err("profile.svg");
    let mut series: Vec<Series> = vec![
        (
            "allowance (before)".into(),
            pts(d.forming.initial.points()),
            RGBColor(170, 170, 170),
        ),
        ("profile".into(), pts(&d.profile.sample(d.step)), BLACK),
    ];
    for (i, pass) in d.passes.iter().enumerate() {
        let colour = if pass.side == Side::Right { BLUE } else { RED };
        series.push((
            format!("pass {}: corner centre (r = {})", i + 1, pass.radius),
            pass.points
                .iter()
                .map(|p| (p.centre.x, p.centre.y))
                .collect(),
            colour,
        ));
        series.push((
            format!("pass {}: point A", i + 1),
            pass.points
                .iter()
                .map(|p| (p.reference.x, p.reference.y))
                .collect(),
            MAGENTA,
        ));
    }
    let rs = d.profile.spec().ball_radius;
    series.push((
        "ball".into(),
        (0..=180)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 180.0;
                (rs * a.cos(), rs * a.sin())
            })
            .collect(),
        GREEN,
    ));
    if let Some(start) = d.passes.first().and_then(|p| p.points.first()) {
        let o = d.dresser.outline(Side::Right, d.forming.chord);
        let c = start.centre;
        let h = 1.0;
        let mut ring: Vec<(f64, f64)> = o.points.iter().map(|p| (p.x + c.x, p.y + c.y)).collect();
        if let (Some(&(x0, y0)), Some(&(x1, y1))) = (ring.first(), ring.last()) {
            let top = y0.max(y1) + h;
            ring.push((x1, top));
            ring.push((x0, top));
            ring.push((x0, y0));
        }
        series.push(("dresser at the start".into(), ring, RGBColor(0, 128, 128)));
    }
    let (x0, x1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.0)));
    let top = series
        .iter()
        .flat_map(|s| s.1.iter().map(|q| q.1))
        .fold(f64::NEG_INFINITY, f64::max);
    let (y0, y1) = (-rs - 0.2, top + 0.2);
    let width = 1000u32;
    let plot_w = f64::from(width - 90);
    let height = (plot_w * (y1 - y0) / (x1 - x0)) as u32 + 110;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("{title}: wheel profile and dresser trajectories"),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("Z (along the wheel's axis), mm")
            .y_desc("X (radial), mm")
            .draw()
            .map_err(|e| err(e.to_string()))?;
        for (label, data, colour) in series {
            chart
                .draw_series(LineSeries::new(data, colour.stroke_width(2)))
                .map_err(|e| err(e.to_string()))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg.into_bytes())
}

/// The removal rate with and without feed control, and the feed, against Z.
fn mrr_svg(title: &str, d: &Dressing) -> Result<Vec<u8>, CliError> {
    let f = &d.feed;
    let per_pass = |values: &[f64]| -> Vec<Vec<(f64, f64)>> {
        d.passes
            .iter()
            .enumerate()
            .map(|(pi, _)| {
                d.forming
                    .steps
                    .iter()
                    .zip(values)
                    .filter(|(s, _)| s.pass == pi)
                    .map(|(s, v)| (s.reference.x, *v))
                    .collect()
            })
            .collect()
    };
    let panels: Vec<Panel> = vec![
        (
            "Z, mm",
            "removal rate, mm²/min",
            per_pass(&f.mrr_uncontrolled)
                .into_iter()
                .map(|s| {
                    (
                        format!("constant feed {:.0} mm/min", f.feed_uncontrolled),
                        s,
                        RGBColor(200, 120, 0),
                    )
                })
                .chain(
                    per_pass(&f.mrr)
                        .into_iter()
                        .map(|s| ("feed control".to_string(), s, BLUE)),
                )
                .collect(),
        ),
        (
            "Z, mm",
            "feed, mm/min",
            per_pass(&f.feed)
                .into_iter()
                .map(|s| ("feed".to_string(), s, RED))
                .collect(),
        ),
        (
            "Z, mm",
            "cut-arc angle, rad",
            per_pass(
                &d.forming
                    .steps
                    .iter()
                    .map(|s| s.cut_angle)
                    .collect::<Vec<_>>(),
            )
            .into_iter()
            .map(|s| ("epsilon".to_string(), s, GREEN))
            .collect(),
        ),
    ];
    Ok(panels_svg(
        "mrr.svg",
        &format!("{title}: removal rate and feed against Z (point A)"),
        panels,
    )?)
}

fn pts(p: &[Point]) -> Vec<(f64, f64)> {
    p.iter().map(|q| (q.x, q.y)).collect()
}
