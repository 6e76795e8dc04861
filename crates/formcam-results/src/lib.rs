//! One description of each result file formcam writes: its name and, for a
//! CSV, its columns with their unit and meaning. `formcam-run` writes every
//! header from it, `formcam-view` reads every column through it, and `docs/`
//! lists it, so the three never disagree.
//!
//! A description is static data ([`Table`], [`Column`]); the fixed names of
//! the other files are in [`names`], and [`Kind::of`] tells a result
//! folder's kind by them. [`markdown`] writes a table's columns as
//! the Markdown table of the docs.
//!
//! ```
//! use formcam_results::{dressing, winding};
//!
//! assert_eq!(winding::PATH.file, "path.csv");
//! assert_eq!(winding::path::ALPHA_DEG.name, "alpha_deg");
//! assert_eq!(dressing::CONTOUR_PASSES.header(), "z,x,pass\n");
//! // A table with a column per axis takes the axes' names.
//! assert_eq!(
//!     winding::BLOCKS.header_with(&["A", "X"], false),
//!     "block,t,A,X,layer,t_star,mu\n"
//! );
//! ```

pub mod correction;
pub mod dressing;
mod kind;
mod markdown;
pub mod names;
mod table;
pub mod winding;

pub use kind::{Entry, Kind};
pub use markdown::{MarkedError, markdown, replace_marked};
pub use table::{Column, Occurs, Table};

/// Every table described, winding, dressing, correction.
pub const TABLES: &[Table] = &[
    winding::PATH,
    winding::EYE,
    winding::AXES,
    winding::PROGRAM_AXES,
    winding::BAND,
    winding::BLOCKS,
    dressing::PROFILE,
    dressing::CONTOUR_INITIAL,
    dressing::CONTOUR_FINAL,
    dressing::CONTOUR_PASSES,
    dressing::DRESSER,
    dressing::MRR,
    correction::NODE_STATUS,
    correction::PREDICTED,
    correction::ROUND_CMM,
];
