//! A machine file checked into a [`Machine`]: errors name the link (or the
//! point, or `[machine]`) and the field.

use super::Machine;
use crate::MachineError;
use crate::file::MachineFile;
pub(crate) use formcam_files::line_col;

mod axis;
mod joint;
mod links;
mod numbers;
mod placement;
mod points;
mod roles;
mod tree;
mod visual;

use links::{Links, links};
use points::key_points;
use roles::{roles, spindle_modulo};
use tree::Tree;
pub(crate) use visual::visual;

impl Machine {
    /// Reads a machine from the text of a TOML machine file.
    pub fn from_toml(text: &str) -> Result<Self, MachineError> {
        let file: MachineFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            MachineError::Syntax {
                line,
                column,
                message: formcam_files::syntax_message(
                    e.message(),
                    text,
                    e.span().map_or(text.len(), |s| s.start),
                ),
            }
        })?;
        Self::from_file(&file)
    }

    /// Builds and checks a machine from its parsed file.
    pub fn from_file(f: &MachineFile) -> Result<Self, MachineError> {
        let tree = Tree::of(&f.links)?;
        let Links {
            links,
            mut axes,
            link_of_axis,
        } = links(&f.links, &tree)?;
        let points = key_points(&f.points, &links)?;
        let roles = roles(&f.machine, &links, &axes, &points)?;
        spindle_modulo(&mut axes, roles.spindle, &f.links, &link_of_axis);
        let collision = crate::collision::settings(f.collision.as_ref(), &links)?;
        Ok(Machine {
            name: f.machine.name.clone(),
            links,
            axes,
            points,
            roles,
            collision,
        })
    }
}
