//! Feed control for a constant material-removal rate (docs/dressing.md,
//! eqs. 15-21).
//!
//! The simulation gives each step the area `A` it removes over its length
//! `L`, so `a = A / L` (mm²/mm) at a feed `F` (mm/min) removes `MRR = a F`
//! mm² of the wheel's section per minute (times the wheel's circumference
//! `pi D` for mm³/min). The feed that holds `MRR` at the target `T` is
//! `F = T / a`, kept within `[feed_min, feed_max]`; then smoothed so that
//! neighbouring points of a pass differ by at most `feed_change_max`, only
//! ever lowering a feed (so the rate never rises above the target where the
//! feed is not at `feed_min`).
//!
//! Without a given target: the largest `T` whose spread of the rate is the
//! least the feed range allows, `T = max(feed_min a_max, feed_max a_min)`
//! over the steady steps ([`Step::steady`]). Where `a_max / a_min` is no more
//! than `feed_max / feed_min`, this is the largest target every steady step
//! holds with its feed within the range; where it is more (the bundled example),
//! the heaviest step runs at `feed_min`, holding `T`, and the lightest at
//! `feed_max`, below it.
//!
//! The spread of the rate, max / min, is reported over the steady steps (on
//! the profile's pieces, on material no earlier pass touched: entering and
//! leaving the allowance at a corner the rate runs down to zero), and over
//! every step that cuts. The uncontrolled program runs at the constant feed
//! that takes the same time.

use crate::error::{finite, num};
use crate::{DressError, Step};

/// The feed limits as users give them, mm/min.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedSpec {
    /// The lowest feed.
    pub feed_min: f64,
    /// The highest feed.
    pub feed_max: f64,
    /// The material-removal rate to hold, mm²/min of the wheel's section;
    /// `None`: the largest the feed range allows (see the module).
    pub target_mrr: Option<f64>,
    /// The largest feed change between neighbouring points, mm/min; `None`:
    /// a tenth of `feed_max - feed_min`.
    pub feed_change_max: Option<f64>,
}

impl FeedSpec {
    /// Checks the limits; errors name the `process.*` field.
    pub fn check(&self) -> Result<FeedSpec, DressError> {
        let lo = finite("process.feed_min", self.feed_min, " mm/min")?;
        let hi = finite("process.feed_max", self.feed_max, " mm/min")?;
        // The programs write feeds to 0.1 mm/min.
        if lo < 0.1 {
            return Err(DressError::field(
                "process.feed_min",
                format!("{} mm/min", num(lo)),
                "must be at least 0.1 mm/min",
            ));
        }
        if hi > 100_000.0 {
            return Err(DressError::field(
                "process.feed_max",
                format!("{} mm/min", num(hi)),
                "must be at most 100000 mm/min",
            ));
        }
        if hi < lo {
            return Err(DressError::field(
                "process.feed_max",
                format!("{} mm/min", num(hi)),
                format!("must be at least process.feed_min = {} mm/min", num(lo)),
            ));
        }
        if let Some(t) = self.target_mrr {
            let t = finite("process.target_mrr", t, " mm²/min")?;
            if t <= 0.0 {
                return Err(DressError::field(
                    "process.target_mrr",
                    format!("{} mm²/min", num(t)),
                    "must be positive",
                ));
            }
        }
        if let Some(d) = self.feed_change_max {
            let d = finite("process.feed_change_max", d, " mm/min")?;
            if d <= 0.0 {
                return Err(DressError::field(
                    "process.feed_change_max",
                    format!("{} mm/min", num(d)),
                    "must be positive",
                ));
            }
        }
        Ok(*self)
    }

    /// The change limit in use.
    pub fn change_max(&self) -> f64 {
        self.feed_change_max
            .unwrap_or(0.1 * (self.feed_max - self.feed_min))
            .max(1e-9)
    }
}

/// The feed along the path and the removal rate it gives.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedPlan {
    /// The target rate, mm²/min.
    pub target: f64,
    /// The target was given (not chosen).
    pub target_given: bool,
    /// The change limit used, mm/min.
    pub change_max: f64,
    /// The feed of each step (of the move ending at its point), mm/min.
    pub feed: Vec<f64>,
    /// The feed each step needs for the target, within the range, before smoothing.
    pub required: Vec<f64>,
    /// The removal rate of each step at its feed, mm²/min.
    pub mrr: Vec<f64>,
    /// The constant feed of the uncontrolled program (same time), mm/min.
    pub feed_uncontrolled: f64,
    /// The removal rate of each step at that feed, mm²/min.
    pub mrr_uncontrolled: Vec<f64>,
    /// Max / min of the rate over the steady steps, constant feed.
    pub ratio_uncontrolled: Option<f64>,
    /// The same with feed control.
    pub ratio_controlled: Option<f64>,
    /// Max / min over every step that cuts, constant feed.
    pub ratio_all_uncontrolled: Option<f64>,
    /// The same with feed control.
    pub ratio_all_controlled: Option<f64>,
    /// The time of the moves, s.
    pub time_s: f64,
}

impl FeedPlan {
    /// Whether step `k`'s feed is at `feed_min` or `feed_max`.
    pub fn at_bound(&self, k: usize, spec: &FeedSpec) -> bool {
        let f = self.feed[k];
        let tol = 1e-9 * spec.feed_max;
        f <= spec.feed_min + tol || f >= spec.feed_max - tol
    }

    /// Whether step `k`'s feed was lowered below what it needs by the change limit.
    pub fn held(&self, k: usize) -> bool {
        self.feed[k] < self.required[k] * (1.0 - 1e-12)
    }
}

/// Plans the feed over `steps` (pass after pass) within `spec` (checked).
pub fn plan_feed(steps: &[Step], spec: &FeedSpec) -> FeedPlan {
    let (lo, hi) = (spec.feed_min, spec.feed_max);
    let a: Vec<f64> = steps.iter().map(Step::area_per_mm).collect();
    let pick = |steady: bool| {
        let mut amin = f64::INFINITY;
        let mut amax: f64 = 0.0;
        for (s, &ak) in steps.iter().zip(&a) {
            if ak > 0.0 && (s.steady || !steady) {
                amin = amin.min(ak);
                amax = amax.max(ak);
            }
        }
        (amax > 0.0).then_some((amin, amax))
    };
    let range = pick(true).or_else(|| pick(false));
    let target = match (spec.target_mrr, range) {
        (Some(t), _) => t,
        (None, Some((amin, amax))) => (lo * amax).max(hi * amin),
        (None, None) => 0.0,
    };
    let required: Vec<f64> = a
        .iter()
        .map(|&ak| {
            if ak > 0.0 {
                (target / ak).clamp(lo, hi)
            } else {
                hi
            }
        })
        .collect();
    let change_max = spec.change_max();
    let mut feed = required.clone();
    // Within each pass: forward then backward, each feed no more than its
    // neighbour's plus the limit (the lower envelope of cones).
    for k in 1..steps.len() {
        if steps[k].pass == steps[k - 1].pass {
            feed[k] = feed[k].min(feed[k - 1] + change_max);
        }
    }
    for k in (0..steps.len().saturating_sub(1)).rev() {
        if steps[k].pass == steps[k + 1].pass {
            feed[k] = feed[k].min(feed[k + 1] + change_max);
        }
    }
    let mrr: Vec<f64> = a.iter().zip(&feed).map(|(ak, f)| ak * f).collect();
    let length: f64 = steps.iter().map(|s| s.length).sum();
    let time_min: f64 = steps.iter().zip(&feed).map(|(s, f)| s.length / f).sum();
    let feed_uncontrolled = if time_min > 0.0 {
        length / time_min
    } else {
        hi
    };
    let mrr_uncontrolled: Vec<f64> = a.iter().map(|ak| ak * feed_uncontrolled).collect();
    let ratio = |rates: &[f64], steady: bool| {
        let mut rmin = f64::INFINITY;
        let mut rmax: f64 = 0.0;
        for ((s, r), ak) in steps.iter().zip(rates).zip(&a) {
            if *ak > 0.0 && (s.steady || !steady) {
                rmin = rmin.min(*r);
                rmax = rmax.max(*r);
            }
        }
        (rmax > 0.0).then_some(rmax / rmin)
    };
    FeedPlan {
        target,
        target_given: spec.target_mrr.is_some(),
        change_max,
        ratio_uncontrolled: ratio(&mrr_uncontrolled, true),
        ratio_controlled: ratio(&mrr, true),
        ratio_all_uncontrolled: ratio(&mrr_uncontrolled, false),
        ratio_all_controlled: ratio(&mrr, false),
        feed,
        required,
        mrr,
        feed_uncontrolled,
        mrr_uncontrolled,
        time_s: time_min * 60.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Point, Stage};

    fn step(pass: usize, area: f64, steady: bool) -> Step {
        Step {
            pass,
            stage: Stage::Flank,
            centre: Point::default(),
            reference: Point::default(),
            contact: None,
            length: 0.01,
            area,
            cut: None,
            cut_angle: 0.0,
            steady,
        }
    }

    fn spec() -> FeedSpec {
        FeedSpec {
            feed_min: 50.0,
            feed_max: 300.0,
            target_mrr: None,
            feed_change_max: Some(1000.0),
        }
    }

    #[test]
    fn a_spread_within_the_feed_range_is_held_exactly() {
        // a from 0.02 to 0.1 (x5 < x6): every step at the target.
        let steps: Vec<Step> = (0..50)
            .map(|i| step(0, 0.0002 + 0.0008 * (i % 11) as f64 / 10.0, true))
            .collect();
        let p = plan_feed(&steps, &spec());
        let amin = steps
            .iter()
            .map(Step::area_per_mm)
            .fold(f64::INFINITY, f64::min);
        assert!((p.target - 300.0 * amin).abs() < 1e-9);
        for (k, m) in p.mrr.iter().enumerate() {
            assert!((m / p.target - 1.0).abs() < 1e-12, "{k} {m}");
        }
        assert!((p.ratio_controlled.unwrap() - 1.0).abs() < 1e-12);
        assert!(p.ratio_uncontrolled.unwrap() > 4.0);
    }

    #[test]
    fn a_wider_spread_runs_the_heaviest_step_at_feed_min() {
        let areas = [0.0005, 0.0005, 0.008, 0.0005, 0.0005, 0.0];
        let steps: Vec<Step> = areas.iter().map(|&a| step(0, a, a > 0.0)).collect();
        let p = plan_feed(&steps, &spec());
        assert!((p.target - 50.0 * 0.8).abs() < 1e-9);
        assert!((p.feed[2] - 50.0).abs() < 1e-12);
        assert!((p.feed[0] - 300.0).abs() < 1e-12);
        // x16 spread, feed range x6: x16/6 with control.
        assert!((p.ratio_uncontrolled.unwrap() - 16.0).abs() < 1e-9);
        assert!((p.ratio_controlled.unwrap() - 16.0 / 6.0).abs() < 1e-9);
        // No area: the highest feed.
        assert!((p.feed[5] - 300.0).abs() < 1e-12);
    }

    #[test]
    fn smoothing_only_lowers_feeds_and_keeps_the_limit() {
        let areas = [
            0.0005, 0.0005, 0.0005, 0.008, 0.0005, 0.0005, 0.0005, 0.0005,
        ];
        let mut steps: Vec<Step> = areas.iter().map(|&a| step(0, a, true)).collect();
        steps[7].pass = 1;
        let mut s = spec();
        s.feed_change_max = Some(100.0);
        let p = plan_feed(&steps, &s);
        for k in 0..steps.len() {
            assert!(p.feed[k] <= p.required[k] + 1e-12);
            assert!(p.feed[k] >= 50.0 - 1e-12);
            assert!(p.mrr[k] <= p.target * (1.0 + 1e-12));
        }
        for k in 1..7 {
            assert!((p.feed[k] - p.feed[k - 1]).abs() <= 100.0 + 1e-9);
        }
        assert_eq!(p.feed[2], 150.0);
        assert!(p.held(2) && !p.held(3));
        // A new pass starts afresh.
        assert_eq!(p.feed[7], 300.0);
        assert!(p.at_bound(3, &s));
    }

    #[test]
    fn bad_limits_name_the_field() {
        let mut s = spec();
        s.feed_max = 10.0;
        assert!(
            s.check()
                .unwrap_err()
                .to_string()
                .starts_with("process.feed_max = 10 mm/min")
        );
        let mut s = spec();
        s.feed_min = f64::NAN;
        assert!(
            s.check()
                .unwrap_err()
                .to_string()
                .starts_with("process.feed_min = NaN")
        );
        let mut s = spec();
        s.target_mrr = Some(-1.0);
        assert!(
            s.check()
                .unwrap_err()
                .to_string()
                .starts_with("process.target_mrr")
        );
    }
}
