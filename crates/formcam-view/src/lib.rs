//! `formcam view`: a local HTTP server for a winding result folder and the
//! browser page that shows it — the machine's solids placed by the poses
//! the server computes, the mandrel, the path and the program's timeline.
//!
//! The server listens on 127.0.0.1 only and answers GET requests: the page
//! (built from `viewer/` and embedded when formcam is compiled, [`Page`]),
//! the result folder's files under `/files/` (plain paths only, nothing
//! outside the folder) and the JSON the page draws under `/api/`
//! (`result`, `timeline?samples=N`, `sample?t=T`, `blocks`, `machine`,
//! `mandrel`, `program`). The page does no kinematics: every pose it draws
//! is one the server sent ([`Timeline`]).

mod error;
mod folder;
mod page;
pub mod request;
mod scene;
mod server;
mod timeline;

pub use error::ViewError;
pub use folder::{ProgramFile, RunFolder, load_machine};
pub use page::Page;
pub use scene::{
    LinkScene, MERIDIAN_POINTS, MachineScene, MandrelScene, PATH_POINTS, Solid, SolidShape, thin,
};
pub use server::{DEFAULT_SAMPLES, MAX_CONNECTIONS, MAX_SAMPLES, View, ViewOptions, ViewServer};
pub use timeline::{AxisHead, Sample, Timeline, TimelineHead, axis_specs, block_lines};
