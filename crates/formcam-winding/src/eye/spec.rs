//! What the user asks of the eye: the mode and its fields, checked against the
//! mandrel.

use std::ops::RangeInclusive;

use formcam_geom::Meridian;
use serde::Serialize;

use crate::WindingError;

/// How the eye trajectory is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EyeMode {
    /// On a line parallel to the axis at `radius`.
    AxisParallel,
    /// At `clearance` from the mandrel.
    Equidistant,
    /// On a user curve `R = f(Z)`.
    Curve,
    /// The pull-speed optimum.
    PullSpeed,
}

/// The least clearance's default, mm.
pub const DEFAULT_CLEARANCE_MM: f64 = 20.0;

/// The points of a geometric trajectory allowed.
pub const SAMPLE_COUNTS: RangeInclusive<usize> = 101..=10_000_000;

/// The points of a geometric trajectory by default.
pub const DEFAULT_SAMPLES: usize = 2001;

/// The intervals of the optimised `l(x)` allowed.
pub const NODE_COUNTS: RangeInclusive<usize> = 100..=200_000;

/// The intervals of the optimised `l(x)` by default.
pub const DEFAULT_NODES: usize = 2000;

/// What the user asks of the eye.
#[derive(Debug, Clone, PartialEq)]
pub struct EyeSpec {
    /// The mode.
    pub mode: EyeMode,
    /// Axis-parallel: radius of the eye's line, mm.
    pub radius: Option<f64>,
    /// Least clearance between the eye and the mandrel in every mode, mm
    /// (and the clearance of `equidistant`).
    pub clearance: f64,
    /// Largest free length, mm.
    pub l_max: f64,
    /// `k = 0` (the bath moves with the eye) or `k = 1` (fixed bath).
    pub bath_moves_with_eye: bool,
    /// Curve mode: `(Z, R)` points with `Z` increasing.
    pub curve: Vec<(f64, f64)>,
    /// Points of the trajectory for the geometric modes.
    pub samples: usize,
    /// Intervals of the discretised `l(x)` of the optimisation.
    pub nodes: usize,
}

impl Default for EyeSpec {
    fn default() -> Self {
        Self {
            mode: EyeMode::PullSpeed,
            radius: None,
            clearance: DEFAULT_CLEARANCE_MM,
            l_max: 400.0,
            bath_moves_with_eye: true,
            curve: Vec::new(),
            samples: DEFAULT_SAMPLES,
            nodes: DEFAULT_NODES,
        }
    }
}

/// Checks the eye's fields (positive lengths, sample and node counts, an
/// axis-parallel line outside the mandrel).
pub(super) fn check_spec<M: Meridian>(m: &M, spec: &EyeSpec) -> Result<(), WindingError> {
    let pos = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(WindingError::field(
                field,
                format!("must be a finite number > 0, got {v}"),
            ))
        }
    };
    pos("eye.clearance", spec.clearance)?;
    pos("eye.l_max", spec.l_max)?;
    let count = |field: &str, v: usize, range: RangeInclusive<usize>| {
        if range.contains(&v) {
            Ok(())
        } else {
            Err(WindingError::field(
                field,
                format!("must be in [{}, {}]", range.start(), range.end()),
            ))
        }
    };
    count("eye.samples", spec.samples, SAMPLE_COUNTS)?;
    count("eye.nodes", spec.nodes, NODE_COUNTS)?;
    if spec.mode == EyeMode::AxisParallel {
        let radius = spec.radius.ok_or_else(|| {
            WindingError::field("eye.radius", "missing: the radius of the eye's line, mm")
        })?;
        pos("eye.radius", radius)?;
        let (za, zb) = m.z_range();
        let r_max = (0..=2000)
            .map(|i| m.r(za + (zb - za) * f64::from(i) / 2000.0))
            .fold(0.0, f64::max);
        if radius <= r_max {
            return Err(WindingError::field(
                "eye.radius",
                format!("{radius} mm is inside the mandrel (its largest radius is {r_max:.3} mm)"),
            ));
        }
    }
    Ok(())
}
