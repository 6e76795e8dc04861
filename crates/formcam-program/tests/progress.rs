//! The winding pipeline's progress hook: every phase reported in order,
//! from 0 to its total, and a hook that asks to stop stops the run with
//! `ProgramError::Cancelled`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;
use std::sync::Mutex;

use formcam_program::{ProgramError, Stage, WindJob, plan_program, plan_until_with};
use formcam_progress::{Hook, Phase, Progress, Step};

/// A helical tube on the shipped 2-axis lathe winder (fast).
const TUBE: &str = include_str!("jobs/tube.toml");

fn job(text: &str) -> WindJob {
    WindJob::from_toml(text, &PathBuf::from(env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// Two helical layers and a skip between them.
fn two_layers() -> String {
    let layer = TUBE
        .split("[winding]")
        .nth(1)
        .unwrap()
        .split("[eye]")
        .next()
        .unwrap();
    let head = TUBE.split("[winding]").next().unwrap();
    let tail = TUBE.split("[eye]").nth(1).unwrap();
    format!(
        "{head}[[layer]]{layer}[[layer]]\nkind = \"skip\"\nmandrel_rotation_deg = 30.0\n\n\
         [[layer]]{layer}[eye]{tail}"
    )
}

/// Records every report.
fn recorded(job: &WindJob, stage: Stage) -> Vec<Step> {
    let seen = Mutex::new(Vec::new());
    let hook = Hook::new(|s| seen.lock().unwrap().push(s));
    plan_until_with(job, stage, &hook).unwrap();
    seen.into_inner().unwrap()
}

/// The phases in the order they first appear; each phase's counts never
/// fall, never pass the total, start at 0 and end at the total.
fn phases(steps: &[Step]) -> Vec<Phase> {
    let mut order: Vec<Phase> = Vec::new();
    for s in steps {
        if !order.contains(&s.phase) {
            order.push(s.phase);
        }
    }
    for p in &order {
        let of: Vec<&Step> = steps.iter().filter(|s| s.phase == *p).collect();
        assert_eq!(of[0].done, 0, "{p} starts at 0: {of:?}");
        assert!(of.windows(2).all(|w| w[0].done <= w[1].done), "{p}: {of:?}");
        assert!(
            of.iter()
                .all(|s| s.done <= s.total && s.total == of[0].total)
        );
        let last = of[of.len() - 1];
        assert_eq!(last.done, last.total, "{p} ends at its total: {of:?}");
    }
    order
}

#[test]
fn a_program_reports_its_phases_in_order() {
    let j = job(TUBE);
    let steps = recorded(&j, Stage::Program);
    assert_eq!(
        phases(&steps),
        [
            Phase::Path,
            Phase::Eye,
            Phase::Axes,
            Phase::Blocks,
            Phase::Assembly
        ]
    );
    // A layer's phases run one after the other.
    let firsts: Vec<usize> = [Phase::Eye, Phase::Axes, Phase::Blocks, Phase::Assembly]
        .iter()
        .map(|p| steps.iter().position(|s| s.phase == *p).unwrap())
        .collect();
    assert!(firsts.windows(2).all(|w| w[0] < w[1]));
    let ends: Vec<usize> = [Phase::Path, Phase::Eye, Phase::Axes, Phase::Blocks]
        .iter()
        .map(|p| steps.iter().rposition(|s| s.phase == *p).unwrap())
        .collect();
    assert!(ends.iter().zip(&firsts).all(|(e, f)| e < f));
}

#[test]
fn stages_report_only_the_phases_they_reach() {
    let j = job(TUBE);
    assert_eq!(phases(&recorded(&j, Stage::Path)), [Phase::Path]);
    assert_eq!(phases(&recorded(&j, Stage::Eye)), [Phase::Path, Phase::Eye]);
    assert_eq!(
        phases(&recorded(&j, Stage::Axes)),
        [Phase::Path, Phase::Eye, Phase::Axes]
    );
}

#[test]
fn a_multi_layer_program_counts_its_layers() {
    let j = job(&two_layers());
    let steps = recorded(&j, Stage::Program);
    assert_eq!(phases(&steps)[0], Phase::Path);
    let total = |p: Phase| steps.iter().find(|s| s.phase == p).unwrap().total;
    // Three layers planned, two of them wound.
    assert_eq!(total(Phase::Path), 3);
    for p in [Phase::Eye, Phase::Axes, Phase::Blocks] {
        assert_eq!(total(p), 2, "{p}");
    }
    assert_eq!(
        steps.last().map(|s| (s.phase, s.done)),
        Some((Phase::Assembly, 1))
    );
}

#[test]
fn the_hook_does_not_change_the_program() {
    let j = job(TUBE);
    let plain = plan_program(&j).unwrap();
    let hook = Hook::new(|_| {});
    let hooked = plan_until_with(&j, Stage::Program, &hook).unwrap();
    assert_eq!(plain.program, hooked.program);
}

/// A hook that cancels at the `at`-th report (0-based) of `phase`.
fn cancel_at(j: &WindJob, stage: Stage, phase: Phase, at: usize) -> ProgramError {
    let count = Mutex::new(0);
    let hook = Hook::new(|_| {});
    let stopper = Stopper {
        hook: &hook,
        phase,
        at,
        count: &count,
    };
    plan_until_with(j, stage, &stopper).unwrap_err()
}

struct Stopper<'a, F> {
    hook: &'a Hook<F>,
    phase: Phase,
    at: usize,
    count: &'a Mutex<usize>,
}

impl<F: Fn(Step) + Sync> Progress for Stopper<'_, F> {
    fn report(&self, step: Step) {
        if step.phase == self.phase {
            let mut c = self.count.lock().unwrap();
            if *c == self.at {
                self.hook.cancel();
            }
            *c += 1;
        }
    }

    fn cancelled(&self) -> bool {
        self.hook.cancelled()
    }
}

#[test]
fn a_hook_that_cancels_at_its_first_report_stops_the_run() {
    let j = job(TUBE);
    for stage in [Stage::Path, Stage::Eye, Stage::Axes, Stage::Program] {
        let e = cancel_at(&j, stage, Phase::Path, 0);
        assert!(matches!(e, ProgramError::Cancelled(_)), "{stage:?}: {e}");
        assert_eq!(e.to_string(), "cancelled");
    }
}

#[test]
fn a_cancel_in_any_phase_stops_the_run() {
    let j = job(&two_layers());
    for phase in [
        Phase::Path,
        Phase::Eye,
        Phase::Axes,
        Phase::Blocks,
        Phase::Assembly,
    ] {
        let e = cancel_at(&j, Stage::Program, phase, 1);
        assert!(matches!(e, ProgramError::Cancelled(_)), "{phase}: {e}");
    }
}
