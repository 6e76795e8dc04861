//! Progress reports and cancellation for the long pipelines: a pipeline
//! tells a hook how far it has come and asks it whether to stop.
//!
//! * [`Progress`] — the hook every long pipeline takes: [`Progress::report`]
//!   receives a [`Step`] (the [`Phase`], how many of its items are done, of
//!   how many), [`Progress::cancelled`] says whether to stop, and
//!   [`Progress::checkpoint`] does both, returning [`Cancelled`] when the run
//!   is to stop. Pipelines report at phase boundaries and every few thousand
//!   items, never per point; a report allocates nothing.
//! * [`Silent`] — reports nothing, never cancels (the old entry points);
//!   [`Muted`] — forwards only the cancel flag (the inner phases of a
//!   pipeline that reports its own outer steps).
//! * [`Hook`] — a ready-made hook over a shared [`AtomicBool`] cancel flag
//!   and a callback (a progress bar, a server's event stream).
//! * [`Tally`] — one phase's count shared by workers in parallel (a
//!   program's layers): each finished item reported in order.
//!
//! ```
//! use formcam_progress::{Cancelled, Hook, Phase, Progress, Step};
//!
//! let hook = Hook::new(|s: Step| eprintln!("{} {}/{}", s.phase, s.done, s.total));
//! assert_eq!(hook.checkpoint(Step::new(Phase::Nodes, 0, 10)), Ok(()));
//! hook.cancel();
//! assert_eq!(hook.checkpoint(Step::new(Phase::Nodes, 5, 10)), Err(Cancelled));
//! ```
//!
//! [`AtomicBool`]: std::sync::atomic::AtomicBool

mod hook;
mod phase;
mod progress;
mod tally;

pub use hook::Hook;
pub use phase::{Phase, Step};
pub use progress::{Cancelled, Muted, Progress, Silent};
pub use tally::Tally;
