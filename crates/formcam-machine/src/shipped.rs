//! The machines shipped with formcam (`machines/*.toml`), compiled in so that
//! a job can name one (`[machine] name = "winder-4axis"`) wherever it runs,
//! and the mesh files they name (`machines/meshes/`), compiled in with them.

use crate::{Machine, MachineError};

/// A shipped machine file: its name (the file's stem) and its text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shipped {
    /// The name a job gives (`winder-4axis`).
    pub name: &'static str,
    /// The machine file's text (TOML).
    pub text: &'static str,
}

impl Shipped {
    /// The machine, read from its text.
    pub fn machine(&self) -> Result<Machine, MachineError> {
        Machine::from_toml(self.text)
    }
}

/// Every shipped machine, by name in alphabetical order.
pub const SHIPPED: [Shipped; 5] = [
    Shipped {
        name: "placement-arm",
        text: include_str!("../../../machines/placement-arm.toml"),
    },
    Shipped {
        name: "winder-2axis",
        text: include_str!("../../../machines/winder-2axis.toml"),
    },
    Shipped {
        name: "winder-4axis",
        text: include_str!("../../../machines/winder-4axis.toml"),
    },
    Shipped {
        name: "winder-6axis",
        text: include_str!("../../../machines/winder-6axis.toml"),
    },
    Shipped {
        name: "winder-xab",
        text: include_str!("../../../machines/winder-xab.toml"),
    },
];

/// The shipped machine named `name`, if there is one.
pub fn shipped(name: &str) -> Option<Shipped> {
    SHIPPED.iter().find(|s| s.name == name).copied()
}

/// The names of the shipped machines.
pub fn names() -> impl Iterator<Item = &'static str> {
    SHIPPED.iter().map(|s| s.name)
}

/// A mesh file a shipped machine names: the name as the machine file
/// writes it (relative to `machines/`) and the file's bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShippedMesh {
    /// The name a shipped machine's `[[link.visual]] file` gives.
    pub file: &'static str,
    /// The file's bytes (STL or OBJ by the name's extension).
    pub bytes: &'static [u8],
}

/// Every mesh file of the shipped machines.
pub const SHIPPED_MESHES: [ShippedMesh; 1] = [ShippedMesh {
    // The 4-axis winder's chuck flange (scripts/chuck_flange_stl.py).
    file: "meshes/chuck-flange.stl",
    bytes: include_bytes!("../../../machines/meshes/chuck-flange.stl"),
}];

/// The shipped mesh file named `file` (as a shipped machine names it).
pub fn shipped_mesh(file: &str) -> Option<ShippedMesh> {
    SHIPPED_MESHES.iter().find(|m| m.file == file).copied()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn every_shipped_machine_reads_and_is_found_by_name() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../machines");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
            .collect();
        on_disk.sort();
        assert_eq!(names().collect::<Vec<_>>(), on_disk);
        for s in SHIPPED {
            let text = std::fs::read_to_string(format!("{dir}/{}.toml", s.name)).unwrap();
            assert_eq!(s.text, text, "{}", s.name);
            assert!(!s.machine().unwrap().axes.is_empty(), "{}", s.name);
            assert_eq!(shipped(s.name), Some(s));
        }
        assert_eq!(shipped("winder-5axis"), None);
    }

    #[test]
    fn every_mesh_a_shipped_machine_names_is_shipped_as_on_disk() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../machines");
        let mut named = Vec::new();
        for s in SHIPPED {
            for link in s.machine().unwrap().links {
                for v in link.visuals {
                    if let crate::Shape::Mesh(file) = v.shape {
                        named.push(file);
                    }
                }
            }
        }
        assert!(!named.is_empty(), "no shipped machine carries a mesh");
        for file in &named {
            let m = shipped_mesh(file).unwrap_or_else(|| panic!("{file} is not shipped"));
            assert_eq!(
                m.bytes,
                std::fs::read(format!("{dir}/{file}")).unwrap(),
                "{file}"
            );
        }
        for m in SHIPPED_MESHES {
            assert!(named.iter().any(|f| f == m.file), "{} unused", m.file);
        }
        assert_eq!(shipped_mesh("meshes/none.stl"), None);
    }
}
