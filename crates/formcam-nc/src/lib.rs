//! NC programs of formcam: the program model, post-processors and readers.
//!
//! A [`Program`] is a list of motion [`Block`]s on named NC axes
//! ([`AxisSpec`]): every block holds the absolute end value of every axis in
//! NC units (mm, degrees for rotary axes), its [`Motion`] (rapid or linear)
//! and its [`Feed`] (per minute, or inverse time as a block time).
//!
//! * [`write()`] writes a program in one of the built-in [`Dialect`]s: APT
//!   CLDATA, Sinumerik 840D, ISO/Fanuc, LinuxCNC and Marlin X/A/B
//!   (FiberPath-style winders).
//! * [`write_template`] writes it with a user [`Template`] read from TOML.
//! * Modulo rotary axes (a winder's spindle) are written within
//!   [`BOUND_DEG`] (100 turns): re-zeroed by `G92` or held modulo 360° with
//!   a direction, per dialect; [`keep_within_turns`] prepares a program.
//! * [`read_gcode`], [`read_gcode_in`] and [`read_cldata`] read programs back.
//! * [`read_toolpath`] reads a 3-axis milling program as lines and tool-path
//!   nodes (arcs linearised); [`Toolpath::write`] writes it back with moved
//!   nodes, every other line byte for byte.
//!
//! ```
//! use formcam_nc::{AxisSpec, Block, Dialect, Feed, Program, write};
//!
//! let mut p = Program::new("DEMO", vec![AxisSpec::linear("X"), AxisSpec::rotary("A")]);
//! p.blocks.push(Block::rapid(vec![0.0, 0.0]));
//! p.blocks.push(Block::linear(vec![100.0, 360.0], Feed::InverseTime(2.0)));
//! let mut out = String::new();
//! write(&p, Dialect::LinuxCnc, &mut out)?;
//! assert!(out.contains("G93 G1 X100 A360 F30"));
//! # Ok::<(), formcam_nc::NcError>(())
//! ```

mod dialect;
mod error;
mod lex;
mod modal;
mod modulo;
mod num;
mod post;
mod program;
mod read;
mod template;
mod toolpath;

pub use dialect::{Aliases, Dialect};
pub use error::{NcError, ProgramFault, Refusal, TemplateProblem, Truncation};
pub use modulo::{BOUND_DEG, ModuloStyle, keep_within_turns};
pub use post::write;
pub use program::{AxisSpec, Block, Dwell, Feed, Motion, Plane, Program};
pub use read::{read_cldata, read_cldata_lines, read_gcode, read_gcode_in, read_gcode_lines_in};
pub use template::{Template, write_template};
pub use toolpath::{Node, NodeKind, Toolpath, ToolpathOptions, read_toolpath};
