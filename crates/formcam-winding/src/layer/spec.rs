//! What a layer asks besides the mandrel ([`LayerSpec`]: the slippage, the
//! ends, the band, the pattern's demands), and its check.

use std::f64::consts::FRAC_PI_2;

use crate::{MuSegment, WindingError};

/// How the slippage of the path is chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum Slippage {
    /// `mu = 0`: geodesic, `r sin(alpha) = C` constant.
    Geodesic,
    /// A given constant `mu`.
    Constant(f64),
    /// The constant `mu` that meets both polar openings (shooting); falls back to
    /// [`Slippage::Minimax`] when that path would bridge a concave part.
    Auto,
    /// Piecewise-constant `mu(z)` given by the user.
    Segments(Vec<MuSegment>),
    /// The smallest worst-case `|mu|` under the bridging limit (eqs. 5–6).
    Minimax,
}

/// Where a pass starts and ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ends {
    /// A closed mandrel: the pass turns at the polar openings of these radii (mm)
    /// (design radii; a polar boss may make the meridian end a little wider).
    Poles {
        /// Opening at `z_start`, mm.
        start: f64,
        /// Opening at `z_end`, mm.
        end: f64,
    },
    /// A tube: the pass runs from `z_start` to `z_end` at the given angle at `z_start`
    /// and the machine turns it around beyond the ends (a dwell of the mandrel).
    Tube {
        /// Winding angle at `z_start`, rad.
        winding_angle: f64,
    },
}

/// How a tube's pass turns at the tube's ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TubeTurn {
    /// The pass runs off the tube's ends and the machine turns the band on the
    /// tube's extension (a dwell of the mandrel).
    #[default]
    Extension,
    /// The pass turns on the tube itself, held by friction: the slippage
    /// ([`Slippage::Constant`]) is the `|mu|` of the turns, the pass is geodesic
    /// between them.
    Friction,
}

/// Everything that defines a layer besides the mandrel.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerSpec {
    /// How the path's slippage is chosen.
    pub slippage: Slippage,
    /// Where passes start and end.
    pub ends: Ends,
    /// Band width, mm.
    pub band_width: f64,
    /// Band thickness, mm.
    pub band_thickness: f64,
    /// Overlap of neighbouring bands, fraction of the band width.
    pub overlap: f64,
    /// Required pattern number.
    pub pattern_number: Option<u32>,
    /// Required skip index.
    pub skip_index: Option<u32>,
    /// Least dwell at each turn-around, rad (tubes need room to turn the band).
    pub dwell_min: f64,
    /// Largest slippage the band and resin can hold (bounds `auto` and `minimax`).
    pub mu_limit: f64,
    /// Points in the sampled pass.
    pub samples: usize,
    /// Grid intervals of the minimax search.
    pub minimax_nodes: usize,
    /// Tubes: where the pass turns.
    pub turnaround: TubeTurn,
}

impl Default for LayerSpec {
    fn default() -> Self {
        Self {
            slippage: Slippage::Geodesic,
            ends: Ends::Poles {
                start: 0.0,
                end: 0.0,
            },
            band_width: 10.0,
            band_thickness: 0.5,
            overlap: 0.0,
            pattern_number: None,
            skip_index: None,
            dwell_min: 0.0,
            mu_limit: 0.6,
            samples: 2001,
            minimax_nodes: 4000,
            turnaround: TubeTurn::Extension,
        }
    }
}

pub(super) fn check_spec(spec: &LayerSpec, (za, zb): (f64, f64)) -> Result<(), WindingError> {
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
    pos("winding.band_width", spec.band_width)?;
    pos("winding.band_thickness", spec.band_thickness)?;
    pos("winding.mu_limit", spec.mu_limit)?;
    if !(spec.dwell_min.is_finite() && spec.dwell_min >= 0.0) {
        return Err(WindingError::field("winding.dwell_min_deg", "must be >= 0"));
    }
    if let Slippage::Constant(m) = spec.slippage
        && (!m.is_finite() || m.abs() > spec.mu_limit)
    {
        {
            return Err(WindingError::field(
                "winding.mu",
                format!(
                    "must be a number with |mu| <= mu_limit ({}), got {m}",
                    spec.mu_limit
                ),
            ));
        }
    }
    if let Slippage::Segments(segs) = &spec.slippage {
        for (i, s) in segs.iter().enumerate() {
            let f = format!("winding.mu_segments[{i}]");
            if !(s.z_from.is_finite() && s.z_to.is_finite() && s.z_from < s.z_to) {
                return Err(WindingError::field(f, "needs finite z_from < z_to"));
            }
            if s.z_to <= za || s.z_from >= zb {
                return Err(WindingError::field(
                    f,
                    format!(
                        "[{}, {}] lies outside the mandrel [{za:.3}, {zb:.3}] mm",
                        s.z_from, s.z_to
                    ),
                ));
            }
            if let Some(prev) = i.checked_sub(1).and_then(|j| segs.get(j))
                && s.z_from < prev.z_to
            {
                return Err(WindingError::field(
                    f,
                    format!(
                        "starts at {} mm, inside the previous segment (to {} mm): segments must be in \
                         order of z and must not overlap",
                        s.z_from, prev.z_to
                    ),
                ));
            }
            if !s.mu.is_finite() || s.mu.abs() > spec.mu_limit {
                return Err(WindingError::field(
                    format!("{f}.mu"),
                    format!("must satisfy |mu| <= mu_limit ({})", spec.mu_limit),
                ));
            }
        }
    }
    if spec.turnaround == TubeTurn::Friction {
        if !matches!(spec.ends, Ends::Tube { .. }) {
            return Err(WindingError::field(
                "winding.turnaround",
                "\"friction\" turns a tube's pass on the tube; a mandrel with polar openings turns there",
            ));
        }
        if !matches!(spec.slippage, Slippage::Constant(m) if m > 0.0) {
            return Err(WindingError::field(
                "winding.mu",
                "with turnaround = \"friction\" give the slippage the turns use, a number > 0",
            ));
        }
    }
    if let Ends::Tube { winding_angle } = spec.ends
        && !(winding_angle > 0.0 && winding_angle < FRAC_PI_2)
    {
        {
            return Err(WindingError::field(
                "winding.winding_angle_deg",
                format!(
                    "must be in (0, 90) degrees, got {}",
                    winding_angle.to_degrees()
                ),
            ));
        }
    }
    Ok(())
}
