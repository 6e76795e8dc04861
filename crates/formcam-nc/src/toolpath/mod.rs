//! Milling programs read as text lines with their tool-path nodes, and
//! written back with only the coordinates of motion blocks changed.
//!
//! [`read_toolpath`] reads a 3-axis milling program (ISO/Fanuc, Sinumerik
//! 840D, LinuxCNC; Marlin as ISO) into a [`Toolpath`]: the program's lines as
//! they are, and the [`Node`]s — the tool's position (mm) at the end of every
//! motion block. [`Toolpath::write`] writes the program again with new node
//! positions: every line that is not a motion block is kept byte for byte,
//! and in motion blocks only the numbers of the `X`, `Y`, `Z` words change,
//! in the same number format (decimals, padding, a missing word added where
//! an axis now moves).
//!
//! Understood: `G0/G1/G2/G3` (also `G00..G03`, modal), `G90/G91` (absolute,
//! incremental), `G90.1/G91.1` (arc centres absolute or incremental; the
//! default is incremental), `G17/G18/G19` (arc planes), `G20/G21` (inch, mm;
//! `G70/G71`, `G700/G710` on Sinumerik), `I J K` centres, `R` (ISO, LinuxCNC)
//! and `CR=` (Sinumerik) radii, helical arcs, `N` numbers, `/` block delete,
//! `(…)` comments (not on Sinumerik), `;` comments, `%` and program-number
//! lines. `G4` dwell lines are kept as they are; `G28/G30/G53` lines too, and
//! the axes they name become unknown until the program sets them again.
//!
//! Arcs are linearised: every arc block becomes `G1` blocks whose chords stay
//! within `arc_tolerance_mm` of the arc (the first keeps the block's other
//! words, the rest are new lines). The caller says so in the header comment it
//! passes to [`Toolpath::write`].
//!
//! Errors name the line (1-based) and quote its text: an unreadable number, a
//! letter without a value, an expression or keyword in a motion block,
//! coordinate-system changes (`G92`, `G52`, `G10`, `G51`, `G68`, Sinumerik
//! frames), canned cycles, rotary or secondary axes, an incremental move from
//! an unknown position, an arc whose end is not on its circle, arcs in
//! inverse-time feed. `refuse` decides which words are read, passed over or
//! refused (polar coordinates, splines, subprogram and cycle calls, frames,
//! radius compensation, program flow: a typed [`crate::Refusal`]) and
//! reports a last line cut off in the middle of a word.
//!
//! The words of each line come from the crate's one G-code lexer and the G
//! codes from its modal state; `read` interprets them per line (positions,
//! arcs in `arc`), `write` is the style-keeping writer.

mod arc;
mod read;
mod refuse;
#[cfg(test)]
mod tests;
mod write;

use std::ops::Range;

use crate::Dialect;

pub use read::read_toolpath;

/// How a node was reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeKind {
    /// A rapid move (`G0`).
    Rapid,
    /// A straight feed move (`G1`).
    Feed,
    /// A point of a linearised arc (`G2`/`G3`).
    Arc,
}

/// A node of the tool path: the tool's position at the end of a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// `X, Y, Z` in mm; NaN for an axis the program has not set yet.
    pub position: [f64; 3],
    /// The move that reached it.
    pub kind: NodeKind,
    /// The program line (1-based).
    pub line: usize,
}

/// Reading options.
#[derive(Debug, Clone, Copy)]
pub struct ToolpathOptions {
    /// The syntax: a G-code dialect ([`Dialect::MarlinXab`] is read as ISO;
    /// [`Dialect::Cldata`] is no G-code and refused).
    pub dialect: Dialect,
    /// The largest distance of an arc's chords from the arc, mm (> 0).
    pub arc_tolerance_mm: f64,
    /// Straight feed moves (`G1`) longer than this (mm) are split into equal
    /// pieces, each a node (written back as `G1` lines), so that a correction
    /// can bend them; `None` keeps them whole.
    pub max_segment_mm: Option<f64>,
}

impl Default for ToolpathOptions {
    fn default() -> Self {
        Self {
            dialect: Dialect::Iso,
            arc_tolerance_mm: 0.001,
            max_segment_mm: None,
        }
    }
}

/// A milling program: its text, lines and tool-path nodes.
#[derive(Debug, Clone)]
pub struct Toolpath {
    text: String,
    lines: Vec<Line>,
    /// The nodes in program order.
    pub nodes: Vec<Node>,
    /// Arc blocks that were linearised.
    pub arcs_linearised: usize,
    /// Feed moves split into pieces (`max_segment_mm`).
    pub moves_split: usize,
    dialect: Dialect,
    format: NumberFormat,
}

impl Toolpath {
    /// The number of lines.
    pub fn line_count(&self) -> usize {
        self.lines.len()
    }

    /// The dialect it was read in.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Decimals of the program's coordinates.
    pub fn decimals(&self) -> u32 {
        self.format.decimals
    }
}

/// One line of the program.
#[derive(Debug, Clone)]
struct Line {
    /// The line's text, without its terminator.
    text: Range<usize>,
    /// Its terminator (`\n`, `\r\n`, or empty at the end).
    eol: Range<usize>,
    /// The motion block on it.
    motion: Option<MotionLine>,
    /// Axes this line leaves unknown (`G28`, `G30`, `G53`).
    forgets: [bool; 3],
}

/// A motion block's editable parts.
#[derive(Debug, Clone)]
struct MotionLine {
    /// The `X`, `Y`, `Z` numbers.
    words: [Option<NumSpan>; 3],
    /// Where a missing axis word goes (a byte offset in the text).
    insert_at: usize,
    /// Incremental (`G91`) block.
    incremental: bool,
    /// mm per program unit.
    scale: f64,
    /// The nodes of the block.
    nodes: Range<usize>,
    /// For an arc block: what turns it into a `G1` block.
    arc: Option<ArcEdit>,
    /// The block starts with `/`: so do the lines added after it.
    block_delete: bool,
}

/// The number of one axis word in the text.
#[derive(Debug, Clone)]
struct NumSpan {
    /// Bytes of the number (after the letter, `=` and blanks).
    range: Range<usize>,
    /// The value as written (program units).
    value: f64,
}

/// The edits that make an arc block a straight one.
#[derive(Debug, Clone)]
struct ArcEdit {
    /// The `G2`/`G3` word (letter and number), if the block has one.
    g_word: Option<Range<usize>>,
    /// Where `G1 ` goes when the arc mode is modal.
    g_insert_at: usize,
    /// The centre and radius words (with the blanks before them).
    remove: Vec<Range<usize>>,
}

/// How the program writes coordinates.
#[derive(Debug, Clone, Copy)]
struct NumberFormat {
    /// Decimals of the most precise axis word.
    decimals: u32,
    /// Every word with a point has all `decimals` places (`10.500`).
    padded: bool,
    /// Whole numbers are written with a point (`10.`).
    whole_point: bool,
    /// Blanks between words.
    spaced: bool,
    /// The motion word of added lines (`G1` or `G01`).
    linear: &'static str,
}
