//! The dressing's progress hook: the simulation of forming reported every
//! few thousand steps, from 0 to its total, the same dressing as without a
//! hook, and `DressError::Cancelled` when the hook asks to stop.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_dress::{DressError, DressJob, DressSpec, dress, dress_with};
use formcam_progress::{Phase, Step};
use formcam_testkit::Recorder;

const EXAMPLE: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");

/// The example at a finer step: several thousand steps of forming.
fn spec() -> DressSpec {
    let mut j = DressJob::from_toml(EXAMPLE).unwrap();
    j.process.step = 0.0015;
    j.spec(None).unwrap()
}

/// A hook recording every report and cancelling at the first one `stop`
/// picks.
fn hook(stop: impl Fn(&Step) -> bool + Sync) -> Recorder<impl Fn(&Step) -> bool + Sync> {
    Recorder::new(stop)
}

#[test]
fn forming_is_reported_in_chunks_of_steps_up_to_its_total() {
    let spec = spec();
    let h = hook(|_| false);
    let d = dress_with(&spec, &h).unwrap();
    assert!(d == dress(&spec).unwrap(), "the hook changes nothing");
    let seen = h.steps();
    let total = d.forming.steps.len() as u64;
    assert!(total > 4096, "{total} steps: the example reports in chunks");
    assert!(
        seen.iter()
            .all(|s| s.phase == Phase::Forming && s.total == total)
    );
    let done: Vec<u64> = seen.iter().map(|s| s.done).collect();
    let mut want: Vec<u64> = (0..=total).step_by(4096).collect();
    want.push(total);
    assert_eq!(done, want);
}

#[test]
fn a_hook_that_cancels_stops_the_dressing() {
    let spec = spec();
    for at in [0, 4096] {
        let h = hook(move |s| s.done == at);
        let Err(e) = dress_with(&spec, &h) else {
            panic!("a cancelled dressing returns no dressing");
        };
        assert_eq!(e, DressError::Cancelled(formcam_progress::Cancelled));
        assert_eq!(e.to_string(), "cancelled");
        assert_eq!(h.steps().last().map(|s| s.done), Some(at));
    }
}
