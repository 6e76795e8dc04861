//! The job file's `[mandrel]` and `[winding]` tables, as users write them, and
//! their translation into a mandrel and a [`LayerSpec`](crate::LayerSpec).
//!
//! Fields are optional in the types so that a missing one is reported by its
//! dotted name (`mandrel.radius`) with what it should be. The tables'
//! descriptions ([`MANDREL`], [`WINDING`], [`LAYER`], [`EYE`]) give every
//! field's type, unit, range, default and help; the job's reader validates
//! against them first, and `docs/winding.md` lists them.
//!
//! One module per concept: `spec` (the tables as users write them), `mandrel`
//! (the mandrel built), `build` (the mandrel and the eye built from their
//! tables), `layer_spec` (a winding table turned into a `LayerSpec`), `schema`
//! (the tables' descriptions).

mod build;
mod layer_spec;
mod mandrel;
mod schema;
mod spec;

pub use mandrel::Mandrel;
pub use schema::{
    EYE, EYE_FIELDS, LAYER, LAYER_FIELDS, MANDREL, MANDREL_FIELDS, WINDING, WINDING_FIELDS,
};
pub use spec::{
    DomeKind, EyeJob, LayerKind, MandrelKind, MandrelSpec, MuField, MuSegmentSpec, WindingSpec,
};
