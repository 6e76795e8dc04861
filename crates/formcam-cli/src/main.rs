//! The `formcam` command line: reads job files, runs the processes of the
//! library crates and writes their outputs atomically.

mod check;
mod correct;
mod dress;
mod error;
mod machine;
mod output;
mod progress;
mod report;
mod studio;
mod view;
mod wind;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand};
use formcam_program::Stage;

pub use error::CliError;

/// formcam: CAM for filament winding, fibre placement, mould correction and wheel dressing.
#[derive(Debug, Parser)]
#[command(name = "formcam", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// The most read of one input file, MiB: a larger input (or a device
    /// that never ends) is refused.
    #[arg(
        long,
        global = true,
        value_name = "MB",
        default_value_t = formcam_files::DEFAULT_MAX_INPUT_BYTES / MIB,
        value_parser = clap::value_parser!(u64).range(1..=MAX_INPUT_MB)
    )]
    max_input_mb: u64,
    /// The most a run may hold in memory, MiB: a winding job estimated
    /// larger is refused before any layer is planned.
    #[arg(
        long,
        global = true,
        value_name = "MB",
        default_value_t = formcam_files::DEFAULT_MAX_MEMORY_BYTES / MIB,
        value_parser = clap::value_parser!(u64).range(1..=MAX_INPUT_MB)
    )]
    max_memory_mb: u64,
}

/// Bytes per MiB.
const MIB: u64 = 1024 * 1024;

/// The largest `--max-input-mb` and `--max-memory-mb` (1 TiB).
const MAX_INPUT_MB: u64 = 1024 * 1024;

#[derive(Debug, Subcommand)]
enum Command {
    /// Filament winding: `formcam wind JOB -o OUT` writes the whole program
    /// and checks it on its machine (exit status 3 when a check fails); the
    /// subcommands stop after a stage.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Wind {
        #[command(subcommand)]
        what: Option<WindCommand>,
        /// The job file (TOML with [mandrel], [winding] or [[layer]], [eye],
        /// [machine], [post]; or a Cyclone/FiberPath `.wind` document).
        #[arg(required = true)]
        job: Option<PathBuf>,
        /// Output folder (program.<ext>, blocks.csv, axes.csv, the eye and path
        /// outputs, summary.json).
        #[arg(short, long, required = true)]
        output: Option<PathBuf>,
        /// `.wind` jobs: the eye's clearance over the mandrel, mm (it rides
        /// parallel to the axis at the mandrel's radius plus this; default 25).
        #[arg(long, value_name = "MM")]
        eye_clearance: Option<f64>,
        /// `.wind` jobs: checks whose failure is accepted (comma-separated);
        /// TOML jobs use `[checks] allow`.
        #[arg(long, value_name = "CHECKS", value_delimiter = ',', value_parser = wind::allow_parser())]
        allow: Vec<formcam_program::Check>,
        /// Do not check the written program on its machine (by default it is
        /// read back and checked as `formcam check` does: check.json, exit
        /// status 3 when a check fails).
        #[arg(long)]
        no_check: bool,
    },
    /// Mould correction: `formcam correct --measurements cmm.csv --program
    /// mould.nc -o corrected.nc`, or `formcam correct JOB.toml -o OUTDIR` (a
    /// `[correct]` job file); `formcam correct simulate SCENARIO -o OUT`
    /// runs the closed loop.
    #[command(args_conflicts_with_subcommands = true)]
    Correct {
        #[command(subcommand)]
        what: Option<CorrectCommand>,
        #[command(flatten)]
        args: Box<correct::CorrectArgs>,
    },
    /// Wheel dressing: `formcam dress JOB -o OUT` writes the program of a
    /// dressing wheel forming a gothic-arch grinding wheel (ball-screw nuts),
    /// with the simulation of forming and feed control.
    Dress {
        /// The job file (TOML with [wheel], [dresser], [process]).
        job: PathBuf,
        /// Output folder (program.cls, program.mpf, profile.csv, dresser.csv,
        /// mrr.csv, the contours, profile.svg, mrr.svg, summary.json).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Machine files: the chain as a table, forward kinematics.
    Machine {
        #[command(subcommand)]
        what: MachineCommand,
    },
    /// Checks a written program on a machine: axis limits, velocity,
    /// velocity jump and acceleration per block, and collisions between the
    /// machine's solids (and, with --mandrel, the mandrel and the free fibre). Exit status 0 when
    /// clean, 3 when a check fails, 2 when an input cannot be read.
    Check {
        /// The program (.mpf, .nc, .ngc, .gcode or .cls: the dialect by its extension).
        program: PathBuf,
        /// The machine file (TOML or URDF), or a shipped machine's name.
        #[arg(long)]
        machine: PathBuf,
        /// The winding job the program was written from (TOML or .wind): its
        /// mandrel, grown by the laminate layer by layer, is checked against
        /// the machine's solids, and the free fibre must not cut the mandrel
        /// nor come near a solid.
        #[arg(long, value_name = "JOB")]
        mandrel: Option<PathBuf>,
        /// Write the report (JSON: every violation) to this file.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Shows a winding result in the browser: serves the page, the result's
    /// files and its timeline on 127.0.0.1 and prints the address first.
    View {
        /// The result folder (the output of `formcam wind`).
        folder: PathBuf,
        /// The port on 127.0.0.1 (0: any free one).
        #[arg(long, default_value_t = 0)]
        port: u16,
        /// The machine file, instead of the one the result's summary names.
        #[arg(long)]
        machine: Option<PathBuf>,
    },
    /// Edits, checks, runs and saves jobs in the browser: serves the job
    /// editor for a folder of job files on 127.0.0.1 and prints the
    /// address first. Runs are written under the folder's `runs/`.
    Studio {
        /// The folder of job files, or a job file (its folder, the job
        /// opened first); default: the current folder.
        #[arg(default_value = ".")]
        path: PathBuf,
        /// The port on 127.0.0.1 (0: any free one).
        #[arg(long, default_value_t = 0)]
        port: u16,
    },
    /// Writes a result's read-only views as one self-contained HTML file
    /// (data and scripts inlined: it opens offline, with no server).
    Report {
        /// The result folder (of `formcam wind`, `dress` or `correct`).
        folder: PathBuf,
        /// The HTML file to write (not inside the result folder).
        #[arg(short, long)]
        output: PathBuf,
        /// The machine file, instead of the one the result's summary names.
        #[arg(long)]
        machine: Option<PathBuf>,
    },
    /// Runs every bundled example job and writes its outputs (the main job).
    /// Exit status 3 when the check of a winding program it wrote fails.
    Demo {
        /// Folder of example jobs.
        #[arg(long, default_value = "examples")]
        examples: PathBuf,
        /// Output folder; each job writes into a subfolder named after it.
        #[arg(short, long, default_value = "out")]
        output: PathBuf,
    },
}

#[derive(Debug, Subcommand)]
enum WindCommand {
    /// The winding path of one pass, the pattern and the layer report.
    Path {
        /// The job file (TOML with [mandrel] and [winding]).
        job: PathBuf,
        /// Output folder (path.csv, path.svg, summary.json).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// The payout-eye trajectory over one circuit and its pull speed.
    Eye {
        /// The job file (TOML with [mandrel], [winding] and [eye]).
        job: PathBuf,
        /// Output folder (eye.csv, eye.svg, path.csv, path.svg, summary.json).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// The machine's axes over one circuit (inverse kinematics).
    Axes {
        /// The job file (TOML with [mandrel], [winding], [eye] and [machine]).
        job: PathBuf,
        /// Output folder (axes.csv, band.csv and the eye outputs, summary.json).
        #[arg(short, long)]
        output: PathBuf,
    },
}

#[derive(Debug, Subcommand)]
enum CorrectCommand {
    /// The closed-loop check: mill, mould with a warp, measure, correct, again.
    Simulate {
        /// The scenario (TOML with [surface], [program], [warp], [cmm], [loop]).
        scenario: PathBuf,
        /// Output folder (programs, CMM reports, report.json, convergence.svg).
        #[arg(short, long)]
        output: PathBuf,
    },
}

#[derive(Debug, Subcommand)]
enum MachineCommand {
    /// The chain as a readable table: links, joints, axes, limits, key points.
    Show {
        /// The machine file (TOML), or a shipped machine's name (`winder-4axis`).
        machine: PathBuf,
    },
    /// Forward kinematics: every key point for each row of an axes file.
    Fk {
        /// The machine file (TOML).
        machine: PathBuf,
        /// Axis values: a CSV with a header naming the axes (mm; degrees for rotary axes).
        #[arg(long)]
        axes: PathBuf,
        /// Output CSV: x (when given), then name_x, name_y, name_z per key point, mm.
        #[arg(short, long)]
        output: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    formcam_files::set_max_input_bytes(cli.max_input_mb * MIB);
    formcam_files::set_max_memory_bytes(cli.max_memory_mb * MIB);
    let result = match cli.command {
        Command::Wind {
            what,
            job: whole,
            output: whole_out,
            eye_clearance,
            allow,
            no_check,
        } => {
            let picked = match (what, whole, whole_out) {
                (Some(WindCommand::Path { job, output }), ..) => (job, output, Stage::Path),
                (Some(WindCommand::Eye { job, output }), ..) => (job, output, Stage::Eye),
                (Some(WindCommand::Axes { job, output }), ..) => (job, output, Stage::Axes),
                (None, Some(job), Some(output)) => (job, output, Stage::Program),
                (None, ..) => Cli::command()
                    .error(
                        clap::error::ErrorKind::MissingRequiredArgument,
                        "wind: give a job and -o OUTDIR (or a subcommand: path, eye, axes)",
                    )
                    .exit(),
            };
            let wound = match picked {
                (job, output, Stage::Program)
                    if formcam_run::JobKind::of_extension(&job)
                        == Some(formcam_run::JobKind::WindFile) =>
                {
                    wind::run_wind_file(
                        &job,
                        &output,
                        eye_clearance.unwrap_or(formcam_program::EYE_CLEARANCE_MM),
                        &allow,
                        no_check,
                    )
                }
                _ if !allow.is_empty() => Err(CliError::AllowForToml),
                _ if eye_clearance.is_some() => Err(CliError::EyeClearanceForToml),
                (job, output, stage) => wind::run(&job, &output, stage, no_check),
            };
            match wound {
                Ok(w) => {
                    println!("{}", w.line);
                    if !w.clean {
                        return ExitCode::from(3);
                    }
                    Ok(())
                }
                Err(e) => Err(e),
            }
        }
        Command::Machine {
            what: MachineCommand::Show { machine },
        } => machine::show(&machine).map(|s| print!("{s}")),
        Command::Machine {
            what:
                MachineCommand::Fk {
                    machine,
                    axes,
                    output,
                },
        } => machine::fk(&machine, &axes, &output).map(|s| println!("{s}")),
        Command::Correct { what, args } => match what {
            Some(CorrectCommand::Simulate { scenario, output }) => {
                correct::simulate(&scenario, &output).map(|s| println!("{s}"))
            }
            None => correct::run(&args).map(|s| println!("{s}")),
        },
        Command::Dress { job, output } => dress::run(&job, &output).map(|s| println!("{s}")),
        Command::Demo { examples, output } => match wind::run_demo(&examples, &output) {
            Ok(false) => return ExitCode::from(3),
            other => other.map(|_| ()),
        },
        Command::Check {
            program,
            machine,
            mandrel,
            output,
        } => match check::run(&program, &machine, mandrel, output.as_deref()) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(3),
            Err(e) => Err(e),
        },
        Command::View {
            folder,
            port,
            machine,
        } => view::run(&folder, port, machine),
        Command::Studio { path, port } => studio::run(&path, port),
        Command::Report {
            folder,
            output,
            machine,
        } => report::run(&folder, &output, machine.as_deref()).map(|s| println!("{s}")),
    };
    finish(result)
}

fn finish(result: Result<(), CliError>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("formcam: error: {e}");
            ExitCode::from(2)
        }
    }
}
