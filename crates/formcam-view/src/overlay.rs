//! What the page draws over the machine as the program runs: the payout
//! point's trajectory over the whole program, the band laid so far (how
//! much of it at each sample) and the checks' violations.

use std::path::Path;

use serde::Serialize;
use ts_rs::TS;

use crate::ViewError;
use crate::band::Band;
use crate::folder::RunFolder;
use crate::scene::thin;
use crate::timeline::{Sample, Timeline};
use crate::violations::Violations;

/// The most points of the eye trajectory sent for drawing.
pub const EYE_POINTS: usize = 20_000;

/// The payout point's path over the whole program (`/api/eye`).
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct EyeTrajectory {
    /// World positions, mm: at the program's start and at block ends
    /// (thinned evenly to at most [`EYE_POINTS`] for drawing).
    pub points: Vec<[f64; 3]>,
    /// The times of `points`, s.
    pub times: Vec<f64>,
    /// Block ends before thinning (the start included).
    pub ends: usize,
}

impl EyeTrajectory {
    /// The payout point at the start and every block end of `tl`, thinned.
    pub fn of(tl: &Timeline) -> Self {
        let sim = tl.sim();
        let times: Vec<f64> = std::iter::once(0.0)
            .chain(sim.blocks().map(|b| b.start_s + b.duration_s))
            .collect();
        let kept = thin(&times, EYE_POINTS);
        let payout = tl.machine().roles.payout;
        let points = kept
            .iter()
            .map(|&t| {
                let p = sim.poses_at(tl.machine(), t).points[payout];
                [p.x, p.y, p.z]
            })
            .collect();
        Self {
            points,
            times: kept,
            ends: times.len(),
        }
    }
}

/// A sample as the page gets it: the timeline's, and how many band points
/// are laid then.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct Shown {
    /// The timeline's sample.
    #[serde(flatten)]
    pub sample: Sample,
    /// Points of `/api/band` laid at this time (absent without a band).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[ts(optional)]
    pub laid: Option<usize>,
}

/// The overlays of a result with a program.
#[derive(Debug, Clone)]
pub struct Overlay {
    /// The band, when the result has its circuit tables.
    pub band: Option<Band>,
    /// The eye trajectory.
    pub eye: EyeTrajectory,
    /// The checks' violations.
    pub violations: Violations,
}

impl Overlay {
    /// The overlays of the result under `root` (read as `folder`) playing
    /// `tl`. `report`: the folder's `check.json` may be shown (the result
    /// is shown on the machine it was checked on).
    ///
    /// # Errors
    ///
    /// A table or `check.json` that cannot be read, naming the file.
    pub fn open(
        root: &Path,
        folder: &RunFolder,
        tl: &Timeline,
        report: bool,
    ) -> Result<Self, ViewError> {
        Ok(Self {
            band: Band::read(root, &folder.summary, tl)?,
            eye: EyeTrajectory::of(tl),
            violations: Violations::of(folder, tl, report)?,
        })
    }

    /// `sample` with the band laid then.
    pub fn shown(&self, sample: Sample) -> Shown {
        Shown {
            laid: self.band.as_ref().map(|b| b.laid(&sample.axes)),
            sample,
        }
    }
}
