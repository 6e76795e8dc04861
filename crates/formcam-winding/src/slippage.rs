use serde::Serialize;

/// A `z` interval with its own constant slippage.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MuSegment {
    /// Start of the interval, mm.
    pub z_from: f64,
    /// End of the interval, mm.
    pub z_to: f64,
    /// Slippage on it.
    pub mu: f64,
}

/// The slippage along the meridian used to integrate a path: `mu(z)`.
#[derive(Debug, Clone, PartialEq)]
pub enum MuLaw {
    /// The same `mu` everywhere (0 = geodesic).
    Constant(f64),
    /// Piecewise constant; `mu = 0` outside every segment.
    Segments(Vec<MuSegment>),
}

impl MuLaw {
    /// `mu` at `z` (a point on a segment boundary takes the later segment).
    pub fn at(&self, z: f64) -> f64 {
        match self {
            MuLaw::Constant(m) => *m,
            MuLaw::Segments(segs) => segs
                .iter()
                .rev()
                .find(|s| z >= s.z_from && z < s.z_to)
                .map_or(0.0, |s| s.mu),
        }
    }

    /// The `z` values where `mu` jumps.
    pub fn breakpoints(&self) -> Vec<f64> {
        match self {
            MuLaw::Constant(_) => Vec::new(),
            MuLaw::Segments(segs) => segs.iter().flat_map(|s| [s.z_from, s.z_to]).collect(),
        }
    }

    /// Largest `|mu|` of the law.
    pub fn max_abs(&self) -> f64 {
        match self {
            MuLaw::Constant(m) => m.abs(),
            MuLaw::Segments(segs) => segs.iter().map(|s| s.mu.abs()).fold(0.0, f64::max),
        }
    }
}
