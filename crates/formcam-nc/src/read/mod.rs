//! Readers: G-code (ISO, LinuxCNC, Marlin, Sinumerik 840D) and APT CLDATA
//! back into a [`Program`].
//!
//! # G-code ([`read_gcode`])
//!
//! Lexed by the crate's G-code lexer (the milling reader's, in its strict
//! syntax: every letter needs a number, nothing else may stand on a line),
//! numbers in `f64`; Sinumerik `NAME=value` words (`J1=12.5`, `X=3`,
//! `A=ACP(90)`) are read as assignments. The G codes go through the modal
//! state both G-code readers share. All lines are lexed before any is
//! interpreted, so a line that cannot be lexed is reported first.
//!
//! Understood: `G0`/`G00` and `G1`/`G01` (modal), `G90`/`G91` (absolute,
//! incremental), `G93`/`G94` (inverse time: `F` on every feed block, block
//! time `60 / F` s; per minute: `F` modal), `F`, axis words of the given
//! axes, `N` numbers, `%`, `O` numbers (the comment on the `O` line is the
//! program's name), `(…)` and `;…` comments. Other G codes (`G17`, `G21`,
//! `G71`, `G54`, …), M codes, `T`, `S` and words of letters that are no NC
//! axis are passed over; the words after an M code or a `T` (up to the next
//! G code) too. `G4` (dwell) takes the words after it as its time, in the
//! dialect's unit ([`Dwell`](crate::Dwell), in [`Program::dwells`]): LinuxCNC
//! and [`read_gcode`] `P` seconds (rs274ngc); Sinumerik 840D `F` seconds (`S`,
//! spindle revolutions, is refused: the time depends on a spindle speed the
//! program does not hold); ISO/Fanuc `X` or `U` seconds, `P` milliseconds
//! written without a decimal point (with one, the control's setting decides:
//! refused); Marlin `P` milliseconds, `S` seconds (`S` wins). A `G4` without
//! its time word, or a negative time, is an error. Errors: arcs (`G2`/`G3`), inch units
//! (`G20`/`G70`/`G700`), feed per revolution (`G95`), an axis word
//! (`X Y Z A B C U V W` or `NAME=`) that is not one of the given axes, axis
//! words before any `G0`/`G1`, a feed block without a feed, `N` or `O` after
//! a G, M or T code, a `/` block delete, and anything that is not a word —
//! every error with its line number and text.
//!
//! Modulo rotary axes ([`crate::modulo`]) come back as unwound angles:
//! `G92` with axis words sets those axes' values without moving (the blocks
//! after it are read in the shifted frame, and the next block is marked
//! [`Block::rezero`](crate::Block::rezero)); Sinumerik `A=ACP(v)`,
//! `A=ACN(v)` and `A=DC(v)` go to `v` modulo 360° in the positive, negative
//! or shorter direction; with [`read_gcode_in`] and the LinuxCNC dialect, a
//! plain word of a modulo axis is a wrapped rotary position (`A-v`: to `|v|`
//! in the negative direction). In each case the axis stays put when `v` is
//! where it stands.
//!
//! Axes not yet programmed start at 0. Comments: on a motion line, the
//! block's comment; a comment line before the first motion, a header comment
//! (`PROGRAM name` gives the name); a comment line after it, the comment of
//! the next motion block.
//!
//! # CLDATA ([`read_cldata`])
//!
//! `PARTNO/name`, `UNITS/MM`, `$$` comments (header comments up to the first
//! statement after `PARTNO`, then the comment of the next `GOTO`), `RAPID` (the next `GOTO` only),
//! `FEDRAT/f[,MMPM]` and `FEDRAT/f,INVERS` (modal), `GOTO/v1,..,vn` with one
//! value per axis, `ORIGIN/A,o` (the values of axis `A` from there on
//! measured from `o`; the next block marked re-zeroed), `FINI`. Other statements are passed over; `UNITS/INCHES`
//! and inch or per-revolution feeds are errors. `$` continuation lines are not
//! supported.

mod cldata;

use crate::lex::{self, Lexed, Syntax, line_error};
use crate::modal::{GCode, Modal, MotionMode};
use crate::modulo::{Direction, unwrap};
use crate::program::check_axes;
use crate::{AxisSpec, Block, Dialect, Feed, Motion, NcError, Program};

pub use cldata::{read_cldata, read_cldata_lines};

const AXIS_LETTERS: &str = "XYZABCUVW";

/// The reader's modal state and the program read so far.
struct Reader<'a> {
    axes: &'a [AxisSpec],
    program: Program,
    /// The G-code modal state.
    modal: Modal,
    feed: Option<f64>,
    /// Where the axes stand (unwound angles for modulo axes).
    pos: Vec<f64>,
    /// What a `G92` or `ORIGIN` shifted each axis by: written = pos - offset.
    offset: Vec<f64>,
    /// Plain words of modulo axes are wrapped rotary positions (LinuxCNC).
    wrapped: bool,
    /// The dialect's `G4` words and units.
    dwell_rule: DwellRule,
    /// The next block follows a re-zero.
    rezeroed: bool,
    pending: Option<String>,
    /// The line being read (1-based) and the line of each block read.
    line: usize,
    lines: Vec<usize>,
}

impl<'a> Reader<'a> {
    fn new(axes: &'a [AxisSpec]) -> Result<Self, NcError> {
        check_axes(axes)?;
        Ok(Self {
            axes,
            program: Program::new("", axes.to_vec()),
            modal: Modal::default(),
            feed: None,
            pos: vec![0.0; axes.len()],
            offset: vec![0.0; axes.len()],
            wrapped: false,
            dwell_rule: DwellRule::Rs274,
            rezeroed: false,
            pending: None,
            line: 0,
            lines: Vec::new(),
        })
    }

    fn axis_names(&self) -> String {
        self.axes
            .iter()
            .map(|a| a.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// A comment line (no motion on it).
    fn comment_line(&mut self, text: String) {
        if self.program.blocks.is_empty() {
            match text.strip_prefix("PROGRAM ") {
                Some(name) if self.program.name.is_empty() => {
                    self.program.name = name.trim().to_string();
                }
                _ => self.program.header_comments.push(text),
            }
        } else {
            self.pending = Some(match self.pending.take() {
                Some(p) => format!("{p}; {text}"),
                None => text,
            });
        }
    }

    fn join_comment(&mut self, inline: Option<String>) -> Option<String> {
        match (self.pending.take(), inline) {
            (Some(p), Some(c)) => Some(format!("{p}; {c}")),
            (p, c) => p.or(c),
        }
    }
}

/// Reads G-code written by formcam's ISO, LinuxCNC, Marlin or Sinumerik 840D
/// writers (and similar hand-written programs) on `axes` (see the module
/// documentation for what is understood). A plain word of a modulo axis is an
/// absolute angle (in the frame of the last `G92`); for LinuxCNC's wrapped
/// rotary axes use [`read_gcode_in`].
pub fn read_gcode(text: &str, axes: &[AxisSpec]) -> Result<Program, NcError> {
    read_gcode_with(text, axes, None).map(|(p, _)| p)
}

/// Reads G-code as [`read_gcode`] does, as `dialect` means it: with
/// [`Dialect::LinuxCnc`] a plain word of a modulo axis is a wrapped rotary
/// position, `|v| < 360` and the sign the direction. `Dialect::Cldata` is
/// not G-code: use [`read_cldata`].
pub fn read_gcode_in(text: &str, axes: &[AxisSpec], dialect: Dialect) -> Result<Program, NcError> {
    read_gcode_lines_in(text, axes, dialect).map(|(p, _)| p)
}

/// Reads G-code as [`read_gcode_in`] does, with the line (1-based) of each
/// block: `lines[i]` is where `program.blocks[i]` stands in `text`.
pub fn read_gcode_lines_in(
    text: &str,
    axes: &[AxisSpec],
    dialect: Dialect,
) -> Result<(Program, Vec<usize>), NcError> {
    read_gcode_with(text, axes, Some(dialect))
}

fn read_gcode_with(
    text: &str,
    axes: &[AxisSpec],
    dialect: Option<Dialect>,
) -> Result<(Program, Vec<usize>), NcError> {
    let mut r = Reader::new(axes)?;
    r.wrapped = dialect == Some(Dialect::LinuxCnc);
    r.dwell_rule = DwellRule::of(dialect);
    // Every line lexed first, then interpreted in order.
    let lines = lex::lines(text)
        .enumerate()
        .map(|(i, (range, _))| {
            let line = &text[range.clone()];
            lex::lex(line, range.start, i + 1, Syntax::PROGRAM).map(|lx| (line, lx))
        })
        .collect::<Result<Vec<_>, _>>()?;
    for (i, (line, lx)) in lines.iter().enumerate() {
        r.line = i + 1;
        r.gcode_line(line, text, lx)
            .map_err(|what| line_error(i + 1, line, what))?;
    }
    Ok((r.program, r.lines))
}

/// Who the words of a line belong to, as they come.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Owner {
    /// The block: they are read.
    Block,
    /// A G code: they are read (before the block's own).
    Code,
    /// An M code or a `T`: their arguments are passed over.
    Skipped,
    /// `G4`: its arguments are its time.
    Dwell,
}

/// How a dialect writes a dwell's time (`G4`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum DwellRule {
    /// rs274ngc (LinuxCNC): `P` seconds.
    Rs274,
    /// Sinumerik 840D: `F` seconds; `S` spindle revolutions.
    Sinumerik,
    /// ISO/Fanuc: `X` or `U` seconds; `P` milliseconds without a point.
    Fanuc,
    /// Marlin: `P` milliseconds, `S` seconds.
    Marlin,
}

impl DwellRule {
    fn of(dialect: Option<Dialect>) -> Self {
        match dialect {
            Some(Dialect::Sinumerik840d) => Self::Sinumerik,
            Some(Dialect::Iso) => Self::Fanuc,
            Some(Dialect::MarlinXab) => Self::Marlin,
            Some(Dialect::LinuxCnc | Dialect::Cldata) | None => Self::Rs274,
        }
    }

    /// The dwell's time in seconds from the words after `G4`: (letter,
    /// value, written with a decimal point).
    fn seconds(self, words: &[(u8, f64, bool)]) -> Result<f64, String> {
        let word = |l: u8| words.iter().rev().find(|w| w.0 == l);
        let t = match self {
            Self::Rs274 => word(b'P').map(|w| w.1),
            Self::Sinumerik => {
                if word(b'S').is_some() {
                    return Err("G4 S (a dwell in spindle revolutions) cannot be timed: \
                                the spindle speed is not in the program; give G4 F seconds"
                        .into());
                }
                word(b'F').map(|w| w.1)
            }
            Self::Fanuc => match (word(b'X').or_else(|| word(b'U')), word(b'P')) {
                (Some(w), _) => Some(w.1),
                (None, Some(&(_, _, true))) => {
                    return Err(
                        "G4 P with a decimal point: its unit depends on the control's \
                                setting; give X seconds or P milliseconds without a point"
                            .into(),
                    );
                }
                (None, Some(w)) => Some(w.1 / 1000.0),
                (None, None) => None,
            },
            Self::Marlin => word(b'S')
                .map(|w| w.1)
                .or_else(|| word(b'P').map(|w| w.1 / 1000.0)),
        };
        let words = match self {
            Self::Rs274 => "P (seconds)",
            Self::Sinumerik => "F (seconds)",
            Self::Fanuc => "X or U (seconds) or P (milliseconds)",
            Self::Marlin => "P (milliseconds) or S (seconds)",
        };
        match t {
            None => Err(format!("G4 without its time: give {words}")),
            Some(t) if !(t.is_finite() && t >= 0.0) => {
                Err(format!("G4 dwell time {t} s is negative"))
            }
            Some(t) => Ok(t),
        }
    }
}

/// What one G-code line says besides its modes.
#[derive(Default)]
struct GcodeLine {
    /// (axis index, value, direction)
    axis_words: Vec<(usize, f64, Option<Direction>)>,
    /// `G92`.
    preset: bool,
    f_word: Option<f64>,
    /// `G4` and the words after it: (letter, value, with a decimal point).
    dwell: Option<Vec<(u8, f64, bool)>>,
}

impl Reader<'_> {
    /// Interprets a lexed line whose text is `line` (of `src`); errors say
    /// what is wrong.
    fn gcode_line(&mut self, line: &str, src: &str, lx: &Lexed) -> Result<(), String> {
        let comments: Vec<String> = lx
            .comments
            .iter()
            .map(|c| src[c.clone()].trim().to_string())
            .collect();
        let t = line.trim_start();
        let program_number =
            t.starts_with(['O', 'o']) && t[1..].starts_with(|c: char| c.is_ascii_digit());
        let words = self.line_words(lx)?;
        if program_number {
            if self.program.name.is_empty()
                && let Some(c) = comments.first()
            {
                self.program.name = c.clone();
            }
            return Ok(());
        }
        self.block(words, comments)
    }

    /// The words of a line: modes taken on, axis words and `F` collected
    /// (the arguments of G codes first, then the block's own words, as
    /// rs274 parsers order them).
    fn line_words(&mut self, lx: &Lexed) -> Result<GcodeLine, String> {
        let mut out = GcodeLine::default();
        let mut owner = Owner::Block;
        let mut after = 0;
        let (mut args, mut own) = (Vec::new(), Vec::new());
        for w in &lx.words {
            // A comment or `%` ends the arguments of a code.
            if lx.breaks.iter().any(|b| (after..w.whole.start).contains(b)) {
                owner = Owner::Block;
            }
            after = w.whole.end;
            match (w.letter, owner) {
                (b'G', _) => {
                    owner = Owner::Code;
                    let Some(code) = GCode::of(w.value, true) else {
                        return Err(format!("`G{}` is not a G code", w.value));
                    };
                    match code {
                        GCode::Motion(MotionMode::ArcCw | MotionMode::ArcCcw) => {
                            return Err("arcs (G2/G3) are not supported".into());
                        }
                        GCode::Inch => return Err("inch units are not supported".into()),
                        GCode::PerRevolution => {
                            return Err("feed per revolution (G95) is not supported".into());
                        }
                        GCode::PresetOther => {
                            return Err("G92.1, G92.2 and G92.3 are not supported".into());
                        }
                        GCode::Preset => out.preset = true,
                        GCode::Dwell => {
                            owner = Owner::Dwell;
                            out.dwell.get_or_insert_with(Vec::new);
                        }
                        _ => {}
                    }
                    self.modal.apply(code);
                }
                (b'M' | b'T', _) => owner = Owner::Skipped,
                (b'N' | b'O', _) | (_, Owner::Skipped) => {}
                (_, Owner::Dwell) => {
                    if let Some(d) = out.dwell.as_mut() {
                        d.push((w.letter, w.value, w.point));
                    }
                }
                (_, Owner::Code) => args.push(w),
                (_, Owner::Block) => own.push(w),
            }
        }
        for w in args.into_iter().chain(own) {
            let letter = w.letter as char;
            if letter == 'F' {
                out.f_word = Some(w.value);
            } else if let Some(k) = self
                .axes
                .iter()
                .position(|a| a.name.len() == 1 && a.name.starts_with(letter))
            {
                out.axis_words.push((k, w.value, None));
            } else if AXIS_LETTERS.contains(letter) {
                return Err(format!(
                    "axis word {letter} is not one of the program's axes ({})",
                    self.axis_names()
                ));
            }
        }
        for a in &lx.assignments {
            match self
                .axes
                .iter()
                .position(|x| x.name.eq_ignore_ascii_case(&a.name))
            {
                Some(k) => out.axis_words.push((k, a.value, a.direction)),
                None => {
                    return Err(format!(
                        "`{}=` is not one of the program's axes ({})",
                        a.name,
                        self.axis_names()
                    ));
                }
            }
        }
        Ok(out)
    }

    /// The block of a line (or its presets and comments).
    fn block(&mut self, words: GcodeLine, comments: Vec<String>) -> Result<(), String> {
        let GcodeLine {
            mut axis_words,
            preset,
            f_word,
            dwell,
        } = words;
        if let Some(d) = dwell {
            let seconds = self.dwell_rule.seconds(&d)?;
            self.program.dwells.push(crate::Dwell {
                blocks_before: self.program.blocks.len(),
                seconds,
                line: self.line,
            });
        }
        if let Some(f) = f_word {
            if !(f.is_finite() && f > 0.0) {
                return Err(format!("feed F{f} is not positive"));
            }
            if !self.modal.inverse_time {
                self.feed = Some(f);
            }
        }
        let inline = (!comments.is_empty()).then(|| comments.join("; "));
        if preset {
            // `G92`: the axes named take these values where they stand.
            for (k, v, _) in axis_words.drain(..) {
                self.offset[k] = self.pos[k] - v;
            }
            self.rezeroed = true;
        }
        if axis_words.is_empty() {
            if let Some(c) = inline {
                self.comment_line(c);
            }
            return Ok(());
        }
        let kind = match self.modal.motion {
            Some(MotionMode::Rapid) => Motion::Rapid,
            Some(MotionMode::Linear) => Motion::Linear,
            _ => return Err("axis words before any G0 or G1".into()),
        };
        let mut target = self.pos.clone();
        for (k, v, dir) in axis_words {
            let wrapped = self.wrapped && self.axes[k].modulo;
            target[k] = match (self.modal.incremental, dir) {
                (true, _) => self.pos[k] + v,
                (false, Some(d)) => unwrap(self.pos[k], v, d),
                (false, None) if wrapped => {
                    let d = if v.is_sign_negative() {
                        Direction::Negative
                    } else {
                        Direction::Positive
                    };
                    unwrap(self.pos[k], v.abs(), d)
                }
                (false, None) => v + self.offset[k],
            };
        }
        let feed = match kind {
            Motion::Rapid => Feed::None,
            Motion::Linear if self.modal.inverse_time => match f_word {
                Some(f) => Feed::InverseTime(60.0 / f),
                None => return Err("inverse-time (G93) move without F".into()),
            },
            Motion::Linear => match self.feed {
                Some(f) => Feed::PerMinute(f),
                None => return Err("feed move without a feed (F)".into()),
            },
        };
        let comment = self.join_comment(inline);
        self.pos.clone_from(&target);
        self.lines.push(self.line);
        self.program.blocks.push(Block {
            kind,
            target,
            feed,
            comment,
            rezero: std::mem::take(&mut self.rezeroed),
        });
        Ok(())
    }
}
#[cfg(test)]
mod tests {
    use super::*;

    fn x_a() -> [AxisSpec; 2] {
        [AxisSpec::linear("X"), AxisSpec::rotary("A")]
    }

    #[test]
    fn dwells_are_timed_in_each_dialects_unit() {
        let read = |text: &str, d: Dialect| {
            read_gcode_lines_in(text, &x_a(), d).map(|(p, _)| {
                p.dwells
                    .iter()
                    .map(|w| (w.blocks_before, w.seconds, w.line))
                    .collect::<Vec<_>>()
            })
        };
        let head = "G1 F100\nX3\n";
        let cases = [
            (Dialect::LinuxCnc, "G4 P1.5", 1.5),
            (Dialect::Sinumerik840d, "G4 F2.5", 2.5),
            (Dialect::Iso, "G04 X0.75", 0.75),
            (Dialect::Iso, "G04 U0.25", 0.25),
            (Dialect::Iso, "G04 P1500", 1.5),
            (Dialect::MarlinXab, "G4 P250", 0.25),
            (Dialect::MarlinXab, "G4 S3", 3.0),
            (Dialect::MarlinXab, "G4 P250 S3", 3.0),
        ];
        for (d, line, t) in cases {
            let text = format!("{head}{line}\nX4\n");
            let got = read(&text, d).unwrap_or_else(|e| panic!("{line}: {e}"));
            assert_eq!(got, [(1, t, 3)], "{d:?} {line}");
        }
        // The feed stays what it was: F of `G4 F` is the dwell's.
        let (p, _) =
            read_gcode_lines_in("G1 F100\nX3\nG4 F2\nX4\n", &x_a(), Dialect::Sinumerik840d)
                .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(p.blocks[1].feed, Feed::PerMinute(100.0));
        for (d, line, says) in [
            (Dialect::Sinumerik840d, "G4 S10", "spindle revolutions"),
            (Dialect::Iso, "G04 P1.5", "decimal point"),
            (Dialect::LinuxCnc, "G4", "without its time"),
            (Dialect::LinuxCnc, "G4 P-1", "negative"),
        ] {
            let text = format!("{head}{line}\n");
            let e = read(&text, d)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(e.contains(says) && e.contains("line 3"), "{line}: {e}");
        }
    }

    #[test]
    fn words_are_read_in_the_order_of_rs274_parsers() {
        // A G code's arguments before the block's own words; the words after
        // an M code, a `T` or `G4` are theirs; a comment or `%` ends them.
        let text = "G1 F100\nX3 N10 G90 X10\nM3 X7 (c) A5\nT1 % X8\nG4 P2 X9 G1 A6\n";
        let p = read_gcode(text, &x_a()).unwrap_or_else(|e| panic!("{e}"));
        let targets: Vec<Vec<f64>> = p.blocks.iter().map(|b| b.target.clone()).collect();
        assert_eq!(
            targets,
            [
                vec![3.0, 0.0],
                vec![3.0, 5.0],
                vec![8.0, 5.0],
                vec![8.0, 6.0]
            ]
        );
        assert_eq!(p.blocks[1].comment.as_deref(), Some("c"));
        // `G4 P2` (rs274: seconds) before the line's own move.
        let dwell = crate::Dwell {
            blocks_before: 3,
            seconds: 2.0,
            line: 5,
        };
        assert_eq!(p.dwells, [dwell]);
        let (_, lines) = read_gcode_lines_in(text, &x_a(), Dialect::Iso).unwrap();
        assert_eq!(lines, [2, 3, 4, 5]);
        let cls = "PARTNO/P\nFEDRAT/100\nGOTO/1,$\n2\n$$ c\nRAPID\nGOTO/3,4\nFINI\n";
        let (p, lines) = read_cldata_lines(cls, &x_a()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((p.blocks.len(), lines), (2, vec![3, 7]));
    }

    #[test]
    fn syntax_errors_come_before_errors_of_meaning() {
        let e = read_gcode("G0 X0\nG1 X1\nG1 X# F10\n", &x_a()).unwrap_err();
        assert!(matches!(e, NcError::Parse { line: 3, .. }), "{e}");
        let e = read_gcode("G0 X0\nG0 N10 X1\n/G0 X2\n", &x_a()).unwrap_err();
        assert!(matches!(e, NcError::Parse { line: 2, .. }), "{e}");
    }
}
