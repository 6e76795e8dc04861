//! Which pairs of solids are checked: not two on one link, not two on
//! links joined directly (as URDF tools do), not a pair the machine file's
//! `[collision] ignore` lists; pairs that never move against each other
//! (no driven joint between their links) are checked once.

use formcam_machine::Machine;

use super::solids::Body;

/// Two solids to check (indices into the bodies).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pair {
    /// The first solid.
    pub a: usize,
    /// The second solid.
    pub b: usize,
    /// Whether no driven joint lies between them (their distance never
    /// changes).
    pub rigid: bool,
}

/// Whether the solids on links `a` and `b` are exempt: the same link, a
/// link and its parent, or a pair `machine` ignores.
pub fn exempt(machine: &Machine, a: usize, b: usize) -> bool {
    let parent = |l: usize| machine.links.get(l).and_then(|x| x.parent);
    a == b
        || parent(a) == Some(b)
        || parent(b) == Some(a)
        || machine.collision.ignore.contains(&[a.min(b), a.max(b)])
}

/// Whether a driven joint lies on the tree path between links `a` and `b`.
fn moves_between(machine: &Machine, a: usize, b: usize) -> bool {
    let driven = |l: usize| machine.links[l].joint.axis.is_some();
    // Every link from `a` up to (not including) the common ancestor, and
    // from `b`.
    let ups = |mut l: usize, other: usize| -> bool {
        while !machine.is_ancestor(l, other) {
            if driven(l) {
                return true;
            }
            match machine.links[l].parent {
                Some(p) => l = p,
                None => break,
            }
        }
        false
    };
    ups(a, b) || ups(b, a)
}

/// Every pair of `bodies` the check looks at; `changes[i]` marks a body that
/// changes between stages (the mandrel), never checked only once.
pub fn pairs(machine: &Machine, bodies: &[Body], changes: &[bool]) -> Vec<Pair> {
    let mut out = Vec::new();
    for a in 0..bodies.len() {
        for b in a + 1..bodies.len() {
            let (la, lb) = (bodies[a].link, bodies[b].link);
            if exempt(machine, la, lb) {
                continue;
            }
            // The bed counts as the base link's (link 0).
            let rigid = !changes[a] && !changes[b] && !moves_between(machine, la, lb);
            out.push(Pair { a, b, rigid });
        }
    }
    out
}
