use crate::{GeomError, Isotensoid, Jet, positive};

/// The kind of a dome, with the parameters that shape it beyond the equator
/// radius and the polar opening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DomeShape {
    /// A hemisphere of the equator radius.
    Hemisphere,
    /// Half an ellipsoid; `axis_ratio` = dome depth / equator radius (0.5 is the 2:1 head).
    Ellipsoid {
        /// Depth of the full (unopened) dome over the equator radius, > 0.
        axis_ratio: f64,
    },
    /// A torispherical head: a crown sphere joined tangentially to a knuckle torus.
    Torispherical {
        /// Crown radius, mm, `>= radius`.
        crown_radius: f64,
        /// Knuckle radius, mm, `0 < knuckle < radius`.
        knuckle_radius: f64,
    },
    /// The geodesic-isotensoid dome designed for the polar opening (netting theory).
    Isotensoid,
}

#[derive(Debug, Clone, PartialEq)]
enum Profile {
    Sphere {
        radius: f64,
    },
    Ellipse {
        a: f64,
        b: f64,
    },
    Torus {
        radius: f64,
        knuckle: f64,
        crown: f64,
        w_centre: f64,
        w_joint: f64,
    },
    Isotensoid(Isotensoid),
}

/// A dome cut at its polar opening, described by the distance `w` from the
/// equator towards the pole: `r(0) = radius`, `r'(0) = 0`, `r(height) = polar_opening`
/// (except the isotensoid, which ends where its meridian turns parallel to the axis,
/// see [`Isotensoid`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Dome {
    profile: Profile,
    radius: f64,
    polar_opening: f64,
    height: f64,
    joints: Vec<f64>,
}

impl Dome {
    /// A dome of `shape` on a cylinder of `radius`, opened at `polar_opening`.
    pub fn new(shape: DomeShape, radius: f64, polar_opening: f64) -> Result<Self, GeomError> {
        let radius = positive("radius", radius)?;
        let polar_opening = positive("polar_opening", polar_opening)?;
        if polar_opening >= radius {
            return Err(GeomError::OutOfRange {
                field: "polar_opening",
                value: polar_opening,
                allowed: format!("0 < polar_opening < radius ({radius})"),
            });
        }
        let rp = polar_opening;
        let (profile, height, joints) = match shape {
            DomeShape::Hemisphere => (
                Profile::Sphere { radius },
                (radius * radius - rp * rp).sqrt(),
                vec![],
            ),
            DomeShape::Ellipsoid { axis_ratio } => {
                let k = positive("axis_ratio", axis_ratio)?;
                let b = k * radius;
                let q = rp / radius;
                (
                    Profile::Ellipse { a: radius, b },
                    b * (1.0 - q * q).sqrt(),
                    vec![],
                )
            }
            DomeShape::Torispherical {
                crown_radius,
                knuckle_radius,
            } => {
                let crown = positive("crown_radius", crown_radius)?;
                let knuckle = positive("knuckle_radius", knuckle_radius)?;
                if knuckle >= radius {
                    return Err(GeomError::OutOfRange {
                        field: "knuckle_radius",
                        value: knuckle,
                        allowed: format!("0 < knuckle_radius < radius ({radius})"),
                    });
                }
                if crown < radius {
                    return Err(GeomError::OutOfRange {
                        field: "crown_radius",
                        value: crown,
                        allowed: format!("crown_radius >= radius ({radius})"),
                    });
                }
                // Knuckle centre at (w = 0, r = radius - knuckle); crown centre on the
                // axis at w = w_centre < 0, at distance crown - knuckle from it.
                let a = radius - knuckle;
                let w_centre = -((crown - knuckle).powi(2) - a * a).max(0.0).sqrt();
                let w_joint = w_centre * (1.0 - crown / (crown - knuckle));
                let r_joint = crown * a / (crown - knuckle);
                let height = if rp <= r_joint {
                    w_centre + (crown * crown - rp * rp).sqrt()
                } else {
                    (knuckle * knuckle - (rp - a).powi(2)).sqrt()
                };
                let joints = if rp < r_joint { vec![w_joint] } else { vec![] };
                (
                    Profile::Torus {
                        radius,
                        knuckle,
                        crown,
                        w_centre,
                        w_joint,
                    },
                    height,
                    joints,
                )
            }
            DomeShape::Isotensoid => {
                let iso = Isotensoid::new(radius, rp)?;
                let h = iso.height();
                (Profile::Isotensoid(iso), h, vec![])
            }
        };
        Ok(Self {
            profile,
            radius,
            polar_opening,
            height,
            joints,
        })
    }

    /// Equator radius, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The polar opening the dome was designed for, mm.
    pub fn polar_opening(&self) -> f64 {
        self.polar_opening
    }

    /// Radius at the dome's end (`w = height`), mm: the polar opening, or for the
    /// isotensoid the radius where its meridian turns parallel to the axis.
    pub fn end_radius(&self) -> f64 {
        self.eval_w(self.height).r
    }

    /// Axial depth from the equator to the dome's end, mm.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Values of `w` where `r''` jumps (the crown–knuckle joint of a torispherical head).
    pub fn joints(&self) -> &[f64] {
        &self.joints
    }

    /// `r(w)` and its derivatives with respect to `w` (distance from the equator).
    pub fn eval_w(&self, w: f64) -> Jet {
        match &self.profile {
            Profile::Sphere { radius } => circle(*radius, 0.0, w, 0.0),
            Profile::Ellipse { a, b } => {
                let u = w / b;
                let s = (1.0 - u * u).sqrt();
                let r = a * s;
                let dr = -a * u / (b * s);
                let d2r = -a / (b * b * s * s * s);
                Jet { r, dr, d2r }
            }
            Profile::Torus {
                radius,
                knuckle,
                crown,
                w_centre,
                w_joint,
            } => {
                if w <= *w_joint {
                    circle(*knuckle, 0.0, w, radius - knuckle)
                } else {
                    circle(*crown, *w_centre, w, 0.0)
                }
            }
            Profile::Isotensoid(iso) => iso.eval_w(w),
        }
    }

    /// `r(w)` alone (cheaper than [`Dome::eval_w`] for the analytic shapes).
    pub fn r_w(&self, w: f64) -> f64 {
        match &self.profile {
            Profile::Sphere { radius } => (radius * radius - w * w).sqrt(),
            Profile::Ellipse { a, b } => {
                let u = w / b;
                a * (1.0 - u * u).sqrt()
            }
            Profile::Torus { .. } | Profile::Isotensoid(_) => self.eval_w(w).r,
        }
    }
}

/// Upper half of a circle of radius `rho` centred at `(w0, r0)`, as `r(w)`.
fn circle(rho: f64, w0: f64, w: f64, r0: f64) -> Jet {
    let d = w - w0;
    let q = (rho * rho - d * d).sqrt();
    Jet {
        r: r0 + q,
        dr: -d / q,
        d2r: -rho * rho / (q * q * q),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_derivatives(d: &Dome) {
        let h = d.height();
        for i in 1..50 {
            let w = h * i as f64 / 50.0;
            let e = 1e-5;
            let (a, b, c) = (d.eval_w(w - e), d.eval_w(w), d.eval_w(w + e));
            if d.joints().iter().any(|j| (j - w).abs() < 2.0 * e) {
                continue;
            }
            assert!((b.dr - (c.r - a.r) / (2.0 * e)).abs() < 1e-6, "dr at {w}");
            assert!(
                (b.d2r - (c.dr - a.dr) / (2.0 * e)).abs() < 1e-5,
                "d2r at {w}"
            );
        }
    }

    #[test]
    fn domes_start_at_equator_and_end_at_opening() {
        for shape in [
            DomeShape::Hemisphere,
            DomeShape::Ellipsoid { axis_ratio: 0.6 },
            DomeShape::Torispherical {
                crown_radius: 160.0,
                knuckle_radius: 25.0,
            },
        ] {
            let d = Dome::new(shape, 100.0, 30.0).unwrap();
            let j0 = d.eval_w(0.0);
            assert!((j0.r - 100.0).abs() < 1e-12, "{shape:?}");
            assert!(j0.dr.abs() < 1e-12);
            assert!(
                (d.end_radius() - 30.0).abs() < 1e-9,
                "{shape:?} {}",
                d.end_radius()
            );
            check_derivatives(&d);
        }
    }

    #[test]
    fn torispherical_is_c1_at_joint() {
        let d = Dome::new(
            DomeShape::Torispherical {
                crown_radius: 160.0,
                knuckle_radius: 25.0,
            },
            100.0,
            30.0,
        )
        .unwrap();
        let wj = d.joints()[0];
        let (a, b) = (d.eval_w(wj - 1e-12), d.eval_w(wj + 1e-12));
        assert!((a.r - b.r).abs() < 1e-9);
        assert!((a.dr - b.dr).abs() < 1e-9);
        assert!((a.d2r - b.d2r).abs() > 1e-3, "curvature jumps at the joint");
    }

    #[test]
    fn rejects_bad_input() {
        assert!(matches!(
            Dome::new(DomeShape::Hemisphere, 100.0, 100.0),
            Err(GeomError::OutOfRange {
                field: "polar_opening",
                ..
            })
        ));
        assert!(matches!(
            Dome::new(DomeShape::Hemisphere, -1.0, 0.5),
            Err(GeomError::NotPositive {
                field: "radius",
                ..
            })
        ));
        assert!(matches!(
            Dome::new(DomeShape::Hemisphere, f64::NAN, 0.5),
            Err(GeomError::NotFinite {
                field: "radius",
                ..
            })
        ));
        assert!(Dome::new(DomeShape::Ellipsoid { axis_ratio: 0.0 }, 100.0, 10.0).is_err());
        assert!(
            Dome::new(
                DomeShape::Torispherical {
                    crown_radius: 90.0,
                    knuckle_radius: 10.0
                },
                100.0,
                10.0
            )
            .is_err()
        );
    }
}
