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
    Program(String),
    /// A template that is not valid TOML or misses a field.
    #[error("template: {0}")]
    Template(String),
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

    pub(crate) fn program(message: impl Into<String>) -> Self {
        Self::Program(message.into())
    }
}
