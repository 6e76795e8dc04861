//! Dressing a grinding wheel for ball-screw nut raceways (docs/dressing.md): the
//! gothic-arch profile, the dresser's path, the simulation of forming and the
//! feed that keeps the material-removal rate constant.
//!
//! Coordinates: the wheel's axial section, `x` along the wheel's axis (the
//! machine's Z), `y` radial and outward (the machine's X), the ball's centre
//! at the origin; the wheel's material lies below its profile. mm, rad,
//! mm/min.
//!
//! * [`Profile`] — the gothic arch from [`WheelSpec`]: flank arcs `R1` whose
//!   centres are offset so that the ball touches them at the contact angle,
//!   concave fillets `R2`, straight flanks at a tilt, joined exactly where
//!   tangent; contact points, clearance at the bottom, sampling.
//! * [`Dresser`] — the dressing wheel's section from [`DresserSpec`] (width,
//!   two corner radii, point A), its periphery as an [`Outline`].
//! * [`dresser_path`] — the two [`Pass`]es: the profile's equidistant at the
//!   corner radius of the half being dressed, with rolls round the wheel's
//!   edge and the apex, cut into steps.
//! * [`simulate`] — forming: the dresser stepped along its path cutting the
//!   wheel's [`Contour`] exactly (polyline graphs, `min(g, d)`); per [`Step`]
//!   the removed area, the cut arc and its angle ([`Forming`]).
//! * [`plan_feed`] — the feed for a constant removal rate within the feed
//!   limits, smoothed ([`FeedSpec`], [`FeedPlan`]).
//! * [`dress`] — all of it from a [`DressSpec`], with the NC program (Z, X,
//!   a feed per point) in a [`Dressing`]; [`DressJob`] is the TOML job.
//!
//! ```
//! use formcam_dress::{DressJob, dress};
//!
//! let job = DressJob::from_toml(
//!     r#"
//!     [wheel]
//!     ball_radius = 1.85
//!     contact_angle_deg = 45.0
//!     r1 = 1.937
//!     r2 = 0.296
//!     width = 6.0
//!     flank_tilt_deg = 10.0
//!     [dresser]
//!     width = 2.9
//!     corner_radius_left = 0.258
//!     corner_radius_right = 0.279
//!     [process]
//!     depth = 0.05
//!     step = 0.02
//!     feed_min = 50.0
//!     feed_max = 300.0
//!     "#,
//! )?;
//! let d = dress(&job.spec(None)?)?;
//! let removed = d.forming.removed();
//! assert!((removed - d.forming.area_between()).abs() < 1e-9 * removed);
//! assert!(d.nc(formcam_nc::Dialect::Sinumerik840d)?.contains("G18"));
//! # Ok::<(), formcam_dress::DressError>(())
//! ```

mod contour;
mod contour_file;
mod curve;
mod dresser;
mod dressing;
mod error;
mod feed;
#[cfg(test)]
mod fixtures;
mod forming;
mod job;
mod path;
mod point;
mod profile;
mod program;

pub use contour::Contour;
pub use contour_file::read_contour;
pub use curve::Piece;
pub use dresser::{Dresser, DresserSpec, Outline, Side};
pub use dressing::{Allowance, DressSpec, Dressing, STEP_MIN, dress, dress_with};
pub use error::{ContourFault, ContourLineProblem, DressError};
pub use feed::{FeedPlan, FeedSpec, plan_feed};
pub use forming::{Forming, Step, offset_contour, simulate, simulate_with};
pub use job::{ARC_ANGLE_DEG, DRESS_JOB, DressJob, DresserJob, ProcessJob, WheelJob};
pub use path::{LEAD_IN, Pass, PathPoint, Stage, Stretch, dresser_path};
pub use point::Point;
pub use profile::{Contact, Element, Joints, Profile, WheelSpec};
pub use program::CLEARANCE;
