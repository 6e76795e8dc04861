//! The post: a wound program written as NC text by its dialect or template.

use std::io::Write;

use formcam_nc::{ModuloStyle, Program, keep_within_turns, write, write_template};

use crate::ProgramError;
use crate::job::Post;
use crate::plan::WoundProgram;

/// Writes the program of `wound` with its post-processor to `out`. Modulo
/// axes stay within 100 turns in the text: re-zeroed, or (840D, LinuxCNC)
/// written modulo with directions.
pub fn write_program(wound: &WoundProgram, out: &mut impl Write) -> Result<(), ProgramError> {
    let Some(assembled) = &wound.program else {
        return Ok(());
    };
    let text = post_text(&assembled.program, &wound.post)?;
    out.write_all(text.as_bytes())?;
    Ok(())
}

/// The text of `program` written by `post`.
fn post_text(program: &Program, post: &Post) -> Result<String, ProgramError> {
    let mut text = String::with_capacity(program.blocks.len() * 64);
    match post {
        Post::Template { file, template } => {
            let within = match template.modulo_style() {
                Some(style) => keep_within_turns(program, style)?,
                None => program.clone(),
            };
            write_template(&within, template, &mut text).map_err(|source| {
                ProgramError::Template {
                    file: file.clone(),
                    source,
                }
            })?;
        }
        Post::Dialect(dialect) => {
            let within = keep_within_turns(program, ModuloStyle::of(*dialect))?;
            write(&within, *dialect, &mut text)?;
        }
    }
    Ok(text)
}
