//! A `[winding]` table (or a `[[layer]]`) turned into a [`LayerSpec`] for a
//! mandrel, with errors that name the dotted field.

use formcam_files::quote;
use formcam_geom::Meridian;

use super::build::need;
use super::{LayerKind, Mandrel, MuField, WindingSpec};
use crate::{Ends, LayerSpec, MuSegment, Slippage, TubeTurn, WindingError};

impl WindingSpec {
    /// The layer specification for `mandrel`.
    pub fn layer_spec(&self, mandrel: &Mandrel) -> Result<LayerSpec, WindingError> {
        let slippage = self.slippage()?;
        let hoop = self.hoop()?;
        self.check_kind_fields(hoop)?;
        let ends = self.ends(mandrel, hoop)?;
        let turnaround = self.turnaround(mandrel, hoop)?;
        let default_dwell = if mandrel.is_tube() && turnaround == TubeTurn::Extension {
            180.0
        } else {
            0.0
        };
        let defaults = LayerSpec::default();
        Ok(LayerSpec {
            slippage,
            ends,
            band_width: need(
                "winding.band_width",
                self.band_width,
                "band width in mm, > 0",
            )?,
            band_thickness: need(
                "winding.band_thickness",
                self.band_thickness,
                "band thickness in mm, > 0",
            )?,
            overlap: self.overlap.unwrap_or(0.0),
            pattern_number: self.pattern_number,
            skip_index: self.skip_index,
            dwell_min: self.dwell_min_deg.unwrap_or(default_dwell).to_radians(),
            mu_limit: self.mu_limit.unwrap_or(defaults.mu_limit),
            samples: self.samples.unwrap_or(defaults.samples),
            minimax_nodes: defaults.minimax_nodes,
            turnaround,
        })
    }

    /// `mu` or `mu_segments`: how the slippage is chosen.
    fn slippage(&self) -> Result<Slippage, WindingError> {
        Ok(match (&self.mu, &self.mu_segments) {
            (Some(_), Some(_)) => {
                return Err(WindingError::field(
                    "winding.mu",
                    "give either mu or mu_segments, not both",
                ));
            }
            (None, Some(segs)) => Slippage::Segments(
                segs.iter()
                    .map(|s| MuSegment {
                        z_from: s.z_from,
                        z_to: s.z_to,
                        mu: s.mu,
                    })
                    .collect(),
            ),
            (None, None) | (Some(MuField::Number(0.0)), None) => Slippage::Geodesic,
            (Some(MuField::Number(m)), None) => Slippage::Constant(*m),
            (Some(MuField::Word(w)), None) => match w.as_str() {
                "auto" => Slippage::Auto,
                "minimax" => Slippage::Minimax,
                "geodesic" => Slippage::Geodesic,
                other => {
                    return Err(WindingError::field(
                        "winding.mu",
                        format!(
                            "\"{}\" is not a slippage; allowed: a number, \"auto\", \"minimax\"",
                            quote(other)
                        ),
                    ));
                }
            },
        })
    }

    /// Whether the layer is a hoop layer (`kind`: `helical` or `hoop` here).
    fn hoop(&self) -> Result<bool, WindingError> {
        Ok(match self.kind {
            None | Some(LayerKind::Helical) => false,
            Some(LayerKind::Hoop) => true,
            Some(other) => {
                return Err(WindingError::field(
                    "winding.kind",
                    format!("\"{}\" is not a layer kind here (helical or hoop)", other),
                ));
            }
        })
    }

    /// Checks that the fields only one kind of layer takes are not given for another.
    fn check_kind_fields(&self, hoop: bool) -> Result<(), WindingError> {
        if self.mandrel_rotation_deg.is_some() {
            return Err(WindingError::field(
                "winding.mandrel_rotation_deg",
                "only for kind = \"skip\"",
            ));
        }
        if self.one_way.is_some() && !hoop {
            return Err(WindingError::field(
                "winding.one_way",
                "only for kind = \"hoop\"",
            ));
        }
        Ok(())
    }

    /// Where the passes start and end: a tube's winding angle (from the band
    /// width for a hoop layer), or the polar openings of a vessel or a profile.
    fn ends(&self, mandrel: &Mandrel, hoop: bool) -> Result<Ends, WindingError> {
        Ok(match mandrel {
            Mandrel::Cylinder(_) | Mandrel::Cone(_) if hoop => {
                if self.winding_angle_deg.is_some() {
                    return Err(WindingError::field(
                        "winding.winding_angle_deg",
                        "a hoop layer's angle follows from the band width; leave it out",
                    ));
                }
                let w = need(
                    "winding.band_width",
                    self.band_width,
                    "band width in mm, > 0",
                )?;
                let (z0, _) = mandrel.z_range();
                // One band width per turn: tan(alpha) = 2 pi r / w.
                Ends::Tube {
                    winding_angle: (std::f64::consts::TAU * mandrel.r(z0) / w).atan(),
                }
            }
            _ if hoop => {
                return Err(WindingError::field(
                    "winding.kind",
                    "hoop layers are wound on tubes and on a vessel's cylinder (multi-layer jobs)",
                ));
            }
            Mandrel::Cylinder(_) | Mandrel::Cone(_) => {
                let deg = need(
                    "winding.winding_angle_deg",
                    self.winding_angle_deg,
                    "the winding angle at z = 0 for a tube, degrees in (0, 90)",
                )?;
                Ends::Tube {
                    winding_angle: deg.to_radians(),
                }
            }
            Mandrel::Vessel(_) | Mandrel::Profile(_) if self.winding_angle_deg.is_some() => {
                return Err(WindingError::field(
                    "winding.winding_angle_deg",
                    format!(
                        "does not apply to a {}: the angle follows from the polar openings \
                         (Clairaut); leave it out",
                        mandrel.kind()
                    ),
                ));
            }
            Mandrel::Vessel(v) => Ends::Poles {
                start: v.start_dome().polar_opening(),
                end: v.end_dome().polar_opening(),
            },
            Mandrel::Profile(t) => {
                let (a, b) = t.z_range();
                Ends::Poles {
                    start: t.r(a),
                    end: t.r(b),
                }
            }
        })
    }

    /// How a tube's pass turns: `extension` (the default) or `friction`.
    fn turnaround(&self, mandrel: &Mandrel, hoop: bool) -> Result<TubeTurn, WindingError> {
        Ok(match self.turnaround.as_deref() {
            Some(_) if !mandrel.is_tube() => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    "only for tubes (cylinder, cone); a vessel's pass turns at its polar openings",
                ));
            }
            None | Some("extension") => TubeTurn::Extension,
            Some("friction") if mandrel.is_tube() && !hoop => TubeTurn::Friction,
            Some("friction") => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    "\"friction\" is for helical layers on tubes (cylinder, cone)",
                ));
            }
            Some(other) => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    format!(
                        "\"{}\" is not a turn-around; allowed: \"extension\" (beyond the tube's \
                         ends), \"friction\" (on the tube, held by mu)",
                        quote(other)
                    ),
                ));
            }
        })
    }
}

impl WindingSpec {
    /// Values that are allowed but implausible on `mandrel`, as lines naming
    /// the field: a band wider than half the circumference of a polar opening
    /// (it cannot lie flat round the opening).
    pub fn warnings(&self, mandrel: &Mandrel) -> Vec<String> {
        let mut out = Vec::new();
        let openings = match mandrel {
            Mandrel::Vessel(v) => [v.start_dome().polar_opening(), v.end_dome().polar_opening()],
            _ => return out,
        };
        let smallest = openings[0].min(openings[1]);
        if let Some(w) = self.band_width
            && w > std::f64::consts::PI * smallest
        {
            out.push(format!(
                "winding.band_width: {w} mm is wider than half the circumference of the \
                 {smallest} mm polar opening ({:.1} mm)",
                std::f64::consts::PI * smallest
            ));
        }
        out
    }
}
