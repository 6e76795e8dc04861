//! Why a winding job could not be read, planned or written: each variant
//! names the table or field, the layer and, for machine files, the file.

use formcam_machine::MachineError;
use formcam_motion::MotionError;
use formcam_nc::NcError;
use formcam_winding::WindingError;

use crate::checks::Check;
use crate::windfile::SPEC_VERSION;

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
    AxisLimits(#[source] MotionError),
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
    Dialect(#[source] NcError),
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
    #[error(transparent)]
    WindFile(#[from] WindFileError),
    /// The program's estimated size exceeds the memory budget: refused
    /// before any layer is planned.
    #[error(
        "[[layer]]: {layers} layers, about {points} points and {blocks} blocks, would take about \
         {mib} MiB, over the memory budget of {budget_mib} MiB; refused before planning (raise \
         the budget with --max-memory-mb, or split the job)"
    )]
    TooLarge {
        /// The job's layers.
        layers: usize,
        /// The points planned, estimated.
        points: u64,
        /// The program's blocks, estimated.
        blocks: u64,
        /// The estimate, MiB.
        mib: u64,
        /// The budget, MiB.
        budget_mib: u64,
    },
    /// What the planned layers keep exceeds the memory budget (the
    /// estimate was too low): the run stops there.
    #[error(
        "[[layer]]: the {layers} layers planned keep {blocks} blocks and their files, about {mib} \
         MiB, over the memory budget of {budget_mib} MiB; stopped (raise the budget with \
         --max-memory-mb, or split the job)"
    )]
    OverBudget {
        /// The layers planned so far.
        layers: usize,
        /// Their blocks.
        blocks: u64,
        /// What they keep, MiB.
        mib: u64,
        /// The budget, MiB.
        budget_mib: u64,
    },
    /// The run was cancelled by its progress hook.
    #[error(transparent)]
    Cancelled(#[from] formcam_progress::Cancelled),
    /// The program could not be written to its destination.
    #[error("cannot write the program: {0}")]
    Write(#[from] std::io::Error),
    /// The simulator refused what the planner handed it for a check (a
    /// layer's circuit the free fibre cannot follow).
    #[error(transparent)]
    Sim(Box<formcam_sim::SimError>),
    /// The mandrel's solid of a layer could not be built for the collision
    /// check (no finite radius).
    #[error("layer {layer}: the mandrel's radius is not finite; no solid for the collision check")]
    MandrelSolid {
        /// The layer (1-based).
        layer: usize,
    },
}

impl From<formcam_sim::SimError> for ProgramError {
    fn from(e: formcam_sim::SimError) -> Self {
        Self::Sim(Box::new(e))
    }
}

/// Why a winding job file could not be read for a check (`--mandrel JOB`,
/// the view's check of a result): the file, or the job in it.
#[derive(Debug, thiserror::Error)]
pub enum JobFileError {
    /// The file could not be read (not a regular file, too large, not UTF-8).
    #[error("{}: {source}", source.path().display())]
    Read {
        /// The reason, with the path.
        #[from]
        source: formcam_files::ReadError,
    },
    /// The job could not be read or planned.
    #[error("{}: {source}", path.display())]
    Job {
        /// The job file.
        path: std::path::PathBuf,
        /// What is wrong.
        source: Box<ProgramError>,
    },
}

impl JobFileError {
    /// The job file `path`'s error `source`.
    pub fn job(path: &std::path::Path, source: ProgramError) -> Self {
        Self::Job {
            path: path.to_path_buf(),
            source: Box::new(source),
        }
    }
}

/// Why a Cyclone/FiberPath `.wind` document cannot be read: each variant
/// names the member by its JSON path (`member`, such as
/// `layers[1].windAngle`) and the rule of the format's specification it breaks.
#[derive(Debug, thiserror::Error)]
pub enum WindFileError {
    /// The shipped X/A/B winder no longer places its eye's arm where the
    /// reader moves it.
    #[error("{machine} (shipped): the eye's arm is not where the .wind reader expects it")]
    ArmMoved {
        /// The shipped machine's name.
        machine: &'static str,
    },
    /// The eye's clearance over the mandrel is not a positive number.
    #[error("--eye-clearance: must be a finite number > 0 mm, got {value}")]
    EyeClearance {
        /// The clearance given, mm.
        value: f64,
    },
    /// The text is not JSON.
    #[error("{}:{}: {}", .0.line(), .0.column(), one_line(.0))]
    Json(#[source] serde_json::Error),
    /// The document is JSON but not an object.
    #[error("the document must be a JSON object")]
    NotADocument,
    /// A member that must be an object is not.
    #[error("{member}: must be an object")]
    NotAnObject {
        /// The member.
        member: String,
    },
    /// A required member is missing; the unknown members beside it are named,
    /// as they may be it misspelt.
    #[error("{member}: missing (required{})", unknown_given(.unknown))]
    Missing {
        /// The member.
        member: String,
        /// The unknown members of the same object.
        unknown: Vec<String>,
    },
    /// A member that must be a finite number is not.
    #[error("{member}: must be a finite number")]
    NotFinite {
        /// The member.
        member: String,
    },
    /// A number that must be positive is not.
    #[error("{member}: must be > 0 {unit}, got {value}")]
    NotPositive {
        /// The member.
        member: String,
        /// Its unit (`mm`, `deg`, `mm/min`).
        unit: &'static str,
        /// The value given.
        value: f64,
    },
    /// A count that must be an integer >= 1 is not.
    #[error("{member}: must be an integer >= 1, got {value}")]
    NotACount {
        /// The member.
        member: String,
        /// The value given.
        value: f64,
    },
    /// A member that must be `true` or `false` is not.
    #[error("{member}: must be true or false")]
    NotABoolean {
        /// The member.
        member: String,
    },
    /// A member that must be a string is not.
    #[error("{member}: must be a string")]
    NotAString {
        /// The member.
        member: String,
    },
    /// `schemaVersion` is not a string.
    #[error("schemaVersion: must be a string such as \"1.3\"")]
    VersionNotAString,
    /// `schemaVersion` is not `<major>.<minor>`.
    #[error("schemaVersion: \"{text}\" is not a version <major>.<minor> (1.x is read)")]
    VersionForm {
        /// The version given.
        text: String,
    },
    /// `schemaVersion` has a major version other than 1.
    #[error(
        "schemaVersion: \"{text}\" is not supported (1.x is; formcam reads the specification up \
         to {}.{})",
        SPEC_VERSION.0,
        SPEC_VERSION.1
    )]
    VersionUnsupported {
        /// The version given.
        text: String,
    },
    /// `skipIndex` and `patternNumber` share a factor.
    #[error(
        "{member}: {skip_index} and patternNumber {pattern} must be coprime (gcd {gcd}) for full \
         coverage"
    )]
    NotCoprime {
        /// The member (`layers[N].skipIndex`).
        member: String,
        /// The skip index.
        skip_index: u32,
        /// The pattern number.
        pattern: u32,
        /// Their greatest common divisor.
        gcd: u32,
    },
    /// The lead-in is as long as the wind length or longer.
    #[error(
        "{member}: {lead_in_mm} mm must be shorter than mandrelParameters.windLength \
         ({wind_length_mm} mm)"
    )]
    LeadInTooLong {
        /// The member (`layers[N].leadInMM`).
        member: String,
        /// The lead-in, mm.
        lead_in_mm: f64,
        /// The wind length, mm.
        wind_length_mm: f64,
    },
    /// The pattern number does not divide the layer's circuits.
    #[error(
        "{member}: {pattern} does not divide the layer's {circuits} circuits (pi x diameter x \
         cos(windAngle) / tow width, rounded up); change the angle, the pattern or the tow"
    )]
    PatternDoesNotDivide {
        /// The member (`layers[N].patternNumber`).
        member: String,
        /// The pattern number.
        pattern: u32,
        /// The layer's circuits.
        circuits: f64,
    },
    /// `lockDegrees` does not step the circuits onto the pattern's slots.
    #[error(
        "{member}: {lock_deg} deg must be a multiple of 180 / patternNumber = {half_slot_deg} deg \
         (nearest: {below_deg}, {above_deg})"
    )]
    LockOffSlot {
        /// The member (`layers[N].lockDegrees`).
        member: String,
        /// The lock given, degrees.
        lock_deg: f64,
        /// Half a slot, `180 / patternNumber`, degrees.
        half_slot_deg: f64,
        /// The nearest multiple below, degrees.
        below_deg: f64,
        /// The nearest multiple above, degrees.
        above_deg: f64,
    },
    /// `lockDegrees` steps the circuits onto each other.
    #[error(
        "{member}: {lock_deg} deg with skipIndex {skip_index} steps each circuit {stride} of \
         {pattern} slots, which is not coprime with patternNumber: circuits would lie on each other"
    )]
    LockStride {
        /// The member (`layers[N].lockDegrees`).
        member: String,
        /// The lock given, degrees.
        lock_deg: f64,
        /// The skip index.
        skip_index: u32,
        /// The slots each circuit steps.
        stride: u32,
        /// The pattern number.
        pattern: u32,
    },
    /// A profile mandrel that also gives an `endDiameter`.
    #[error(
        "mandrelParameters.profile: profile and endDiameter are mutually exclusive (a profile \
         defines the whole surface)"
    )]
    ProfileAndEndDiameter,
    /// A profile mandrel, which formcam does not wind.
    #[error(
        "mandrelParameters.profile: a \"{kind}\" profile mandrel (1.2+) changes the geometry and \
         formcam does not wind it yet (cylinders and reducing cones it does)"
    )]
    ProfileMandrel {
        /// The profile's `type` (`?` when absent).
        kind: String,
    },
    /// An `endDiameter` larger than the diameter.
    #[error(
        "mandrelParameters.endDiameter: {end_mm} mm > diameter {diameter_mm} mm is an expanding \
         cone; .wind cones are reducing frustums only (endDiameter < diameter: mount the large \
         end at z = 0)"
    )]
    ExpandingCone {
        /// The end diameter, mm.
        end_mm: f64,
        /// The diameter, mm.
        diameter_mm: f64,
    },
    /// `layers` is not an array.
    #[error("layers: must be an array")]
    LayersNotAnArray,
    /// A hoop layer on a cone.
    #[error(
        "{layer}: a hoop layer on a cone is refused by the specification (a hoop is not a \
         geodesic of a cone)"
    )]
    HoopOnCone {
        /// The layer (`layers[N]`).
        layer: String,
    },
    /// A terminal hoop before the last layer.
    #[error("{member}: a terminal hoop must be the last layer")]
    TerminalNotLast {
        /// The member (`layers[N].terminal`).
        member: String,
    },
    /// A wind angle outside (0, 90] degrees.
    #[error("{member}: {angle_deg} deg: a wind angle lies in (0, 90] degrees from the axis")]
    WindAngle {
        /// The member (`layers[N].windAngle`).
        member: String,
        /// The angle given, degrees.
        angle_deg: f64,
    },
    /// A negative `frictionLambda`.
    #[error("{member}: must be >= 0, got {value}")]
    FrictionNegative {
        /// The member (`layers[N].frictionLambda`).
        member: String,
        /// The value given.
        value: f64,
    },
    /// A non-zero `frictionLambda` on a cylinder or cone.
    #[error(
        "{member}: {value}: non-geodesic winding needs a profile mandrel; a {} is wound \
         geodesically (0)",
        if *.cone { "cone" } else { "cylinder" }
    )]
    FrictionNotGeodesic {
        /// The member (`layers[N].frictionLambda`).
        member: String,
        /// The value given.
        value: f64,
        /// Whether the mandrel is a cone (else a cylinder).
        cone: bool,
    },
    /// A helical layer whose geodesic turns before the cone's small end.
    #[error(
        "{member}: {angle_deg} deg is too steep for the cone: its geodesic turns before the small \
         end (diameter x sin(windAngle) must be <= endDiameter; at most {max_deg:.4} deg)"
    )]
    TooSteepForCone {
        /// The member (`layers[N].windAngle`).
        member: String,
        /// The angle given, degrees.
        angle_deg: f64,
        /// The steepest angle that reaches the small end, degrees.
        max_deg: f64,
    },
    /// A `windType` formcam does not wind.
    #[error("{member}: \"{kind}\" is not a layer type formcam winds (hoop, helical, skip)")]
    UnknownLayerType {
        /// The member (`layers[N].windType`).
        member: String,
        /// The type given.
        kind: String,
    },
}

/// serde_json's message on one line, without the ` at line L column C` it
/// ends with (the position is given once, before it).
fn one_line(e: &serde_json::Error) -> String {
    let text = e.to_string();
    let at = format!(" at line {} column {}", e.line(), e.column());
    text.strip_suffix(&at).unwrap_or(&text).replace('\n', " ")
}

/// `; unknown members given: a, b` when there are any.
fn unknown_given(unknown: &[String]) -> String {
    if unknown.is_empty() {
        String::new()
    } else {
        format!("; unknown members given: {}", unknown.join(", "))
    }
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
        WindingError::Shooting { fault, .. } => WindingError::Shooting {
            layer: Some(layer),
            fault,
        },
        other => other,
    }
}
