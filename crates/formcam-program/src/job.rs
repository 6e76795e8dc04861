//! The winding job: the `[mandrel]`, `[winding]` or `[[layer]]`, `[eye]`,
//! `[machine]`, `[motion]`, `[post]` and `[checks]` tables users write, read
//! with errors that name the field.

use std::path::{Path, PathBuf};

use formcam_machine::IkMethod;
use formcam_machine::Machine;
use formcam_machine::shipped::{names, shipped};
use formcam_nc::{Dialect, Template};
use formcam_winding::job::{EyeJob, MandrelSpec, WindingSpec};
use serde::{Deserialize, Serialize};

use crate::ProgramError;
use crate::checks::{Check, ChecksJob};

/// A whole winding job, read and checked: the mandrel, its layers, the eye,
/// the machine, the motion, the post and the checks it accepts.
#[derive(Debug, Clone)]
pub struct WindJob {
    /// How the job is named in the program's header and the summary (the
    /// job file's path as given; `job.toml` until [`WindJob::named`]).
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
    /// Also keep the machine's acceleration limits (`a_max_*` of its axes):
    /// neighbouring blocks slowed until each velocity change can ramp within
    /// half of each block (default false).
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
        let file: JobFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            ProgramError::Syntax {
                line,
                column,
                message: e.message().replace('\n', " "),
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
    /// program's header and the summary, its stem names the program.
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
            let text = std::fs::read_to_string(base_dir.join(&file)).map_err(|source| {
                ProgramError::MachineNotFound {
                    file: file.clone(),
                    source,
                }
            })?;
            let m = Machine::from_toml(&text).map_err(|e| ProgramError::machine(&file, e))?;
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
            let text =
                std::fs::read_to_string(&path).map_err(|source| ProgramError::TemplateRead {
                    file: path.display().to_string(),
                    source,
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

/// Line and column (1-based) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
