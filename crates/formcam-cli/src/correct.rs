//! `formcam correct`: a mould's milling program corrected from CMM
//! measurements of the part (the options, or a `[correct]` job file);
//! `formcam correct simulate`: the closed loop. The work is
//! `formcam_run`'s; here the arguments are read and the files written.

use std::path::{Path, PathBuf};

use formcam_correct::{
    CorrectionJob, DEFAULT_ARC_TOLERANCE_MM, DEFAULT_GAIN, DEFAULT_MAX_DEVIATION_MM, Given,
    Interpolation, MILLING_DIALECTS, Options, Rule, Settings, Tool,
};
use formcam_nc::Dialect;
use formcam_run::{CorrectRunError, History, RunError, RunOutput};

use crate::CliError;
use crate::output::{write_files, write_run};
use crate::progress::with_bar;

/// Options of `formcam correct`.
#[derive(Debug, clap::Args)]
pub struct CorrectArgs {
    /// A job file with a `[correct]` table holding these options (instead of
    /// --measurements and --program); -o then names the output folder.
    #[arg(conflicts_with_all = ["measurements", "program", "report"])]
    pub job: Option<PathBuf>,
    /// The CMM report: CSV (section, point, x_nom, y_nom, z_nom, x_act,
    /// y_act, z_act[, nx, ny, nz]) or DMIS (.dmi, .dms, .dmo) point features.
    #[arg(long)]
    pub measurements: Option<PathBuf>,
    /// The milling program (G-code: ISO, .mpf Sinumerik, .ngc LinuxCNC) or a
    /// node table (.csv: x, y, z).
    #[arg(long)]
    pub program: Option<PathBuf>,
    /// The corrected program (never the input itself).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Displacement = -gain x interpolated deviation; allowed (0, 2].
    #[arg(long, default_value_t = DEFAULT_GAIN)]
    pub gain: f64,
    /// `point` (nodes on the surface) or `ball:R` (nodes at the centre of a
    /// ball-end tool of radius R mm) [possible values: point, ball:R].
    #[arg(long, default_value = "point")]
    pub tool: Tool,
    /// `bilinear` (the seed's Coons patches) or `bicubic` (C1 Hermite)
    /// [possible values: bilinear, bicubic].
    #[arg(long, default_value = "bilinear")]
    pub interpolation: Interpolation,
    /// The report (JSON); an existing report there keeps its history.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Nodes up to this far beyond the measured area (mm) are corrected by
    /// extrapolation; 0 leaves every node outside unchanged.
    #[arg(long, default_value_t = 0.0)]
    pub margin: f64,
    /// The CMM's noise (standard deviation, mm): the deviations are smoothed
    /// to separate it from the warp; 0 takes them as measured.
    #[arg(long, default_value_t = 0.0)]
    pub noise: f64,
    /// Arcs (G2/G3) are written back as G1 chords within this distance, mm.
    #[arg(long, default_value_t = DEFAULT_ARC_TOLERANCE_MM)]
    pub arc_tolerance: f64,
    /// Split straight feed moves longer than this (mm) into pieces, so the
    /// correction can bend them (default: moves are kept whole).
    #[arg(long)]
    pub max_segment: Option<f64>,
    /// The program's syntax: iso (fanuc), sinumerik-840d (sinumerik, 840d),
    /// linuxcnc, marlin-xab (default: from the extension).
    #[arg(long)]
    pub dialect: Option<String>,
    /// Resample every section to this many points (default: as measured when
    /// all sections have the same count, else the largest count).
    #[arg(long)]
    pub points_per_section: Option<usize>,
    /// The largest plausible deviation and node displacement, mm: a measured
    /// deviation or a displacement beyond it stops the run (a typing error in
    /// the report, or a part too far off to correct by re-milling).
    #[arg(long, default_value_t = DEFAULT_MAX_DEVIATION_MM)]
    pub max_deviation: f64,
}

pub(crate) fn read_text(path: &Path) -> Result<String, CliError> {
    formcam_files::read_text(path).map_err(|e| CliError::Read {
        path: path.to_path_buf(),
        source: e.into(),
    })
}

/// Runs `formcam correct` (a job file, or the options on the command line);
/// returns the one-line summary.
pub fn run(a: &CorrectArgs) -> Result<String, CliError> {
    let Some(job) = &a.job else {
        return run_args(a);
    };
    let out = a
        .output
        .clone()
        .ok_or_else(|| CliError::CorrectJobNeedsOutput { job: job.clone() })?;
    let text = read_text(job)?;
    let done = with_bar(|p| formcam_run::correct_job_with(job, &text, &out, p))?;
    guard_job(job, &text, &out, &done)?;
    write_run(&out, &done)?;
    Ok(done.line)
}

/// Runs `formcam correct` with the options on the command line.
fn run_args(a: &CorrectArgs) -> Result<String, CliError> {
    let need =
        |p: &Option<PathBuf>, flag: &'static str| p.clone().ok_or(CliError::CorrectNeeds { flag });
    let meas_path = need(&a.measurements, "--measurements cmm.csv")?;
    let prog_path = need(&a.program, "--program mould.nc")?;
    let out_path = need(&a.output, "-o corrected.nc")?;
    guard_outputs(&meas_path, &prog_path, &out_path, a.report.as_deref())?;
    let dialect = match &a.dialect {
        Some(d) => Some(milling_dialect(d)?),
        None => None,
    };
    let job = CorrectionJob {
        measurements: meas_path,
        program: prog_path,
        settings: Settings {
            options: Options {
                gain: a.gain,
                tool: a.tool,
                interpolation: a.interpolation,
                margin_mm: a.margin,
            },
            noise_mm: a.noise,
            arc_tolerance_mm: a.arc_tolerance,
            dialect,
            points_per_section: a.points_per_section,
            max_segment_mm: a.max_segment,
            max_deviation_mm: a.max_deviation,
        },
    };
    // The report history is the one file the command extends: read here,
    // its new text written here.
    let history = match &a.report {
        Some(rp) => Some(History {
            path: rp.clone(),
            previous: if rp.exists() {
                Some(read_text(rp)?)
            } else {
                None
            },
        }),
        None => None,
    };
    let done = with_bar(|p| formcam_run::correct_with(&job, &out_path, history.as_ref(), p))?;
    // The side files first, the report next, the program last: a report
    // that cannot be written stops the run before the program is in place.
    let folder = formcam_run::output_folder(&out_path);
    let program = out_path.file_name().map(|n| n.to_string_lossy());
    let (main, side): (Vec<_>, Vec<_>) = done
        .run
        .files
        .iter()
        .partition(|f| program.as_deref() == Some(f.name.as_str()));
    let mut files: Vec<(PathBuf, &[u8])> = side
        .iter()
        .map(|f| (folder.join(&f.name), f.bytes.as_slice()))
        .collect();
    if let (Some(rp), Some(report)) = (&a.report, &done.report) {
        files.push((rp.clone(), report.as_slice()));
    }
    files.extend(main.iter().map(|f| (out_path.clone(), f.bytes.as_slice())));
    write_files(&files, &done.run.inputs)?;
    Ok(done.run.line)
}

/// The dialect `--dialect name` names, refused in the words of the job
/// file's `dialect` field (`--dialect "foo": allowed iso, fanuc, ...`).
fn milling_dialect(name: &str) -> Result<Dialect, CliError> {
    let listed = MILLING_DIALECTS
        .iter()
        .any(|m| m.eq_ignore_ascii_case(name));
    match Dialect::from_name(name) {
        Ok(d) if listed => Ok(d),
        _ => Err(RunError::from(CorrectRunError::Flag {
            flag: "dialect",
            value: Given::Word(formcam_files::quote(name).to_string()),
            rule: Rule::Word {
                allowed: MILLING_DIALECTS,
            },
        })
        .into()),
    }
}

/// No output may land on an input or on another output.
fn guard_outputs(
    measurements: &Path,
    program: &Path,
    output: &Path,
    report: Option<&Path>,
) -> Result<(), CliError> {
    let mut outputs = vec![("-o", output)];
    if let Some(r) = report {
        outputs.push(("--report", r));
    }
    for (flag, o) in outputs {
        for (what, input) in [("program", program), ("measurements", measurements)] {
            if formcam_files::same_file(o, input) {
                return Err(CliError::Refused {
                    path: o.to_path_buf(),
                    flag,
                    what,
                });
            }
        }
    }
    if let Some(r) = report
        && formcam_files::same_file(r, output)
    {
        return Err(CliError::SameReport {
            path: r.to_path_buf(),
        });
    }
    Ok(())
}

/// No result file of the correction job at `path` (text `text`), written
/// into `out`, may land on the job's program or measurements.
pub(crate) fn guard_job(
    path: &Path,
    text: &str,
    out: &Path,
    done: &RunOutput,
) -> Result<(), CliError> {
    // The job was read by the run, so it reads here too.
    let base = path.parent().unwrap_or(Path::new("."));
    let Ok(job) = CorrectionJob::from_toml(text, base) else {
        return Ok(());
    };
    for f in &done.files {
        let o = out.join(&f.name);
        for (what, input) in [
            ("program", &job.program),
            ("measurements", &job.measurements),
        ] {
            if formcam_files::same_file(&o, input) {
                return Err(CliError::RefusedByJob {
                    path: o,
                    what,
                    job: path.to_path_buf(),
                });
            }
        }
    }
    Ok(())
}

/// Runs `formcam correct simulate`; returns the one-line summary.
pub fn simulate(path: &Path, out: &Path) -> Result<String, CliError> {
    let text = read_text(path)?;
    let done = with_bar(|p| formcam_run::correct_simulate_with(path, &text, out, p))?;
    write_run(out, &done)?;
    Ok(done.line)
}
