//! Post-processors: a [`Program`] written as the text of one NC dialect.
//!
//! Every writer validates the program first ([`Program::validate`]) and the
//! axis names against what the dialect can address, then writes into a
//! `String` (reserved up front). Numbers are written with fixed decimals and
//! trailing zeros stripped: 3 for mm, 4 for degrees, 1 for per-minute feeds
//! given by the program and 3 for feeds computed from block times (G93 `F`,
//! converted feeds). An axis word is written only when its printed value
//! changes (the first motion block writes every axis); CLDATA's `GOTO` always
//! carries every axis.
//!
//! | dialect | file | motion | inverse time |
//! | --- | --- | --- | --- |
//! | `cldata` | `.cls` | `RAPID`, `GOTO/v1,v2,..` | `FEDRAT/f,MMPM` from the linear travel, else `FEDRAT/f,INVERS` |
//! | `sinumerik-840d` | `.mpf` | `N10 G0 X.. J1=..` | `G93` … `G94` |
//! | `iso` | `.nc` | `G00`/`G01 X12.` | `G93` … `G94` |
//! | `linuxcnc` | `.ngc` | `G0`/`G1` | `G93` … `G94` |
//! | `marlin-xab` | `.gcode` | `G0`/`G1` | converted: `F = travel / t * 60` |
//!
//! Notes per dialect:
//!
//! * Sinumerik 840D: every block numbered (`N10`, `N20`, …; comment lines
//!   are not); single-letter axes are written `X12.5`, longer names (`J1`)
//!   `J1=12.5`; header `G90 G94 G71`, end `M30`.
//! * A program's working plane ([`Program::plane`](crate::Program::plane)),
//!   where set, opens the G-code dialects' setup line (`G18 G90 G94 G71`;
//!   Marlin: a line of its own); CLDATA and templates do not write it.
//! * ISO: `%`, `O0001 (NAME)`, `G21 G90 G94`, two-digit `G00`/`G01`, whole
//!   numbers with a decimal point (`X12.`, as Fanuc-style controls without
//!   decimal-point programming would otherwise read micrometres), `M30`, `%`.
//! * LinuxCNC: axes `X Y Z A B C U V W` only; `(PROGRAM NAME)`, `G21 G90 G94`, `M2`.
//! * Marlin X/A/B: axes `X Y Z A B C` only; `G21`, `G90`, `G94` (Marlin answers
//!   `G94` with "unknown command" and goes on), no end code. The travel of a
//!   converted inverse-time block is the Euclidean norm of all axis deltas in
//!   NC units, mm and degrees mixed, as FiberPath computes it; a block that
//!   moves nothing keeps the previous feed. `G0` moves at the firmware's
//!   rapid rate only where `G0_FEEDRATE` is configured.
//! * In the `G93` dialects a `G93` block always carries `F`; the first
//!   per-minute block after inverse time writes `G94` and its `F` again.
//! * Modulo rotary axes ([`crate::modulo`]): ISO and Marlin write `G92 A..`
//!   on a line of its own before a re-zeroed block and the angle less the
//!   re-zeroed turns; Sinumerik 840D writes `A=ACP(..)` / `A=ACN(..)`,
//!   LinuxCNC `A..` / `A-..` (wrapped rotary), the angle within `[0, 360)`.
//! * Comments: line breaks become spaces; in parenthesis comments `(`/`)`
//!   become `[`/`]`.
//!
//! The G-code writers cut programs of 65 536 blocks or more into runs written
//! in parallel on rayon's global pool (each run starting from the modal state
//! the runs before it leave); the text is the same as written in one run.

mod cldata;
mod gcode;

use crate::modulo::{self, ModuloStyle};
use crate::num::{self, Out};
use crate::{Dialect, NcError, Program};

/// Writes `program` in `dialect`, appending to `out`.
///
/// Fails, writing nothing, when the program is inconsistent
/// ([`Program::validate`]), has an axis the dialect cannot address, or has a
/// modulo axis it cannot write within the bound ([`BOUND_DEG`](crate::BOUND_DEG): run
/// [`keep_within_turns`](crate::keep_within_turns) first).
pub fn write(program: &Program, dialect: Dialect, out: &mut String) -> Result<(), NcError> {
    program.validate()?;
    modulo::check(program, ModuloStyle::of(dialect))?;
    num::with_out(out, |out| match dialect {
        Dialect::Cldata => {
            cldata::write(program, out);
            Ok(())
        }
        Dialect::Sinumerik840d => gcode::write(program, &gcode::SINUMERIK, out),
        Dialect::Iso => gcode::write(program, &gcode::ISO, out),
        Dialect::LinuxCnc => gcode::write(program, &gcode::LINUXCNC, out),
        Dialect::MarlinXab => gcode::write(program, &gcode::MARLIN, out),
    })
}

/// Appends `text` with line breaks made spaces and, for parenthesis comments,
/// `(`/`)` made `[`/`]`.
pub(crate) fn push_comment_text(out: &mut Out, text: &str, parens: bool) {
    // Bytes of multi-byte UTF-8 sequences are never ASCII: byte-wise
    // replacement keeps the text valid.
    for b in text.bytes() {
        out.byte(comment_byte(b, parens));
    }
}

/// A byte of a comment's text as written: line breaks made spaces and, for
/// parenthesis comments, `(`/`)` made `[`/`]`.
fn comment_byte(b: u8, parens: bool) -> u8 {
    match b {
        b'\n' | b'\r' => b' ',
        b'(' if parens => b'[',
        b')' if parens => b']',
        b => b,
    }
}

impl Dialect {
    /// The text a comment `text` has in a program written in this dialect,
    /// as its reader gives it back: line breaks made spaces and, where
    /// comments are in parentheses (ISO, LinuxCNC), `(`/`)` made `[`/`]`.
    /// Whoever looks for a comment it wrote (a layer's label) looks for this.
    pub fn comment_as_written(self, text: &str) -> String {
        let parens = match self {
            Dialect::Cldata => false,
            Dialect::Sinumerik840d => gcode::SINUMERIK.parens(),
            Dialect::Iso => gcode::ISO.parens(),
            Dialect::LinuxCnc => gcode::LINUXCNC.parens(),
            Dialect::MarlinXab => gcode::MARLIN.parens(),
        };
        let bytes: Vec<u8> = text.bytes().map(|b| comment_byte(b, parens)).collect();
        // Only ASCII bytes were replaced by ASCII bytes: still UTF-8.
        String::from_utf8(bytes).unwrap_or_else(|_| text.to_owned())
    }
}
