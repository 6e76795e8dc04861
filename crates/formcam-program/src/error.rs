//! Why a winding job could not be read, planned or written: each variant
//! names the table or field, the layer and, for machine files, the file.

use formcam_machine::MachineError;
use formcam_motion::MotionError;
use formcam_nc::NcError;
use formcam_winding::WindingError;

use crate::checks::Check;

/// Everything that can stop a winding program.
#[derive(Debug, thiserror::Error)]
pub enum ProgramError {
    /// The job is not valid TOML or does not match the format.
    #[error("{line}:{column}: {message}")]
    Syntax {
        /// Line (1-based; 0 when unknown).
        line: usize,
        /// Column (1-based; 0 when unknown).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The job does not match its description ([`crate::WINDING_JOB`]): an
    /// unknown table or field, a wrong type, a value out of range, a word
    /// not in the list, a missing field; each names `table.field`, its
    /// `line:column` and what is allowed.
    #[error(transparent)]
    Schema(formcam_schema::SchemaError),
    /// A table the job needs is missing (`[winding]`, `[eye]`, `[machine]`).
    #[error("{table}: missing table")]
    MissingTable {
        /// The table, as users write it.
        table: &'static str,
    },
    /// A multi-layer job without a machine.
    #[error("[machine]: missing table (a program needs a machine)")]
    NoMachine,
    /// A multi-layer job with an empty `[[layer]]` list.
    #[error("[[layer]]: no layers")]
    NoLayers,
    /// Both `[winding]` and `[[layer]]`.
    #[error("[winding] and [[layer]]: give one of them")]
    WindingAndLayers,
    /// A multi-layer job asked to stop before the program.
    #[error(
        "[[layer]]: a multi-layer job runs as a whole program (`formcam wind JOB -o OUT`); path, \
         eye and axes take one [winding]"
    )]
    LayeredStage,
    /// The mandrel, a layer or the eye cannot be planned as asked (fields
    /// named `mandrel.*`, `winding.*`, `layer[N].*`, `eye.*`).
    #[error(transparent)]
    Winding(#[from] WindingError),
    /// `[machine]` gives both or neither of `name` and `file`.
    #[error(
        "[machine]: give name = \"...\" (one of {names}) or file = \"...\", exactly one of them"
    )]
    MachineChoice {
        /// The shipped machines' names.
        names: String,
    },
    /// `machine.name` is not a shipped machine.
    #[error("machine.name: \"{name}\" is not a shipped machine (shipped: {names})")]
    UnknownMachine {
        /// The name given.
        name: String,
        /// The shipped machines' names.
        names: String,
    },
    /// `machine.file` does not exist.
    #[error("machine.file: \"{file}\" not found (looked in the job's folder): {source}")]
    MachineNotFound {
        /// The file as the job wrote it.
        file: String,
        /// The reason.
        source: std::io::Error,
    },
    /// The machine file is not valid TOML or does not match the format.
    #[error("{file}:{line}:{column}: {message}")]
    MachineSyntax {
        /// The file as the job wrote it (or the shipped machine's name).
        file: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The machine file is read but invalid (a link, a point, a field).
    #[error("{file}: {source}")]
    Machine {
        /// The file as the job wrote it (or the shipped machine's name).
        file: String,
        /// What is wrong.
        source: MachineError,
    },
    /// The inverse kinematics of a layer failed.
    #[error("{layer}{file}: {source}")]
    Ik {
        /// `layer 2 (helical): ` in multi-layer jobs, else empty.
        layer: String,
        /// The machine, as the job named it.
        file: String,
        /// Why.
        source: MachineError,
    },
    /// A `[motion]` number that must be positive is not.
    #[error("{field}: must be a finite number > 0, got {value}")]
    NotPositive {
        /// The dotted field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// The axes cannot be cut into blocks within the tolerances.
    #[error("motion: {0}")]
    Motion(#[from] MotionError),
    /// The machine's axis limits do not allow block times.
    #[error("machine: {0}")]
    AxisLimits(MotionError),
    /// A skip layer's `mandrel_rotation_deg` is missing.
    #[error("layer[{layer}].mandrel_rotation_deg: missing: how far the mandrel turns, degrees")]
    SkipTurnMissing {
        /// The layer (1-based).
        layer: usize,
    },
    /// A skip layer's turn is not a finite number.
    #[error("{label}: mandrel_rotation_deg must be a finite number")]
    SkipTurnNotFinite {
        /// The layer's label.
        label: String,
    },
    /// A skip layer on a machine without a spindle.
    #[error("{label}: a skip layer turns the spindle, and {machine} has none")]
    NoSpindle {
        /// The layer's label.
        label: String,
        /// The machine's name.
        machine: String,
    },
    /// A check failed that the job does not accept.
    #[error(
        "checks: {layer}: the program would {detail}; no program written (a job that accepts \
         this gives [checks] allow = [\"{}\"])", check.name()
    )]
    Refused {
        /// The check.
        check: Check,
        /// The layer's label.
        layer: String,
        /// What failed, where.
        detail: String,
    },
    /// `[post]` gives both a dialect and a template.
    #[error("post: give either dialect or template, not both")]
    PostBoth,
    /// `post.dialect` is not a dialect.
    #[error("post.dialect: {0}")]
    Dialect(NcError),
    /// The template file cannot be read.
    #[error("post.template: cannot read {file}: {source}")]
    TemplateRead {
        /// The file (in the job's folder).
        file: String,
        /// The reason.
        source: std::io::Error,
    },
    /// The template is invalid or cannot write this program.
    #[error("{file}: {source}")]
    Template {
        /// The file (in the job's folder).
        file: String,
        /// What is wrong.
        source: NcError,
    },
    /// The post-processor cannot write the program.
    #[error("post: {0}")]
    Post(#[from] NcError),
    /// A `.wind` document that cannot be read, naming the member
    /// (`layers[1].windAngle`).
    #[error("{0}")]
    WindFile(String),
    /// The program could not be written to its destination.
    #[error("cannot write the program: {0}")]
    Write(#[from] std::io::Error),
}

impl ProgramError {
    /// A machine's error, with the file (or shipped name) it came from.
    pub fn machine(file: &str, e: MachineError) -> Self {
        match e {
            MachineError::Syntax {
                line,
                column,
                message,
            } => Self::MachineSyntax {
                file: file.to_string(),
                line,
                column,
                message,
            },
            other => Self::Machine {
                file: file.to_string(),
                source: other,
            },
        }
    }

    /// Whether the error is the job's own syntax (its place is `line:column`
    /// and follows the file's name without a space).
    pub fn is_syntax(&self) -> bool {
        matches!(self, Self::Syntax { .. })
    }
}

/// A winding error of layer `layer` (1-based) of a multi-layer job: its
/// `winding.*` field named `layer[N].*`.
pub fn in_layer(layer: usize, e: WindingError) -> WindingError {
    let rename = |field: String| match field.strip_prefix("winding.") {
        Some(rest) => format!("layer[{layer}].{rest}"),
        None => field,
    };
    match e {
        WindingError::Field { field, reason } => WindingError::Field {
            field: rename(field),
            reason,
        },
        WindingError::Infeasible { field, reason } => WindingError::Infeasible {
            field: rename(field),
            reason,
        },
        WindingError::Shooting(reason) => WindingError::Infeasible {
            field: format!("layer[{layer}].mu = \"auto\""),
            reason,
        },
        other => other,
    }
}
