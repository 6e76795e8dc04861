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
    /// The program itself is inconsistent (axis count, non-finite values, feeds).
    #[error("program: {0}")]
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
    /// Too many decimals.
    #[error("{field} = {decimals}: at most 9 decimals")]
    Decimals {
        /// The field (`decimals_mm`, `decimals_deg`).
        field: &'static str,
        /// The decimals given.
        decimals: u32,
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
