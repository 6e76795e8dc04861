use thiserror::Error;

/// Everything that can stop writing or reading an NC program.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NcError {
    /// A dialect name that is not one of the known ones.
    #[error("unknown dialect `{name}`; allowed: {allowed}")]
    UnknownDialect {
        /// The name asked for.
        name: String,
        /// The allowed names, comma separated.
        allowed: String,
    },
    /// An axis name the dialect cannot address.
    #[error("the {dialect} dialect cannot address axis `{axis}` (allowed: {allowed})")]
    UnsupportedAxis {
        /// The dialect's name.
        dialect: &'static str,
        /// The program's axis name.
        axis: String,
        /// What the dialect allows.
        allowed: &'static str,
    },
    /// The program itself is inconsistent (axis count, non-finite values,
    /// feeds), or a milling program's line is refused (named by its line).
    #[error("{}{}", program_prefix(.0), .0)]
    Program(#[from] ProgramFault),
    /// A template that is not valid TOML or cannot be used.
    #[error("template: {}{problem}", file_prefix(.file))]
    Template {
        /// The template file, when it was read from one.
        file: Option<String>,
        /// What is wrong.
        problem: TemplateProblem,
    },
    /// A template placeholder that is not known.
    #[error(
        "template field `{field}`: unknown placeholder `{{{placeholder}}}` (allowed: {allowed})"
    )]
    UnknownPlaceholder {
        /// The placeholder's name (without braces).
        placeholder: String,
        /// The template field it is in.
        field: String,
        /// The placeholders the field allows.
        allowed: String,
    },
    /// A file that cannot be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// A line of an NC program that cannot be read.
    #[error("line {line}: {message}")]
    Parse {
        /// Line of the error (1-based).
        line: usize,
        /// What is wrong.
        message: String,
    },
}

impl NcError {
    pub(crate) fn parse(line: usize, message: impl Into<String>) -> Self {
        Self::Parse {
            line,
            message: message.into(),
        }
    }

    pub(crate) fn template(problem: TemplateProblem) -> Self {
        Self::Template {
            file: None,
            problem,
        }
    }
}

/// `file: ` when there is a file.
fn file_prefix(file: &Option<String>) -> String {
    file.as_ref().map(|f| format!("{f}: ")).unwrap_or_default()
}

/// `program: ` before a fault that names no line of a program.
fn program_prefix(fault: &ProgramFault) -> &'static str {
    match fault {
        ProgramFault::Refused { .. } | ProgramFault::Truncated { .. } => "",
        _ => "program: ",
    }
}

/// Why a program (or a milling program's options) cannot be written or read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ProgramFault {
    /// An axis without a name.
    #[error("an axis has an empty name")]
    EmptyAxisName,
    /// Two axes of the same name.
    #[error("axis {axis} appears twice")]
    AxisTwice {
        /// The axis.
        axis: String,
    },
    /// A modulo axis that is linear.
    #[error("axis {axis} is modulo but not rotary")]
    ModuloNotRotary {
        /// The axis.
        axis: String,
    },
    /// A block with another number of values than the program has axes.
    #[error("block {block}: {values} axis values for {axes} axes")]
    AxisCount {
        /// The block (0-based).
        block: usize,
        /// Its values.
        values: usize,
        /// The program's axes.
        axes: usize,
    },
    /// A block whose axis value is NaN or infinite.
    #[error("block {block}: axis {axis} is not finite")]
    NotFinite {
        /// The block (0-based).
        block: usize,
        /// The axis.
        axis: String,
    },
    /// A rapid block with a feed.
    #[error("block {block}: a rapid block has a feed")]
    RapidWithFeed {
        /// The block (0-based).
        block: usize,
    },
    /// A linear block without a feed.
    #[error("block {block}: a linear block has no feed")]
    LinearWithoutFeed {
        /// The block (0-based).
        block: usize,
    },
    /// A feed or inverse-time block time that is not positive.
    #[error("block {block}: feed or block time {value} is not positive")]
    FeedNotPositive {
        /// The block (0-based).
        block: usize,
        /// The feed (mm/min) or block time (s).
        value: f64,
    },
    /// A block turning a modulo axis too far to be split.
    #[error("block {block} turns a modulo axis by more than {turns:.0} turns")]
    TurnsTooFar {
        /// The block (0-based).
        block: usize,
        /// The most turns a block may make.
        turns: f64,
    },
    /// A modulo angle too large to be printed.
    #[error("block {block}: modulo axis {axis} at {angle_deg}° is beyond what can be written")]
    Unwritable {
        /// The block (0-based).
        block: usize,
        /// The axis.
        axis: String,
        /// The angle, degrees.
        angle_deg: f64,
    },
    /// A modulo angle beyond the bound that has not been re-zeroed.
    #[error(
        "block {block}: modulo axis {axis} would be written beyond ±{bound_deg}° (re-zero it \
         first: keep_within_turns)"
    )]
    BeyondBound {
        /// The block (0-based).
        block: usize,
        /// The axis.
        axis: String,
        /// The bound, degrees.
        bound_deg: f64,
    },
    /// A block turning a modulo axis a whole turn or more.
    #[error(
        "block {block}: modulo axis {axis} turns a whole turn or more in one block (split it \
         first: keep_within_turns)"
    )]
    WholeTurn {
        /// The block (0-based).
        block: usize,
        /// The axis.
        axis: String,
    },
    /// A milling program asked to be read as CLDATA.
    #[error(
        "CLDATA is no G-code: a milling program is read as iso, sinumerik-840d, linuxcnc or \
         marlin-xab"
    )]
    CldataToolpath,
    /// A largest segment that is not positive.
    #[error("largest segment {mm} mm: must be > 0")]
    SegmentNotPositive {
        /// The value given, mm.
        mm: f64,
    },
    /// An arc tolerance that is not positive.
    #[error("arc tolerance {mm} mm: must be > 0")]
    ArcToleranceNotPositive {
        /// The value given, mm.
        mm: f64,
    },
    /// New positions for another number of nodes than the program has.
    #[error("{positions} positions for {nodes} nodes")]
    PositionCount {
        /// The positions given.
        positions: usize,
        /// The program's nodes.
        nodes: usize,
    },
    /// A milling program's word the reader does not follow.
    #[error("line {line}: `{excerpt}`: {refusal}")]
    Refused {
        /// The line (1-based).
        line: usize,
        /// The line's text, quoted (at most 80 characters).
        excerpt: String,
        /// The word and what it would do.
        refusal: Refusal,
    },
    /// A milling program whose last line stops in the middle of a word.
    #[error(
        "line {line}: `{excerpt}`: the program ends in the middle of {cut} (was the file cut \
         off?); a complete last line ends with a line break or a whole word"
    )]
    Truncated {
        /// The last line (1-based).
        line: usize,
        /// The line's text, quoted (at most 80 characters).
        excerpt: String,
        /// What is left open.
        cut: Truncation,
    },
}

/// A word of a milling program the correction does not follow: what it
/// would do to the tool's path, and what to write instead. Each holds the
/// word as written, quoted.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum Refusal {
    /// Polar coordinates (`G16`, 840D `AP=`/`RP=`, poles `G110..G112`,
    /// Fanuc's polar interpolation `G12.1`).
    #[error("polar coordinates (`{word}`) are not supported; give the end point as X, Y, Z")]
    Polar {
        /// The word.
        word: String,
    },
    /// A subprogram or macro call or definition (`M98`, `G65`, 840D `L123`,
    /// `CALL`, LinuxCNC `o.. call`, `o.. sub`).
    #[error(
        "`{word}` calls a subprogram or macro, whose moves are not in this file; write them out \
         as G0/G1/G2/G3 blocks"
    )]
    Subprogram {
        /// The word.
        word: String,
    },
    /// A canned cycle (`G81..G89`, 840D `CYCLE81(..)`, `POCKET3(..)`).
    #[error("the canned cycle `{word}` is not supported; write its moves as G0/G1/G2/G3 blocks")]
    Cycle {
        /// The word.
        word: String,
    },
    /// A spline (LinuxCNC `G5`, `G5.1`, `G5.2`; 840D `BSPLINE`, `ASPLINE`,
    /// `CSPLINE`, `POLY`).
    #[error("the spline `{word}` is not supported; write the path as G1 or G2/G3 blocks")]
    Spline {
        /// The word.
        word: String,
    },
    /// A change of the coordinate system or of the axes' meaning (`G92`,
    /// `G52`, `G10`, `G51`, `G68`, 840D frames and transformations, `G7`).
    #[error(
        "`{word}` changes the coordinate system, which is not supported; post the program in \
         one work offset, without shifts, rotations, scaling or mirroring"
    )]
    Frame {
        /// The word.
        word: String,
    },
    /// Arcs in the planes of the U, V, W axes (LinuxCNC `G17.1..G19.1`).
    #[error("`{word}`: arcs in the U, V, W planes are not supported; use G17, G18 or G19")]
    Plane {
        /// The word.
        word: String,
    },
    /// A probing or skip move, which ends where the probe trips.
    #[error(
        "`{word}` is a probing move, which ends where the probe trips; correct a program \
         without probing"
    )]
    Probe {
        /// The word.
        word: String,
    },
    /// Tool radius compensation (`G41`, `G42`, 840D `CUT3D..`), or a
    /// length offset given in the program (`G43.1`).
    #[error(
        "`{word}` offsets the tool from the programmed path (compensation), which is not \
         supported; post the program for the tool centre, with G40"
    )]
    Compensation {
        /// The word.
        word: String,
    },
    /// Jumps, loops and conditions.
    #[error(
        "`{word}` jumps, loops or branches, which is not supported; give the program with \
         every move written out"
    )]
    Flow {
        /// The word.
        word: String,
    },
    /// An 840D arc form the reader does not compute (`CIP`, `CT`, `AR=`,
    /// `TURN=`).
    #[error("the arc form `{word}` is not supported; give G2/G3 with I, J, K or the radius (CR=)")]
    ArcForm {
        /// The word.
        word: String,
    },
    /// A G code the reader does not know, on a line with axis words.
    #[error("`{word}` with axis words is not supported; X, Y, Z are read in G0/G1/G2/G3 moves")]
    AxesWithCode {
        /// The word.
        word: String,
    },
    /// An 840D keyword not known to leave the path alone (it may name a
    /// subprogram).
    #[error(
        "`{word}` is a keyword the correction does not know (it may call a subprogram or \
         change the path); give G0/G1/G2/G3 moves in X, Y, Z"
    )]
    Keyword {
        /// The word.
        word: String,
    },
}

/// What the last line of a program leaves open.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum Truncation {
    /// A letter or `NAME=` without its number (`X`, `X-`, `Z=`), quoted.
    #[error("the word `{word}`")]
    Word {
        /// The word as written.
        word: String,
    },
    /// A `(` comment without `)`.
    #[error("a comment")]
    Comment,
    /// A `"` string without its closing `"`.
    #[error("a string")]
    String,
    /// A `(` or `[` without its closing bracket.
    #[error("a bracket")]
    Bracket,
}

/// Why a template cannot be used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TemplateProblem {
    /// The text is not TOML or misses a field.
    #[error("{}{message}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
    Toml {
        /// The line of the problem (1-based), when known.
        line: Option<usize>,
        /// What the TOML reader said (or what it expected).
        message: String,
    },
    /// Decimals outside 0 to 9.
    #[error("{field} = {decimals}: allowed 0 to 9 (decimals)")]
    Decimals {
        /// The field (`decimals_mm`, `decimals_deg`).
        field: &'static str,
        /// The decimals given.
        decimals: i64,
    },
    /// A `{` without its `}`.
    #[error("field `{field}`: `{{` without a closing `}}`")]
    Unclosed {
        /// The template field.
        field: &'static str,
    },
    /// An extension that is no plain file extension (a dot, a slash, empty).
    #[error(
        "extension = \"{extension}\": letters, digits, `_` and `-` only, without the dot (`h`, `nc`)"
    )]
    Extension {
        /// The extension given (quoted).
        extension: String,
    },
    /// Line numbers that do not advance.
    #[error("line_numbers.step = 0: allowed >= 1")]
    LineStep,
}
