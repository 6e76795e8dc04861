//! The formats of a machine file and the one reader that chooses between
//! them by the file's extension.

use std::path::Path;

use crate::MachineError;
use crate::machine::Machine;

/// The format of a machine file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MachineFormat {
    /// A TOML machine file (`[machine]`, `[[link]]`, `[[point]]`).
    Toml,
    /// A URDF document whose `<formcam>` element holds the `[machine]` table
    /// and the key points (see [`Machine::from_urdf_document`]).
    Urdf,
}

impl MachineFormat {
    /// The format of the file at `path`: URDF for the extensions `.urdf` and
    /// `.xml` (in any case), TOML for every other.
    pub fn of(path: &Path) -> Self {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("urdf") || e.eq_ignore_ascii_case("xml") => {
                Self::Urdf
            }
            _ => Self::Toml,
        }
    }
}

impl Machine {
    /// Reads a machine from the text of a machine file in `format`.
    ///
    /// # Errors
    ///
    /// Those of [`Machine::from_toml`] or [`Machine::from_urdf_document`].
    pub fn parse(text: &str, format: MachineFormat) -> Result<Self, MachineError> {
        match format {
            MachineFormat::Toml => Self::from_toml(text),
            MachineFormat::Urdf => Self::from_urdf_document(text),
        }
    }

    /// Reads a machine from `text`, the content of the file `path`, in the
    /// format its extension names ([`MachineFormat::of`]): the reader of
    /// every machine file a user gives (`formcam machine show|fk`, a winding
    /// job's `[machine] file`).
    ///
    /// # Errors
    ///
    /// Those of [`Machine::parse`].
    pub fn from_file_text(path: &Path, text: &str) -> Result<Self, MachineError> {
        Self::parse(text, MachineFormat::of(path))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_chooses_the_format() {
        for (p, f) in [
            ("robot.urdf", MachineFormat::Urdf),
            ("dir/robot.URDF", MachineFormat::Urdf),
            ("robot.xml", MachineFormat::Urdf),
            ("winder.toml", MachineFormat::Toml),
            ("winder", MachineFormat::Toml),
            ("urdf", MachineFormat::Toml),
            ("robot.urdf.toml", MachineFormat::Toml),
        ] {
            assert_eq!(MachineFormat::of(Path::new(p)), f, "{p}");
        }
    }
}
