//! Filament-winding process of formcam: the winding path on a mandrel (a
//! surface of revolution), its slippage, the pattern of circuits that covers
//! the mandrel, and the layer report.
//!
//! * [`trace`] integrates a pass in path length through its turn-arounds;
//! * [`shoot`] finds the constant slippage for `mu = "auto"`;
//! * [`minimax`] solves the concave-meridian problem (eqs. 5–6, docs/winding.md), flaring ends included;
//! * [`friction_turns`] turns a tube's pass on the tube, held by friction;
//! * [`plan_layer`] turns a [`LayerSpec`] into a [`Layer`]: pass, pattern, report;
//! * [`eye`] builds the payout eye's trajectory over a circuit;
//! * [`job`] reads the job file's `[mandrel]`, `[winding]` and `[eye]` tables.
//!
//! Modules are private and their items re-exported here, except the two
//! namespaces `eye` and `job`.

mod circuit;
mod error;
pub mod eye;
mod friction;
pub mod job;
mod layer;
mod minimax;
mod ode;
mod path;
mod pattern;
mod shooting;
mod slippage;

pub use circuit::{Circuit, CircuitPoint, PassPath, Turnaround};
pub use error::{ShootingFault, WindingError};
pub use friction::{FrictionTurns, friction_turns};
pub use layer::{
    Ends, Layer, LayerReport, LayerSpec, Method, PassSummary, Slippage, TubeTurn, plan_layer,
};
pub use minimax::{MinimaxPath, b_factor, bridging_limit, clairaut_points, minimax};
pub use ode::{Tolerance, find_root};
pub use path::{PassEnd, PathPoint, Trace, TraceOptions, trace};
pub use pattern::{Pattern, PatternRequest, choose_pattern};
pub use shooting::{Shot, shoot};
pub use slippage::{MuLaw, MuSegment};
