//! The bundled examples (`examples/` of the source tree) the studio starts
//! a job from: every job of the four kinds, compiled in with the files each
//! names (meridian and eye-curve tables, the CMM report and the program of
//! the correction), so that the studio works from any folder.
//! [`start_example`] writes one into the studio's folder keeping the inputs'
//! relative paths; a job naming a machine file of `machines/`
//! (`../machines/winder-4axis.toml`) is written naming the same shipped
//! machine (`name = "winder-4axis"`), as the studio writes only in its
//! folder.

use std::fs;
use std::path::{Path, PathBuf};

use toml_edit::{DocumentMut, Item, value};

use crate::{JobKind, StudioError};

/// A bundled example job and the files it names.
#[derive(Debug, Clone, Copy)]
pub struct Example {
    /// Its name, the job file's stem (`vessel-program-840d`).
    pub name: &'static str,
    /// Its kind.
    pub kind: JobKind,
    /// The job's text as bundled.
    pub text: &'static str,
    /// The files it names, by their paths relative to the job
    /// (`correct/cmm.csv`), with their text.
    pub inputs: &'static [(&'static str, &'static str)],
}

/// Where a shipped machine's file lies relative to the examples.
const MACHINES: &str = "../machines/";

impl Example {
    /// The job's file name in the studio's folder (`NAME.toml`).
    pub fn file_name(&self) -> String {
        format!("{}.toml", self.name)
    }

    /// The job's text as it is written into the studio's folder: a machine
    /// file of `machines/` named as the shipped machine it is.
    pub fn job_text(&self) -> String {
        let Ok(mut doc) = self.text.parse::<DocumentMut>() else {
            return self.text.to_string();
        };
        let shipped = doc
            .get("machine")
            .and_then(|m| m.get("file"))
            .and_then(Item::as_str)
            .and_then(|f| f.strip_prefix(MACHINES))
            .and_then(|f| f.strip_suffix(".toml"))
            .map(str::to_string);
        let Some(name) = shipped else {
            return self.text.to_string();
        };
        if let Some(m) = doc.get_mut("machine").and_then(Item::as_table_like_mut) {
            m.remove("file");
            m.insert("name", value(name));
        }
        doc.to_string()
    }

    /// The files written for this example: each input, then the job.
    fn files(&self) -> Vec<(String, Vec<u8>)> {
        self.inputs
            .iter()
            .map(|(p, t)| (p.to_string(), t.as_bytes().to_vec()))
            .chain(std::iter::once((
                self.file_name(),
                self.job_text().into_bytes(),
            )))
            .collect()
    }
}

macro_rules! example {
    ($name:literal, $kind:ident) => {
        example!($name, $kind, [])
    };
    ($name:literal, $kind:ident, [$($input:literal),*]) => {
        Example {
            name: $name,
            kind: JobKind::$kind,
            text: include_str!(concat!("../../../examples/", $name, ".toml")),
            inputs: &[$(($input, include_str!(concat!("../../../examples/", $input)))),*],
        }
    };
}

/// Every bundled example job, sorted by name.
static EXAMPLES: [Example; 23] = [
    example!("cone-tube", Winding),
    example!(
        "correct-mould",
        Correction,
        ["correct/cmm.csv", "correct/mould.nc"]
    ),
    example!("correct-panel-loop", Scenario),
    example!("dress-ballscrew-nut", Dressing),
    example!("profile-flare-minimax", Winding, ["flare-meridian.csv"]),
    example!("profile-waist", Winding, ["waist-meridian.csv"]),
    example!("tube-axes-2axis", Winding),
    example!("tube-eye-axis-parallel", Winding),
    example!("tube-friction", Winding),
    example!("tube-helical", Winding),
    example!("tube-layers-4axis", Winding),
    example!("tube-placement-arm", Winding),
    example!("vessel-auto", Winding),
    example!("vessel-axes-4axis", Winding),
    example!("vessel-axes-6axis", Winding),
    example!("vessel-eye-curve", Winding, ["eye-curve.csv"]),
    example!("vessel-eye-pull-speed", Winding),
    example!("vessel-geodesic", Winding),
    example!("vessel-isotensoid", Winding),
    example!("vessel-layers-840d", Winding),
    example!("vessel-mu-segments", Winding),
    example!("vessel-program-840d", Winding),
    example!("vessel-torispherical", Winding),
];

/// Every bundled example job, sorted by name.
pub fn examples() -> &'static [Example] {
    &EXAMPLES
}

/// The bundled example named `name`.
pub fn example(name: &str) -> Option<&'static Example> {
    EXAMPLES.iter().find(|e| e.name == name)
}

/// Writes the example `name` into `dir`: its input files at their relative
/// paths (folders such as `correct/` created), then the job; returns the
/// job's file name. A file already there with the same bytes is left; one
/// with other bytes is never replaced: nothing is written and the error
/// names it.
pub fn start_example(dir: &Path, name: &str) -> Result<String, StudioError> {
    let ex = example(name).ok_or_else(|| StudioError::UnknownExample {
        name: name.to_string(),
        known: EXAMPLES
            .iter()
            .map(|e| e.name)
            .collect::<Vec<_>>()
            .join(", "),
    })?;
    let mut missing: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for (rel, bytes) in ex.files() {
        let path = dir.join(&rel);
        match fs::symlink_metadata(&path) {
            Err(_) => missing.push((path, bytes)),
            Ok(m) if m.is_file() && fs::read(&path).is_ok_and(|b| b == bytes) => {}
            Ok(_) => {
                return Err(StudioError::ExampleClash {
                    path,
                    example: ex.name,
                });
            }
        }
    }
    formcam_files::write_files(&missing, &[])?;
    Ok(ex.file_name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_files_of_the_tree_become_shipped_names() {
        let ex = example("vessel-program-840d").expect("bundled");
        assert!(ex.text.contains("file = \"../machines/winder-4axis.toml\""));
        let text = ex.job_text();
        assert!(!text.contains("../machines"), "{text}");
        let v = crate::values_of(&text).expect("toml");
        assert_eq!(v["machine"]["name"], serde_json::json!("winder-4axis"));
        // The rest as bundled, comments included.
        assert!(text.starts_with("# The whole winding program"));
        let plain = example("vessel-geodesic").expect("bundled");
        assert_eq!(plain.job_text(), plain.text);
    }

    #[test]
    fn examples_are_sorted_and_their_kinds_told_by_their_tables() {
        let names: Vec<&str> = examples().iter().map(|e| e.name).collect();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        assert_eq!(names, sorted);
        for e in examples() {
            assert_eq!(JobKind::of_text(e.text), Some(e.kind), "{}", e.name);
        }
        assert!(matches!(
            start_example(Path::new("."), "no-such"),
            Err(StudioError::UnknownExample { .. })
        ));
    }
}
