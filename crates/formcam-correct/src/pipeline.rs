//! The correction of a program from a CMM report: the deviations checked,
//! the grid built and smoothed, the nodes corrected, the report drawn up.

use formcam_progress::{Phase, Progress, Silent, Step};

use crate::{
    Applied, CorrectError, Corrector, Grid, Measurements, MillingProgram, Report, Settings,
    predict_next, smooth,
};

/// A program corrected from measurements.
#[derive(Debug, Clone)]
pub struct Correction {
    /// The corrected program and its nodes.
    pub applied: Applied,
    /// The grid the correction interpolated (smoothed when a noise level
    /// was given).
    pub grid: Grid,
    /// What the CMM is predicted to read of the next part, made on the
    /// corrected mould ([`predict_next`]).
    pub predicted: Measurements,
    /// What was done.
    pub report: Report,
}

/// Corrects `program` from `measurements` with `settings`: every
/// deviation checked against `settings.max_deviation_mm`, the sections
/// harmonised into a grid, smoothed for `settings.noise_mm`, the movable
/// nodes corrected (each displacement checked against the same limit), the
/// next part predicted.
pub fn correct_program(
    measurements: &Measurements,
    program: &MillingProgram,
    settings: &Settings,
) -> Result<Correction, CorrectError> {
    correct_program_with(measurements, program, settings, &Silent)
}

/// [`correct_program`] reporting to `progress` (the grid, then the nodes
/// chunk by chunk); [`CorrectError::Cancelled`] when it asks to stop.
pub fn correct_program_with(
    measurements: &Measurements,
    program: &MillingProgram,
    settings: &Settings,
    progress: &dyn Progress,
) -> Result<Correction, CorrectError> {
    settings.check()?;
    measurements.check_deviation(settings.max_deviation_mm)?;
    progress.checkpoint(Step::new(Phase::Grid, 0, 1))?;
    let mut grid = Grid::from_measurements(measurements, settings.points_per_section)?;
    let smoothing = smooth(&mut grid, settings.noise_mm);
    progress.checkpoint(Step::new(Phase::Grid, 1, 1))?;
    let corrector = Corrector::new(&grid, settings.options)?;
    let applied = corrector.apply_with(program, Some(settings.max_deviation_mm), progress)?;
    let predicted = predict_next(measurements, &corrector);
    let smoothing = (settings.noise_mm > 0.0).then_some(smoothing);
    let mut report = Report::new(measurements, &grid, smoothing, program, &applied, settings);
    report.predict(&predicted);
    Ok(Correction {
        applied,
        grid,
        predicted,
        report,
    })
}
