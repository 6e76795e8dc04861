//! The correction of a program from a CMM report: the deviations checked,
//! the grid built and smoothed, the nodes corrected, the report drawn up.

use crate::{
    Applied, CorrectError, Corrector, Grid, Measurements, MillingProgram, Report, Settings, smooth,
};

/// A program corrected from measurements.
#[derive(Debug, Clone)]
pub struct Correction {
    /// The corrected program and its nodes.
    pub applied: Applied,
    /// The grid the correction interpolated (smoothed when a noise level
    /// was given).
    pub grid: Grid,
    /// What was done.
    pub report: Report,
}

/// Corrects `program` from `measurements` with `settings`: every
/// deviation checked against `settings.max_deviation_mm`, the sections
/// harmonised into a grid, smoothed for `settings.noise_mm`, the movable
/// nodes corrected (each displacement checked against the same limit).
pub fn correct_program(
    measurements: &Measurements,
    program: &MillingProgram,
    settings: &Settings,
) -> Result<Correction, CorrectError> {
    settings.check()?;
    measurements.check_deviation(settings.max_deviation_mm)?;
    let mut grid = Grid::from_measurements(measurements, settings.points_per_section)?;
    let smoothing = smooth(&mut grid, settings.noise_mm);
    let applied =
        Corrector::new(&grid, settings.options)?.apply(program, Some(settings.max_deviation_mm))?;
    let smoothing = (settings.noise_mm > 0.0).then_some(smoothing);
    let report = Report::new(measurements, &grid, smoothing, program, &applied, settings);
    Ok(Correction {
        applied,
        grid,
        report,
    })
}
