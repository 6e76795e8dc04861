//! The tables' descriptions for `formcam-schema`: every field's type, unit,
//! range, default and help. The job's reader validates against them before
//! serde, and `docs/winding.md` lists them.

use std::ops::RangeInclusive;

use formcam_schema::{
    Condition, Default as Given, Field, Kind, Range, Repeat, Table, Unit, Value, field,
};

use super::{DomeKind, MandrelKind};
use crate::eye::{
    DEFAULT_CLEARANCE_MM, DEFAULT_NODES, DEFAULT_SAMPLES, NODE_COUNTS, SAMPLE_COUNTS,
};

const fn when(field: &'static str, words: &'static [&'static str]) -> Given {
    Given::RequiredWhen(Condition::Is { field, words })
}

const POSITIVE: Option<Range> = Some(Range::above(0.0));
const NOT_NEGATIVE: Option<Range> = Some(Range::at_least(0.0));

/// The fields of `[mandrel]`.
pub const MANDREL_FIELDS: &[Field] = &[
    field(
        "kind",
        Kind::Word(MandrelKind::NAMES),
        Unit::None,
        None,
        Given::Required,
        "the mandrel's shape",
    ),
    field(
        "radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cylinder", "vessel"]),
        "a cylinder's radius; a vessel's cylinder radius",
    ),
    field(
        "length",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cylinder", "cone"]),
        "a tube's length",
    ),
    field(
        "radius_start",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cone"]),
        "a cone's radius at `z = 0`",
    ),
    field(
        "radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cone"]),
        "a cone's radius at `z = length`",
    ),
    field(
        "cylinder_length",
        Kind::Number,
        Unit::Mm,
        NOT_NEGATIVE,
        when("kind", &["vessel"]),
        "a vessel's cylinder length",
    ),
    field(
        "dome",
        Kind::Word(DomeKind::NAMES),
        Unit::None,
        None,
        Given::Value(Value::Text("hemisphere")),
        "a vessel's dome at the start (and at the end unless `dome_end`); `isotensoid` is the \
         geodesic-isotensoid",
    ),
    field(
        "dome_end",
        Kind::Word(DomeKind::NAMES),
        Unit::None,
        None,
        Given::Described("`dome`"),
        "a vessel's dome at the end",
    ),
    field(
        "polar_opening",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["vessel"]),
        "the **radius** of the polar opening at the start (not its diameter), below `radius`; \
         also at the end unless `polar_opening_end`",
    ),
    field(
        "polar_opening_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`polar_opening`"),
        "the radius of the polar opening at the end",
    ),
    field(
        "axis_ratio",
        Kind::Number,
        Unit::None,
        POSITIVE,
        when("dome", &["ellipsoid"]),
        "an ellipsoidal dome's depth / radius (0.5 for a 2:1 head)",
    ),
    field(
        "axis_ratio_end",
        Kind::Number,
        Unit::None,
        POSITIVE,
        Given::Described("`axis_ratio`"),
        "the same for the end dome",
    ),
    field(
        "crown_radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("dome", &["torispherical"]),
        "a torispherical dome's crown radius, >= `radius`",
    ),
    field(
        "knuckle_radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("dome", &["torispherical"]),
        "a torispherical dome's knuckle radius, below `radius`",
    ),
    field(
        "crown_radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`crown_radius`"),
        "the same for the end dome",
    ),
    field(
        "knuckle_radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`knuckle_radius`"),
        "the same for the end dome",
    ),
    field(
        "file",
        Kind::File,
        Unit::None,
        None,
        when("kind", &["profile"]),
        "a profile's CSV of `z,r` points (mm), relative to the job's folder; the meridian runs \
         between the first and the last point, which are the polar openings",
    ),
    field(
        "smoothing",
        Kind::Number,
        Unit::None,
        NOT_NEGATIVE,
        Given::Value(Value::Number(0.0)),
        "a profile's spline smoothing (0: interpolate)",
    ),
    field(
        "offset_mm",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Value(Value::Number(0.0)),
        "added to every `r` of a profile",
    ),
];

const MU_SEGMENT_FIELDS: &[Field] = &[
    field(
        "z_from",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Required,
        "the interval's start",
    ),
    field(
        "z_to",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Required,
        "the interval's end",
    ),
    field(
        "mu",
        Kind::Number,
        Unit::None,
        None,
        Given::Required,
        "the slippage on it",
    ),
];

const MU: Field = field(
    "mu",
    Kind::NumberOrWord(&["auto", "minimax", "geodesic"]),
    Unit::None,
    None,
    Given::Value(Value::Number(0.0)),
    "the slippage: a number (constant, `|mu| <= mu_limit`; 0 = geodesic), `auto` (shooting, \
     vessels and profiles), `minimax` (vessels and profiles) or `geodesic`",
);
const MU_SEGMENTS: Field = field(
    "mu_segments",
    Kind::Tables(MU_SEGMENT_FIELDS),
    Unit::None,
    None,
    Given::None,
    "instead of `mu`: piecewise-constant slippage on `z` intervals in order, not overlapping, \
     within the mandrel",
);
const NOT_SKIP: Given = Given::RequiredWhen(Condition::Not {
    field: "kind",
    words: &["skip"],
});
const BAND_WIDTH: Field = field(
    "band_width",
    Kind::Number,
    Unit::Mm,
    POSITIVE,
    NOT_SKIP,
    "the band's width",
);
const BAND_THICKNESS: Field = field(
    "band_thickness",
    Kind::Number,
    Unit::Mm,
    POSITIVE,
    NOT_SKIP,
    "the band's thickness",
);
const OVERLAP: Field = field(
    "overlap",
    Kind::Number,
    Unit::None,
    Some(Range::closed_open(0.0, 1.0)),
    Given::Value(Value::Number(0.0)),
    "overlap of neighbouring bands, a fraction of the band width",
);
const WINDING_ANGLE: Field = field(
    "winding_angle_deg",
    Kind::Number,
    Unit::Deg,
    Some(Range::open(0.0, 90.0)),
    Given::Described("required for helical layers on tubes"),
    "tubes only: the winding angle at `z = 0`; an error on a vessel or a profile and for hoop \
     layers (their angle follows from the band width)",
);
const TURNAROUND: Field = field(
    "turnaround",
    Kind::Word(&["extension", "friction"]),
    Unit::None,
    None,
    Given::Described("`extension` (tubes only)"),
    "tubes only: `extension` (the band turns beyond the tube's ends) or `friction` (on the tube, \
     held by `mu` > 0)",
);
const PATTERN_NUMBER: Field = field(
    "pattern_number",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(1.0, u32::MAX as f64)),
    Given::Described("chosen"),
    "the pattern number",
);
const SKIP_INDEX: Field = field(
    "skip_index",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(0.0, u32::MAX as f64)),
    Given::Described("chosen"),
    "the skip index",
);
const DWELL_MIN: Field = field(
    "dwell_min_deg",
    Kind::Number,
    Unit::Deg,
    NOT_NEGATIVE,
    Given::Described("180 for tubes turned on an extension, else 0"),
    "the least dwell per turn-around",
);
const MU_LIMIT: Field = field(
    "mu_limit",
    Kind::Number,
    Unit::None,
    POSITIVE,
    Given::Value(Value::Number(0.6)),
    "the largest slippage the band holds; bounds `auto` and `minimax`",
);
const SAMPLES: Field = field(
    "samples",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(2.0, 10_000_000.0)),
    Given::Value(Value::Integer(2001)),
    "points of `path.csv` per pass",
);
const ONE_WAY: Field = field(
    "one_way",
    Kind::Boolean,
    Unit::None,
    None,
    Given::Described("false (out and back); hoop layers only"),
    "hoop layers: one pass only, ending at the far end (a terminal hoop)",
);

/// The fields of `[winding]` (a single-layer job).
pub const WINDING_FIELDS: &[Field] = &[
    MU,
    MU_SEGMENTS,
    BAND_WIDTH,
    BAND_THICKNESS,
    OVERLAP,
    WINDING_ANGLE,
    TURNAROUND,
    PATTERN_NUMBER,
    SKIP_INDEX,
    DWELL_MIN,
    MU_LIMIT,
    SAMPLES,
    field(
        "kind",
        Kind::Word(&["helical", "hoop"]),
        Unit::None,
        None,
        Given::Value(Value::Text("helical")),
        "`helical` (or polar) circuits, or `hoop` (tubes: the band advances one width per turn)",
    ),
    ONE_WAY,
];

/// The fields of a `[[layer]]` (multi-layer jobs): those of `[winding]`
/// and the layer's kind.
pub const LAYER_FIELDS: &[Field] = &[
    field(
        "kind",
        Kind::Word(&["helical", "hoop", "skip"]),
        Unit::None,
        None,
        Given::Value(Value::Text("helical")),
        "`helical` (or polar) circuits, `hoop` (the band advances one width per turn; tubes and \
         a vessel's cylinder) or `skip` (the mandrel turns alone)",
    ),
    MU,
    MU_SEGMENTS,
    BAND_WIDTH,
    BAND_THICKNESS,
    OVERLAP,
    WINDING_ANGLE,
    TURNAROUND,
    PATTERN_NUMBER,
    SKIP_INDEX,
    DWELL_MIN,
    MU_LIMIT,
    SAMPLES,
    ONE_WAY,
    field(
        "mandrel_rotation_deg",
        Kind::Number,
        Unit::Deg,
        None,
        when("kind", &["skip"]),
        "skip layers: how far the mandrel turns alone",
    ),
];

/// A range of counts as the description's closed range.
const fn counts(range: RangeInclusive<usize>) -> Range {
    Range::closed(*range.start() as f64, *range.end() as f64)
}

/// The fields of `[eye]`.
pub const EYE_FIELDS: &[Field] = &[
    field(
        "mode",
        Kind::Word(&["pull-speed", "axis-parallel", "equidistant", "curve"]),
        Unit::None,
        None,
        Given::Value(Value::Text("pull-speed")),
        "the eye's trajectory: the pull-speed optimum, a line parallel to the axis, the \
         equidistant at `clearance`, or a user curve",
    ),
    field(
        "radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("mode", &["axis-parallel"]),
        "axis-parallel: the radius of the eye's line, outside the mandrel (pull-speed: compared \
         with it)",
    ),
    field(
        "clearance",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Value(Value::Number(DEFAULT_CLEARANCE_MM)),
        "the least clearance round the mandrel for every mode, and the equidistant's distance",
    ),
    field(
        "l_max",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Required,
        "the largest free length",
    ),
    field(
        "bath_moves_with_eye",
        Kind::Boolean,
        Unit::None,
        None,
        Given::Value(Value::Boolean(true)),
        "`true`: `k = 0` in eq. 12; `false`: a fixed bath, `k = 1`",
    ),
    field(
        "curve",
        Kind::File,
        Unit::None,
        None,
        when("mode", &["curve"]),
        "curve mode: CSV of `Z,R` points (mm), `Z` increasing, `R > 0`, relative to the job's \
         folder; covering the winding zone, outside the mandrel",
    ),
    field(
        "samples",
        Kind::Integer,
        Unit::None,
        Some(counts(SAMPLE_COUNTS)),
        Given::Value(Value::Integer(DEFAULT_SAMPLES as i64)),
        "points of a geometric trajectory",
    ),
    field(
        "nodes",
        Kind::Integer,
        Unit::None,
        Some(counts(NODE_COUNTS)),
        Given::Value(Value::Integer(DEFAULT_NODES as i64)),
        "intervals of the optimised `l(x)` (pull-speed)",
    ),
];

/// `[mandrel]`: the mandrel before any layer.
pub const MANDREL: Table = Table {
    name: "mandrel",
    repeat: Repeat::Single,
    required: true,
    help: "the mandrel before any layer",
    fields: MANDREL_FIELDS,
};

/// `[winding]`: the one layer of a single-layer job.
pub const WINDING: Table = Table {
    name: "winding",
    repeat: Repeat::Single,
    required: false,
    help: "the one layer of a single-layer job (instead of `[[layer]]`)",
    fields: WINDING_FIELDS,
};

/// `[[layer]]`: the layers of a multi-layer job, in winding order.
pub const LAYER: Table = Table {
    name: "layer",
    repeat: Repeat::Array,
    required: false,
    help: "the layers of a multi-layer job, in winding order (instead of `[winding]`)",
    fields: LAYER_FIELDS,
};

/// `[eye]`: the payout eye.
pub const EYE: Table = Table {
    name: "eye",
    repeat: Repeat::Single,
    required: false,
    help: "the payout eye's trajectory",
    fields: EYE_FIELDS,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::LayerKind;

    #[test]
    fn the_described_words_are_the_enums_names() {
        assert_eq!(MandrelKind::ALL.map(MandrelKind::name), MandrelKind::NAMES);
        assert_eq!(DomeKind::ALL.map(DomeKind::name), DomeKind::NAMES);
        let layer = LAYER.field("kind").map(|f| f.kind.words());
        let names = [LayerKind::Helical, LayerKind::Hoop, LayerKind::Skip].map(LayerKind::name);
        assert_eq!(layer, Some(&names[..]));
    }
}
