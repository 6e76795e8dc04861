//! A correction applied to a whole program: its movable nodes corrected,
//! the displacement limit checked, the program written back.

use formcam_progress::{Cancelled, Phase, Progress, Silent, Step};

use crate::vec3::{V3, add, norm};
use crate::{CorrectError, Corrector, MillingProgram, NodeCorrection, Placement, Totals};

/// A program corrected by [`Corrector::apply`].
#[derive(Debug, Clone)]
pub struct Applied {
    /// The corrected program's text, in the program's own format.
    pub text: String,
    /// Every node's corrected position, mm.
    pub positions: Vec<V3>,
    /// The movable nodes before the correction, mm (rapid moves left out).
    pub nodes: Vec<V3>,
    /// The correction of each movable node, in the order of `nodes`.
    pub corrections: Vec<NodeCorrection>,
    /// The program line (1-based) of each movable node, in the order of
    /// `nodes`.
    pub lines: Vec<usize>,
    /// The program lines (1-based, ascending, each once) of the nodes left
    /// unchanged because they lie beyond the margin.
    pub outside_lines: Vec<usize>,
    /// The totals over `corrections`.
    pub totals: Totals,
}

/// Nodes corrected between two progress reports: enough to keep every
/// worker of the pool busy, and a multiple of the corrector's runs, so the
/// pieces change nothing.
const CHUNK: usize = 16 * crate::correct::RUN;

impl Corrector<'_> {
    /// Corrects every movable node of `program` and writes it back. With
    /// `limit_mm`, a node that would move farther is an error naming its
    /// program line ([`CorrectError::NodeDisplacement`]).
    pub fn apply(
        &self,
        program: &MillingProgram,
        limit_mm: Option<f64>,
    ) -> Result<Applied, CorrectError> {
        self.apply_with(program, limit_mm, &Silent)
    }

    /// [`Self::apply`] reporting the nodes corrected to `progress` (every
    /// 65 536 nodes); [`CorrectError::Cancelled`] when it asks to stop.
    pub fn apply_with(
        &self,
        program: &MillingProgram,
        limit_mm: Option<f64>,
        progress: &dyn Progress,
    ) -> Result<Applied, CorrectError> {
        let positions = program.positions();
        let movable = program.movable();
        let lines: Vec<usize> = (0..positions.len())
            .filter(|&k| movable[k])
            .map(|k| program.line_of(k))
            .collect();
        let nodes: Vec<V3> = positions
            .iter()
            .zip(&movable)
            .filter(|(_, m)| **m)
            .map(|(p, _)| *p)
            .collect();
        let corrections = self.correct_in_chunks(&nodes, progress)?;
        if let Some(limit_mm) = limit_mm {
            check_limit(&corrections, &lines, limit_mm)?;
        }
        let mut moved = positions;
        let mut next = corrections.iter();
        for (p, _) in moved.iter_mut().zip(&movable).filter(|(_, m)| **m) {
            if let Some(c) = next.next() {
                *p = add(*p, c.displacement);
            }
        }
        let mut outside_lines: Vec<usize> = corrections
            .iter()
            .zip(&lines)
            .filter(|(c, _)| c.placement == Placement::Outside)
            .map(|(_, l)| *l)
            .collect();
        outside_lines.dedup();
        Ok(Applied {
            text: program.write(&moved)?,
            positions: moved,
            totals: Totals::of(&corrections),
            nodes,
            corrections,
            lines,
            outside_lines,
        })
    }
}

/// The file of a correction's result that lists what happened to each
/// movable node ([`Applied::status_csv`]).
pub const NODE_STATUS_FILE: &str = "node-status.csv";

impl Applied {
    /// What happened to each movable node, as CSV: `line` (the program
    /// line), `x, y, z` (the node before the correction, mm), `placement`
    /// ([`Placement::name`]), `dx, dy, dz` (its displacement, mm), in the
    /// program's order; numbers as Rust's shortest round trip writes them.
    pub fn status_csv(&self) -> String {
        let mut out = String::with_capacity(64 * (self.nodes.len() + 1));
        out.push_str("line,x,y,z,placement,dx,dy,dz\n");
        for ((p, c), line) in self.nodes.iter().zip(&self.corrections).zip(&self.lines) {
            let [x, y, z] = *p;
            let [dx, dy, dz] = c.displacement;
            let word = c.placement.name();
            out.push_str(&format!("{line},{x},{y},{z},{word},{dx},{dy},{dz}\n"));
        }
        out
    }
}

impl Corrector<'_> {
    /// [`Corrector::correct`] chunk by chunk, each chunk reported.
    fn correct_in_chunks(
        &self,
        nodes: &[V3],
        progress: &dyn Progress,
    ) -> Result<Vec<NodeCorrection>, Cancelled> {
        let total = nodes.len() as u64;
        progress.checkpoint(Step::new(Phase::Nodes, 0, total))?;
        let mut out = Vec::with_capacity(nodes.len());
        for chunk in nodes.chunks(CHUNK) {
            out.extend(self.correct(chunk));
            progress.checkpoint(Step::new(Phase::Nodes, out.len() as u64, total))?;
        }
        Ok(out)
    }
}

/// The first node (in program order) moving farther than `limit_mm`, as an
/// error naming its program line.
fn check_limit(
    corrections: &[NodeCorrection],
    lines: &[usize],
    limit_mm: f64,
) -> Result<(), CorrectError> {
    for (c, line) in corrections.iter().zip(lines) {
        let d = norm(c.displacement);
        if d.is_nan() || d > limit_mm {
            return Err(CorrectError::NodeDisplacement {
                line: *line,
                displacement_mm: d,
                limit_mm,
            });
        }
    }
    Ok(())
}

/// Program lines as ranges: `1-3, 7, 9-12`.
pub fn line_ranges(lines: &[usize]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        let start = lines[k];
        let mut end = start;
        while k + 1 < lines.len() && lines[k + 1] <= end + 1 {
            k += 1;
            end = lines[k];
        }
        out.push(if end == start {
            start.to_string()
        } else {
            format!("{start}-{end}")
        });
        k += 1;
    }
    out.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_read_as_ranges() {
        assert_eq!(line_ranges(&[1, 2, 3, 7, 9, 10, 11, 12]), "1-3, 7, 9-12");
        assert_eq!(line_ranges(&[4]), "4");
        assert_eq!(line_ranges(&[]), "");
    }
}
