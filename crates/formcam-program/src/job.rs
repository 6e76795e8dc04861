//! The winding job: the `[mandrel]`, `[winding]` or `[[layer]]`, `[eye]`,
//! `[machine]`, `[motion]`, `[post]` and `[checks]` tables users write, read
//! with errors that name the field. [`WINDING_JOB`] describes every table
//! and field; the reader validates a job against it before reading it.

use formcam_files::line_col;
use std::path::{Path, PathBuf};

use formcam_machine::IkMethod;
use formcam_machine::Machine;
use formcam_machine::shipped::{names, shipped};
use formcam_motion::{DEFAULT_TAU_S, DEFAULT_TOLERANCE_DEG, DEFAULT_TOLERANCE_MM};
use formcam_nc::{Aliases, Dialect, Template};
use formcam_schema::{
    Default as Given, EmptyList, JobSchema, Kind, Range, Repeat, SchemaError, Table, Unit, Value,
    field, validate,
};
use formcam_winding::job::{EYE, EyeJob, LAYER, MANDREL, MandrelSpec, WINDING, WindingSpec};
use serde::{Deserialize, Serialize};

use crate::ProgramError;
use crate::checks::{Check, ChecksJob};

/// A whole winding job, read and checked: the mandrel, its layers, the eye,
/// the machine, the motion, the post and the checks it accepts.
#[derive(Debug, Clone)]
pub struct WindJob {
    /// How the job is named in the program's header and the run's line
    /// (the job file's path as given; `job.toml` until [`WindJob::named`]).
    /// The summary records the job file by its absolute path instead.
    pub title: String,
    /// The NC program's name (the job file's stem).
    pub program_name: String,
    /// The folder files named by the job are relative to.
    pub base_dir: PathBuf,
    /// The mandrel before any layer.
    pub mandrel: MandrelSpec,
    /// One `[winding]` or a list of `[[layer]]`s.
    pub layers: Layers,
    /// The payout eye.
    pub eye: Option<EyeJob>,
    /// The machine, read.
    pub machine: Option<JobMachine>,
    /// Tolerances and block times.
    pub motion: MotionJob,
    /// The post-processor (`None`: the `[post]` table was not given; the
    /// program is written for Sinumerik 840D).
    pub post: Option<Post>,
    /// Checks whose failure the job accepts.
    pub allow: Vec<Check>,
    /// Remarks found while reading (implausible values, ignored members).
    pub warnings: Vec<String>,
    /// What a `.wind` document's reader adds to the summary.
    pub wind_file: Option<WindImport>,
}

/// The layers of a job.
#[derive(Debug, Clone)]
pub enum Layers {
    /// A single-layer job (`[winding]`): one layer, whose outputs are the
    /// job's own.
    Single(Box<WindingSpec>),
    /// A multi-layer job (`[[layer]]`), in winding order.
    Multi(Vec<WindingSpec>),
}

impl Layers {
    /// The layers' specifications in winding order.
    pub fn specs(&self) -> &[WindingSpec] {
        match self {
            Layers::Single(w) => std::slice::from_ref(&**w),
            Layers::Multi(v) => v,
        }
    }
}

/// The machine of a job, read, and how the job named it.
#[derive(Debug, Clone)]
pub struct JobMachine {
    /// The machine.
    pub machine: Machine,
    /// Its name or file, as the job gave it.
    pub source: MachineSource,
    /// The inverse-kinematics method.
    pub ik: IkMethod,
}

/// How a job names its machine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MachineSource {
    /// A shipped machine by name (`name = "winder-4axis"`).
    Shipped(String),
    /// A machine file, relative to the job's folder (`file = "..."`), as
    /// the job wrote it.
    File(String),
}

impl MachineSource {
    /// The name or the file as the job wrote it.
    pub fn as_str(&self) -> &str {
        match self {
            MachineSource::Shipped(s) | MachineSource::File(s) => s,
        }
    }
}

/// `machine.ik`: the inverse-kinematics method.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Ik {
    /// The closed form where the machine has one, else the solver.
    #[default]
    Auto,
    /// Levenberg–Marquardt for every machine.
    Solver,
    /// The closed form (an error where the machine has none).
    ClosedForm,
}

impl From<Ik> for IkMethod {
    fn from(ik: Ik) -> Self {
        match ik {
            Ik::Auto => IkMethod::Auto,
            Ik::Solver => IkMethod::Solver,
            Ik::ClosedForm => IkMethod::ClosedForm,
        }
    }
}

/// `motion.times`: which block times the program uses.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Times {
    /// The optimum under the velocity and jump limits.
    #[default]
    Global,
    /// The seed's pairwise method (eq. 18).
    Pairwise,
}

impl Times {
    /// The name users write.
    pub fn name(self) -> &'static str {
        match self {
            Times::Global => "global",
            Times::Pairwise => "pairwise",
        }
    }
}

/// The `[motion]` table of a job.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionJob {
    /// Tolerance of the linear axes, mm (default 0.05).
    pub tolerance_mm: Option<f64>,
    /// Tolerance of the rotary axes, degrees (default 0.05).
    pub tolerance_deg: Option<f64>,
    /// Tolerance on the payout point's position, mm (none by default).
    pub position_tolerance_mm: Option<f64>,
    /// The controller's least block time, s (default 0.004).
    pub tau_s: Option<f64>,
    /// Which block times the program uses.
    #[serde(default)]
    pub times: Times,
    /// Keep the machine's acceleration limits (`a_max_*` of its axes):
    /// neighbouring blocks slowed until each velocity change can ramp within
    /// half of each block (default true; `false` keeps only the velocity and
    /// velocity-jump limits).
    pub acceleration: Option<bool>,
}

/// The post-processor of a job.
#[derive(Debug, Clone)]
pub enum Post {
    /// A built-in dialect.
    Dialect(Dialect),
    /// A user template, read from `file` (relative to the job's folder).
    Template {
        /// The file as the job wrote it.
        file: String,
        /// The template.
        template: Box<Template>,
    },
}

impl Post {
    /// The program file's extension.
    pub fn extension(&self) -> &str {
        match self {
            Post::Dialect(d) => d.extension(),
            Post::Template { template, .. } => template.extension(),
        }
    }
}

/// What a `.wind` document's reader reports in the summary.
#[derive(Debug, Clone, PartialEq)]
pub struct WindImport {
    /// The document's `schemaVersion` (1.0 when absent).
    pub schema_version: String,
    /// The eye's distance from the spindle axis, mm.
    pub eye_radius_mm: f64,
    /// The eye's clearance over the mandrel's largest radius, mm.
    pub eye_clearance_mm: f64,
}

/// A winding job file: a table it does not know (a misspelt `[motoin]`) is an
/// error.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JobFile {
    mandrel: Option<MandrelSpec>,
    winding: Option<WindingSpec>,
    eye: Option<EyeJob>,
    machine: Option<MachineTable>,
    layer: Option<Vec<WindingSpec>>,
    motion: Option<MotionJob>,
    post: Option<PostTable>,
    checks: Option<ChecksJob>,
}

/// The `[machine]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MachineTable {
    name: Option<String>,
    file: Option<String>,
    #[serde(default)]
    ik: Ik,
}

/// The `[post]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PostTable {
    /// `sinumerik-840d` (default), `iso`, `linuxcnc`, `marlin-xab` or `cldata`.
    dialect: Option<String>,
    /// A user post-processor template (TOML), relative to the job's folder.
    template: Option<String>,
}

impl WindJob {
    /// Reads a job from its TOML text; files it names (profiles, eye curves,
    /// the machine, templates) are relative to `base_dir`.
    pub fn from_toml(text: &str, base_dir: &Path) -> Result<WindJob, ProgramError> {
        validate(&WINDING_JOB, text).map_err(|e| match e {
            SchemaError::Syntax {
                line,
                column,
                message,
            } => ProgramError::Syntax {
                line,
                column,
                message,
            },
            other => ProgramError::Schema(other),
        })?;
        let file: JobFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            ProgramError::Syntax {
                line,
                column,
                message: formcam_files::syntax_message(
                    e.message(),
                    text,
                    e.span().map_or(text.len(), |s| s.start),
                ),
            }
        })?;
        let layers = match (file.winding, file.layer) {
            (Some(_), Some(_)) => return Err(ProgramError::WindingAndLayers),
            (Some(w), None) => Layers::Single(Box::new(w)),
            (None, Some(v)) => Layers::Multi(v),
            (None, None) => {
                file.mandrel
                    .as_ref()
                    .ok_or(ProgramError::MissingTable { table: "[mandrel]" })?;
                return Err(ProgramError::MissingTable { table: "[winding]" });
            }
        };
        let mandrel = file
            .mandrel
            .ok_or(ProgramError::MissingTable { table: "[mandrel]" })?;
        if matches!(&layers, Layers::Multi(v) if v.is_empty()) {
            return Err(ProgramError::NoLayers);
        }
        let machine = file
            .machine
            .map(|m| read_machine(m, base_dir))
            .transpose()?;
        let post = file.post.map(|p| read_post(p, base_dir)).transpose()?;
        Ok(WindJob {
            title: "job.toml".into(),
            program_name: "job".into(),
            base_dir: base_dir.to_path_buf(),
            mandrel,
            layers,
            eye: file.eye,
            machine,
            motion: file.motion.unwrap_or_default(),
            post,
            allow: file.checks.unwrap_or_default().allow,
            warnings: Vec::new(),
            wind_file: None,
        })
    }

    /// The job named after its file: `path` as given names it in the
    /// program's header and the run's line, its stem names the program.
    pub fn named(mut self, path: &Path) -> Self {
        self.title = path.display().to_string();
        self.program_name = path
            .file_stem()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        self
    }

    /// Whether the job is a multi-layer one.
    pub fn is_layered(&self) -> bool {
        matches!(self.layers, Layers::Multi(_))
    }

    /// The post-processor (Sinumerik 840D when the job gives none).
    pub fn post(&self) -> Post {
        self.post
            .clone()
            .unwrap_or(Post::Dialect(Dialect::Sinumerik840d))
    }

    /// The furthest stage the job's tables reach: the program with a
    /// machine and a `[post]` (or layers), the axes with a machine, the eye
    /// with an `[eye]`, else the path.
    pub fn furthest_stage(&self) -> crate::Stage {
        use crate::Stage;
        match (&self.machine, &self.eye) {
            (Some(_), _) if self.post.is_some() || self.is_layered() => Stage::Program,
            (Some(_), _) => Stage::Axes,
            (None, Some(_)) => Stage::Eye,
            (None, None) => Stage::Path,
        }
    }
}

/// The machine a `[machine]` table names: exactly one of a shipped name and
/// a file (relative to the job's folder).
fn read_machine(table: MachineTable, base_dir: &Path) -> Result<JobMachine, ProgramError> {
    let all = || names().collect::<Vec<_>>().join(", ");
    let (machine, source) = match (table.name, table.file) {
        (Some(name), None) => {
            let s = shipped(&name).ok_or_else(|| ProgramError::UnknownMachine {
                name: name.clone(),
                names: all(),
            })?;
            let m = s.machine().map_err(|e| ProgramError::machine(&name, e))?;
            (m, MachineSource::Shipped(name))
        }
        (None, Some(file)) => {
            let path = base_dir.join(&file);
            let text =
                formcam_files::read_text(&path).map_err(|e| ProgramError::MachineNotFound {
                    file: file.clone(),
                    source: e.into(),
                })?;
            let m = Machine::from_file_text(&path, &text)
                .map_err(|e| ProgramError::machine(&file, e))?;
            (m, MachineSource::File(file))
        }
        _ => return Err(ProgramError::MachineChoice { names: all() }),
    };
    Ok(JobMachine {
        machine,
        source,
        ik: table.ik.into(),
    })
}

/// The post-processor a `[post]` table names.
fn read_post(table: PostTable, base_dir: &Path) -> Result<Post, ProgramError> {
    match (table.dialect, table.template) {
        (Some(_), Some(_)) => Err(ProgramError::PostBoth),
        (None, Some(file)) => {
            let path = base_dir.join(&file);
            let text = formcam_files::read_text(&path).map_err(|e| ProgramError::TemplateRead {
                file: path.display().to_string(),
                source: e.into(),
            })?;
            let template = Template::from_toml(&text).map_err(|source| ProgramError::Template {
                file: path.display().to_string(),
                source,
            })?;
            Ok(Post::Template {
                file,
                template: Box::new(template),
            })
        }
        (d, None) => Dialect::from_name(d.as_deref().unwrap_or("sinumerik-840d"))
            .map(Post::Dialect)
            .map_err(ProgramError::Dialect),
    }
}

/// The names `[post] dialect` takes: the dialects, the default first, then
/// their aliases.
const DIALECTS: &[&str] = &Dialect::names_of::<8>(
    &[
        Dialect::Sinumerik840d,
        Dialect::Iso,
        Dialect::LinuxCnc,
        Dialect::MarlinXab,
        Dialect::Cldata,
    ],
    Aliases::Last,
);

/// The shipped machines' names, as `[machine] name` takes them.
const MACHINES: &[&str] = &[
    "placement-arm",
    "winder-2axis",
    "winder-4axis",
    "winder-6axis",
    "winder-xab",
];

const POSITIVE: Option<Range> = Some(Range::above(0.0));

/// `[machine]`: the machine, shipped or from a file.
pub const MACHINE: Table = Table {
    name: "machine",
    repeat: Repeat::Single,
    required: false,
    help: "the machine: exactly one of `name` and `file`; needed for `wind axes` and programs",
    fields: &[
        field(
            "name",
            Kind::Word(MACHINES),
            Unit::None,
            None,
            Given::Described("exactly one of `name` and `file`"),
            "a machine shipped with formcam (a job anywhere reaches it; see machines.md)",
        ),
        field(
            "file",
            Kind::File,
            Unit::None,
            None,
            Given::Described("exactly one of `name` and `file`"),
            "a machine file (TOML), relative to the job's folder",
        ),
        field(
            "ik",
            Kind::Word(&["auto", "solver", "closed-form"]),
            Unit::None,
            None,
            Given::Value(Value::Text("auto")),
            "the inverse kinematics: the closed form where the machine has one (`auto`),              Levenberg–Marquardt for every machine (`solver`), or the closed form only",
        ),
    ],
};

/// `[motion]`: tolerances and block times.
pub const MOTION: Table = Table {
    name: "motion",
    repeat: Repeat::Single,
    required: false,
    help: "the blocks' tolerances and times",
    fields: &[
        field(
            "tolerance_mm",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Value(Value::Number(DEFAULT_TOLERANCE_MM)),
            "linear axes' tolerance of the blocks",
        ),
        field(
            "tolerance_deg",
            Kind::Number,
            Unit::Deg,
            POSITIVE,
            Given::Value(Value::Number(DEFAULT_TOLERANCE_DEG)),
            "rotary axes' tolerance",
        ),
        field(
            "position_tolerance_mm",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::None,
            "the payout point's tolerance through forward kinematics",
        ),
        field(
            "tau_s",
            Kind::Number,
            Unit::S,
            POSITIVE,
            Given::Value(Value::Number(DEFAULT_TAU_S)),
            "the controller's least block time",
        ),
        field(
            "times",
            Kind::Word(&["global", "pairwise"]),
            Unit::None,
            None,
            Given::Value(Value::Text("global")),
            "the optimum under the velocity and jump limits (`global`) or eq. 18 (`pairwise`)",
        ),
        field(
            "acceleration",
            Kind::Boolean,
            Unit::None,
            None,
            Given::Value(Value::Boolean(true)),
            "keep the axes' `a_max` too (`false`: only the velocity and jump limits)",
        ),
    ],
};

/// `[post]`: the post-processor.
pub const POST: Table = Table {
    name: "post",
    repeat: Repeat::Single,
    required: false,
    help: "the post-processor: a dialect or a user template",
    fields: &[
        field(
            "dialect",
            Kind::Name(DIALECTS),
            Unit::None,
            None,
            Given::Value(Value::Text("sinumerik-840d")),
            "the controller's language (`fanuc` is `iso`; `sinumerik` and `840d` are \
             `sinumerik-840d`); see dialects.md",
        ),
        field(
            "template",
            Kind::File,
            Unit::None,
            None,
            Given::None,
            "a user post-processor (TOML), relative to the job's folder; instead of `dialect`",
        ),
    ],
};

/// `[checks]`: the checks whose failure a job accepts.
pub const CHECKS: Table = Table {
    name: "checks",
    repeat: Repeat::Single,
    required: false,
    help: "checks whose failure the job accepts",
    fields: &[field(
        "allow",
        Kind::Words(crate::checks::CHECK_NAMES),
        Unit::None,
        None,
        Given::Value(Value::EmptyList(EmptyList)),
        "names of checks whose failure the job accepts: the program is written anyway",
    )],
};

/// The winding job: every table of [`WindJob`]'s file.
pub const WINDING_JOB: JobSchema = JobSchema {
    name: "winding",
    help: "a winding job: the mandrel, one layer or several, the eye, the machine, the motion, \
           the post and the checks accepted",
    tables: &[MANDREL, WINDING, LAYER, EYE, MACHINE, MOTION, POST, CHECKS],
};

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn every_key_the_reader_takes_is_described() {
        let sorted = |mut v: Vec<String>| {
            v.sort();
            v
        };
        assert_eq!(
            sorted(formcam_schema::reader_keys::<MachineTable>()),
            MACHINE.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<PostTable>()),
            POST.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<MotionJob>()),
            MOTION.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<crate::checks::ChecksJob>()),
            CHECKS.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<MandrelSpec>()),
            MANDREL.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<EyeJob>()),
            EYE.field_names()
        );
        assert_eq!(
            sorted(formcam_schema::reader_keys::<WindingSpec>()),
            LAYER.field_names()
        );
        // `[winding]` is one layer: a skip layer's turn has no place there.
        let mut winding = WINDING.field_names();
        winding.push("mandrel_rotation_deg".into());
        assert_eq!(sorted(winding), LAYER.field_names());
        let mut tables: Vec<String> = WINDING_JOB.tables.iter().map(|t| t.name.into()).collect();
        tables.sort();
        assert_eq!(sorted(formcam_schema::reader_keys::<JobFile>()), tables);
    }

    #[test]
    fn the_described_words_are_the_readers() {
        let names: Vec<&str> = names().collect();
        assert_eq!(MACHINES, names.as_slice());
        for d in DIALECTS {
            assert!(Dialect::from_name(d).is_ok(), "{d}");
        }
        for n in Dialect::NAMES {
            assert!(DIALECTS.contains(&n), "{n}");
        }
        let checks: Vec<&str> = crate::checks::Check::ALL.iter().map(|c| c.name()).collect();
        assert_eq!(crate::checks::CHECK_NAMES, checks.as_slice());
    }
}
