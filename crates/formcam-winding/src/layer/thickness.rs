//! `thickness`: the layer's thickness of two plies along the pass, held near
//! the turn-arounds.

use std::f64::consts::TAU;

use formcam_geom::Meridian;

use super::lay::Laid;
use super::spec::LayerSpec;
use crate::PathPoint;

/// Layer thickness of two plies, `n` bands of width `b` across a parallel of
/// circumference `2 pi r` at angle `alpha`, mm.
pub(super) fn ply_thickness(spec: &LayerSpec, n: f64, r: f64, alpha: f64) -> f64 {
    2.0 * spec.band_thickness * n * spec.band_width / (TAU * r * alpha.cos().max(1e-12))
}

/// The thickness at the points asked for and the largest along the dense pass.
/// Near a turn-around `cos(alpha) -> 0` and the formula diverges: within one
/// band width of the turn radius it is held at its value one band width out
/// (`turns_on_mandrel`: false for a tube turned beyond its ends).
pub(super) fn thickness<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    laid: &Laid,
    eq: &PathPoint,
    n: f64,
    turns_on_mandrel: bool,
) -> (Vec<f64>, f64) {
    let (za, zb) = m.z_range();
    let dense = &laid.dense;
    // The cap of each end: the thickness where the path first (from that end) is a
    // band width above its turn radius, held constant towards the turn; where the
    // meridian does not narrow towards the end (a tube turned by friction, a
    // flaring end), where the path is a band width from the turn along the meridian.
    let full = |p: &PathPoint| ply_thickness(spec, n, p.r, p.alpha);
    let cap_of = |mut it: Box<dyn Iterator<Item = &PathPoint> + '_>, narrows: bool| {
        let first = it.next().copied()?;
        if narrows {
            let reach = (first.c + spec.band_width).min(eq.r);
            it.find(|p| p.r >= reach).map(|p| (p.z, full(p)))
        } else {
            it.find(|p| (p.z - first.z).hypot(p.r - first.r) >= spec.band_width)
                .map(|p| (p.z, full(p)))
        }
    };
    let start_cap = if turns_on_mandrel {
        cap_of(Box::new(dense.iter()), m.dr(za) > 0.0)
    } else {
        None
    };
    let end_cap = if turns_on_mandrel {
        cap_of(Box::new(dense.iter().rev()), m.dr(zb) < 0.0)
    } else {
        None
    };
    let thick = |p: &PathPoint| match (start_cap, end_cap) {
        (Some((z, t)), _) if p.z < z => t,
        (_, Some((z, t))) if p.z > z => t,
        _ => full(p),
    };
    let thickness: Vec<f64> = laid.points.iter().map(thick).collect();
    let thickness_max = dense.iter().map(thick).fold(0.0, f64::max);
    (thickness, thickness_max)
}
