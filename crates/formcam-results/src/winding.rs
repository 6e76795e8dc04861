//! A winding run's tables: a pass's path, the eye over a circuit, the axes
//! (of a circuit, or of the whole program), the band passed per key point,
//! and the program's blocks. A multi-layer program writes the per-circuit
//! ones again for each layer in its `layer-NN/` folder.

use crate::table::Table;

/// `path.csv`: one pass, `samples` points.
pub const PATH: Table = Table {
    id: "winding.path",
    file: "path.csv",
    columns: &[
        path::S,
        path::Z,
        path::R,
        path::V,
        path::ALPHA,
        path::C,
        path::MU,
        path::ALPHA_DEG,
        path::THICKNESS,
    ],
};

/// `eye.csv`: the eye over one circuit.
pub const EYE: Table = Table {
    id: "winding.eye",
    file: "eye.csv",
    columns: &[
        eye::X,
        eye::Z,
        eye::R,
        eye::V,
        eye::ALPHA,
        eye::L,
        eye::EYE_Z,
        eye::EYE_R,
        eye::EYE_V,
        eye::LAMBDA,
        eye::U,
        eye::MARGIN,
    ],
};

/// `axes.csv` of one circuit (a single-layer job, a layer's folder).
pub const AXES: Table = Table {
    id: "winding.axes",
    file: "axes.csv",
    columns: &[axes::X, axes::AXIS],
};

/// `axes.csv` of a multi-layer program or a `.wind` job: the whole
/// program, its start and each block's end.
pub const PROGRAM_AXES: Table = Table {
    id: "winding.program-axes",
    file: "axes.csv",
    columns: &[program_axes::T, program_axes::AXIS],
};

/// `band.csv`: the band passed per key point over one circuit.
pub const BAND: Table = Table {
    id: "winding.band",
    file: "band.csv",
    columns: &[band::X, band::POINT],
};

/// `blocks.csv`: every block of the program.
pub const BLOCKS: Table = Table {
    id: "winding.blocks",
    file: "blocks.csv",
    columns: &[
        blocks::BLOCK,
        blocks::T,
        blocks::AXIS,
        blocks::LAYER,
        blocks::T_STAR,
        blocks::MU,
    ],
};

/// The columns of [`PATH`].
pub mod path {
    use crate::table::Column;

    /// Path length from the pass's start.
    pub const S: Column = Column::new("s", "mm", "path length from the pass's start");
    /// Axial position.
    pub const Z: Column = Column::new("z", "mm", "axial position");
    /// Meridian radius.
    pub const R: Column = Column::new("r", "mm", "meridian radius there");
    /// Turn angle about the axis.
    pub const V: Column = Column::new("v", "rad", "turn angle about the axis");
    /// Winding angle from the meridian.
    pub const ALPHA: Column = Column::new("alpha", "rad", "winding angle from the meridian");
    /// Clairaut function.
    pub const C: Column = Column::new("c", "mm", "Clairaut function `r sin(alpha)`");
    /// Slippage.
    pub const MU: Column = Column::new("mu", "", "slippage at the point");
    /// Winding angle in degrees.
    pub const ALPHA_DEG: Column = Column::new("alpha_deg", "deg", "winding angle");
    /// Layer thickness.
    pub const THICKNESS: Column =
        Column::new("thickness", "mm", "layer thickness there (two plies)");
}

/// The columns of [`EYE`].
pub mod eye {
    use crate::table::Column;

    /// Laid band length.
    pub const X: Column = Column::new("x", "mm", "laid band length along the circuit");
    /// The path point's axial position.
    pub const Z: Column = Column::new("z", "mm", "the path point being laid: axial position");
    /// The path point's radius.
    pub const R: Column = Column::new("r", "mm", "the path point being laid: radius");
    /// The path point's turn angle.
    pub const V: Column = Column::new("v", "rad", "the path point being laid: turn angle");
    /// The path point's winding angle.
    pub const ALPHA: Column =
        Column::new("alpha", "rad", "the path point being laid: winding angle");
    /// Free length.
    pub const L: Column = Column::new("l", "mm", "free length from the eye to the path point");
    /// The eye's axial position.
    pub const EYE_Z: Column = Column::new("eye_z", "mm", "the eye's axial position (eq. 10)");
    /// The eye's radius.
    pub const EYE_R: Column = Column::new("eye_r", "mm", "the eye's radius (eq. 10)");
    /// The eye's turn angle.
    pub const EYE_V: Column = Column::new("eye_v", "rad", "the eye's turn angle (eq. 10)");
    /// Length pulled through the bath.
    pub const LAMBDA: Column =
        Column::new("lambda", "mm", "length pulled through the bath (eq. 12)");
    /// Relative pull speed.
    pub const U: Column = Column::new("u", "", "relative pull speed `d lambda / dx`");
    /// The eye's radial margin.
    pub const MARGIN: Column = Column::new(
        "margin",
        "mm",
        "the eye's radial margin over the clearance zone",
    );
}

/// The columns of [`AXES`].
pub mod axes {
    use crate::table::Column;

    /// Laid band length.
    pub const X: Column = Column::new("x", "mm", "laid band length");
    /// One column per driven axis.
    pub const AXIS: Column = Column::each(
        "<axis>",
        "mm, deg",
        "one column per driven axis, named by its NC address in the machine's order: \
         `A`, `X`, `Y`, `Z`, `B`, `C` on the shipped winders, `A`, `J1`, `J2`, `J3`, `J4`, \
         `J5`, `J6` on the placement arm",
    );
}

/// The columns of [`PROGRAM_AXES`].
pub mod program_axes {
    use crate::table::Column;

    /// Time from the program's start.
    pub const T: Column = Column::new("t", "s", "time from the program's start");
    /// One column per driven axis.
    pub const AXIS: Column = Column::each(
        "<axis>",
        "mm, deg",
        "the axes at the program's start and at each block's end, in the machine's order",
    );
}

/// The columns of [`BAND`].
pub mod band {
    use crate::table::Column;

    /// Laid band length.
    pub const X: Column = Column::new("x", "mm", "laid band length");
    /// One column per key point of the machine's `band_path`.
    pub const POINT: Column = Column::each(
        "<point>",
        "mm",
        "per key point of the machine's `band_path` (named as in the machine file: `bath`, \
         `guide`, `payout` on the winders; `creel`, `roller` on the placement arm) the band \
         length that has passed it",
    );
}

/// The columns of [`BLOCKS`].
pub mod blocks {
    use crate::table::Column;

    /// The block's number.
    pub const BLOCK: Column = Column::new("block", "", "the block's number (1, 2, …)");
    /// The block's time.
    pub const T: Column = Column::new("t", "s", "the block's time");
    /// One column per driven axis.
    pub const AXIS: Column = Column::each(
        "<axis>",
        "mm, deg",
        "the axes at the block's end (unwound), in the machine's order",
    );
    /// The block's layer.
    pub const LAYER: Column =
        Column::new("layer", "", "the layer the block belongs to or leads into");
    /// The preliminary time.
    pub const T_STAR: Column = Column::new("t_star", "s", "its preliminary time of eq. 17");
    /// The time ratio.
    pub const MU: Column = Column::new("mu", "", "`t_star / t`");
}
