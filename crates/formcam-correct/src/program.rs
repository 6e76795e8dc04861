//! A milling program read for correction: a G-code tool path or a node
//! table, its nodes, which of them may move, and how to write it back.

use formcam_nc::{Dialect, NodeKind, Toolpath, ToolpathOptions, read_toolpath};

use crate::vec3::V3;
use crate::{CorrectError, NodeTable, ProgramError, Settings};

/// A milling program to correct.
#[derive(Debug, Clone)]
pub enum MillingProgram {
    /// A G-code program, with the options it was read with.
    Gcode {
        /// The tool path, every byte of the text kept.
        toolpath: Toolpath,
        /// How it was read (dialect, arc tolerance, move splitting).
        options: ToolpathOptions,
    },
    /// A CSV table of nodes `x, y, z`.
    Table(NodeTable),
}

impl MillingProgram {
    /// Reads a program by its file extension: `csv` is a node table, any
    /// other a G-code program in `settings.dialect` (default: the
    /// extension's), arcs and long moves handled as `settings` say.
    pub fn read(text: &str, extension: &str, settings: &Settings) -> Result<Self, CorrectError> {
        if extension.eq_ignore_ascii_case("csv") {
            return NodeTable::from_csv(text).map(Self::Table);
        }
        let dialect = settings
            .dialect
            .unwrap_or_else(|| Dialect::from_extension(extension).unwrap_or(Dialect::Iso));
        Self::gcode(
            text,
            ToolpathOptions {
                dialect,
                arc_tolerance_mm: settings.arc_tolerance_mm,
                max_segment_mm: settings.max_segment_mm,
            },
        )
    }

    /// Reads a G-code program; an empty one, or one without motion blocks,
    /// is an error.
    pub fn gcode(text: &str, options: ToolpathOptions) -> Result<Self, CorrectError> {
        if text.trim().is_empty() {
            return Err(ProgramError::Empty.into());
        }
        let toolpath = read_toolpath(text, &options)?;
        if toolpath.nodes.is_empty() {
            return Err(ProgramError::NoMotion.into());
        }
        Ok(Self::Gcode { toolpath, options })
    }

    /// Every node's position, mm.
    pub fn positions(&self) -> Vec<V3> {
        match self {
            Self::Gcode { toolpath, .. } => toolpath.nodes.iter().map(|n| n.position).collect(),
            Self::Table(t) => t.nodes.clone(),
        }
    }

    /// Whether each node may be corrected: feed moves may, rapid moves are
    /// left alone.
    pub fn movable(&self) -> Vec<bool> {
        match self {
            Self::Gcode { toolpath, .. } => toolpath
                .nodes
                .iter()
                .map(|n| n.kind != NodeKind::Rapid)
                .collect(),
            Self::Table(t) => vec![true; t.nodes.len()],
        }
    }

    /// The program line (1-based) of node `k`.
    pub fn line_of(&self, k: usize) -> usize {
        match self {
            Self::Gcode { toolpath, .. } => toolpath.nodes.get(k).map_or(0, |n| n.line),
            Self::Table(_) => k + 1,
        }
    }

    /// The program's syntax as reports name it: the dialect's name
    /// (`iso`, `sinumerik-840d`, `linuxcnc`, ...) or `csv`.
    pub fn syntax(&self) -> String {
        match self {
            Self::Gcode { toolpath, .. } => toolpath.dialect().name().to_string(),
            Self::Table(_) => "csv".into(),
        }
    }

    /// Arc blocks (G2/G3) read as G1 chords.
    pub fn arcs_linearised(&self) -> usize {
        match self {
            Self::Gcode { toolpath, .. } => toolpath.arcs_linearised,
            Self::Table(_) => 0,
        }
    }

    /// Straight feed moves split into pieces.
    pub fn moves_split(&self) -> usize {
        match self {
            Self::Gcode { toolpath, .. } => toolpath.moves_split,
            Self::Table(_) => 0,
        }
    }

    /// The comment lines a corrected G-code program starts with: what the
    /// reading changed (arcs linearised, moves split).
    fn header(&self) -> Vec<String> {
        let mut header = Vec::new();
        if let Self::Gcode { toolpath, options } = self {
            if toolpath.arcs_linearised > 0 {
                header.push(format!(
                    "formcam correct: {} arc blocks G2/G3 linearised as G1 chords within {} mm",
                    toolpath.arcs_linearised, options.arc_tolerance_mm
                ));
            }
            if let Some(m) = options.max_segment_mm
                && toolpath.moves_split > 0
            {
                header.push(format!(
                    "formcam correct: {} G1 moves split into pieces of at most {m} mm",
                    toolpath.moves_split
                ));
            }
        }
        header
    }

    /// The program with every node at `positions` (one per node), in the
    /// program's own format.
    pub fn write(&self, positions: &[V3]) -> Result<String, CorrectError> {
        match self {
            Self::Gcode { toolpath, .. } => Ok(toolpath.write(positions, &self.header())?),
            Self::Table(t) => Ok(t.write(positions)),
        }
    }
}
