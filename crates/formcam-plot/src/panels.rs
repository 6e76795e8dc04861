//! Stacked panels of line series in one SVG document (plotters, SVG backend).

use plotters::prelude::*;

use crate::{PlotError, PlotFault};

/// One line: legend label (empty, or one shown before in the panel: no new
/// legend entry), points, colour.
pub type Series = (String, Vec<(f64, f64)>, RGBColor);

/// One panel: x label, y label, its lines.
pub type Panel = (&'static str, &'static str, Vec<Series>);

/// Maps a plotting error to one naming the file.
pub fn svg_err(file: &str) -> impl Fn(PlotFault) -> PlotError + '_ {
    move |fault| PlotError {
        file: file.to_string(),
        fault,
    }
}

/// The range of `values` with 5 % padding; `(0, 1)` when there are none.
/// The span is at least 1e-3 of the values' magnitude (1 when they are all
/// 0), centred on them: a series constant to rounding reads as constant,
/// not as a wild oscillation over the whole height.
pub fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
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
pub fn tick_label(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
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
pub fn panels_svg(file: &str, title: &str, panels: Vec<Panel>) -> Result<Vec<u8>, PlotError> {
    let err = svg_err(file);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (900, 300 * panels.len() as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let root = root
            .titled(title, ("sans-serif", 20))
            .map_err(|e| err(e.into()))?;
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
                .map_err(|e| err(e.into()))?;
            chart
                .configure_mesh()
                .x_desc(xlabel)
                .y_desc(ylabel)
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .draw()
                .map_err(|e| err(e.into()))?;
            let mut shown: Vec<String> = Vec::new();
            for (label, data, color) in series {
                let drawn = chart
                    .draw_series(LineSeries::new(data, color.stroke_width(2)))
                    .map_err(|e| err(e.into()))?;
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
                .map_err(|e| err(e.into()))?;
        }
        root.present().map_err(|e| err(e.into()))?;
    }
    Ok(svg.into_bytes())
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
