//! Helpers shared by formcam's tests, so that each is written once: a
//! plain HTTP/1.1 client for the local servers (`formcam view`, `formcam
//! studio`), a progress hook that records what a pipeline reports and
//! cancels where asked, and the repository's own files (examples,
//! machines). A dev-dependency only; it depends on no formcam crate above
//! the foundations, so any crate's tests may use it.
//!
//! ```
//! use formcam_testkit::{Recorder, repo_root};
//! use formcam_progress::{Phase, Progress, Step};
//!
//! let rec = Recorder::new(|s: &Step| s.done == 2);
//! rec.report(Step::new(Phase::Files, 1, 3));
//! assert!(!rec.cancelled());
//! rec.report(Step::new(Phase::Files, 2, 3));
//! assert!(rec.cancelled());
//! assert_eq!(rec.steps().len(), 2);
//! assert!(repo_root().join("examples").is_dir());
//! ```

mod http;
mod progress;
mod repo;

pub use http::{Answer, get, post_json, send};
pub use progress::Recorder;
pub use repo::{example_path, machine_path, machine_text, repo_root};
