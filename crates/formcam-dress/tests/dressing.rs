//! The dressing against what can be checked without the crate's own cutting
//! code: the profile's joints and contacts, the areas, the formed profile,
//! and the removal rate recomputed on a fine grid with exact circles from the
//! program's own feeds.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_dress::{DressJob, DressSpec, Dressing, Side, WheelSpec, dress};
use formcam_nc::{AxisSpec, Dialect, Feed, Motion, read_cldata};

const EXAMPLE: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");

fn job(edit: impl FnOnce(&mut DressJob)) -> DressSpec {
    let mut j = DressJob::from_toml(EXAMPLE).unwrap();
    edit(&mut j);
    j.spec(None).unwrap()
}

fn example() -> Dressing {
    dress(&job(|_| {})).unwrap()
}

/// The wheel's contour on a uniform grid, cut by the dresser's exact section
/// (circular corners, flat, faces) at every path point of the dressing.
struct Grid {
    x0: f64,
    dx: f64,
    g: Vec<f64>,
}

impl Grid {
    /// The grid's `i`-th abscissa (the last one exactly at the wheel's edge).
    fn x(&self, i: usize) -> f64 {
        let n = (self.g.len() - 1) as f64;
        self.x0 * (1.0 - 2.0 * i as f64 / n)
    }

    /// The profile offset by `depth` (less than the fillet radius), from the
    /// pieces' closed forms: the flank arcs' circles grown by `depth`, the
    /// fillets' shrunk, the flanks moved out along their normal, a disc at
    /// the apex; the highest where several reach.
    fn allowance(d: &Dressing, depth: f64, n: usize) -> Grid {
        let p = &d.profile;
        let s = p.spec();
        let half = p.d.x;
        let dx = 2.0 * half / n as f64;
        let (tilt, arc) = (s.flank_tilt, s.arc_angle);
        let circle_top = |c: formcam_dress::Point, r: f64, x: f64| {
            let t = r * r - (x - c.x) * (x - c.x);
            (t >= 0.0).then(|| c.y + t.sqrt())
        };
        let g = (0..=n)
            .map(|i| {
                let x = (half * (2.0 * i as f64 / n as f64 - 1.0)).abs();
                let mut y = f64::NEG_INFINITY;
                // The flank arc between the apex's and B's polar angles.
                let r = s.r1 + depth;
                let (xa, xb) = (p.o1.x + r * p.apex_angle.cos(), p.o1.x + r * arc.cos());
                if x >= xa && x <= xb {
                    y = y.max(circle_top(p.o1, r, x).unwrap_or(y));
                }
                // The fillet: the lower half of a circle about O2.
                let r = s.r2 - depth;
                let (fa, fb) = (
                    std::f64::consts::PI + arc,
                    1.5 * std::f64::consts::PI - tilt,
                );
                let (xa, xb) = (p.o2.x + r * fa.cos(), p.o2.x + r * fb.cos());
                if x >= xa && x <= xb {
                    let t = (r * r - (x - p.o2.x).powi(2)).max(0.0);
                    y = y.max(p.o2.y - t.sqrt());
                }
                // The flank.
                if x >= p.c.x + depth * tilt.sin() {
                    y = y.max(p.c.y + depth / tilt.cos() - (x - p.c.x) * tilt.tan());
                }
                // The apex.
                if let Some(v) = circle_top(p.apex, depth, x) {
                    y = y.max(v);
                }
                y
            })
            .collect();
        Grid { x0: -half, dx, g }
    }

    /// Cuts with the dresser whose corner dressing `side` is centred at `c`;
    /// returns the removed area (trapezoids).
    fn cut(&mut self, d: &Dressing, side: Side, c: formcam_dress::Point) -> f64 {
        let (rr, rl, b) = (d.dresser.r_right, d.dresser.r_left, d.dresser.width);
        let flat = b - rr - rl;
        // Centres of the lower-left (rr) and lower-right (rl) corners.
        let (cl, cr) = match side {
            Side::Right => ((c.x, c.y), (c.x + flat, c.y - rr + rl)),
            Side::Left => ((c.x - flat, c.y - rl + rr), (c.x, c.y)),
        };
        let (xl, xr) = (cl.0 - rr, cr.0 + rl);
        let lower = |x: f64| {
            if x < cl.0 {
                cl.1 - (rr * rr - (x - cl.0).powi(2)).max(0.0).sqrt()
            } else if x <= cr.0 {
                cl.1 - rr
            } else {
                cr.1 - (rl * rl - (x - cr.0).powi(2)).max(0.0).sqrt()
            }
        };
        let n = self.g.len() - 1;
        let i0 = (((xl - self.x0) / self.dx).ceil().max(0.0)) as usize;
        let i1 = ((((xr - self.x0) / self.dx).floor()) as usize).min(n);
        let mut removed = 0.0;
        let bottom = cl.1 - rr;
        for i in i0..=i1.max(i0).min(n) {
            let x = self.x(i);
            if x < xl || x > xr || self.g[i] <= bottom {
                continue;
            }
            let y = lower(x);
            if self.g[i] > y {
                let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                removed += (self.g[i] - y) * self.dx * w;
                self.g[i] = y;
            }
        }
        removed
    }
}

/// The areas removed step by step on the grid.
fn grid_areas(d: &Dressing, depth: f64) -> (Vec<f64>, Grid) {
    let mut grid = Grid::allowance(d, depth, 600_000);
    let mut areas = Vec::new();
    for pass in &d.passes {
        for q in &pass.points[1..] {
            areas.push(grid.cut(d, pass.side, q.centre));
        }
    }
    (areas, grid)
}

#[test]
fn profiles_join_tangent_and_touch_the_ball_at_the_contact_angle() {
    let seed = job(|_| {}).wheel;
    let variants = [
        seed,
        WheelSpec {
            ball_radius: 3.175,
            contact_angle: 40f64.to_radians(),
            r1: 3.3,
            r2: 0.5,
            width: 9.0,
            flank_tilt: 5f64.to_radians(),
            arc_angle: 10f64.to_radians(),
        },
        WheelSpec {
            flank_tilt: -15f64.to_radians(),
            ..seed
        },
    ];
    for w in variants {
        let p = formcam_dress::Profile::new(&w).unwrap();
        let j = p.joints();
        assert!(j.gap < 1e-9 && j.angle < 1e-9, "{w:?}: {j:?}");
        for (c, angle) in p
            .contacts()
            .iter()
            .zip([w.contact_angle, std::f64::consts::PI - w.contact_angle])
        {
            assert!(c.gap.abs() < 1e-9, "{c:?}");
            assert!((c.angle - angle).abs() < 1e-9, "{c:?}");
        }
        // The contact points are the ball's only touching points.
        assert!(p.ball_gap().abs() < 1e-9);
        assert!(p.clearance() > 0.0);
        // Symmetric about the y axis.
        for x in [0.3, 1.0, 1.9, 2.5] {
            assert_eq!(p.y_at(x), p.y_at(-x));
        }
    }
}

#[test]
fn removed_areas_add_up_to_the_area_between_the_contours() {
    for step in [0.01, 0.004] {
        let d = dress(&job(|j| j.process.step = step)).unwrap();
        let (removed, between) = (d.forming.removed(), d.forming.area_between());
        let rel = ((removed - between) / between).abs();
        assert!(rel < 1e-9, "step {step}: {removed} vs {between} ({rel:e})");
    }
}

#[test]
fn a_worn_user_contour_is_dressed_to_the_profile() {
    // A wavy contour 0.02..0.08 above the profile, cut through the apex.
    let base = example();
    let pts: Vec<formcam_dress::Point> = (0..=1200)
        .map(|i| {
            let x = -3.0 + 0.005 * i as f64;
            let y = base.profile.y_at(x).unwrap() + 0.05 + 0.03 * (9.0 * x).sin();
            formcam_dress::Point::new(x, y)
        })
        .collect();
    let mut spec = job(|_| {});
    spec.allowance = formcam_dress::Allowance::Contour(pts);
    let d = dress(&spec).unwrap();
    let (removed, between) = (d.forming.removed(), d.forming.area_between());
    assert!(((removed - between) / between).abs() < 1e-9);
    let (lo, hi) = d.forming.deviation(&d.profile, d.step);
    assert!(lo > -1e-9 && hi <= d.scallop_bound(), "{lo} {hi}");
}

#[test]
fn the_final_contour_is_the_profile_within_the_scallop() {
    for step in [0.01, 0.002] {
        let d = dress(&job(|j| j.process.step = step)).unwrap();
        let (lo, hi) = d.forming.deviation(&d.profile, d.step);
        let bound = d.scallop_bound();
        assert!(
            lo > -1e-9,
            "step {step}: the wheel is cut below its profile by {lo}"
        );
        assert!(
            hi <= bound,
            "step {step}: {hi} above the profile, bound {bound}"
        );
        // The bound is no loose one: the scallops come close to it.
        assert!(hi > 0.3 * bound, "step {step}: {hi} vs {bound}");
    }
}

#[test]
fn areas_agree_with_a_grid_of_exact_circles() {
    let d = example();
    let (areas, grid) = grid_areas(&d, 0.05);
    let lib = &d.forming.steps;
    assert_eq!(areas.len(), lib.len());
    let total_grid: f64 = areas.iter().sum();
    let total = d.forming.removed();
    assert!(
        ((total_grid - total) / total).abs() < 2e-3,
        "{total_grid} {total}"
    );
    // Step by step where a step removes a fair share.
    let mut compared = 0;
    for (k, (a, s)) in areas.iter().zip(lib).enumerate() {
        // Where the cut spans many columns of the grid.
        if s.cut.is_some_and(|(a, b)| b.x - a.x > 0.05) {
            assert!(
                ((a - s.area) / s.area).abs() < 0.02,
                "step {k}: grid {a} vs {}",
                s.area
            );
            compared += 1;
        }
    }
    assert!(compared > 500, "{compared}");
    // The grid's wheel after dressing is the profile too, within the height
    // of a scallop across the steep pieces (measured vertically here), and
    // the rounding of exact circles at their vertical tangents (the wheel's
    // edges, the faces: 1e-8).
    for (i, gi) in grid.g.iter().enumerate() {
        let x = grid.x(i);
        let y = d.profile.y_at(x).unwrap();
        assert!(*gi - y > -1e-7 && *gi - y < 3e-4, "x {x}: {}", gi - y);
    }
}

/// The linear blocks: length (from the point before, as planned) and feed
/// (as the CLDATA program writes it). No block is of zero length as written.
fn program_blocks(d: &Dressing) -> Vec<(f64, f64)> {
    let text = d.nc(Dialect::Cldata).unwrap();
    let p = read_cldata(&text, &[AxisSpec::linear("Z"), AxisSpec::linear("X")]).unwrap();
    assert_eq!(p.blocks.len(), d.program.blocks.len());
    let mut out = Vec::new();
    let (mut at, mut at_written) = (vec![0.0, 0.0], vec![0.0, 0.0]);
    for (b, w) in d.program.blocks.iter().zip(&p.blocks) {
        if w.kind == Motion::Linear {
            let f = match w.feed {
                Feed::PerMinute(f) => f,
                other => panic!("{other:?}"),
            };
            let written = (w.target[0] - at_written[0]).hypot(w.target[1] - at_written[1]);
            assert!(written > 0.0, "a zero-length block: {w:?}");
            out.push(((b.target[0] - at[0]).hypot(b.target[1] - at[1]), f));
        }
        at.clone_from(&b.target);
        at_written.clone_from(&w.target);
    }
    out
}

/// Checks the rate from the grid's areas and the program's blocks (length
/// and feed as written): within ±5 % of the target over every block whose
/// steps have their feed at no bound (the range, or held back by the change
/// limit), never above it where the feed is above the lowest. Steps that
/// would print as zero-length moves share a block.
fn check_rate(d: &Dressing) -> usize {
    let (areas, _) = grid_areas(d, 0.05);
    let blocks = program_blocks(d);
    assert_eq!(d.step_block.len(), areas.len());
    assert_eq!(d.step_block.last().map(|b| b + 1), Some(blocks.len()));
    let target = d.feed.target;
    let spec = &d.feed_spec;
    let mut free = 0;
    let mut k = 0;
    while k < areas.len() {
        let b = d.step_block[k];
        let mut e = k;
        while e < areas.len() && d.step_block[e] == b {
            e += 1;
        }
        let (len, f) = blocks[b];
        let area: f64 = areas[k..e].iter().sum();
        let rate = area / (len / f);
        if (k..e).all(|i| !d.feed.at_bound(i, spec) && !d.feed.held(i)) {
            assert!(
                (rate / target - 1.0).abs() < 0.05,
                "steps {k}..{e} ({:?}): {rate} vs {target} at {f}",
                d.forming.steps[k].stage
            );
            free += 1;
        }
        if f > spec.feed_min + 0.1 && e == k + 1 {
            assert!(rate < target * 1.05, "step {k}: {rate} above {target}");
        }
        k = e;
    }
    // Neighbouring feeds within the change limit (the written feeds are
    // rounded to 0.1) where blocks are single steps.
    let single: Vec<bool> = (0..blocks.len())
        .map(|b| d.step_block.iter().filter(|&&x| x == b).count() == 1)
        .collect();
    for w in 1..blocks.len() {
        if single[w] && single[w - 1] {
            assert!(
                (blocks[w].1 - blocks[w - 1].1).abs() <= d.feed.change_max + 0.11 || {
                    // The first block of the second pass follows the first pass.
                    d.step_block
                        .iter()
                        .position(|&x| x == w)
                        .is_some_and(|i| d.passes[0].points.len() - 1 == i)
                },
                "blocks {w}: {:?} {:?}",
                blocks[w - 1],
                blocks[w]
            );
        }
    }
    free
}

#[test]
fn feed_control_holds_the_largest_rate_the_feeds_allow() {
    let d = example();
    let free = check_rate(&d);
    assert!(free >= 10, "{free} steps with a free feed");
    // The example's case: the spread is more than the feed range (x6), so the
    // heaviest step runs at the lowest feed.
    let (u, c) = (
        d.feed.ratio_uncontrolled.unwrap(),
        d.feed.ratio_controlled.unwrap(),
    );
    assert!(u > 6.0, "{u}");
    assert!((c - u / 6.0).abs() < 1e-9 * u, "{c} {u}");
}

#[test]
fn feed_control_holds_a_given_rate() {
    let d = dress(&job(|j| {
        j.process.target_mrr = Some(11.0);
        j.process.feed_change_max = Some(40.0);
    }))
    .unwrap();
    assert_eq!(d.feed.target, 11.0);
    let free = check_rate(&d);
    // Most of the path: the flanks and arcs need 220..300 mm/min.
    assert!(free > d.forming.steps.len() / 2, "{free}");
    assert!(d.feed.ratio_controlled.unwrap() < d.feed.ratio_uncontrolled.unwrap());
}

#[test]
fn dressing_time_is_the_path_over_the_feeds() {
    let d = example();
    let t: f64 = d
        .forming
        .steps
        .iter()
        .zip(&d.feed.feed)
        .map(|(s, f)| s.length / f * 60.0)
        .sum();
    assert!((d.dressing_time_s() - t).abs() < 1e-9 * t);
    assert!((d.feed.time_s - t).abs() < 1e-9 * t);
    // Three rapid moves per pass and one linear block per step, but for
    // steps merged because they would print at one place.
    let linear = d.step_block.last().map_or(0, |b| b + 1);
    assert_eq!(d.points(), 3 * d.passes.len() + linear);
    let steps: usize = d.passes.iter().map(|p| p.points.len() - 1).sum();
    assert!(linear < steps && linear + 50 > steps, "{linear} of {steps}");
}

#[test]
fn bad_input_is_one_line_naming_the_field() {
    type Edit = Box<dyn Fn(&mut DressJob)>;
    let cases: Vec<(Edit, &str)> = vec![
        (
            Box::new(|j| j.wheel.r2 = 2.0),
            "wheel.r2 = 2 mm: the fillet does not fit",
        ),
        (
            Box::new(|j| j.wheel.contact_angle_deg = 90.0),
            "wheel.contact_angle_deg = 90°",
        ),
        (
            Box::new(|j| j.wheel.contact_angle_deg = 0.0),
            "wheel.contact_angle_deg = 0°",
        ),
        (Box::new(|j| j.wheel.r1 = 1.85), "wheel.r1 = 1.85 mm"),
        (Box::new(|j| j.wheel.r1 = 1.2), "wheel.r1 = 1.2 mm"),
        (Box::new(|j| j.process.step = 0.0), "process.step = 0 mm"),
        (
            Box::new(|j| j.process.depth = Some(2.0)),
            "process.depth = 2 mm: larger than the wheel",
        ),
        (
            Box::new(|j| j.process.depth = Some(0.3)),
            "process.depth = 0.3 mm",
        ),
        (
            Box::new(|j| j.wheel.ball_radius = f64::NAN),
            "wheel.ball_radius = NaN",
        ),
        (
            Box::new(|j| j.process.feed_max = f64::NAN),
            "process.feed_max = NaN",
        ),
        (
            Box::new(|j| j.wheel.flank_tilt_deg = -15.0),
            "wheel.flank_tilt_deg = -15°: flanks rising",
        ),
        (
            Box::new(|j| j.dresser.corner_radius_left = 0.3),
            "dresser.corner_radius_left = 0.3 mm: larger than",
        ),
    ];
    for (edit, start) in cases {
        let mut j = DressJob::from_toml(EXAMPLE).unwrap();
        edit(&mut j);
        let e = j
            .spec(None)
            .and_then(|s| dress(&s))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(start), "{e:?} should start with {start:?}");
        assert!(!e.contains('\n'), "{e:?}");
    }
    let e = DressJob::from_toml(&EXAMPLE.replace("[process]", "[process]\nspeed = 2.0"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown field `speed`"), "{e}");
}

/// The message after `line N, column M: ` of a dressing job's TOML error.
fn toml_message(text: &str) -> String {
    let e = DressJob::from_toml(text).unwrap_err();
    let shown = e.to_string();
    assert!(shown.starts_with("line "), "{shown}");
    let said = shown.split_once(": ").map_or("", |(_, said)| said).trim();
    assert!(!said.is_empty(), "an empty message: {shown:?}");
    assert!(!shown.chars().any(char::is_control), "{shown:?}");
    said.to_string()
}

#[test]
fn a_dressing_job_cut_after_its_equals_sign_says_a_value_is_expected() {
    let at = EXAMPLE.find("r2 = ").unwrap() + "r2 =".len();
    let cut = &EXAMPLE[..at];
    let said = toml_message(cut);
    assert!(said.contains("expected"), "{said}");
    let rest = &EXAMPLE[at..];
    let blanked = format!("{cut}{}", &rest[rest.find('\n').unwrap()..]);
    let said = toml_message(&blanked);
    assert!(said.contains("expected"), "{said}");
}

#[test]
fn a_dressing_job_with_a_nul_says_nul_is_not_allowed() {
    let text = EXAMPLE.replacen("r2 = 0.296", "r2 = 0.296\0", 1);
    let said = toml_message(&text);
    assert!(said.contains("NUL"), "{said}");
}

#[test]
fn a_huge_contour_header_is_quoted_short_and_escaped() {
    let text = format!("z,q\u{1b}[2J\0{}\n0,1\n1,1\n", ",y".repeat(5 << 20));
    let e = formcam_dress::read_contour(&text).unwrap_err().to_string();
    assert!(e.starts_with("process.initial_contour, line 1: the header names the columns z,q"));
    assert!(e.chars().count() < 300, "{} characters", e.chars().count());
    assert!(!e.chars().any(char::is_control), "{e:?}");
    assert!(e.contains("\\u{1b}[2J\\0,y,y") && e.contains('…'), "{e}");
}
