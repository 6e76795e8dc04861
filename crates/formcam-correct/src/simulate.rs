//! The closed-loop check of the correction on a simulated warp.
//!
//! A mould surface `z = f(x, y)` (a doubly curved panel or a nose-cone
//! panel) is milled by a raster program (G-code, ball-end or point tool).
//! Milling: the mould's surface is the surface of the program's nodes, offset
//! by the ball radius along its normal. Moulding: the part is the mould's
//! surface displaced along the nominal normal by a smooth warp field (the
//! same every time: the process repeats its error). Measuring: a CMM probes
//! the part along the nominal normal at points of control sections
//! `x = const`, with Gaussian noise. Correcting: [`crate::Corrector`] moves
//! the program's nodes, and the program is written and read again as text.
//! The true error after each round is also measured without noise on a
//! dense check grid.

use formcam_nc::{Dialect, ToolpathOptions};
use formcam_progress::{Muted, Phase, Progress, Silent, Step};

use crate::vec3::{V3, axpy, cross, dot, norm, scale, sub, unit};
use crate::{
    CorrectError, Corrector, Given, Grid, Interpolation, MeasuredPoint, Measurements,
    MillingProgram, Options, Rule, ScenarioError, ScenarioField, Section, Tool, smooth,
};

/// The nominal mould surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// `z = (x - L/2)^2 / (2 rx) + (y - W/2)^2 / (2 ry)`: a doubly curved panel.
    Panel {
        /// Radius of curvature along x, mm.
        radius_x: f64,
        /// Radius of curvature along y, mm.
        radius_y: f64,
    },
    /// `z = sqrt(r(x)^2 - (y - W/2)^2)`, `r` linear from `radius_start` to
    /// `radius_end`: a panel of a conical nose.
    NoseCone {
        /// Radius at x = 0, mm.
        radius_start: f64,
        /// Radius at x = L, mm.
        radius_end: f64,
    },
}

/// A closed-loop scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// The surface shape.
    pub shape: Shape,
    /// Panel length along x, mm.
    pub length: f64,
    /// Panel width along y, mm.
    pub width: f64,
    /// The tool.
    pub tool: Tool,
    /// Distance between raster lines (along y), mm.
    pub step_over: f64,
    /// Distance between nodes along a raster line (x), mm.
    pub step: f64,
    /// Feed, mm/min.
    pub feed: f64,
    /// Warp amplitude, mm.
    pub warp_amplitude: f64,
    /// Control sections (x = const, spanning the panel).
    pub sections: usize,
    /// Points per section (spanning the width).
    pub points: usize,
    /// CMM noise, standard deviation along the normal, mm.
    pub noise: f64,
    /// Smooth the measured deviations for the stated noise before correcting.
    pub smoothing: bool,
    /// Seed of the noise.
    pub seed: u64,
    /// Correction rounds.
    pub iterations: usize,
    /// Correction options.
    pub options: Options,
}

impl Scenario {
    /// Checks every field against the scenario file's description
    /// ([`crate::SCENARIO_JOB`]) and the limits between fields; the message
    /// names the field.
    pub fn validate(&self) -> Result<(), CorrectError> {
        use ScenarioField as F;
        for (field, v) in [
            (F::Length, self.length),
            (F::Width, self.width),
            (F::StepOver, self.step_over),
            (F::Step, self.step),
            (F::Feed, self.feed),
        ] {
            field.check(v)?;
        }
        match self.shape {
            Shape::Panel { radius_x, radius_y } => {
                F::RadiusX.check(radius_x)?;
                F::RadiusY.check(radius_y)?;
            }
            Shape::NoseCone {
                radius_start,
                radius_end,
            } => {
                F::RadiusStart.check(radius_start)?;
                F::RadiusEnd.check(radius_end)?;
                if self.width / 2.0 >= 0.95 * radius_start.min(radius_end) {
                    return Err(ScenarioError::NoseConeWidth {
                        width: self.width,
                        radius: radius_start.min(radius_end),
                    }
                    .into());
                }
            }
        }
        for (field, v) in [
            (F::Amplitude, self.warp_amplitude),
            (F::Noise, self.noise),
            (F::Sections, self.sections as f64),
            (F::Points, self.points as f64),
        ] {
            field.check(v)?;
        }
        let lines = (self.width / self.step_over).round() as usize + 1;
        let per_line = (self.length / self.step).round() as usize + 1;
        if lines.saturating_mul(per_line) > 20_000_000 {
            return Err(ScenarioError::Nodes { lines, per_line }.into());
        }
        F::Iterations.check(self.iterations as f64)?;
        if let Tool::Ball { radius } = self.tool {
            let curvature = match self.shape {
                Shape::Panel { radius_x, radius_y } => radius_x.min(radius_y),
                Shape::NoseCone { .. } => f64::INFINITY,
            };
            if !(radius.is_finite() && radius > 0.0) {
                return Err(ScenarioError::Field {
                    field: F::Tool,
                    value: Given::Tool(self.tool),
                    rule: Rule::BallRadius,
                }
                .into());
            }
            if radius >= curvature {
                return Err(ScenarioError::BallRadius { radius, curvature }.into());
            }
        }
        F::Gain.check(self.options.gain)?;
        F::Margin.check(self.options.margin_mm)?;
        self.options.validate()
    }

    /// `(z, dz/dx, dz/dy)` of the nominal surface.
    fn height(&self, x: f64, y: f64) -> (f64, f64, f64) {
        let (xc, yc) = (x - self.length / 2.0, y - self.width / 2.0);
        match self.shape {
            Shape::Panel { radius_x, radius_y } => (
                xc * xc / (2.0 * radius_x) + yc * yc / (2.0 * radius_y),
                xc / radius_x,
                yc / radius_y,
            ),
            Shape::NoseCone {
                radius_start,
                radius_end,
            } => {
                let dr = (radius_end - radius_start) / self.length;
                let r = radius_start + dr * x;
                let z = (r * r - yc * yc).max(1e-12).sqrt();
                (z, r * dr / z, -yc / z)
            }
        }
    }

    /// The nominal point and its unit normal (upward, toward the tool).
    pub fn surface(&self, x: f64, y: f64) -> (V3, V3) {
        let (z, zx, zy) = self.height(x, y);
        ([x, y, z], unit([-zx, -zy, 1.0]))
    }

    /// The warp the moulding adds along the normal, mm.
    pub fn warp(&self, x: f64, y: f64) -> f64 {
        let pi = std::f64::consts::PI;
        let (u, v) = (x / self.length, y / self.width);
        self.warp_amplitude
            * (0.6 * (pi * u).sin() * (pi * v).sin()
                + 0.3 * (2.0 * u - 1.0) * (2.0 * v - 1.0)
                + 0.1 * (3.0 * pi * u + 0.3).sin() * (2.0 * pi * v).cos())
    }

    fn raster(&self) -> (usize, usize) {
        (
            (self.length / self.step).round() as usize + 1,
            (self.width / self.step_over).round() as usize + 1,
        )
    }

    fn tool_radius(&self) -> f64 {
        match self.tool {
            Tool::Point => 0.0,
            Tool::Ball { radius } => radius,
        }
    }

    /// The nominal raster program (ISO G-code, mm, 4 decimals): zig-zag
    /// lines along x, one per step-over, the tool's centre (ball) or tip
    /// (point) on the nominal surface.
    pub fn program(&self) -> String {
        let (nx, ny) = self.raster();
        let r = self.tool_radius();
        let mut out = String::with_capacity(nx * ny * 40 + 200);
        out.push_str("%\nO0001 (FORMCAM RASTER FINISHING)\nN10 G21 G90 G17 G94\n");
        out.push_str(&format!(
            "(tool: {} r={r} mm, step {} mm, step-over {} mm)\n",
            if r > 0.0 { "ball" } else { "point" },
            self.step,
            self.step_over
        ));
        let clearance = self
            .height(0.0, 0.0)
            .0
            .max(self.height(self.length, self.width).0)
            + r
            + 20.0;
        for k in 0..ny {
            let y = self.width * k as f64 / (ny - 1) as f64;
            for m in 0..nx {
                let i = if k % 2 == 0 { m } else { nx - 1 - m };
                let x = self.length * i as f64 / (nx - 1) as f64;
                let (p, n) = self.surface(x, y);
                let c = axpy(p, r, n);
                if k == 0 && m == 0 {
                    out.push_str(&format!("G0 X{:.4} Y{:.4} Z{clearance:.4}\n", c[0], c[1]));
                    out.push_str(&format!("G1 Z{:.4} F{}\n", c[2], self.feed));
                } else {
                    out.push_str(&format!("X{:.4} Y{:.4} Z{:.4}\n", c[0], c[1], c[2]));
                }
            }
        }
        out.push_str(&format!("G0 Z{clearance:.4}\nM30\n%\n"));
        out
    }

    /// The part made from a mould milled along the program's `feed` nodes:
    /// the part's surface points on the raster grid (`k * nx + i`, `i` along
    /// x).
    fn part(&self, feed: &[V3]) -> Result<Vec<V3>, CorrectError> {
        let (nx, ny) = self.raster();
        if feed.len() != nx * ny {
            return Err(ScenarioError::Raster {
                feed: feed.len(),
                raster: nx * ny,
            }
            .into());
        }
        let mut centre = vec![[0.0; 3]; nx * ny];
        for (m, p) in feed.iter().enumerate() {
            let (k, mm) = (m / nx, m % nx);
            let i = if k % 2 == 0 { mm } else { nx - 1 - mm };
            centre[k * nx + i] = *p;
        }
        let r = self.tool_radius();
        let mut part = vec![[0.0; 3]; nx * ny];
        for k in 0..ny {
            for i in 0..nx {
                let c = centre[k * nx + i];
                // The mould's surface: the centre surface offset by -r along its normal.
                let q = if r > 0.0 {
                    let du = slope(|a| centre[k * nx + a], i, nx);
                    let dv = slope(|a| centre[a * nx + i], k, ny);
                    axpy(c, -r, unit(cross(du, dv)))
                } else {
                    c
                };
                let x = self.length * i as f64 / (nx - 1) as f64;
                let y = self.width * k as f64 / (ny - 1) as f64;
                let (_, n) = self.surface(x, y);
                part[k * nx + i] = axpy(q, self.warp(x, y), n);
            }
        }
        Ok(part)
    }

    /// Where the line `p + lambda n` meets the part surface (bilinear over the
    /// raster grid): `lambda`, by Newton's method on `(u, v, lambda)`.
    fn probe(&self, part: &[V3], p: V3, n: V3) -> Option<f64> {
        let (nx, ny) = self.raster();
        let mut u = p[0] / self.length * (nx - 1) as f64;
        let mut v = p[1] / self.width * (ny - 1) as f64;
        let mut lambda = 0.0;
        for _ in 0..30 {
            let i = (u.floor().max(0.0) as usize).min(nx - 2);
            let k = (v.floor().max(0.0) as usize).min(ny - 2);
            let (a, b) = (u - i as f64, v - k as f64);
            let p00 = part[k * nx + i];
            let p10 = part[k * nx + i + 1];
            let p01 = part[(k + 1) * nx + i];
            let p11 = part[(k + 1) * nx + i + 1];
            let e0 = sub(p10, p00);
            let e1 = sub(p11, p01);
            let f0 = axpy(p00, a, e0);
            let f1 = axpy(p01, a, e1);
            let f = axpy(f0, b, sub(f1, f0));
            let fu = axpy(e0, b, sub(e1, e0));
            let fv = sub(f1, f0);
            // F(u, v) - (p + lambda n) = 0.
            let r = sub(f, axpy(p, lambda, n));
            if norm(r) < 1e-12 {
                return Some(lambda);
            }
            // Solve [fu fv -n] d = -r by Cramer's rule.
            let m = [fu, fv, scale(n, -1.0)];
            let det = dot(m[0], cross(m[1], m[2]));
            if det.abs() < 1e-300 {
                return None;
            }
            let rhs = scale(r, -1.0);
            let du = dot(rhs, cross(m[1], m[2])) / det;
            let dv = dot(m[0], cross(rhs, m[2])) / det;
            let dl = dot(m[0], cross(m[1], rhs)) / det;
            u = (u + du).clamp(0.0, (nx - 1) as f64);
            v = (v + dv).clamp(0.0, (ny - 1) as f64);
            lambda += dl;
        }
        Some(lambda)
    }

    /// Measures the part: `sections x points` CMM points with noise.
    fn measure(&self, part: &[V3], sections: usize, points: usize, rng: &mut Rng) -> Measurements {
        let mut m = Measurements::default();
        for j in 0..sections {
            let x = self.length * j as f64 / (sections - 1) as f64;
            let mut s = Section {
                name: format!("X{x:.1}"),
                points: Vec::new(),
            };
            for i in 0..points {
                let y = self.width * i as f64 / (points - 1) as f64;
                let (p, n) = self.surface(x, y);
                let d = self.probe(part, p, n).unwrap_or(f64::NAN) + self.noise * rng.gauss();
                s.points.push(MeasuredPoint {
                    point: (i + 1).to_string(),
                    nominal: p,
                    actual: axpy(p, d, n),
                    normal: Some(n),
                });
            }
            m.sections.push(s);
        }
        m
    }

    /// The true deviation of the part along the normal on a check grid of
    /// `count x count` points: `(max |d|, rms)`.
    fn true_error(&self, part: &[V3], count: usize) -> (f64, f64) {
        let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
        for a in 0..count {
            for b in 0..count {
                let x = self.length * a as f64 / (count - 1) as f64;
                let y = self.width * b as f64 / (count - 1) as f64;
                let (p, nn) = self.surface(x, y);
                if let Some(d) = self.probe(part, p, nn) {
                    max = max.max(d.abs());
                    sum += d * d;
                    n += 1;
                }
            }
        }
        (max, (sum / n.max(1) as f64).sqrt())
    }

    /// Corrects a program read by [`feed_nodes`] from `m`; returns its text.
    fn correct(
        &self,
        (program, _): &(MillingProgram, Vec<V3>),
        m: &Measurements,
        options: Options,
        progress: &dyn Progress,
    ) -> Result<String, CorrectError> {
        let mut grid = Grid::from_measurements(m, None)?;
        if self.smoothing {
            smooth(&mut grid, self.noise);
        }
        Ok(Corrector::new(&grid, options)?
            .apply_with(program, None, &Muted(progress))?
            .text)
    }

    /// Runs the loop: measure the part of the nominal program, then
    /// `iterations` times correct, re-mill, mould and measure again.
    pub fn run(&self) -> Result<LoopResult, CorrectError> {
        self.run_with(&Silent)
    }

    /// [`Self::run`] reporting each round to `progress` (which may stop
    /// the loop within a round too: [`CorrectError::Cancelled`]).
    pub fn run_with(&self, progress: &dyn Progress) -> Result<LoopResult, CorrectError> {
        self.validate()?;
        let total = self.iterations as u64 + 1;
        let mut rng = Rng::new(self.seed);
        let mut program = self.program();
        let mut rounds = Vec::new();
        let check = 61;
        for k in 0..=self.iterations {
            progress.checkpoint(Step::new(Phase::Round, k as u64, total))?;
            let read = feed_nodes(&program)?;
            let part = self.part(&read.1)?;
            let m = self.measure(&part, self.sections, self.points, &mut rng);
            let (true_max, true_rms) = self.true_error(&part, check);
            let next = if k < self.iterations {
                Some(self.correct(&read, &m, self.options, progress)?)
            } else {
                None
            };
            rounds.push(Round {
                program,
                measured_max_mm: m.max_deviation(),
                measured_rms_mm: m.rms_deviation(),
                true_max_mm: true_max,
                true_rms_mm: true_rms,
                measurements: m,
            });
            match next {
                Some(p) => program = p,
                None => break,
            }
        }
        progress.checkpoint(Step::new(Phase::Round, total, total))?;
        Ok(LoopResult { rounds })
    }

    /// The true error after one correction for each section count in
    /// `section_counts` (points per section scaled alike) and each
    /// interpolation: how the residual depends on the section spacing.
    pub fn spacing_study(&self, section_counts: &[usize]) -> Result<Vec<SpacingRow>, CorrectError> {
        self.spacing_study_with(section_counts, &Silent)
    }

    /// [`Self::spacing_study`] reporting each correction to `progress`
    /// ([`CorrectError::Cancelled`] when it asks to stop).
    pub fn spacing_study_with(
        &self,
        section_counts: &[usize],
        progress: &dyn Progress,
    ) -> Result<Vec<SpacingRow>, CorrectError> {
        self.validate()?;
        let total = 2 * section_counts.len() as u64;
        progress.checkpoint(Step::new(Phase::Study, 0, total))?;
        let nominal = self.program();
        let read = feed_nodes(&nominal)?;
        let part0 = self.part(&read.1)?;
        let mut rows = Vec::new();
        for &count in section_counts {
            ScenarioField::SectionStudy.check(count as f64)?;
            let points = (((self.points - 1) as f64) * (count - 1) as f64
                / (self.sections - 1).max(1) as f64)
                .round()
                .max(1.0) as usize
                + 1;
            for interpolation in [Interpolation::Bilinear, Interpolation::Bicubic] {
                let mut rng = Rng::new(self.seed);
                let m = self.measure(&part0, count, points, &mut rng);
                let opts = Options {
                    interpolation,
                    ..self.options
                };
                let corrected = self.correct(&read, &m, opts, progress)?;
                let part = self.part(&feed_nodes(&corrected)?.1)?;
                let (max, rms) = self.true_error(&part, 61);
                rows.push(SpacingRow {
                    sections: count,
                    points,
                    spacing_mm: self.length / (count - 1) as f64,
                    interpolation,
                    true_max_mm: max,
                    true_rms_mm: rms,
                });
                progress.checkpoint(Step::new(Phase::Study, rows.len() as u64, total))?;
            }
        }
        Ok(rows)
    }
}

/// Reads a program of the loop: the program and its feed nodes.
fn feed_nodes(text: &str) -> Result<(MillingProgram, Vec<V3>), CorrectError> {
    let program = MillingProgram::gcode(
        text,
        ToolpathOptions {
            dialect: Dialect::Iso,
            arc_tolerance_mm: crate::DEFAULT_ARC_TOLERANCE_MM,
            max_segment_mm: None,
        },
    )?;
    let feed = program
        .positions()
        .into_iter()
        .zip(program.movable())
        .filter(|(_, m)| *m)
        .map(|(p, _)| p)
        .collect();
    Ok((program, feed))
}

/// The slope of a sequence at `k` of `n` (`n >= 2`): central differences,
/// second-order one-sided ones at the ends.
fn slope(at: impl Fn(usize) -> V3, k: usize, n: usize) -> V3 {
    if n < 3 {
        return sub(at(1), at(0));
    }
    let comb = |a: V3, b: V3, c: V3, w: [f64; 3]| {
        [0, 1, 2].map(|x| (w[0] * a[x] + w[1] * b[x] + w[2] * c[x]) / 2.0)
    };
    if k == 0 {
        comb(at(0), at(1), at(2), [-3.0, 4.0, -1.0])
    } else if k == n - 1 {
        comb(at(n - 1), at(n - 2), at(n - 3), [3.0, -4.0, 1.0])
    } else {
        scale(sub(at(k + 1), at(k - 1)), 0.5)
    }
}

/// One round of the loop.
#[derive(Debug, Clone)]
pub struct Round {
    /// The program milled in this round.
    pub program: String,
    /// What the CMM measured on its part.
    pub measurements: Measurements,
    /// Largest measured deviation, mm.
    pub measured_max_mm: f64,
    /// RMS measured deviation, mm.
    pub measured_rms_mm: f64,
    /// Largest true deviation on the check grid, mm.
    pub true_max_mm: f64,
    /// RMS true deviation on the check grid, mm.
    pub true_rms_mm: f64,
}

/// The rounds of a loop: round 0 is the nominal program.
#[derive(Debug, Clone)]
pub struct LoopResult {
    /// The rounds in order.
    pub rounds: Vec<Round>,
}

/// One row of the spacing study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpacingRow {
    /// Control sections.
    pub sections: usize,
    /// Points per section.
    pub points: usize,
    /// Distance between sections, mm.
    pub spacing_mm: f64,
    /// The interpolation.
    pub interpolation: Interpolation,
    /// Largest true deviation after one correction, mm.
    pub true_max_mm: f64,
    /// RMS true deviation after one correction, mm.
    pub true_rms_mm: f64,
}

/// A small deterministic generator (SplitMix64) with Gaussian samples.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal sample (Box–Muller).
    fn gauss(&mut self) -> f64 {
        let (a, b) = (self.next_f64(), self.next_f64());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario() -> Scenario {
        Scenario {
            shape: Shape::Panel {
                radius_x: 800.0,
                radius_y: 600.0,
            },
            length: 200.0,
            width: 150.0,
            tool: Tool::Ball { radius: 6.0 },
            step_over: 3.0,
            step: 2.0,
            feed: 2000.0,
            warp_amplitude: 0.4,
            sections: 11,
            points: 11,
            noise: 0.0,
            smoothing: false,
            seed: 7,
            iterations: 2,
            options: Options {
                margin_mm: 1.0,
                ..Options::default()
            },
        }
    }

    #[test]
    fn with_no_warp_the_part_is_the_nominal_surface() {
        let s = Scenario {
            warp_amplitude: 0.0,
            iterations: 0,
            ..scenario()
        };
        let r = s.run().unwrap();
        // What is left is the model's chord sag between raster nodes,
        // h^2 / (8 R) along x and y (2 mm on R 800, 3 mm on R 600), plus
        // 4-decimal coordinates.
        let sag = 2.0f64.powi(2) / (8.0 * 800.0) + 3.0f64.powi(2) / (8.0 * 600.0);
        let e = r.rounds[0].true_max_mm;
        assert!(e < sag + 1e-4 && e > 0.5 * sag, "{e} vs sag {sag}");
    }

    #[test]
    fn the_loop_converges() {
        let r = scenario().run().unwrap();
        let e: Vec<f64> = r.rounds.iter().map(|r| r.true_max_mm).collect();
        assert!(e[0] > 0.25, "{e:?}");
        assert!(e[1] < 0.1 * e[0], "{e:?}");
        assert!(e[2] <= e[1] + 1e-4, "{e:?}");
    }
}
