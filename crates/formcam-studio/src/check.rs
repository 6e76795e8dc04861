//! A job checked as `formcam` would read it before running: its
//! description's [`validate`] and then the process crate's own reader with
//! the studio's folder as the job's folder (and the files the job names,
//! read as the run reads them), so that every message is word for word the
//! line `formcam` prints for the same file (after `formcam: error: `). Each
//! error is placed at its field for the form: `table.field`, or
//! `layer[1].band_width` with the 0-based index of the repeated table as in
//! the form's values (the message keeps the file's 1-based words).

use std::path::{Path, PathBuf};

use formcam_correct::{CorrectError, CorrectionJob, MillingProgram, ScenarioError, ScenarioJob};
use formcam_dress::{DressError, DressJob, Dresser, Point, Profile};
use formcam_machine::MachineKind;
use formcam_program::{ProgramError, Stage, WindJob, estimate};
use formcam_run::{CorrectRunError, RunError};
use formcam_schema::{SchemaError, validate};
use formcam_winding::WindingError;
use serde::{Deserialize, Serialize};
use toml_edit::{ImDocument, Item};

use crate::values::line_col;
use crate::{JobKind, StudioError, apply_values_as};

/// A problem of a job, placed at its field for the form.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FieldError {
    /// The field (`mandrel.radius`, `layer[1].band_width` with the 0-based
    /// index of the repeated table, a table alone: `machine`); `None` when
    /// the problem is the whole job's.
    pub field: Option<String>,
    /// The line of the job's text (1-based) where the problem is, when
    /// known.
    pub line: Option<usize>,
    /// What `formcam` prints for the same file, naming the file, the field
    /// and what is allowed.
    pub message: String,
}

/// The problems of the job `file_name` in the folder `dir` whose text is
/// `text`, as a job of `kind`: empty when `formcam` would read it and the
/// files it names and start the run; else the first problem, as `formcam`
/// stops at it.
pub fn check_job(kind: JobKind, dir: &Path, file_name: &str, text: &str) -> Vec<FieldError> {
    let path = dir.join(file_name);
    let described = kind.schema().and_then(|s| validate(s, text).err());
    let read = match kind {
        JobKind::WindFile => Err(Refusal {
            message: format!("{}: a .wind document is not edited here", path.display()),
            field: None,
            line: None,
        }),
        JobKind::Winding => winding(&path, text),
        JobKind::Dressing => dressing(&path, text),
        JobKind::Correction => correction(&path, text),
        JobKind::Scenario => scenario(&path, text),
    };
    let refusal = match (read, &described) {
        (Err(r), _) => r,
        (Ok(()), None) => return Vec::new(),
        // Every reader validates first; should one let pass what its
        // description refuses, the description's words are shown.
        (Ok(()), Some(e)) => Refusal {
            message: format!("{}: {e}", path.display()),
            field: None,
            line: None,
        },
    };
    let (schema_field, schema_line) = described.as_ref().map_or((None, None), schema_place);
    let field = refusal.field.or(schema_field).map(|f| form_field(&f));
    let line = refusal
        .line
        .or(schema_line)
        .or_else(|| field.as_deref().and_then(|f| line_of(text, f)));
    vec![FieldError {
        field,
        line,
        message: refusal.message,
    }]
}

/// A form applied to a job: its new text and its problems, as the page's
/// Apply shows them.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Applied {
    /// Whether the job checks clean.
    pub ok: bool,
    /// The job's text with the form's values (the base text when they
    /// could not be written).
    pub text: String,
    /// Its problems, each at its field ([`check_job`]).
    pub errors: Vec<FieldError>,
}

/// The form's `values` written into `base` (the job `file_name` of `dir`
/// as saved, a job of `kind`; see [`apply_values_as`]) and the result
/// checked ([`check_job`]). Values that cannot be written are a problem at
/// their field, the text left as it was.
pub fn apply_job(
    kind: JobKind,
    dir: &Path,
    file_name: &str,
    base: &str,
    values: &serde_json::Value,
) -> Applied {
    match apply_values_as(Some(kind), base, values) {
        Ok(text) => {
            let errors = check_job(kind, dir, file_name, &text);
            Applied {
                ok: errors.is_empty(),
                text,
                errors,
            }
        }
        Err(e) => Applied {
            ok: false,
            text: base.to_string(),
            errors: vec![FieldError::from(&e)],
        },
    }
}

impl From<&StudioError> for FieldError {
    /// A studio error as a problem of the form: values at their field, a
    /// text that is no TOML at its line.
    fn from(e: &StudioError) -> Self {
        let (field, line) = match e {
            StudioError::Values { field, .. } if !field.is_empty() => (Some(field.clone()), None),
            StudioError::NotToml { line, .. } => (None, Some(*line)),
            _ => (None, None),
        };
        FieldError {
            field,
            line,
            message: e.to_string(),
        }
    }
}

/// A reader's refusal: the message `formcam` prints and where.
#[derive(Debug)]
struct Refusal {
    message: String,
    field: Option<String>,
    line: Option<usize>,
}

impl Refusal {
    fn new(e: RunError, field: Option<String>, line: Option<usize>) -> Self {
        Self {
            message: e.to_string(),
            field,
            line,
        }
    }
}

// ---------------------------------------------------------------- winding

/// A winding job as `formcam wind` reads it: the tables (machine file and
/// post's template read), the eye's curve, and every layer checked on the
/// mandrel (its meridian's table read) with the program's size, as the run
/// does before planning.
fn winding(path: &Path, text: &str) -> Result<(), Refusal> {
    let base = path.parent().unwrap_or(Path::new(""));
    let at = |e: ProgramError| {
        let (field, line) = program_place(&e, text);
        Refusal::new(RunError::wind(path, e), field, line)
    };
    let job = WindJob::from_toml(text, base).map_err(at)?.named(path);
    let stage = job.furthest_stage();
    let read = |name: &str| {
        let p = job.base_dir.join(name);
        formcam_files::read_text(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let eye = job
        .eye
        .as_ref()
        .map(|e| e.spec(read))
        .transpose()
        .map_err(|e| at(ProgramError::from(e)))?;
    let placement = job
        .machine
        .as_ref()
        .is_some_and(|m| m.machine.roles.kind == MachineKind::Placement);
    let eye_used = if stage >= Stage::Eye && !placement {
        eye.as_ref()
    } else {
        None
    };
    estimate(&job, stage, eye_used)
        .and_then(|size| size.within(formcam_files::max_memory_bytes()))
        .map_err(at)
}

/// Where a winding job's error is: its field and line.
fn program_place(e: &ProgramError, text: &str) -> (Option<String>, Option<usize>) {
    let field = |s: &str| (Some(s.to_string()), None);
    match e {
        ProgramError::Syntax { line, .. } => (None, Some(*line).filter(|l| *l > 0)),
        ProgramError::Schema(se) => schema_place(se),
        ProgramError::MissingTable { table } => field(table),
        ProgramError::NoMachine => field("machine"),
        ProgramError::NoLayers => field("layer"),
        ProgramError::Winding(w) => (winding_field(w), None),
        ProgramError::MachineChoice { .. } | ProgramError::UnknownMachine { .. } => {
            field("machine.name")
        }
        ProgramError::MachineNotFound { .. } => field("machine.file"),
        ProgramError::MachineSyntax { .. } | ProgramError::Machine { .. } => {
            if machine_from_file(text) {
                field("machine.file")
            } else {
                field("machine.name")
            }
        }
        ProgramError::NotPositive { field: f, .. } => field(f),
        ProgramError::SkipTurnMissing { layer } => {
            (Some(format!("layer[{layer}].mandrel_rotation_deg")), None)
        }
        ProgramError::PostBoth
        | ProgramError::TemplateRead { .. }
        | ProgramError::Template { .. } => field("post.template"),
        ProgramError::Dialect(_) => field("post.dialect"),
        _ => (None, None),
    }
}

/// The field a winding error names (`winding.mu`, `layer[2].band_width`).
fn winding_field(e: &WindingError) -> Option<String> {
    match e {
        WindingError::Field { field, .. } | WindingError::Infeasible { field, .. } => {
            Some(field.clone())
        }
        WindingError::Shooting { layer, .. } => Some(match layer {
            Some(n) => format!("layer[{n}].mu"),
            None => "winding.mu".into(),
        }),
        WindingError::Geometry(_) => Some("mandrel".into()),
        _ => None,
    }
}

/// Whether the job's `[machine]` names a file (else a shipped name).
fn machine_from_file(text: &str) -> bool {
    text.parse::<toml::Table>().is_ok_and(|t| {
        t.get("machine")
            .and_then(toml::Value::as_table)
            .is_some_and(|m| m.contains_key("file"))
    })
}

// ---------------------------------------------------------------- dressing

/// A dressing job as `formcam dress` reads it: the tables, the initial
/// contour's file, the dressing asked for, the wheel's profile and the
/// dresser on it.
fn dressing(path: &Path, text: &str) -> Result<(), Refusal> {
    let parsed = DressJob::from_toml(text).map_err(|e| dress_refusal(path, e))?;
    let contour_file = parsed
        .process
        .initial_contour
        .as_ref()
        .map(|file| resolve(path, file));
    let initial = match &contour_file {
        Some(p) => Some(read_initial(p)?),
        None => None,
    };
    // A contour that cannot be dressed is named by its own file (as the run
    // names it).
    let blame = |e: DressError| match (&e, &contour_file) {
        (DressError::Contour(_), Some(p)) => dress_refusal(p, e),
        _ => dress_refusal(path, e),
    };
    let spec = parsed.spec(initial).map_err(blame)?;
    let profile = Profile::new(&spec.wheel).map_err(blame)?;
    Dresser::new(&spec.dresser, &profile).map_err(blame)?;
    Ok(())
}

/// A dressing error of the file `file` in `formcam-run`'s words.
fn dress_refusal(file: &Path, e: DressError) -> Refusal {
    let (field, line) = match &e {
        DressError::Field { field, .. } | DressError::Missing { field, .. } => {
            (Some(field.clone()), None)
        }
        DressError::Toml { line, .. } => (None, Some(*line).filter(|l| *l > 0)),
        DressError::Schema(se) => schema_place(se),
        DressError::Contour(_) | DressError::ContourLine { .. } => {
            (Some("process.initial_contour".to_string()), None)
        }
        _ => (None, None),
    };
    let run = match e {
        DressError::Toml {
            line,
            column,
            message,
        } => dress_error(file, &format!(":{line}:{column}"), message),
        e => dress_error(file, "", e.to_string()),
    };
    Refusal::new(run, field, line)
}

fn dress_error(file: &Path, at: &str, message: String) -> RunError {
    RunError::Dress {
        file: file.to_path_buf(),
        at: at.to_string(),
        message,
    }
}

/// A file a dressing job names: beside the job if it is there, else as
/// given (the run's rule).
fn resolve(job: &Path, file: &str) -> PathBuf {
    match job.parent().map(|p| p.join(file)) {
        Some(p) if p.exists() => p,
        _ => PathBuf::from(file),
    }
}

/// The points of `process.initial_contour`, read as the run reads them.
fn read_initial(path: &Path) -> Result<Vec<Point>, Refusal> {
    let field = Some("process.initial_contour".to_string());
    let text = formcam_files::read_text(path).map_err(|e| {
        let message = format!("process.initial_contour: cannot read: {e}");
        Refusal::new(dress_error(path, "", message), field.clone(), None)
    })?;
    formcam_dress::read_contour(&text).map_err(|e| {
        let run = match e {
            DressError::ContourLine { line, problem } => dress_error(
                path,
                &format!(":{line}"),
                format!("process.initial_contour: {problem}"),
            ),
            e => dress_error(path, "", e.to_string()),
        };
        Refusal::new(run, field.clone(), None)
    })
}

// ---------------------------------------------------------------- correction

/// A correction job as `formcam correct JOB` reads it: the table, its
/// settings' ranges, the CMM report and the program it names, each read.
fn correction(path: &Path, text: &str) -> Result<(), Refusal> {
    let base = path.parent().unwrap_or(Path::new("."));
    let job = CorrectionJob::from_toml(text, base).map_err(|e| correct_refusal(path, e))?;
    job.settings.check().map_err(|e| correct_refusal(path, e))?;
    formcam_run::read_measurements(&job.measurements)
        .map_err(|e| named(e, path, "correct.measurements"))?;
    let program = formcam_files::read_text(&job.program).map_err(|e| {
        let read = RunError::Read {
            path: job.program.clone(),
            source: e.into(),
        };
        named(read, path, "correct.program")
    })?;
    let ext = job
        .program
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    MillingProgram::read(&program, &ext, &job.settings).map_err(|source| {
        let run = RunError::from(CorrectRunError::File {
            path: job.program.clone(),
            source,
        });
        Refusal::new(run, Some("correct.program".into()), None)
    })?;
    Ok(())
}

/// A closed-loop scenario as `formcam correct simulate` reads it.
fn scenario(path: &Path, text: &str) -> Result<(), Refusal> {
    ScenarioJob::from_toml(text).map_err(|e| correct_refusal(path, e))?;
    Ok(())
}

/// A correction's or scenario's error of the job file `path`.
fn correct_refusal(path: &Path, e: CorrectError) -> Refusal {
    let (field, line) = correct_place(&e);
    let run = RunError::from(CorrectRunError::File {
        path: path.to_path_buf(),
        source: e,
    });
    Refusal::new(run, field, line)
}

/// A file the correction job names (by `field`) that cannot be read or used:
/// named as the run names it.
fn named(e: RunError, job: &Path, field: &'static str) -> Refusal {
    let run = match e {
        RunError::Read { path, source } => RunError::ReadNamed {
            job: job.to_path_buf(),
            field,
            path,
            source,
        },
        e => e,
    };
    Refusal::new(run, Some(field.to_string()), None)
}

fn correct_place(e: &CorrectError) -> (Option<String>, Option<usize>) {
    match e {
        CorrectError::Field { field, .. } => (Some(field.to_string()), None),
        CorrectError::Job(se) => schema_place(se),
        CorrectError::NoCorrectTable => (Some("correct".into()), None),
        CorrectError::Scenario(s) => match s {
            ScenarioError::Field { field, .. } | ScenarioError::Missing { field, .. } => {
                (Some(field.to_string()), None)
            }
            ScenarioError::Schema(se) => schema_place(se),
            ScenarioError::NoseConeWidth { .. } => (Some("surface.width".into()), None),
            ScenarioError::Nodes { .. } => (Some("program.step".into()), None),
            ScenarioError::BallRadius { .. } => (Some("program.tool".into()), None),
            _ => (None, None),
        },
        _ => (None, None),
    }
}

// ---------------------------------------------------------------- places

/// The field (as the file names it) and line of a description's refusal.
fn schema_place(e: &SchemaError) -> (Option<String>, Option<usize>) {
    match e {
        SchemaError::Syntax { line, .. } => (None, Some(*line)),
        SchemaError::UnknownTable { table, line, .. } => (Some(table.clone()), Some(*line)),
        SchemaError::UnknownKey { field, line, .. }
        | SchemaError::WrongType { field, line, .. }
        | SchemaError::OutOfRange { field, line, .. }
        | SchemaError::NotAWord { field, line, .. }
        | SchemaError::Missing { field, line, .. } => (Some(field.clone()), Some(*line)),
        SchemaError::MissingTable { table } => (Some(table.clone()), None),
    }
}

/// A field as the file's messages name it (`layer[2].kind`,
/// `checks.allow[1]`, `[mandrel]`) as the form names it: the repeated
/// table's index 0-based, the key without what is inside its value
/// (`layer[1].kind`, `checks.allow`, `mandrel`).
pub(crate) fn form_field(named: &str) -> String {
    let named = named.trim_matches(|c| c == '[' || c == ']');
    let (head, rest) = match named.split_once('.') {
        Some((h, r)) => (h, Some(r)),
        None => (named, None),
    };
    let head = match head.split_once('[') {
        Some((name, index)) => match index.trim_end_matches(']').parse::<usize>() {
            Ok(n) if n >= 1 => format!("{name}[{}]", n - 1),
            _ => name.to_string(),
        },
        None => head.to_string(),
    };
    match rest {
        Some(r) => {
            let key = r.split(['.', '[']).next().unwrap_or(r);
            format!("{head}.{key}")
        }
        None => head,
    }
}

/// The line (1-based) of a form's field in `text`: its key, or the table's
/// header for a table alone.
fn line_of(text: &str, field: &str) -> Option<usize> {
    let doc = ImDocument::parse(text).ok()?;
    let (head, key) = match field.split_once('.') {
        Some((h, k)) => (h, Some(k)),
        None => (field, None),
    };
    let (name, index) = match head.split_once('[') {
        Some((n, i)) => (n, i.trim_end_matches(']').parse::<usize>().ok()),
        None => (head, None),
    };
    let (table_key, item) = doc.as_table().get_key_value(name)?;
    let table: &dyn toml_edit::TableLike = match (item, index) {
        (Item::ArrayOfTables(a), Some(i)) => a.get(i)?,
        (item, None) => item.as_table_like()?,
        _ => return None,
    };
    let span = match key {
        Some(k) => table.get_key_value(k).and_then(|(k, _)| k.span()),
        None => match item {
            Item::Table(t) => t.span(),
            _ => table_key.span(),
        },
    }?;
    Some(line_col(text, span.start).0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_form_applied_is_its_text_and_its_problems() {
        let dir = std::env::temp_dir();
        let base = "[mandrel]\nkind = \"cylinder\"\nradius = 50.0\nlength = 300.0\n\n[winding]\nwinding_angle_deg = 45.0 # deg\nband_width = 10.0\nband_thickness = 0.5\n";
        let mut values = crate::values_of(base).expect("toml");
        values["winding"]["winding_angle_deg"] = serde_json::json!(30);
        let applied = apply_job(JobKind::Winding, &dir, "a.toml", base, &values);
        assert!(applied.ok, "{applied:?}");
        assert!(applied.text.contains("winding_angle_deg = 30.0 # deg\n"));
        values["winding"]["band_width"] = serde_json::json!(0);
        let applied = apply_job(JobKind::Winding, &dir, "a.toml", base, &values);
        assert!(!applied.ok);
        assert_eq!(
            applied.errors[0].field.as_deref(),
            Some("winding.band_width")
        );
        let refused = apply_job(
            JobKind::Winding,
            &dir,
            "a.toml",
            base,
            &serde_json::json!({"mandrel": 1}),
        );
        assert_eq!(refused.text, base);
        assert_eq!(refused.errors[0].field.as_deref(), Some("mandrel"));
        let json = serde_json::to_value(&refused).expect("serialises");
        assert_eq!(json["ok"], serde_json::json!(false));
        assert!(json["errors"][0]["message"].is_string());
    }

    #[test]
    fn fields_as_the_form_names_them() {
        assert_eq!(form_field("layer[2].kind"), "layer[1].kind");
        assert_eq!(form_field("checks.allow[1]"), "checks.allow");
        assert_eq!(
            form_field("winding.mu_segments[1].mu"),
            "winding.mu_segments"
        );
        assert_eq!(form_field("[mandrel]"), "mandrel");
        assert_eq!(form_field("[[layer]]"), "layer");
        assert_eq!(form_field("machine.name"), "machine.name");
        assert_eq!(form_field("layer[1]"), "layer[0]");
    }

    #[test]
    fn lines_of_fields_keys_and_tables() {
        let text = "[mandrel]\nkind = \"cylinder\"\n\n[[layer]]\nkind = \"hoop\"\n\n[[layer]]\nkind = \"skip\"\nmandrel_rotation_deg = 90\n";
        assert_eq!(line_of(text, "mandrel.kind"), Some(2));
        assert_eq!(line_of(text, "layer[1].mandrel_rotation_deg"), Some(9));
        assert_eq!(line_of(text, "layer[0].kind"), Some(5));
        assert_eq!(line_of(text, "mandrel"), Some(1));
        assert_eq!(line_of(text, "mandrel.radius"), None);
        assert_eq!(line_of(text, "layer[5].kind"), None);
    }

    #[test]
    fn a_clean_job_has_no_problem_and_a_bad_one_its_field() {
        let dir = std::env::temp_dir();
        let good = "[mandrel]\nkind = \"cylinder\"\nradius = 50.0\nlength = 300.0\n\n[winding]\nwinding_angle_deg = 45.0\nband_width = 10.0\nband_thickness = 0.5\n";
        assert_eq!(
            check_job(JobKind::Winding, &dir, "a.toml", good),
            Vec::new()
        );
        let bad = good.replace("45.0", "95.0");
        let found = check_job(JobKind::Winding, &dir, "a.toml", &bad);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].field.as_deref(), Some("winding.winding_angle_deg"));
        assert_eq!(found[0].line, Some(7));
        assert!(
            found[0].message.ends_with(
                "a.toml: winding.winding_angle_deg = 95.0 at 7:21: out of range; allowed (0, 90) deg"
            ),
            "{}",
            found[0].message
        );
    }
}
