//! The files users give formcam and the folders it writes.
//!
//! * `quote` — short, escaped excerpts of user text for error messages.
//! * `position` — the line and column of a place in a user's text.
//! * `read` — reading an input: regular files only, with a size cap.
//! * `memory` — the process-wide memory budget of a run.
//! * `write` — a run's output folder written whole, never over an input.

mod memory;
mod position;
mod quote;
mod read;
mod write;

pub use memory::{DEFAULT_MAX_MEMORY_BYTES, max_memory_bytes, set_max_memory_bytes};
pub use position::line_col;
pub use quote::{QUOTE_MAX_CHARS, Quote, excerpt, nearest, quote, syntax_message};
pub use read::{
    DEFAULT_MAX_INPUT_BYTES, FileKind, ReadError, max_input_bytes, read_bytes, read_bytes_capped,
    read_text, read_text_capped, set_max_input_bytes,
};
pub use write::{
    Hook, MARKER, Point, WriteError, Writer, resolve, same_file, write_files, write_folder,
};
