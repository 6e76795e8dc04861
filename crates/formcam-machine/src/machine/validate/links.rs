//! The links in tree order, each with its joint checked, its axis (an NC
//! address that drives one joint only) and its solids.

use super::joint::joint;
use super::tree::Tree;
use super::visual::visual;
use crate::MachineError;
use crate::file::LinkSpec;
use crate::machine::{Axis, Link};

/// The links, parents first, and the axes driving them, in that order.
pub(super) struct Links {
    /// The links.
    pub(super) links: Vec<Link>,
    /// The driven axes.
    pub(super) axes: Vec<Axis>,
    /// The file's link of each axis.
    pub(super) link_of_axis: Vec<usize>,
}

/// The file's links built in the order of `tree`.
pub(super) fn links(specs: &[LinkSpec], tree: &Tree) -> Result<Links, MachineError> {
    let mut links = Vec::with_capacity(tree.order.len());
    let mut axes: Vec<Axis> = Vec::new();
    let mut link_of_axis: Vec<usize> = Vec::new();
    for &i in &tree.order {
        let l = &specs[i];
        let place = format!("link \"{}\"", l.name);
        let (mut j, axis) = joint(l, &place)?;
        if let Some(mut a) = axis {
            if axes.iter().any(|b| b.name == a.name) {
                return Err(MachineError::field(
                    place,
                    "axis",
                    format!("\"{}\" drives two joints", a.name),
                ));
            }
            a.link = links.len();
            j.axis = Some(axes.len());
            axes.push(a);
            link_of_axis.push(i);
        }
        let visuals = l
            .visuals
            .iter()
            .map(|v| visual(v, &place))
            .collect::<Result<Vec<_>, _>>()?;
        links.push(Link {
            name: l.name.clone(),
            parent: tree.parent(i),
            joint: j,
            visuals,
        });
    }
    Ok(Links {
        links,
        axes,
        link_of_axis,
    })
}

/// The index of the link named `name`, which `place`'s `field` names.
pub(super) fn link_named(
    links: &[Link],
    name: &str,
    place: &str,
    field: &str,
) -> Result<usize, MachineError> {
    links
        .iter()
        .position(|l| l.name == name)
        .ok_or_else(|| MachineError::field(place, field, format!("no link is named \"{name}\"")))
}
