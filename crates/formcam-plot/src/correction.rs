//! The plots of a correction: the measured deviations per section, the
//! nodes' displacement over the plan, and the closed loop's convergence.

use formcam_correct::simulate::LoopResult;
use formcam_correct::{Grid, Measurements, NodeCorrection, Placement};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::{PlotError, Series, panels_svg, svg_err, tick_label};

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// The measured deviation along the surface normal, per section, against
/// the arc length along the section (a legend naming the sections, up to 16
/// sections; none beyond).
pub fn deviations_svg(m: &Measurements, grid: &Grid) -> Result<Vec<u8>, PlotError> {
    let legend = m.sections.len() <= 16;
    let mut series: Vec<Series> = Vec::new();
    // The grid normal of the section's first point orients the sign.
    for (j, s) in m.sections.iter().enumerate() {
        let n0 = grid.normal_at(0, j.min(grid.nv - 1));
        let mut acc = 0.0;
        let mut pts = Vec::new();
        for (k, p) in s.points.iter().enumerate() {
            if k > 0 {
                let q = s.points[k - 1].nominal;
                acc += ((p.nominal[0] - q[0]).powi(2)
                    + (p.nominal[1] - q[1]).powi(2)
                    + (p.nominal[2] - q[2]).powi(2))
                .sqrt();
            }
            let d = p.deviation();
            let n = p.normal.unwrap_or(n0);
            pts.push((acc, d[0] * n[0] + d[1] * n[1] + d[2] * n[2]));
        }
        let label = if legend {
            format!("section {}", s.name)
        } else {
            String::new()
        };
        series.push((label, pts, PALETTE[j % PALETTE.len()]));
    }
    panels_svg(
        "deviations.svg",
        &format!(
            "Measured deviation per section (max {:.4} mm, rms {:.4} mm)",
            m.max_deviation(),
            m.rms_deviation()
        ),
        vec![(
            "length along the section, mm",
            "deviation along the normal, mm",
            series,
        )],
    )
}

/// The displacement of the nodes (along the surface normal, coloured) over
/// `x, y`, with the measured points; at most 20 000 nodes drawn.
pub fn displacement_svg(
    nodes: &[[f64; 3]],
    corrections: &[NodeCorrection],
    grid: &Grid,
) -> Result<Vec<u8>, PlotError> {
    let pts = node_points(nodes, corrections, grid);
    // The colour scale's half range: the largest displacement, at least
    // 1 um (a map of nothing moved is white, not noise).
    let lim = pts.iter().fold(1e-3f64, |m, p| m.max(p.2.abs()));
    let (xr, yr) = plan_ranges(&pts, grid);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 800)).into_drawing_area();
        root.fill(&WHITE).map_err(displacement_err)?;
        let root = root
            .titled(
                "Node displacement along the surface normal",
                ("sans-serif", 18),
            )
            .map_err(displacement_err)?;
        let (map, bar) = root.split_horizontally(880);
        draw_map(&map, &pts, grid, lim, xr, yr)?;
        draw_colour_bar(&bar, lim)?;
        root.present().map_err(displacement_err)?;
    }
    Ok(svg.into_bytes())
}

/// A node as drawn: `x, y`, its displacement along the surface normal and
/// where it lies.
type NodePoint = (f64, f64, f64, Placement);

/// A part of the displacement plot's drawing.
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A drawing error of the displacement plot.
fn displacement_err<E: std::error::Error + Send + Sync + 'static>(
    e: DrawingAreaErrorKind<E>,
) -> PlotError {
    svg_err("displacement.svg")(e.into())
}

/// Every `step`-th node (at most 20 000) with its displacement along the
/// grid's normal at its facet.
fn node_points(nodes: &[[f64; 3]], corrections: &[NodeCorrection], grid: &Grid) -> Vec<NodePoint> {
    let step = nodes.len().div_ceil(20_000).max(1);
    let mut pts = Vec::new();
    for (p, c) in nodes.iter().zip(corrections).step_by(step) {
        let (i, j) = (c.facet.0 as usize, c.facet.1 as usize);
        let n = grid.normal_at(i.min(grid.nu - 1), j.min(grid.nv - 1));
        let d = c.displacement;
        pts.push((
            p[0],
            p[1],
            d[0] * n[0] + d[1] * n[1] + d[2] * n[2],
            c.placement,
        ));
    }
    pts
}

/// The `x` and `y` ranges of the map: the nodes and the measured points,
/// padded by 3 % of the larger span (the unit square when there are none).
fn plan_ranges(pts: &[NodePoint], grid: &Grid) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in pts
        .iter()
        .map(|p| (p.0, p.1))
        .chain(grid.nominal.iter().map(|q| (q[0], q[1])))
    {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = 0.03 * (x1 - x0).max(y1 - y0).max(1e-9);
    ((x0 - pad, x1 + pad), (y0 - pad, y1 + pad))
}

/// The colour of displacement `d` on the scale `-lim..lim`: red up, blue
/// down, white at 0.
fn colour(d: f64, lim: f64) -> RGBColor {
    let f = (d / lim).clamp(-1.0, 1.0);
    if f >= 0.0 {
        RGBColor(255, (255.0 * (1.0 - f)) as u8, (255.0 * (1.0 - f)) as u8)
    } else {
        RGBColor((255.0 * (1.0 + f)) as u8, (255.0 * (1.0 + f)) as u8, 255)
    }
}

/// The map: the moved nodes coloured, the unchanged ones grey, the measured
/// points black, and the legend.
fn draw_map(
    map: &Area,
    pts: &[NodePoint],
    grid: &Grid,
    lim: f64,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<(), PlotError> {
    let grey = RGBColor(190, 190, 190);
    let (fx, fy) = (tick_label(xr.0, xr.1), tick_label(yr.0, yr.1));
    let mut chart = ChartBuilder::on(map)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(displacement_err)?;
    chart
        .configure_mesh()
        .x_desc("x, mm")
        .y_desc("y, mm")
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .draw()
        .map_err(displacement_err)?;
    let (unchanged, moved): (Vec<_>, Vec<_>) = pts
        .iter()
        .partition(|p| matches!(p.3, Placement::Outside | Placement::Unknown));
    chart
        .draw_series(
            moved
                .iter()
                .map(|&&(x, y, d, _)| Circle::new((x, y), 2, colour(d, lim).filled())),
        )
        .map_err(displacement_err)?;
    if !unchanged.is_empty() {
        chart
            .draw_series(
                unchanged
                    .iter()
                    .map(|p| Circle::new((p.0, p.1), 2, grey.filled())),
            )
            .map_err(displacement_err)?
            .label("node left unchanged (outside the measured area)")
            .legend(move |(x, y)| Circle::new((x + 10, y), 3, grey.filled()));
    }
    chart
        .draw_series(
            grid.nominal
                .iter()
                .map(|q| Circle::new((q[0], q[1]), 2, BLACK.filled())),
        )
        .map_err(displacement_err)?
        .label("measured point")
        .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.8))
        .draw()
        .map_err(displacement_err)?;
    Ok(())
}

/// The colour bar: the displacement each colour stands for.
fn draw_colour_bar(bar: &Area, lim: f64) -> Result<(), PlotError> {
    let fbar = tick_label(-lim, lim);
    let mut scale = ChartBuilder::on(bar)
        .margin_top(10)
        .margin_bottom(45)
        .margin_right(5)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, -lim..lim)
        .map_err(displacement_err)?;
    scale
        .configure_mesh()
        .disable_x_mesh()
        .disable_x_axis()
        .disable_y_mesh()
        .y_desc("displacement, mm")
        .y_label_formatter(&fbar)
        .draw()
        .map_err(displacement_err)?;
    let steps = 100;
    scale
        .draw_series((0..steps).map(|k| {
            let a = -lim + 2.0 * lim * k as f64 / steps as f64;
            let b = -lim + 2.0 * lim * (k + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], colour(0.5 * (a + b), lim).filled())
        }))
        .map_err(displacement_err)?;
    Ok(())
}

/// A named, coloured line of a plot.
type Line = (&'static str, Vec<(f64, f64)>, RGBColor);
/// The closed loop: max and RMS deviation per round (true and measured),
/// log scale.
pub fn convergence_svg(r: &LoopResult) -> Result<Vec<u8>, PlotError> {
    let err = svg_err("convergence.svg");
    let n = r.rounds.len();
    let lines: [Line; 4] = [
        (
            "true max |deviation| (check grid)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.true_max_mm))
                .collect(),
            PALETTE[3],
        ),
        (
            "true rms deviation (check grid)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.true_rms_mm))
                .collect(),
            PALETTE[0],
        ),
        (
            "measured max |deviation| (CMM)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.measured_max_mm))
                .collect(),
            PALETTE[1],
        ),
        (
            "measured rms deviation (CMM)",
            r.rounds
                .iter()
                .enumerate()
                .map(|(k, x)| (k as f64, x.measured_rms_mm))
                .collect(),
            PALETTE[2],
        ),
    ];
    let (lo, hi) = lines
        .iter()
        .flat_map(|l| l.1.iter().map(|p| p.1))
        .filter(|v| *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let (lo, hi) = if lo.is_finite() {
        (lo / 2.0, hi * 2.0)
    } else {
        (1e-4, 1.0)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Closed loop: deviation of the part per round",
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.2..(n as f64 - 0.8), (lo..hi).log_scale())
            .map_err(|e| err(e.into()))?;
        // Rounds are whole numbers: at most one label per round, no minor
        // lines between them.
        let round = |v: &f64| format!("{v:.0}");
        chart
            .configure_mesh()
            .x_desc("round (0: nominal program)")
            .y_desc("deviation, mm")
            .x_labels(n.max(1))
            .x_max_light_lines(1)
            .x_label_formatter(&round)
            .draw()
            .map_err(|e| err(e.into()))?;
        for (name, pts, color) in lines {
            let pts: Vec<(f64, f64)> = pts.into_iter().map(|(x, y)| (x, y.max(lo))).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| err(e.into()))?
                .label(name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
                .map_err(|e| err(e.into()))?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()
            .map_err(|e| err(e.into()))?;
        root.present().map_err(|e| err(e.into()))?;
    }
    Ok(svg.into_bytes())
}
