//! The fixed names of a result folder's files that are not CSV tables, and
//! the patterns of the numbered ones.

/// A run's summary (winding, dressing): `summary.json`.
pub const SUMMARY: &str = "summary.json";
/// The check of a written program on its machine: `check.json`.
pub const CHECK: &str = "check.json";
/// A correction's or a closed loop's report: `report.json`.
pub const REPORT: &str = "report.json";
/// The job as it ran, a TOML job's text (winding, dressing, correction,
/// closed loop): `job.toml`. The job file may change or move after the
/// run; this copy stays with its result (the view plans a winding
/// result's job again from it, the files the job names found from the
/// job's folder the summary records).
pub const JOB: &str = "job.toml";
/// The job as it ran, a Cyclone/FiberPath document's text: `job.wind`
/// (as [`JOB`] for a TOML job).
pub const JOB_WIND: &str = "job.wind";
/// A winding pass's plot: `path.svg`.
pub const PATH_SVG: &str = "path.svg";
/// The eye's plot over a circuit: `eye.svg`.
pub const EYE_SVG: &str = "eye.svg";
/// A dressing's profile plot: `profile.svg`.
pub const PROFILE_SVG: &str = "profile.svg";
/// A dressing's removal rate plot: `mrr.svg`.
pub const MRR_SVG: &str = "mrr.svg";
/// A closed loop's deviations before the first round: `deviations-before.svg`.
pub const DEVIATIONS_BEFORE_SVG: &str = "deviations-before.svg";
/// A closed loop's deviations after the last round: `deviations-after.svg`.
pub const DEVIATIONS_AFTER_SVG: &str = "deviations-after.svg";
/// A closed loop's deviation per round: `convergence.svg`.
pub const CONVERGENCE_SVG: &str = "convergence.svg";
/// The stem of a program's file: `program.<ext>`.
pub const PROGRAM_STEM: &str = "program";
/// A dressing's program, the one its view plays: `program.mpf` (Siemens
/// 840D); [`program`] of `mpf`.
pub const DRESSING_PROGRAM: &str = "program.mpf";
/// The stem of a corrected program's file: `corrected.<ext>`.
pub const CORRECTED_STEM: &str = "corrected";
/// The prefix of a layer's folder: `layer-NN/`.
pub const LAYER_PREFIX: &str = "layer-";

/// A program's file with the dialect's extension: `program.mpf`.
pub fn program(ext: &str) -> String {
    format!("{PROGRAM_STEM}.{ext}")
}

/// Whether `name` is a program's file as [`program`] names it.
pub fn is_program(name: &str) -> bool {
    name.strip_prefix(PROGRAM_STEM)
        .is_some_and(|rest| rest.starts_with('.'))
}

/// A corrected program's file with the program's extension: `corrected.nc`.
pub fn corrected(ext: &str) -> String {
    format!("{CORRECTED_STEM}.{ext}")
}

/// Whether `name` starts as [`corrected`] names a file: `corrected.` (the
/// program, and its plots' `corrected.<plot>.svg`).
pub fn is_corrected(name: &str) -> bool {
    name.strip_prefix(CORRECTED_STEM)
        .is_some_and(|rest| rest.starts_with('.'))
}

/// The folder of winding layer `n` (1-based): `layer-01`.
pub fn layer_dir(n: usize) -> String {
    format!("{LAYER_PREFIX}{n:02}")
}

/// The layer number of a folder named as [`layer_dir`] names it.
pub fn layer_of(dir: &str) -> Option<usize> {
    dir.strip_prefix(LAYER_PREFIX)?.parse().ok()
}

/// A file `name` in layer `n`'s folder: `layer-01/path.csv`.
pub fn in_layer(n: usize, name: &str) -> String {
    format!("{}/{name}", layer_dir(n))
}

/// A closed loop's CMM report of round `k` (0: before any correction).
pub fn round_cmm(k: usize) -> String {
    format!("cmm-{k}.csv")
}

/// A closed loop's program of round `k`.
pub fn round_program(k: usize) -> String {
    format!("program-{k}.nc")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbered_names_read_back() {
        assert_eq!(program("mpf"), "program.mpf");
        assert!(is_program("program.ngc") && !is_program("programs.csv"));
        assert_eq!(DRESSING_PROGRAM, program("mpf"));
        assert_eq!(corrected("nc"), "corrected.nc");
        assert!(is_corrected("corrected.nc") && !is_corrected("corrections.nc"));
        assert_eq!(layer_dir(3), "layer-03");
        assert_eq!(layer_of(&layer_dir(12)), Some(12));
        assert_eq!(layer_of("layers"), None);
        assert_eq!(in_layer(1, PATH_SVG), "layer-01/path.svg");
        assert_eq!(round_cmm(2), "cmm-2.csv");
        assert_eq!(round_program(0), "program-0.nc");
    }
}
