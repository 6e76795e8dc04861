//! A dressing run's tables: the profile, the wheel's contour before, after
//! each pass and after both, the dresser's path and every simulated step.

use crate::table::Table;

/// `profile.csv`: the profile sampled at the step, left edge to right edge.
pub const PROFILE: Table = Table {
    id: "dressing.zx",
    file: "profile.csv",
    columns: &[zx::Z, zx::X],
};

/// `contour_initial.csv`: the wheel's contour before dressing (its
/// vertices).
pub const CONTOUR_INITIAL: Table = Table {
    id: "dressing.zx",
    file: "contour_initial.csv",
    columns: &[zx::Z, zx::X],
};

/// `contour_final.csv`: the contour after both passes.
pub const CONTOUR_FINAL: Table = Table {
    id: "dressing.zx",
    file: "contour_final.csv",
    columns: &[zx::Z, zx::X],
};

/// `contour_passes.csv`: the contour after each pass, pass after pass.
pub const CONTOUR_PASSES: Table = Table {
    id: "dressing.contour-passes",
    file: "contour_passes.csv",
    columns: &[zx::Z, zx::X, contour_passes::PASS],
};

/// `dresser.csv`: every path point of both passes.
pub const DRESSER: Table = Table {
    id: "dressing.dresser",
    file: "dresser.csv",
    columns: &[
        dresser::Z,
        dresser::X,
        dresser::PASS,
        dresser::STAGE,
        dresser::CORNER_Z,
        dresser::CORNER_X,
    ],
};

/// `mrr.csv`: every step of the simulation.
pub const MRR: Table = Table {
    id: "dressing.mrr",
    file: "mrr.csv",
    columns: &[
        mrr::Z,
        mrr::X,
        mrr::AREA,
        mrr::MRR,
        mrr::FEED,
        mrr::PASS,
        mrr::STAGE,
        mrr::LENGTH,
        mrr::AREA_PER_MM,
        mrr::FEED_REQUIRED,
        mrr::MRR_UNCONTROLLED,
        mrr::CUT_ANGLE,
        mrr::CUT_ANALOGUE,
        mrr::STEADY,
        mrr::MRR_VOLUME,
        mrr::MRR_VOLUME_UNCONTROLLED,
    ],
};

/// The columns of [`PROFILE`], [`CONTOUR_INITIAL`] and [`CONTOUR_FINAL`].
pub mod zx {
    use crate::table::Column;

    /// Along the wheel's axis.
    pub const Z: Column = Column::new("z", "mm", "along the wheel's axis");
    /// Radial.
    pub const X: Column = Column::new("x", "mm", "radial");
}

/// The columns of [`CONTOUR_PASSES`] after [`zx`]'s.
pub mod contour_passes {
    use crate::table::Column;

    /// The pass after which the contour is.
    pub const PASS: Column = Column::new(
        "pass",
        "",
        "1: the contour after the right half's pass, 2: after the left half's (the \
         contour's vertices in order of `z` within each)",
    );
}

/// The columns of [`DRESSER`].
pub mod dresser {
    use crate::table::Column;

    /// Point A's `z`.
    pub const Z: Column = Column::new("z", "mm", "point A (eq. 9), as programmed: along the axis");
    /// Point A's `x`.
    pub const X: Column = Column::new("x", "mm", "point A (eq. 9), as programmed: radial");
    /// The pass.
    pub const PASS: Column = Column::new("pass", "", "1: the right half, 2: the left half");
    /// The stretch.
    pub const STAGE: Column = Column::new(
        "stage",
        "",
        "`approach`, `edge`, `flank`, `fillet`, `arch`, `apex` (the stretch)",
    );
    /// The dressing corner's centre, `z`.
    pub const CORNER_Z: Column = Column::new(
        "corner_z",
        "mm",
        "the dressing corner's centre (eqs. 7, 8): along the axis",
    );
    /// The dressing corner's centre, `x`.
    pub const CORNER_X: Column = Column::new(
        "corner_x",
        "mm",
        "the dressing corner's centre (eqs. 7, 8): radial",
    );
}

/// The columns of [`MRR`].
pub mod mrr {
    use crate::table::Column;

    /// Point A at the step's end, `z`.
    pub const Z: Column = Column::new("z", "mm", "point A at the step's end: along the axis");
    /// Point A at the step's end, `x`.
    pub const X: Column = Column::new("x", "mm", "point A at the step's end: radial");
    /// Area removed.
    pub const AREA: Column = Column::new("area", "mm²", "`ΔA`, removed in the step (eq. 11)");
    /// Removal rate with feed control.
    pub const MRR: Column = Column::new("mrr", "mm²/min", "with feed control (eq. 16)");
    /// Feed.
    pub const FEED: Column = Column::new("feed", "mm/min", "`F_k` (eq. 20)");
    /// The pass.
    pub const PASS: Column = Column::new("pass", "", "1 or 2");
    /// The stretch.
    pub const STAGE: Column = Column::new("stage", "", "the stretch");
    /// The step's length.
    pub const LENGTH: Column = Column::new("length", "mm", "`L_k`");
    /// Area per length.
    pub const AREA_PER_MM: Column = Column::new("area_per_mm", "mm²/mm", "`a_k` (eq. 15)");
    /// Feed required.
    pub const FEED_REQUIRED: Column = Column::new("feed_required", "mm/min", "`F*_k` (eq. 18)");
    /// Removal rate without feed control.
    pub const MRR_UNCONTROLLED: Column = Column::new(
        "mrr_uncontrolled",
        "mm²/min",
        "at the constant feed `F0` (eq. 21)",
    );
    /// Cut-arc angle.
    pub const CUT_ANGLE: Column = Column::new("cut_angle", "rad", "`ε` (eq. 12)");
    /// Cut analogue.
    pub const CUT_ANALOGUE: Column = Column::new("cut_analogue", "mm²", "`Q` (eq. 13)");
    /// Steady step.
    pub const STEADY: Column = Column::new("steady", "", "1 for a steady step, else 0");
    /// Volume rate with feed control.
    pub const MRR_VOLUME: Column = Column::optional(
        "mrr_volume",
        "mm³/min",
        "with `wheel.diameter` only: eq. 17 of `mrr`",
    );
    /// Volume rate without feed control.
    pub const MRR_VOLUME_UNCONTROLLED: Column = Column::optional(
        "mrr_volume_uncontrolled",
        "mm³/min",
        "with `wheel.diameter` only: eq. 17 of `mrr_uncontrolled`",
    );
}
