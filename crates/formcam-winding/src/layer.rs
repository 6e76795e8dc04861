//! One layer: the pass, the pattern of circuits and the layer report.

use std::f64::consts::{FRAC_PI_2, TAU};

use formcam_geom::Meridian;
use serde::Serialize;

use crate::circuit::{PassPath, Turnaround};
use crate::friction::friction_turns;
use crate::minimax::{bridging_limit, minimax};
use crate::path::{PassEnd, TANGENT_ALPHA_TOL, TraceOptions, trace};
use crate::pattern::{Pattern, PatternRequest, choose_pattern};
use crate::shooting::{Shot, shoot};
use crate::{MuLaw, MuSegment, PathPoint, ShootingFault, WindingError};

/// How the slippage of the path is chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum Slippage {
    /// `mu = 0`: geodesic, `r sin(alpha) = C` constant.
    Geodesic,
    /// A given constant `mu`.
    Constant(f64),
    /// The constant `mu` that meets both polar openings (shooting); falls back to
    /// [`Slippage::Minimax`] when that path would bridge a concave part.
    Auto,
    /// Piecewise-constant `mu(z)` given by the user.
    Segments(Vec<MuSegment>),
    /// The smallest worst-case `|mu|` under the bridging limit (eqs. 5–6).
    Minimax,
}

/// Where a pass starts and ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ends {
    /// A closed mandrel: the pass turns at the polar openings of these radii (mm)
    /// (design radii; a polar boss may make the meridian end a little wider).
    Poles {
        /// Opening at `z_start`, mm.
        start: f64,
        /// Opening at `z_end`, mm.
        end: f64,
    },
    /// A tube: the pass runs from `z_start` to `z_end` at the given angle at `z_start`
    /// and the machine turns it around beyond the ends (a dwell of the mandrel).
    Tube {
        /// Winding angle at `z_start`, rad.
        winding_angle: f64,
    },
}

/// How a tube's pass turns at the tube's ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TubeTurn {
    /// The pass runs off the tube's ends and the machine turns the band on the
    /// tube's extension (a dwell of the mandrel).
    #[default]
    Extension,
    /// The pass turns on the tube itself, held by friction: the slippage
    /// ([`Slippage::Constant`]) is the `|mu|` of the turns, the pass is geodesic
    /// between them.
    Friction,
}

/// Everything that defines a layer besides the mandrel.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerSpec {
    /// How the path's slippage is chosen.
    pub slippage: Slippage,
    /// Where passes start and end.
    pub ends: Ends,
    /// Band width, mm.
    pub band_width: f64,
    /// Band thickness, mm.
    pub band_thickness: f64,
    /// Overlap of neighbouring bands, fraction of the band width.
    pub overlap: f64,
    /// Required pattern number.
    pub pattern_number: Option<u32>,
    /// Required skip index.
    pub skip_index: Option<u32>,
    /// Least dwell at each turn-around, rad (tubes need room to turn the band).
    pub dwell_min: f64,
    /// Largest slippage the band and resin can hold (bounds `auto` and `minimax`).
    pub mu_limit: f64,
    /// Points in the sampled pass.
    pub samples: usize,
    /// Grid intervals of the minimax search.
    pub minimax_nodes: usize,
    /// Tubes: where the pass turns.
    pub turnaround: TubeTurn,
}

impl Default for LayerSpec {
    fn default() -> Self {
        Self {
            slippage: Slippage::Geodesic,
            ends: Ends::Poles {
                start: 0.0,
                end: 0.0,
            },
            band_width: 10.0,
            band_thickness: 0.5,
            overlap: 0.0,
            pattern_number: None,
            skip_index: None,
            dwell_min: 0.0,
            mu_limit: 0.6,
            samples: 2001,
            minimax_nodes: 4000,
            turnaround: TubeTurn::Extension,
        }
    }
}

/// Which method produced the pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Clairaut's relation, integrated as a geodesic.
    Geodesic,
    /// A given constant or piecewise slippage.
    GivenSlippage,
    /// Shooting on a constant slippage.
    Shooting,
    /// The minimax direct search of eqs. 5–6.
    Minimax,
    /// A tube's geodesic with turn-arounds held by friction at both ends.
    FrictionTurn,
}

/// What one pass is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassSummary {
    /// Method used.
    pub method: Method,
    /// The constant slippage (geodesic, given or shot), or `None` for variable `mu`.
    pub mu: Option<f64>,
    /// Worst `|mu|` along the pass.
    pub mu_max_abs: f64,
    /// Minimax: the least worst-case `|mu|` of any path between the openings (the
    /// pass is laid at it, or a hair above where only a path grazing a
    /// turn-around would reach it).
    pub mu_optimal: Option<f64>,
    /// Where the pass starts.
    pub start: PassEnd,
    /// Where the pass ends.
    pub end: PassEnd,
    /// Path length on the mandrel, mm.
    pub length_mm: f64,
    /// Turn angle on the mandrel, rad.
    pub turn_angle_surface_rad: f64,
    /// Turn angle added where the path leaves the meridian with `alpha < pi/2` at a
    /// polar boss (a straight geodesic on the boss face up to the turn), rad.
    pub turn_angle_boss_rad: f64,
    /// Shooting: residual of the far boundary condition, mm.
    pub boundary_residual_mm: Option<f64>,
    /// Shooting: passes integrated.
    pub shooting_evaluations: Option<usize>,
    /// Minimax: `z` intervals (mm) where the bridging limit is active.
    pub bridging_active: Vec<(f64, f64)>,
    /// Smallest margin `C - C_b` to the bridging limit on concave parts, mm (None if convex).
    pub bridging_margin_mm: Option<f64>,
}

/// The layer report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LayerReport {
    /// Winding angle at the equator (the widest parallel), rad.
    pub alpha_equator_rad: f64,
    /// `z` of that parallel, mm.
    pub z_equator: f64,
    /// Turn angle of one pass, boss included, dwell excluded, rad.
    pub turn_angle_pass_rad: f64,
    /// Turn angle of one circuit (two passes), dwell excluded, rad.
    pub turn_angle_circuit_rad: f64,
    /// Turn angle of one circuit with the pattern's dwell, rad.
    pub turn_angle_circuit_with_dwell_rad: f64,
    /// Dwell per circuit, degrees.
    pub dwell_deg: f64,
    /// Dwell at each turn-around, degrees.
    pub dwell_per_turnaround_deg: f64,
    /// Fibre length of one pass, mm.
    pub pass_length_mm: f64,
    /// Fibre (band) length of one circuit, dwell arcs included, mm.
    pub circuit_length_mm: f64,
    /// Band length of the whole layer, mm.
    pub fibre_length_mm: f64,
    /// Layer thickness at the equator (two plies, +alpha and -alpha), mm.
    pub thickness_equator_mm: f64,
    /// Largest layer thickness along the meridian (capped one band width from the turn), mm.
    pub thickness_max_mm: f64,
}

/// A planned layer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layer {
    /// The pass, sampled.
    #[serde(skip)]
    pub points: Vec<PathPoint>,
    /// Band thickness of the layer at each sample, mm.
    #[serde(skip)]
    pub thickness: Vec<f64>,
    /// The pass.
    pub pass: PassSummary,
    /// The pattern.
    pub pattern: Pattern,
    /// The report.
    pub report: LayerReport,
    /// Things the user should know.
    pub warnings: Vec<String>,
    /// The pass, for evaluation anywhere (the circuit and the eye use it).
    #[serde(skip)]
    pub pass_path: PassPath,
    /// Whether the mandrel is a tube (turn-arounds off the winding zone).
    #[serde(skip)]
    pub tube: bool,
}

fn check_spec(spec: &LayerSpec, (za, zb): (f64, f64)) -> Result<(), WindingError> {
    let pos = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(WindingError::field(
                field,
                format!("must be a finite number > 0, got {v}"),
            ))
        }
    };
    pos("winding.band_width", spec.band_width)?;
    pos("winding.band_thickness", spec.band_thickness)?;
    pos("winding.mu_limit", spec.mu_limit)?;
    if !(spec.dwell_min.is_finite() && spec.dwell_min >= 0.0) {
        return Err(WindingError::field("winding.dwell_min_deg", "must be >= 0"));
    }
    if let Slippage::Constant(m) = spec.slippage
        && (!m.is_finite() || m.abs() > spec.mu_limit)
    {
        {
            return Err(WindingError::field(
                "winding.mu",
                format!(
                    "must be a number with |mu| <= mu_limit ({}), got {m}",
                    spec.mu_limit
                ),
            ));
        }
    }
    if let Slippage::Segments(segs) = &spec.slippage {
        for (i, s) in segs.iter().enumerate() {
            let f = format!("winding.mu_segments[{i}]");
            if !(s.z_from.is_finite() && s.z_to.is_finite() && s.z_from < s.z_to) {
                return Err(WindingError::field(f, "needs finite z_from < z_to"));
            }
            if s.z_to <= za || s.z_from >= zb {
                return Err(WindingError::field(
                    f,
                    format!(
                        "[{}, {}] lies outside the mandrel [{za:.3}, {zb:.3}] mm",
                        s.z_from, s.z_to
                    ),
                ));
            }
            if let Some(prev) = i.checked_sub(1).and_then(|j| segs.get(j))
                && s.z_from < prev.z_to
            {
                return Err(WindingError::field(
                    f,
                    format!(
                        "starts at {} mm, inside the previous segment (to {} mm): segments must be in \
                         order of z and must not overlap",
                        s.z_from, prev.z_to
                    ),
                ));
            }
            if !s.mu.is_finite() || s.mu.abs() > spec.mu_limit {
                return Err(WindingError::field(
                    format!("{f}.mu"),
                    format!("must satisfy |mu| <= mu_limit ({})", spec.mu_limit),
                ));
            }
        }
    }
    if spec.turnaround == TubeTurn::Friction {
        if !matches!(spec.ends, Ends::Tube { .. }) {
            return Err(WindingError::field(
                "winding.turnaround",
                "\"friction\" turns a tube's pass on the tube; a mandrel with polar openings turns there",
            ));
        }
        if !matches!(spec.slippage, Slippage::Constant(m) if m > 0.0) {
            return Err(WindingError::field(
                "winding.mu",
                "with turnaround = \"friction\" give the slippage the turns use, a number > 0",
            ));
        }
    }
    if let Ends::Tube { winding_angle } = spec.ends
        && !(winding_angle > 0.0 && winding_angle < FRAC_PI_2)
    {
        {
            return Err(WindingError::field(
                "winding.winding_angle_deg",
                format!(
                    "must be in (0, 90) degrees, got {}",
                    winding_angle.to_degrees()
                ),
            ));
        }
    }
    Ok(())
}

/// Points of the dense sampling behind the report (equator, thickness, bridging).
const DENSE: usize = 4001;

/// How far before the far opening a turn still counts as at the opening, mm.
const FAR_TOL_MM: f64 = 1e-3;

/// The job field that sets the slippage.
fn slippage_field(s: &Slippage) -> &'static str {
    match s {
        Slippage::Segments(_) => "winding.mu_segments",
        _ => "winding.mu",
    }
}

/// Smallest `C - C_b` on concave parts and the first `z` where it is negative.
fn bridging_margin(m: &impl Meridian, pts: &[PathPoint]) -> (Option<f64>, Option<f64>) {
    let mut margin: Option<f64> = None;
    let mut first_bad = None;
    for p in pts {
        let j = m.eval(p.z);
        if j.d2r > 0.0 {
            let d = p.c - bridging_limit(&j);
            margin = Some(margin.map_or(d, |m: f64| m.min(d)));
            if d < -1e-9 * j.r && first_bad.is_none() {
                first_bad = Some(p.z);
            }
        }
    }
    (margin, first_bad)
}

/// Plans one layer on mandrel `m`.
pub fn plan_layer<M: Meridian>(m: &M, spec: &LayerSpec) -> Result<Layer, WindingError> {
    check_spec(spec, m.z_range())?;
    let tube = matches!(spec.ends, Ends::Tube { .. });
    let friction = spec.turnaround == TubeTurn::Friction;
    let mut warnings = Vec::new();
    let mut choice = choose_method(m, spec, friction, &mut warnings)?;
    let laid = lay_pass(m, spec, friction, &mut choice, &mut warnings)?;
    let last = *laid
        .points
        .last()
        .ok_or_else(|| WindingError::field("winding.samples", "no points"))?;
    check_far_end(m, spec, friction, laid.end)?;
    let turn = pass_turn(m, spec, &laid, &last);
    let eq = equator(&laid.dense);
    let pattern = choose_pattern(&PatternRequest {
        band_width: spec.band_width,
        overlap: spec.overlap,
        radius: eq.r,
        alpha: eq.alpha,
        natural_turn: 2.0 * turn.total(),
        dwell_min: 2.0 * spec.dwell_min,
        pattern_number: spec.pattern_number,
        skip_index: spec.skip_index,
    })?;
    let circuit_len = circuit_length(m, &laid, &last, &pattern, tube);
    let n = f64::from(pattern.circuits);
    let (thickness, thickness_max) = thickness(m, spec, &laid, &eq, n, !tube || friction);
    let pass = pass_summary(m, &choice, &laid, &last, &turn);
    let report = layer_report(spec, &eq, &turn, &pattern, circuit_len, thickness_max);
    Ok(Layer {
        points: laid.points,
        thickness,
        pass,
        pattern,
        report,
        warnings,
        pass_path: laid.pass_path,
        tube,
    })
}

/// The method chosen for a layer, the slippage law and start angle of its pass.
struct Choice {
    method: Method,
    law: MuLaw,
    /// Winding angle at `z_start`, rad.
    alpha0: f64,
    /// The shot pass of `mu = "auto"`.
    shot: Option<Shot>,
    /// The minimax search's figures.
    minimax: Option<MinimaxFigures>,
}

/// What the minimax search reports besides its path.
struct MinimaxFigures {
    /// The worst `|mu|` of the path laid.
    mu_path: f64,
    /// The least worst-case `|mu|` of any path.
    mu_max: f64,
    /// `z` intervals (mm) where the bridging limit is active.
    bridging_active: Vec<(f64, f64)>,
}

/// The pass laid: the dense sampling behind the report, the points asked for,
/// the pass for evaluation anywhere and its ends.
struct Laid {
    dense: Vec<PathPoint>,
    points: Vec<PathPoint>,
    pass_path: PassPath,
    start: PassEnd,
    end: PassEnd,
}

/// Turn angles of one pass and its fibre length.
struct PassTurn {
    /// On the mandrel's surface, rad.
    surface: f64,
    /// Added at polar bosses where the path leaves the meridian below 90°, rad.
    boss: f64,
    /// Fibre length of the pass, the bosses' faces included, mm.
    length: f64,
}

impl PassTurn {
    /// The turn of one pass, boss included, rad.
    fn total(&self) -> f64 {
        self.surface + self.boss
    }
}

/// Chooses the method from the slippage asked for and the pass's ends: the law
/// and the start angle, shooting `mu = "auto"` (minimax where no constant
/// slippage turns at both ends) and a tube's friction turns.
fn choose_method<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    warnings: &mut Vec<String>,
) -> Result<Choice, WindingError> {
    let (za, _) = m.z_range();
    let mut shot = None;
    let (method, law, alpha0) = match (&spec.slippage, spec.ends) {
        (Slippage::Constant(mu), Ends::Tube { winding_angle }) if friction => {
            let turns = friction_turns(m, *mu, winding_angle, spec.mu_limit)?;
            (Method::FrictionTurn, turns.law, FRAC_PI_2)
        }
        (Slippage::Auto | Slippage::Minimax, Ends::Tube { .. }) => {
            return Err(WindingError::field(
                "winding.mu",
                "\"auto\" and \"minimax\" need a mandrel with polar openings; give a number for a tube",
            ));
        }
        (Slippage::Geodesic, Ends::Poles { start, end }) => {
            if (start - end).abs() > 1e-9 * start.max(end) {
                return Err(WindingError::infeasible(
                    "winding.mu",
                    format!(
                        "a geodesic (mu = 0) needs equal polar openings, these are {start} and {end} mm; \
                         use mu = \"auto\""
                    ),
                ));
            }
            // The path is tangent to the opening when the meridian starts at it; compare
            // with a tolerance, since asin near 1 turns a rounding error of 1e-16 into 1e-8.
            let a0 = (start / m.r(za)).clamp(-1.0, 1.0).asin();
            // Within a hair of tangent is tangent, as at the far end (see `trace`).
            let a0 = if a0 > FRAC_PI_2 - TANGENT_ALPHA_TOL {
                FRAC_PI_2
            } else {
                a0
            };
            (Method::Geodesic, MuLaw::Constant(0.0), a0)
        }
        (Slippage::Geodesic, Ends::Tube { winding_angle }) => {
            (Method::Geodesic, MuLaw::Constant(0.0), winding_angle)
        }
        (Slippage::Constant(mu), Ends::Poles { .. }) => {
            (Method::GivenSlippage, MuLaw::Constant(*mu), FRAC_PI_2)
        }
        (Slippage::Constant(mu), Ends::Tube { winding_angle }) => {
            (Method::GivenSlippage, MuLaw::Constant(*mu), winding_angle)
        }
        (Slippage::Segments(s), Ends::Poles { .. }) => {
            (Method::GivenSlippage, MuLaw::Segments(s.clone()), FRAC_PI_2)
        }
        (Slippage::Segments(s), Ends::Tube { winding_angle }) => (
            Method::GivenSlippage,
            MuLaw::Segments(s.clone()),
            winding_angle,
        ),
        (Slippage::Auto, Ends::Poles { .. }) => match shoot(m, spec.mu_limit) {
            Ok(s) => {
                let mu = s.mu;
                shot = Some(s);
                (Method::Shooting, MuLaw::Constant(mu), FRAC_PI_2)
            }
            Err(e) => {
                warnings.push(format!(
                    "no constant slippage turns this shell at both ends (shooting: {e}); \
                     the minimax search was used instead"
                ));
                (Method::Minimax, MuLaw::Constant(0.0), FRAC_PI_2)
            }
        },
        (Slippage::Minimax, Ends::Poles { .. }) => {
            (Method::Minimax, MuLaw::Constant(0.0), FRAC_PI_2)
        }
    };
    Ok(Choice {
        method,
        law,
        alpha0,
        shot,
        minimax: None,
    })
}

/// Lays the pass of the chosen method: traced (and checked for bridging, where
/// `mu = "auto"` falls back to minimax) or the minimax search's path.
fn lay_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    choice: &mut Choice,
    warnings: &mut Vec<String>,
) -> Result<Laid, WindingError> {
    if choice.method != Method::Minimax {
        let laid = traced_pass(m, spec, friction, choice)?;
        let (_, bad) = bridging_margin(m, &laid.dense);
        let Some(zbad) = bad else {
            return Ok(laid);
        };
        if spec.slippage != Slippage::Auto {
            return Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the band bridges (lifts off the concave surface) at z = {zbad:.3} mm; \
                     use mu = \"minimax\""
                ),
            ));
        }
        warnings.push(format!(
            "the constant-mu path bridges the concave meridian at z = {zbad:.3} mm; the minimax \
             search was used instead"
        ));
        choice.method = Method::Minimax;
    }
    minimax_pass(m, spec, choice)
}

/// The pass traced in path length (the shot pass of `auto` as it is), sampled
/// densely for the report and as the job asks.
fn traced_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    choice: &Choice,
) -> Result<Laid, WindingError> {
    let (za, _) = m.z_range();
    let samples = spec.samples.max(2);
    let law = &choice.law;
    let tr = match &choice.shot {
        Some(s) => s.trace.clone(),
        None if friction => {
            // A tighter tolerance than a plain pass: the far turn must land on
            // the tube's end, which the error gathered over the pass would move.
            let mut opts = TraceOptions::default();
            opts.tol.rtol = 3e-15;
            opts.tol.atol = 3e-15;
            trace(m, law, choice.alpha0, &opts)?
        }
        None => trace(m, law, choice.alpha0, &TraceOptions::default())?,
    };
    let dense = tr.sample(m, law, samples.max(DENSE));
    let points = if samples >= DENSE {
        dense.clone()
    } else {
        tr.sample(m, law, samples)
    };
    let start = if choice.alpha0 < FRAC_PI_2 {
        PassEnd::Exit {
            z: za,
            alpha: choice.alpha0,
        }
    } else {
        PassEnd::TurnAround { z: za }
    };
    let end = tr.end;
    Ok(Laid {
        dense,
        points,
        pass_path: PassPath::Traced(tr),
        start,
        end,
    })
}

/// The minimax search's pass (eqs. 5–6), turning at both openings; notes its
/// slippage figures in `choice` and drops the shot pass.
fn minimax_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    choice: &mut Choice,
) -> Result<Laid, WindingError> {
    let (za, zb) = m.z_range();
    let mm = minimax(m, spec.minimax_nodes, spec.mu_limit).map_err(|e| {
        if spec.slippage == Slippage::Auto && choice.shot.is_none() {
            WindingError::shooting(ShootingFault::NorMinimax {
                mu_limit: spec.mu_limit,
                minimax: Box::new(e),
            })
        } else {
            e
        }
    })?;
    let dense = mm.points(m);
    let points = resample(&dense, spec.samples.max(2));
    choice.minimax = Some(MinimaxFigures {
        mu_path: mm.mu_path,
        mu_max: mm.mu_max,
        bridging_active: mm.bridging_active,
    });
    choice.shot = None;
    Ok(Laid {
        pass_path: PassPath::Points(dense.clone()),
        dense,
        points,
        start: PassEnd::TurnAround { z: za },
        end: PassEnd::TurnAround { z: zb },
    })
}

/// Checks that the pass ends where the mandrel asks: at a tube's end, at the far
/// polar opening (not before it, not leaving the mandrel there).
fn check_far_end<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    end: PassEnd,
) -> Result<(), WindingError> {
    let (_, zb) = m.z_range();
    match (spec.ends, end) {
        (Ends::Tube { .. }, PassEnd::TurnAround { z })
            if friction && (z - zb).abs() <= FAR_TOL_MM => {}
        (Ends::Tube { .. }, PassEnd::TurnAround { z }) if friction => {
            return Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the pass with friction turn-arounds turns at z = {z:.6} mm instead of the tube's \
                     end ({zb:.6} mm)"
                ),
            ));
        }
        (Ends::Tube { .. }, PassEnd::TurnAround { z }) => {
            return Err(WindingError::infeasible(
                "winding.winding_angle_deg",
                format!(
                    "the path turns at z = {z:.3} mm before the tube's end ({zb:.3} mm); lower the \
                     winding angle or the slippage"
                ),
            ));
        }
        (Ends::Poles { .. }, PassEnd::TurnAround { z }) if z < zb - FAR_TOL_MM => {
            return Err(WindingError::infeasible(
                slippage_field(&spec.slippage),
                format!(
                    "the pass turns at z = {z:.3} mm, before the far polar opening at {zb:.3} mm; \
                     use mu = \"auto\" to meet both openings"
                ),
            ));
        }
        (Ends::Poles { end: opening, .. }, PassEnd::Exit { alpha, .. })
            if m.r(zb) - opening <= 1e-6 * m.r(zb) =>
        {
            return Err(WindingError::infeasible(
                slippage_field(&spec.slippage),
                format!(
                    "the band reaches the far polar opening at a winding angle of {:.2} deg and would \
                     leave the mandrel there; use mu = \"auto\" to meet both openings",
                    alpha.to_degrees()
                ),
            ));
        }
        _ => {}
    }
    Ok(())
}

/// The turn angles of one pass (on the surface, and at polar bosses where the
/// path leaves the meridian below 90°) and its length with the bosses' faces.
fn pass_turn<M: Meridian>(m: &M, spec: &LayerSpec, laid: &Laid, last: &PathPoint) -> PassTurn {
    let (za, zb) = m.z_range();
    let poles = matches!(spec.ends, Ends::Poles { .. });
    let boss = if poles {
        let mut b = 0.0;
        if let PassEnd::Exit { alpha, .. } = laid.start {
            b += FRAC_PI_2 - alpha;
        }
        if let PassEnd::Exit { alpha, .. } = laid.end {
            b += FRAC_PI_2 - alpha;
        }
        b
    } else {
        0.0
    };
    let boss_len = |pe: &PassEnd, r: f64| match pe {
        PassEnd::Exit { alpha, .. } if poles => r * alpha.cos(),
        _ => 0.0,
    };
    PassTurn {
        surface: last.v,
        boss,
        length: last.s + boss_len(&laid.start, m.r(za)) + boss_len(&laid.end, m.r(zb)),
    }
}

/// The parallel the pattern must cover: the widest, or, where the pass turns on
/// it (a tube turned by friction, a shell whose ends flare), the parallel the
/// bands cross most widely (largest `r cos(alpha)`).
fn equator(dense: &[PathPoint]) -> PathPoint {
    let widest = dense
        .iter()
        .copied()
        .fold(dense[0], |a, p| if p.r > a.r { p } else { a });
    if widest.alpha >= FRAC_PI_2 - TANGENT_ALPHA_TOL {
        let across = |p: &PathPoint| p.r * p.alpha.cos();
        dense
            .iter()
            .copied()
            .fold(dense[0], |a, p| if across(&p) > across(&a) { p } else { a })
    } else {
        widest
    }
}

/// The band length of one circuit: two passes and the turn-arounds (see
/// `circuit`: the band laid while the mandrel dwells, and at a boss the rest of
/// the turn).
fn circuit_length<M: Meridian>(
    m: &M,
    laid: &Laid,
    last: &PathPoint,
    pattern: &Pattern,
    tube: bool,
) -> f64 {
    let dwell_end = 0.5 * pattern.dwell_rad;
    let far = Turnaround::new(m, &laid.end, dwell_end, tube, true);
    let near = Turnaround::new(m, &laid.start, dwell_end, tube, false);
    2.0 * last.s + far.length() + near.length()
}

/// Layer thickness of two plies, `n` bands of width `b` across a parallel of
/// circumference `2 pi r` at angle `alpha`, mm.
fn ply_thickness(spec: &LayerSpec, n: f64, r: f64, alpha: f64) -> f64 {
    2.0 * spec.band_thickness * n * spec.band_width / (TAU * r * alpha.cos().max(1e-12))
}

/// The thickness at the points asked for and the largest along the dense pass.
/// Near a turn-around `cos(alpha) -> 0` and the formula diverges: within one
/// band width of the turn radius it is held at its value one band width out
/// (`turns_on_mandrel`: false for a tube turned beyond its ends).
fn thickness<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    laid: &Laid,
    eq: &PathPoint,
    n: f64,
    turns_on_mandrel: bool,
) -> (Vec<f64>, f64) {
    let (za, zb) = m.z_range();
    let dense = &laid.dense;
    // The cap of each end: the thickness where the path first (from that end) is a
    // band width above its turn radius, held constant towards the turn; where the
    // meridian does not narrow towards the end (a tube turned by friction, a
    // flaring end), where the path is a band width from the turn along the meridian.
    let full = |p: &PathPoint| ply_thickness(spec, n, p.r, p.alpha);
    let cap_of = |mut it: Box<dyn Iterator<Item = &PathPoint> + '_>, narrows: bool| {
        let first = it.next().copied()?;
        if narrows {
            let reach = (first.c + spec.band_width).min(eq.r);
            it.find(|p| p.r >= reach).map(|p| (p.z, full(p)))
        } else {
            it.find(|p| (p.z - first.z).hypot(p.r - first.r) >= spec.band_width)
                .map(|p| (p.z, full(p)))
        }
    };
    let start_cap = if turns_on_mandrel {
        cap_of(Box::new(dense.iter()), m.dr(za) > 0.0)
    } else {
        None
    };
    let end_cap = if turns_on_mandrel {
        cap_of(Box::new(dense.iter().rev()), m.dr(zb) < 0.0)
    } else {
        None
    };
    let thick = |p: &PathPoint| match (start_cap, end_cap) {
        (Some((z, t)), _) if p.z < z => t,
        (_, Some((z, t))) if p.z > z => t,
        _ => full(p),
    };
    let thickness: Vec<f64> = laid.points.iter().map(thick).collect();
    let thickness_max = dense.iter().map(thick).fold(0.0, f64::max);
    (thickness, thickness_max)
}

/// What the pass is: method, slippage, ends, length, turn angles, the shooting
/// and minimax figures, the margin to the bridging limit.
fn pass_summary<M: Meridian>(
    m: &M,
    choice: &Choice,
    laid: &Laid,
    last: &PathPoint,
    turn: &PassTurn,
) -> PassSummary {
    let (mu, mu_max_abs) = match (choice.method, &choice.law) {
        (Method::Minimax, _) => (None, choice.minimax.as_ref().map_or(0.0, |x| x.mu_path)),
        (_, MuLaw::Constant(mu)) => (Some(*mu), mu.abs()),
        (_, l) => (None, l.max_abs()),
    };
    let (bridging_margin_mm, _) = bridging_margin(m, &laid.dense);
    let shot = choice.shot.as_ref();
    PassSummary {
        method: choice.method,
        mu,
        mu_max_abs,
        mu_optimal: choice.minimax.as_ref().map(|x| x.mu_max),
        start: laid.start,
        end: laid.end,
        length_mm: last.s,
        turn_angle_surface_rad: turn.surface,
        turn_angle_boss_rad: turn.boss,
        boundary_residual_mm: shot.map(|s| s.residual_mm),
        shooting_evaluations: shot.map(|s| s.evaluations),
        bridging_active: choice
            .minimax
            .as_ref()
            .map(|x| x.bridging_active.clone())
            .unwrap_or_default(),
        bridging_margin_mm,
    }
}

/// The layer report: equator, turn angles with and without dwell, lengths,
/// thickness.
fn layer_report(
    spec: &LayerSpec,
    eq: &PathPoint,
    turn: &PassTurn,
    pattern: &Pattern,
    circuit_len: f64,
    thickness_max: f64,
) -> LayerReport {
    let n = f64::from(pattern.circuits);
    let turn_circuit = 2.0 * turn.total();
    LayerReport {
        alpha_equator_rad: eq.alpha,
        z_equator: eq.z,
        turn_angle_pass_rad: turn.total(),
        turn_angle_circuit_rad: turn_circuit,
        turn_angle_circuit_with_dwell_rad: turn_circuit + pattern.dwell_rad,
        dwell_deg: pattern.dwell_rad.to_degrees(),
        dwell_per_turnaround_deg: 0.5 * pattern.dwell_rad.to_degrees(),
        pass_length_mm: turn.length,
        circuit_length_mm: circuit_len,
        fibre_length_mm: n * circuit_len,
        thickness_equator_mm: ply_thickness(spec, n, eq.r, eq.alpha),
        thickness_max_mm: thickness_max,
    }
}

/// `n` points evenly spaced in path length, interpolated linearly between the
/// points of a dense path (the minimax grid), ends kept exactly.
fn resample(pts: &[PathPoint], n: usize) -> Vec<PathPoint> {
    let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
        return Vec::new();
    };
    let total = last.s;
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    for k in 0..n {
        let s = total * k as f64 / (n - 1).max(1) as f64;
        while i + 2 < pts.len() && pts[i + 1].s < s {
            i += 1;
        }
        let p = if k == 0 {
            *first
        } else if k + 1 == n {
            *last
        } else {
            let (a, b) = (pts[i], pts[(i + 1).min(pts.len() - 1)]);
            let t = if b.s > a.s {
                ((s - a.s) / (b.s - a.s)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let lerp = |x: f64, y: f64| x + t * (y - x);
            PathPoint {
                s,
                z: lerp(a.z, b.z),
                r: lerp(a.r, b.r),
                v: lerp(a.v, b.v),
                alpha: lerp(a.alpha, b.alpha),
                c: lerp(a.c, b.c),
                mu: if t < 0.5 { a.mu } else { b.mu },
            }
        };
        out.push(p);
    }
    out
}
