//! `equator`: the parallel the pattern must cover.

use std::f64::consts::FRAC_PI_2;

use crate::PathPoint;
use crate::path::TANGENT_ALPHA_TOL;

/// The parallel the pattern must cover: the widest, or, where the pass turns on
/// it (a tube turned by friction, a shell whose ends flare), the parallel the
/// bands cross most widely (largest `r cos(alpha)`).
pub(super) fn equator(dense: &[PathPoint]) -> PathPoint {
    let widest = dense
        .iter()
        .copied()
        .fold(dense[0], |a, p| if p.r > a.r { p } else { a });
    if widest.alpha >= FRAC_PI_2 - TANGENT_ALPHA_TOL {
        let across = |p: &PathPoint| p.r * p.alpha.cos();
        dense
            .iter()
            .copied()
            .fold(dense[0], |a, p| if across(&p) > across(&a) { p } else { a })
    } else {
        widest
    }
}
