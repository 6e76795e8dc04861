//! `formcam view`: a local HTTP server for a winding result folder and the
//! browser page that shows it — the machine's solids placed by the poses
//! the server computes, the mandrel, the path and the program's timeline.
//!
//! The server listens on 127.0.0.1 only and answers GET requests: the page
//! (built from `viewer/` and embedded when formcam is compiled, [`Page`]),
//! the result folder's files under `/files/` (plain paths only, nothing
//! outside the folder) and the JSON the page draws under `/api/`
//! (`result`, `timeline?samples=N`, `sample?t=T`, `blocks`, `machine`,
//! `mandrel`, `mesh/N`, `program`, `violations`, `eye`, `band`, `overlays`; `path`
//! for a winding result without a program). The page does no
//! kinematics: every pose it draws is one the server sent ([`Timeline`],
//! the simulator's timeline of formcam-sim), and every violation one the
//! checks found ([`Violations`]).

mod band;
mod correction;
mod dressing;
mod error;
mod folder;
mod mesh;
mod overlay;
mod page;
mod pathview;
mod plots;
mod report;
pub mod request;
mod scene;
mod server;
mod table;
mod timeline;
mod typescript;
mod violations;

pub use band::{BAND_POINTS, Band};
pub use correction::{
    CorrectionBody, DeviationMap, NODE_MARKS, NodeCounts, NodeMarks, RoundMap, SectionStats,
    SurfaceMesh, plain_path, signed_deviation,
};
pub use dressing::{
    DRESSING_PROGRAM, DresserPass, DresserSample, DressingBody, DressingView, MrrPlot,
};
pub use error::ViewError;
pub use folder::{ProgramFile, ResultKind, RunFolder, load_machine};
pub use mesh::{DrawnMesh, MESH_TRIANGLES};
pub use overlay::{EYE_POINTS, EyeTrajectory, Overlay, Shown};
pub use page::Page;
pub use pathview::{PathBand, PathBody, PathView};
pub use plots::{AxisPlots, MeridianPlot, PullPlot, WindingPlots};
pub use report::{
    KNOT_TOLERANCE_MM, KNOT_TOLERANCE_RAD, MAX_KNOT_VALUES, Report, TIMELINE_HEAD, report,
};
pub use scene::{
    LinkScene, MERIDIAN_POINTS, MachineScene, MandrelScene, PATH_POINTS, Solid, SolidShape, thin,
};
pub use server::{
    DEFAULT_SAMPLES, Local, MAX_CONNECTIONS, MAX_SAMPLES, View, ViewOptions, ViewServer,
    content_type, has_body, head_refusal, refused, reply, serve_router,
};
pub use table::Table;
pub use timeline::{AxisHead, Sample, Timeline, TimelineHead};
pub use typescript::{TS_INDEX, TsFile, typescript};
pub use violations::{AxisRange, Violations};
