//! Dressing a grinding wheel for ball-screw nut raceways.

mod contour;
mod curve;
mod dresser;
mod error;
mod path;
mod point;
mod profile;

pub use contour::Contour;
pub use curve::Piece;
pub use dresser::{Dresser, DresserSpec, Outline, Side};
pub use error::DressError;
pub use path::{LEAD_IN, Pass, PathPoint, Stage, Stretch, dresser_path};
pub use point::Point;
pub use profile::{Contact, Element, Joints, Profile, WheelSpec};
