//! The file's links as a tree: names given once, parents found, one base, no
//! cycle; ordered parents first.

use std::collections::HashMap;

use crate::MachineError;
use crate::file::LinkSpec;

/// The file's links as a tree, ordered parents first.
pub(super) struct Tree {
    /// The file's index of each link, parents first.
    pub(super) order: Vec<usize>,
    /// Each link's parent, both file indices.
    parent: Vec<Option<usize>>,
    /// Each link's place in `order`, by file index.
    new_index: Vec<usize>,
}

impl Tree {
    /// The tree of the file's `links`.
    pub(super) fn of(links: &[LinkSpec]) -> Result<Self, MachineError> {
        let index = names(links)?;
        let parent = parents(links, &index)?;
        let roots = roots(links, &parent)?;
        let order = parents_first(links, &parent, roots)?;
        let mut new_index = vec![0; links.len()];
        for (k, &i) in order.iter().enumerate() {
            new_index[i] = k;
        }
        Ok(Self {
            order,
            parent,
            new_index,
        })
    }

    /// The parent of the file's link `i`, as an index into the ordered links.
    pub(super) fn parent(&self, i: usize) -> Option<usize> {
        self.parent[i].map(|p| self.new_index[p])
    }
}

/// Each link's file index by its name, every name given and used once.
fn names(links: &[LinkSpec]) -> Result<HashMap<&str, usize>, MachineError> {
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, l) in links.iter().enumerate() {
        if l.name.is_empty() {
            return Err(MachineError::field(
                format!("link #{}", i + 1),
                "name",
                "must not be empty",
            ));
        }
        if index.insert(l.name.as_str(), i).is_some() {
            return Err(MachineError::field(
                format!("link \"{}\"", l.name),
                "name",
                "used by two links",
            ));
        }
    }
    Ok(index)
}

/// Each link's parent's file index, every parent named found.
fn parents(
    links: &[LinkSpec],
    index: &HashMap<&str, usize>,
) -> Result<Vec<Option<usize>>, MachineError> {
    let mut parent = vec![None; links.len()];
    for (i, l) in links.iter().enumerate() {
        if let Some(p) = &l.parent {
            let j = *index.get(p.as_str()).ok_or_else(|| {
                MachineError::field(
                    format!("link \"{}\"", l.name),
                    "parent",
                    format!("no link is named \"{p}\""),
                )
            })?;
            parent[i] = Some(j);
        }
    }
    Ok(parent)
}

/// The links without a parent: the base alone (none when every link has a
/// parent, a cycle that [`parents_first`] names).
fn roots(links: &[LinkSpec], parent: &[Option<usize>]) -> Result<Vec<usize>, MachineError> {
    let roots: Vec<usize> = (0..links.len()).filter(|&i| parent[i].is_none()).collect();
    match roots.as_slice() {
        [_] => {}
        [] if links.is_empty() => {
            return Err(MachineError::field(
                "[machine]",
                "link",
                "no links: give at least the base ([[link]] without a parent)",
            ));
        }
        [] => {}
        [a, b, ..] => {
            return Err(MachineError::field(
                format!("link \"{}\"", links[*b].name),
                "parent",
                format!(
                    "missing: only the base (\"{}\") has no parent",
                    links[*a].name
                ),
            ));
        }
    }
    Ok(roots)
}

/// The file indices of the links, parents first from `roots`; links never
/// reached lie on a cycle.
fn parents_first(
    links: &[LinkSpec],
    parent: &[Option<usize>],
    roots: Vec<usize>,
) -> Result<Vec<usize>, MachineError> {
    let mut order = Vec::with_capacity(links.len());
    let mut placed = vec![false; links.len()];
    let mut frontier: Vec<usize> = roots;
    while let Some(i) = frontier.pop() {
        placed[i] = true;
        order.push(i);
        for (j, p) in parent.iter().enumerate().rev() {
            if *p == Some(i) && !placed[j] {
                frontier.push(j);
            }
        }
    }
    if let Some(i) = (0..links.len()).find(|&i| !placed[i]) {
        return Err(MachineError::field(
            format!("link \"{}\"", links[i].name),
            "parent",
            "the links form a cycle (a link is its own ancestor)",
        ));
    }
    Ok(order)
}
