//! SVG plots of a layer: the meridian with the Clairaut function, the winding
//! angle and the layer thickness along `z`.

use formcam_geom::Meridian;
use formcam_winding::Layer;
use formcam_winding::minimax::bridging_limit;
use plotters::prelude::*;

use crate::CliError;

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(1e-9);
    (lo - pad, hi + pad)
}

/// The layer as an SVG document (three panels stacked).
pub fn layer_svg(title: &str, mandrel: &impl Meridian, layer: &Layer) -> Result<Vec<u8>, CliError> {
    let err = |e: String| CliError(format!("path.svg: {e}"));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 900)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let root = root
            .titled(title, ("sans-serif", 20))
            .map_err(|e| err(e.to_string()))?;
        let panels = root.split_evenly((3, 1));
        let pts = &layer.points;
        let (z0, z1) = range(pts.iter().map(|p| p.z));
        type Series<'a> = (&'a str, Vec<(f64, f64)>, RGBColor);
        let plots: [(&str, Vec<Series>); 3] = [
            (
                "radius, mm",
                vec![
                    (
                        "meridian r",
                        pts.iter().map(|p| (p.z, p.r)).collect(),
                        BLACK,
                    ),
                    (
                        "Clairaut C = r sin(alpha)",
                        pts.iter().map(|p| (p.z, p.c)).collect(),
                        BLUE,
                    ),
                ],
            ),
            (
                "winding angle, deg",
                vec![(
                    "alpha",
                    pts.iter().map(|p| (p.z, p.alpha.to_degrees())).collect(),
                    RED,
                )],
            ),
            (
                "layer thickness, mm",
                vec![(
                    "two plies",
                    pts.iter()
                        .zip(&layer.thickness)
                        .map(|(p, t)| (p.z, *t))
                        .collect(),
                    GREEN,
                )],
            ),
        ];
        // The bridging limit where the meridian is concave, one series per stretch.
        let mut bridging: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut open = false;
        for p in pts {
            let cb = bridging_limit(&mandrel.eval(p.z));
            if cb > 0.0 {
                if !open {
                    bridging.push(Vec::new());
                }
                if let Some(last) = bridging.last_mut() {
                    last.push((p.z, cb));
                }
            }
            open = cb > 0.0;
        }
        let mut plots = plots;
        for (i, stretch) in bridging.into_iter().enumerate() {
            let label = if i == 0 { "bridging limit C_b" } else { "" };
            plots[0].1.push((label, stretch, MAGENTA));
        }
        for (area, (ylabel, series)) in panels.iter().zip(plots) {
            let (y0, y1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.1)));
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(z0..z1, y0..y1)
                .map_err(|e| err(e.to_string()))?;
            chart
                .configure_mesh()
                .x_desc("z, mm")
                .y_desc(ylabel)
                .draw()
                .map_err(|e| err(e.to_string()))?;
            for (label, data, color) in series {
                let drawn = chart
                    .draw_series(LineSeries::new(data, color.stroke_width(2)))
                    .map_err(|e| err(e.to_string()))?;
                if !label.is_empty() {
                    drawn
                        .label(label)
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
                }
            }
            chart
                .configure_series_labels()
                .border_style(BLACK)
                .background_style(WHITE.mix(0.8))
                .draw()
                .map_err(|e| err(e.to_string()))?;
        }
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg.into_bytes())
}

/// The eye trajectory in the `Z x R` plane with the path, and `l(x)`, `u(x)`.
pub fn eye_svg(title: &str, t: &formcam_winding::eye::EyeTrajectory) -> Result<Vec<u8>, CliError> {
    let err = |e: String| CliError(format!("eye.svg: {e}"));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 900)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let root = root
            .titled(title, ("sans-serif", 20))
            .map_err(|e| err(e.to_string()))?;
        let panels = root.split_evenly((3, 1));
        let pts = &t.points;
        type Series<'a> = (&'a str, Vec<(f64, f64)>, RGBColor);
        let plots: [(&str, &str, Vec<Series>); 3] = [
            (
                "Z, mm",
                "R, mm",
                vec![
                    (
                        "path (z, r)",
                        pts.iter().map(|p| (p.z, p.r)).collect(),
                        BLACK,
                    ),
                    (
                        "eye (Z, R)",
                        pts.iter().map(|p| (p.eye_z, p.eye_r)).collect(),
                        RED,
                    ),
                ],
            ),
            ("x (laid band length), mm", "free length, mm", {
                let mut v = vec![("l", pts.iter().map(|p| (p.x, p.l)).collect(), RED)];
                if t.l_min.len() == pts.len() {
                    let lm = pts.iter().zip(&t.l_min).map(|(p, l)| (p.x, *l)).collect();
                    v.push(("l_min (clearance)", lm, BLUE));
                }
                v
            }),
            (
                "x (laid band length), mm",
                "pull speed u",
                vec![(
                    "u = d lambda / dx",
                    pts.iter().map(|p| (p.x, p.u)).collect(),
                    GREEN,
                )],
            ),
        ];
        for (area, (xlabel, ylabel, series)) in panels.iter().zip(plots) {
            let (x0, x1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.0)));
            let (y0, y1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.1)));
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(e.to_string()))?;
            chart
                .configure_mesh()
                .x_desc(xlabel)
                .y_desc(ylabel)
                .draw()
                .map_err(|e| err(e.to_string()))?;
            for (label, data, color) in series {
                chart
                    .draw_series(LineSeries::new(data, color.stroke_width(2)))
                    .map_err(|e| err(e.to_string()))?
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            }
            chart
                .configure_series_labels()
                .border_style(BLACK)
                .background_style(WHITE.mix(0.8))
                .draw()
                .map_err(|e| err(e.to_string()))?;
        }
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg.into_bytes())
}
