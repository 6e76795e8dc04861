//! SVG plots: stacked panels of line series (plotters, SVG backend).

use formcam_geom::Meridian;
use formcam_winding::Layer;
use formcam_winding::eye::EyeTrajectory;
use formcam_winding::minimax::bridging_limit;
use plotters::prelude::*;

use crate::CliError;

/// One line: legend label (empty, or one shown before in the panel: no new
/// legend entry), points, colour.
pub(crate) type Series = (String, Vec<(f64, f64)>, RGBColor);

/// One panel: x label, y label, its lines.
pub(crate) type Panel = (&'static str, &'static str, Vec<Series>);

/// Maps a plotting error to one naming the file.
pub(crate) fn svg_err(file: &str) -> impl Fn(String) -> CliError + '_ {
    move |e| CliError(format!("{file}: {e}"))
}

/// The range of `values` with 5 % padding; `(0, 1)` when there are none.
/// The span is at least 1e-3 of the values' magnitude (1 when they are all
/// 0), centred on them: a series constant to rounding reads as constant,
/// not as a wild oscillation over the whole height.
pub(crate) fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    let magnitude = lo.abs().max(hi.abs());
    let least = if magnitude > 0.0 {
        1e-3 * magnitude
    } else {
        1.0
    };
    let span = (hi - lo).max(least);
    let mid = 0.5 * (lo + hi);
    let (lo, hi) = (lo.min(mid - 0.5 * span), hi.max(mid + 0.5 * span));
    let pad = 0.05 * span;
    (lo - pad, hi + pad)
}

/// Tick labels for an axis over `lo..hi`: as many decimals as ticks a
/// twentieth of the span apart need to read differently (plotters' own
/// labels stop at 5 decimals), and no `-0`.
pub(crate) fn tick_label(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let step = (hi - lo).abs() / 20.0;
    let decimals = if step.is_finite() && step > 0.0 {
        (-step.log10().floor()).clamp(0.0, 15.0) as usize
    } else {
        1
    };
    move |v: &f64| {
        let text = format!("{v:.decimals$}");
        match text.strip_prefix('-') {
            Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
            _ => text,
        }
    }
}

/// Panels stacked in one SVG document; `file` names it in errors.
pub(crate) fn panels_svg(file: &str, title: &str, panels: Vec<Panel>) -> Result<Vec<u8>, CliError> {
    let err = svg_err(file);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (900, 300 * panels.len() as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let root = root
            .titled(title, ("sans-serif", 20))
            .map_err(|e| err(e.to_string()))?;
        let areas = root.split_evenly((panels.len(), 1));
        for (area, (xlabel, ylabel, series)) in areas.iter().zip(panels) {
            let (x0, x1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.0)));
            let (y0, y1) = range(series.iter().flat_map(|s| s.1.iter().map(|q| q.1)));
            let (fx, fy) = (tick_label(x0, x1), tick_label(y0, y1));
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(e.to_string()))?;
            chart
                .configure_mesh()
                .x_desc(xlabel)
                .y_desc(ylabel)
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .draw()
                .map_err(|e| err(e.to_string()))?;
            let mut shown: Vec<String> = Vec::new();
            for (label, data, color) in series {
                let drawn = chart
                    .draw_series(LineSeries::new(data, color.stroke_width(2)))
                    .map_err(|e| err(e.to_string()))?;
                if !label.is_empty() && !shown.contains(&label) {
                    drawn
                        .label(label.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
                    shown.push(label);
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

/// The layer: meridian with the Clairaut function and the bridging limit, the
/// winding angle and the layer thickness along `z`.
pub fn layer_svg(title: &str, mandrel: &impl Meridian, layer: &Layer) -> Result<Vec<u8>, CliError> {
    let pts = &layer.points;
    let mut radius: Vec<Series> = vec![
        (
            "meridian r".into(),
            pts.iter().map(|p| (p.z, p.r)).collect(),
            BLACK,
        ),
        (
            "Clairaut C = r sin(alpha)".into(),
            pts.iter().map(|p| (p.z, p.c)).collect(),
            BLUE,
        ),
    ];
    // The bridging limit where the meridian is concave, one series per stretch.
    let mut stretch: Vec<(f64, f64)> = Vec::new();
    for p in pts {
        let cb = bridging_limit(&mandrel.eval(p.z));
        if cb > 0.0 {
            stretch.push((p.z, cb));
        } else if !stretch.is_empty() {
            let label = if radius.len() == 2 {
                "bridging limit C_b"
            } else {
                ""
            };
            radius.push((label.into(), std::mem::take(&mut stretch), MAGENTA));
        }
    }
    if !stretch.is_empty() {
        let label = if radius.len() == 2 {
            "bridging limit C_b"
        } else {
            ""
        };
        radius.push((label.into(), stretch, MAGENTA));
    }
    let panels = vec![
        ("z, mm", "radius, mm", radius),
        (
            "z, mm",
            "winding angle, deg",
            vec![(
                "alpha".into(),
                pts.iter().map(|p| (p.z, p.alpha.to_degrees())).collect(),
                RED,
            )],
        ),
        (
            "z, mm",
            "layer thickness, mm",
            vec![(
                "two plies".into(),
                pts.iter()
                    .zip(&layer.thickness)
                    .map(|(p, t)| (p.z, *t))
                    .collect(),
                GREEN,
            )],
        ),
    ];
    panels_svg("path.svg", title, panels)
}

/// The eye trajectory in the `Z x R` plane with the path, and `l(x)`, `u(x)`.
pub fn eye_svg(title: &str, t: &EyeTrajectory) -> Result<Vec<u8>, CliError> {
    let pts = &t.points;
    let mut lengths: Vec<Series> =
        vec![("l".into(), pts.iter().map(|p| (p.x, p.l)).collect(), RED)];
    if t.l_min.len() == pts.len() {
        let lm = pts.iter().zip(&t.l_min).map(|(p, l)| (p.x, *l)).collect();
        lengths.push(("l_min (clearance)".into(), lm, BLUE));
    }
    let panels = vec![
        (
            "Z, mm",
            "R, mm",
            vec![
                (
                    "path (z, r)".into(),
                    pts.iter().map(|p| (p.z, p.r)).collect(),
                    BLACK,
                ),
                (
                    "eye (Z, R)".into(),
                    pts.iter().map(|p| (p.eye_z, p.eye_r)).collect(),
                    RED,
                ),
            ],
        ),
        ("x (laid band length), mm", "free length, mm", lengths),
        (
            "x (laid band length), mm",
            "pull speed u",
            vec![(
                "u = d lambda / dx".into(),
                pts.iter().map(|p| (p.x, p.u)).collect(),
                GREEN,
            )],
        ),
    ];
    panels_svg("eye.svg", title, panels)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// The texts of an SVG document that read as numbers (the tick labels).
    fn numbers(svg: &str) -> Vec<(String, f64)> {
        svg.split("</text>")
            .filter_map(|chunk| chunk.rsplit('>').next())
            .filter_map(|t| {
                t.trim()
                    .parse::<f64>()
                    .ok()
                    .map(|v| (t.trim().to_string(), v))
            })
            .collect()
    }

    #[test]
    fn a_nearly_constant_series_gets_distinct_tick_labels() {
        // u = 1 +- 1e-7 over x in [0, 1000] (the pull speed of a path
        // that needs none of the bath's slack).
        let u: Vec<(f64, f64)> = (0..=200)
            .map(|k| (5.0 * k as f64, 1.0 + 1e-7 * (k as f64 / 7.0).sin()))
            .collect();
        let svg = panels_svg("t.svg", "t", vec![("x", "u", vec![("u".into(), u, GREEN)])]).unwrap();
        let svg = String::from_utf8(svg).unwrap();
        let y: Vec<(String, f64)> = numbers(&svg)
            .into_iter()
            .filter(|(_, v)| (v - 1.0).abs() < 0.01)
            .collect();
        assert!(y.len() >= 3, "{y:?}");
        let mut labels: Vec<&str> = y.iter().map(|(t, _)| t.as_str()).collect();
        labels.sort_unstable();
        labels.dedup();
        assert_eq!(labels.len(), y.len(), "repeated tick labels: {y:?}");
        // The axis spans at least 1e-3 of the value: the series sits in a
        // thin band in its middle.
        let (lo, hi) = (y[0].1.min(y[y.len() - 1].1), y[0].1.max(y[y.len() - 1].1));
        assert!(hi - lo >= 0.5e-3, "{y:?}");
    }

    #[test]
    fn the_span_is_at_least_a_thousandth_of_the_magnitude() {
        let (lo, hi) = range([1.0 - 1e-7, 1.0 + 1e-7].into_iter());
        assert!(hi - lo >= 1e-3 && lo < 1.0 && hi > 1.0, "{lo} {hi}");
        let (lo, hi) = range([0.0, 0.0].into_iter());
        assert!(hi - lo >= 1.0 && lo < 0.0 && hi > 0.0, "{lo} {hi}");
        // A real spread is kept, padded by 5 %.
        let (lo, hi) = range([2.0, 4.0].into_iter());
        assert!(
            (lo - 1.9).abs() < 1e-12 && (hi - 4.1).abs() < 1e-12,
            "{lo} {hi}"
        );
        let f = tick_label(-1e-9, 1e-3);
        assert_eq!(f(&-1e-12), "0.00000");
    }
}
