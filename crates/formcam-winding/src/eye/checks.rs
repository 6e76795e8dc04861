//! The constraints (docs/winding.md), checked for every mode — cyclicity, the
//! clearance (`l >= l_min(x)`) and `l <= l_max`, no slack (`d(l + s)/dx >= 0`),
//! no reverse rotation of the mandrel (`dV/dx >= 0`) — and the pull-speed
//! statistics, summed run by run and joined in order.

use std::fmt;

use serde::Serialize;

use super::spec::EyeSpec;
use super::trajectory::EyePoint;

/// A constraint of the eye trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, strum::IntoStaticStr)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum Constraint {
    /// The trajectory closes: the free length and the eye's position (after the
    /// circuit's turn) at the end are those at the start.
    Cyclicity,
    /// The eye keeps the clearance from the mandrel.
    Clearance,
    /// The free length stays under `l_max`.
    #[serde(rename = "l_max")]
    #[strum(serialize = "l_max")]
    LMax,
    /// The band never slackens: `d(l + s)/dx >= 0`.
    Slack,
    /// The mandrel never turns back: `dV/dx >= 0`.
    ReverseRotation,
}

impl Constraint {
    /// Every constraint, in the order of the checks' slots.
    pub const ALL: [Constraint; 5] = [
        Constraint::Cyclicity,
        Constraint::Clearance,
        Constraint::LMax,
        Constraint::Slack,
        Constraint::ReverseRotation,
    ];

    /// The name in files and messages: `cyclicity`, `clearance`, `l_max`,
    /// `slack`, `reverse-rotation`.
    pub fn name(self) -> &'static str {
        self.into()
    }
}

impl fmt::Display for Constraint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// A broken constraint, summarised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// Which.
    pub constraint: Constraint,
    /// The first `x` where it fails, mm.
    pub x: f64,
    /// How many points or intervals fail.
    pub count: usize,
    /// The worst excess (mm, or rad for the rotation), positive.
    pub worst: f64,
}

/// Statistics of the pull speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PullStats {
    /// Least `u`.
    pub u_min: f64,
    /// Largest `u`.
    pub u_max: f64,
    /// Mean `U` (weighted by `dx`).
    pub u_mean: f64,
    /// RMS of `u - U`.
    pub u_rms_dev: f64,
}

/// The pull speed and the constraints over a run of consecutive eye points:
/// what can be summed run by run and joined.
#[derive(Debug, Clone)]
pub(super) struct Checks {
    u_min: f64,
    u_max: f64,
    /// Sums over the intervals: length, `(u - 1) dx`, `(u - 1)^2 dx` (the mean
    /// pull speed of a closed cycle is 1).
    sums: (f64, f64, f64),
    /// Per constraint: the first `x` where it fails, how often, the worst excess.
    pub(super) broken: [Option<(f64, usize, f64)>; 5],
}

impl Checks {
    /// Sets `u` on every interval of `e` and checks its points and intervals.
    pub(super) fn of_run(e: &mut [EyePoint], spec: &EyeSpec) -> Self {
        let mut c = Self::new();
        c.scan(e, 0, spec);
        c
    }

    pub(super) fn new() -> Self {
        Self {
            u_min: f64::INFINITY,
            u_max: f64::NEG_INFINITY,
            sums: (0.0, 0.0, 0.0),
            broken: [None; 5],
        }
    }

    /// Checks the points of `e` from `from` on, and the intervals that end there.
    pub(super) fn scan(&mut self, e: &mut [EyePoint], from: usize, spec: &EyeSpec) {
        for i in from..e.len() {
            self.point(&e[i], spec);
            if i > 0 {
                let next = e[i];
                self.interval(&mut e[i - 1], &next);
            }
        }
    }

    fn note(&mut self, kind: Constraint, x: f64, count: usize, excess: f64) {
        let slot = &mut self.broken[kind as usize];
        *slot = Some(match *slot {
            Some((x0, n, worst)) => (x0.min(x), n + count, worst.max(excess)),
            None => (x, count, excess),
        });
    }

    fn point(&mut self, e: &EyePoint, spec: &EyeSpec) {
        if e.margin < -1e-6 * (1.0 + spec.clearance) {
            self.note(Constraint::Clearance, e.x, 1, -e.margin);
        }
        if e.l > spec.l_max + 1e-6 {
            self.note(Constraint::LMax, e.x, 1, e.l - spec.l_max);
        }
    }

    /// The interval from `a` to the next point `b`: sets `a.u`.
    pub(super) fn interval(&mut self, a: &mut EyePoint, b: &EyePoint) {
        let dx = b.x - a.x;
        a.u = if dx > 0.0 {
            (b.lambda - a.lambda) / dx
        } else {
            1.0
        };
        self.u_min = self.u_min.min(a.u);
        self.u_max = self.u_max.max(a.u);
        let d = a.u - 1.0;
        self.sums.0 += dx;
        self.sums.1 += d * dx;
        self.sums.2 += d * d * dx;
        let slack = (b.l - a.l) + dx;
        if slack < -1e-6 {
            self.note(Constraint::Slack, a.x, 1, -slack);
        }
        let dv = b.eye_v - a.eye_v;
        if dv < -1e-9 {
            self.note(Constraint::ReverseRotation, a.x, 1, -dv);
        }
    }

    /// Adds the checks of the run that follows this one.
    pub(super) fn join(&mut self, next: Checks) {
        self.u_min = self.u_min.min(next.u_min);
        self.u_max = self.u_max.max(next.u_max);
        self.sums.0 += next.sums.0;
        self.sums.1 += next.sums.1;
        self.sums.2 += next.sums.2;
        for (kind, b) in Constraint::ALL.into_iter().zip(next.broken) {
            if let Some((x, count, worst)) = b {
                self.note(kind, x, count, worst);
            }
        }
    }

    pub(super) fn stats(&self) -> PullStats {
        let (total, s1, s2) = self.sums;
        let (mean, dev) = if total > 0.0 {
            let shift = s1 / total;
            (1.0 + shift, (s2 / total - shift * shift).max(0.0).sqrt())
        } else {
            (1.0, 0.0)
        };
        let (u_min, u_max) = if self.u_min <= self.u_max {
            (self.u_min, self.u_max)
        } else {
            (0.0, 0.0)
        };
        PullStats {
            u_min,
            u_max,
            u_mean: mean,
            u_rms_dev: dev,
        }
    }

    /// Closes the cycle: the last point takes the first one's pull speed; the
    /// free length and the eye's position (`closure_mm` apart after the circuit's
    /// turn) are checked for cyclicity.
    pub(super) fn close(
        mut self,
        e: &mut [EyePoint],
        closure_mm: f64,
    ) -> (PullStats, Vec<Violation>) {
        let u0 = e.first().map_or(0.0, |p| p.u);
        if e.len() >= 2
            && let Some(last) = e.last_mut()
        {
            last.u = u0;
        }
        if let (Some(a), Some(b)) = (e.first(), e.last())
            && (a.l - b.l).abs() > 1e-6
        {
            self.note(Constraint::Cyclicity, b.x, 1, (a.l - b.l).abs());
        }
        if closure_mm > 1e-6 {
            let x = e.last().map_or(0.0, |p| p.x);
            self.note(Constraint::Cyclicity, x, 1, closure_mm);
        }
        (self.stats(), self.violations())
    }

    /// The broken constraints, in the order they first fail along `x`.
    fn violations(&self) -> Vec<Violation> {
        let mut v: Vec<Violation> = Constraint::ALL
            .iter()
            .zip(&self.broken)
            .filter_map(|(&constraint, b)| {
                b.map(|(x, count, worst)| Violation {
                    constraint,
                    x,
                    count,
                    worst,
                })
            })
            .collect();
        v.sort_by(|a, b| a.x.total_cmp(&b.x));
        v
    }
}

/// Distance between the first eye point turned by the circuit's turn and the last.
pub(super) fn closure(e: &[EyePoint], turn: f64) -> f64 {
    let (Some(a), Some(b)) = (e.first(), e.last()) else {
        return 0.0;
    };
    let pa = (
        a.eye_r * (a.eye_v + turn).cos(),
        a.eye_r * (a.eye_v + turn).sin(),
        a.eye_z,
    );
    let pb = (b.eye_r * b.eye_v.cos(), b.eye_r * b.eye_v.sin(), b.eye_z);
    ((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2) + (pa.2 - pb.2).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    /// The names `summary.json`, `eye.csv` readers and `[checks] allow` know.
    #[test]
    fn constraints_keep_their_names_in_files_and_messages() {
        let names = [
            "cyclicity",
            "clearance",
            "l_max",
            "slack",
            "reverse-rotation",
        ];
        for (c, name) in Constraint::ALL.into_iter().zip(names) {
            assert_eq!(c.to_string(), name);
            assert_eq!(format!("{c:>18}"), format!("{name:>18}"));
            assert_eq!(serde_json::to_value(c).unwrap(), name);
        }
    }

    /// Eye points along `x = 0..n` with every constraint broken somewhere.
    fn run(n: usize) -> Vec<EyePoint> {
        (0..n)
            .map(|i| {
                let x = i as f64;
                // Free length falling faster than the band is laid round i = 7
                // (slack), beyond l_max at 11..13, inside the clearance at 4 and 17,
                // the eye turning back at 21.
                let l = 50.0
                    + if (7..9).contains(&i) { -3.0 * x } else { 0.0 }
                    + if (11..14).contains(&i) { 60.0 } else { 0.0 };
                let eye_v = 0.01 * x - if i == 22 { 0.05 } else { 0.0 };
                EyePoint {
                    x,
                    z: x,
                    r: 100.0,
                    v: 0.01 * x,
                    alpha: 0.5,
                    l,
                    margin: if i == 4 || i == 17 { -0.5 } else { 1.0 },
                    eye_z: x,
                    eye_r: 120.0,
                    eye_v,
                    lambda: l + x - (0.3 * x).sin(),
                    u: 0.0,
                }
            })
            .collect()
    }

    /// Checks summed run by run and joined in order are the checks of the
    /// whole: the same violations (first `x`, count, worst) in the same order,
    /// the same pull speeds.
    #[test]
    fn runs_joined_in_order_check_as_one() {
        let spec = EyeSpec {
            l_max: 100.0,
            ..EyeSpec::default()
        };
        let mut whole = run(30);
        let one = Checks::of_run(&mut whole, &spec);
        for cut in [1, 5, 8, 12, 18, 29] {
            let mut a = run(30);
            let mut b = a.split_off(cut);
            let mut joined = Checks::of_run(&mut a, &spec);
            let next = Checks::of_run(&mut b, &spec);
            if let (Some(last), Some(first)) = (a.last_mut(), b.first()) {
                joined.interval(last, first);
            }
            joined.join(next);
            a.extend(b);
            assert_eq!(joined.violations(), one.violations(), "cut at {cut}");
            let (s, t) = (joined.stats(), one.stats());
            assert_eq!((s.u_min, s.u_max), (t.u_min, t.u_max), "cut at {cut}");
            assert!((s.u_mean - t.u_mean).abs() < 1e-12, "cut at {cut}");
            assert!((s.u_rms_dev - t.u_rms_dev).abs() < 1e-12, "cut at {cut}");
            let u = |e: &[EyePoint]| e.iter().map(|p| p.u).collect::<Vec<_>>();
            assert_eq!(u(&a), u(&whole), "cut at {cut}");
        }
        let kinds: Vec<Constraint> = one.violations().iter().map(|v| v.constraint).collect();
        assert_eq!(
            kinds,
            [
                Constraint::Clearance,
                Constraint::Slack,
                Constraint::LMax,
                Constraint::ReverseRotation
            ]
        );
    }
}
