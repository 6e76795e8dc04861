//! The plots of a winding layer and of the payout eye.

use formcam_geom::Meridian;
use formcam_winding::Layer;
use formcam_winding::bridging_limit;
use formcam_winding::eye::EyeTrajectory;
use plotters::prelude::*;

use crate::{PlotError, Series, panels_svg};

/// The layer: meridian with the Clairaut function and the bridging limit, the
/// winding angle and the layer thickness along `z`.
pub fn layer_svg(
    title: &str,
    mandrel: &impl Meridian,
    layer: &Layer,
) -> Result<Vec<u8>, PlotError> {
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
pub fn eye_svg(title: &str, t: &EyeTrajectory) -> Result<Vec<u8>, PlotError> {
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
