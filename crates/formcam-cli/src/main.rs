//! The `formcam` command line: reads job files, runs the processes of the
//! library crates and writes their outputs atomically.

mod output;
mod plot;
mod wind;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// formcam: CAM for filament winding, fibre placement, mould correction and wheel dressing.
#[derive(Debug, Parser)]
#[command(name = "formcam", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Filament winding.
    Wind {
        #[command(subcommand)]
        what: WindCommand,
    },
    /// Runs every bundled example job and writes its outputs (the main job).
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
}

/// An error for the user: one line, naming the file and the field.
#[derive(Debug)]
pub struct CliError(pub String);

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Wind {
            what: WindCommand::Path { job, output },
        } => wind::run_path(&job, &output).map(|s| println!("{s}")),
        Command::Wind {
            what: WindCommand::Eye { job, output },
        } => wind::run_eye(&job, &output).map(|s| println!("{s}")),
        Command::Demo { examples, output } => wind::run_demo(&examples, &output),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError(msg)) => {
            eprintln!("formcam: error: {msg}");
            ExitCode::from(2)
        }
    }
}
