//! The files users give formcam and the folders it writes.
//!
//! * `quote` — short, escaped excerpts of user text for error messages.
//! * `read` — reading an input: regular files only, with a size cap.
//! * `write` — a run's output folder written whole, never over an input.

mod quote;
mod read;
mod write;

pub use quote::{QUOTE_MAX_CHARS, Quote, excerpt, quote, syntax_message};
