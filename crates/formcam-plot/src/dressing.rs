//! The plots of a dressing: the profile with the dresser's paths, and the
//! removal rate with the feed along the wheel's axis.

use formcam_dress::{Dressing, Point, Side};
use plotters::prelude::*;

use crate::{Panel, PlotError, Series, panels_svg, range, svg_err};

/// The profile, the allowance, the dresser's paths (corner centre and point
/// A), the dresser at the start of the first pass and the ball, to scale, in
/// the program's axes (`Z` along the wheel's axis, `X` radial).
pub fn profile_svg(title: &str, d: &Dressing) -> Result<Vec<u8>, PlotError> {
    let err = svg_err("profile.svg");
    let series = profile_series(d);
    let rs = d.profile.spec().ball_radius;
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
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("{title}: wheel profile and dresser trajectories"),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(e.into()))?;
        chart
            .configure_mesh()
            .x_desc("Z (along the wheel's axis), mm")
            .y_desc("X (radial), mm")
            .draw()
            .map_err(|e| err(e.into()))?;
        for (label, data, colour) in series {
            chart
                .draw_series(LineSeries::new(data, colour.stroke_width(2)))
                .map_err(|e| err(e.into()))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .draw()
            .map_err(|e| err(e.into()))?;
        root.present().map_err(|e| err(e.into()))?;
    }
    Ok(svg.into_bytes())
}

/// The lines of the profile plot, `(Z, X)` points.
fn profile_series(d: &Dressing) -> Vec<Series> {
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
    series
}

/// The removal rate with and without feed control, the feed and the cut-arc
/// angle against `Z` (point A).
pub fn mrr_svg(title: &str, d: &Dressing) -> Result<Vec<u8>, PlotError> {
    let f = &d.feed;
    let per_pass = |values: &[f64]| -> Vec<Vec<(f64, f64)>> {
        (0..d.passes.len())
            .map(|pi| {
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
    let cut_angles: Vec<f64> = d.forming.steps.iter().map(|s| s.cut_angle).collect();
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
            per_pass(&cut_angles)
                .into_iter()
                .map(|s| ("epsilon".to_string(), s, GREEN))
                .collect(),
        ),
    ];
    panels_svg(
        "mrr.svg",
        &format!("{title}: removal rate and feed against Z (point A)"),
        panels,
    )
}

fn pts(p: &[Point]) -> Vec<(f64, f64)> {
    p.iter().map(|q| (q.x, q.y)).collect()
}
