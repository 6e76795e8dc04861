//! The key points (`[[point]]`): names used once, positions finite, on links
//! that exist.

use nalgebra::Point3;

use super::links::link_named;
use super::numbers::finite;
use crate::MachineError;
use crate::file::PointSpec;
use crate::machine::{KeyPoint, Link};

/// The file's key points on `links`.
pub(super) fn key_points(
    specs: &[PointSpec],
    links: &[Link],
) -> Result<Vec<KeyPoint>, MachineError> {
    let mut points = Vec::with_capacity(specs.len());
    for p in specs {
        let place = format!("point \"{}\"", p.name);
        if points.iter().any(|q: &KeyPoint| q.name == p.name) {
            return Err(MachineError::field(place, "name", "used by two points"));
        }
        for v in p.xyz {
            finite(v, &place, "xyz")?;
        }
        points.push(KeyPoint {
            name: p.name.clone(),
            link: link_named(links, &p.link, &place, "link")?,
            position: Point3::from(p.xyz),
        });
    }
    Ok(points)
}
