//! `formcam check PROGRAM --machine MACHINE [--mandrel JOB]` as one call:
//! the machine read, the winding job (when given) read and planned once
//! for its laminate and free fibre, then the program read and checked on
//! the virtual machine.

use std::path::Path;

use formcam_sim::{CheckMachine, CheckRun, check_file};

use crate::RunError;

/// Checks the program file `program` on `machine` (a machine file or a
/// shipped machine's name), with the mandrel of the winding job `mandrel`
/// (TOML or `.wind`) when given. The run's inputs are the program, the
/// machine file and the job, in that order.
pub fn check(program: &Path, machine: &Path, mandrel: Option<&Path>) -> Result<CheckRun, RunError> {
    let machine = CheckMachine::read(machine)?;
    let mandrel = match mandrel {
        Some(job) => Some((job, formcam_program::mandrel_check_of_file(job)?)),
        None => None,
    };
    let mut run = check_file(program, &machine, mandrel.as_ref().map(|(_, m)| m))?;
    run.inputs.extend(mandrel.map(|(job, _)| job.to_path_buf()));
    Ok(run)
}
