//! One description of each job type formcam reads: its tables and fields,
//! their types, units, ranges, defaults and help. The TOML readers validate
//! a job against it, `docs/` lists it, and the browser's job editor is drawn
//! from it, so the three never disagree.
//!
//! A description is static data ([`JobSchema`], [`Table`], [`Field`]),
//! serialisable to JSON; [`validate`] checks a job's text against it before
//! the reader's serde structs see it, and [`markdown()`] writes a table's
//! fields as the Markdown table of the docs (the pieces of any docs table
//! in [`mod@markdown`]).

mod describe;
pub mod markdown;
mod validate;

pub use describe::{
    Bound, Condition, Default, EmptyList, Field, JobSchema, Kind, Range, Repeat, Table, Unit,
    Value, field, reader_keys,
};
pub use markdown::{MarkedError, markdown, replace_marked};
pub use validate::{SchemaError, validate};
