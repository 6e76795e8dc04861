//! A correction's tables: what happened to each node, the next part's
//! predicted CMM report, and a closed loop's CMM report of each round.

use crate::table::Table;

/// `node-status.csv`: each node of a feed move, in the program's order.
pub const NODE_STATUS: Table = Table {
    id: "correction.node-status",
    file: "node-status.csv",
    columns: &[
        node_status::LINE,
        node_status::X,
        node_status::Y,
        node_status::Z,
        node_status::PLACEMENT,
        node_status::DX,
        node_status::DY,
        node_status::DZ,
    ],
};

/// The columns of a CMM report as formcam writes one.
const CMM_COLUMNS: &[crate::table::Column] = &[
    cmm::SECTION,
    cmm::POINT,
    cmm::X_NOM,
    cmm::Y_NOM,
    cmm::Z_NOM,
    cmm::X_ACT,
    cmm::Y_ACT,
    cmm::Z_ACT,
    cmm::NX,
    cmm::NY,
    cmm::NZ,
];

/// `predicted-cmm.csv`: the CMM report foreseen for the next part.
pub const PREDICTED: Table = Table {
    id: "correction.cmm",
    file: "predicted-cmm.csv",
    columns: CMM_COLUMNS,
};

/// `cmm-<k>.csv`: a closed loop's CMM report of round `k` (with normals);
/// its name is [`crate::names::round_cmm`].
pub const ROUND_CMM: Table = Table {
    id: "correction.cmm",
    file: "cmm-<k>.csv",
    columns: CMM_COLUMNS,
};

/// The columns of [`NODE_STATUS`].
pub mod node_status {
    use crate::table::Column;

    /// The program line.
    pub const LINE: Column = Column::new("line", "", "the program line");
    /// The node's `x` before the correction.
    pub const X: Column = Column::new("x", "mm", "the node before the correction: x");
    /// The node's `y` before the correction.
    pub const Y: Column = Column::new("y", "mm", "the node before the correction: y");
    /// The node's `z` before the correction.
    pub const Z: Column = Column::new("z", "mm", "the node before the correction: z");
    /// Where the node lies.
    pub const PLACEMENT: Column = Column::new(
        "placement",
        "",
        "`inside` (over the measured area: moved by the interpolated deviation), \
         `extrapolated` (beyond it within `margin_mm`: moved by the deviation continued from \
         the edge), `outside` (beyond the margin: left as it was) or `unknown` (a coordinate \
         the program had not set yet: left)",
    );
    /// The displacement, `x`.
    pub const DX: Column = Column::new("dx", "mm", "the displacement: x (0 for a node left)");
    /// The displacement, `y`.
    pub const DY: Column = Column::new("dy", "mm", "the displacement: y (0 for a node left)");
    /// The displacement, `z`.
    pub const DZ: Column = Column::new("dz", "mm", "the displacement: z (0 for a node left)");
}

/// The columns of [`PREDICTED`] and [`ROUND_CMM`].
pub mod cmm {
    use crate::table::Column;

    /// The section's name.
    pub const SECTION: Column = Column::new("section", "", "the section's name");
    /// The point's name.
    pub const POINT: Column = Column::new("point", "", "the point's name within its section");
    /// Nominal `x`.
    pub const X_NOM: Column = Column::new("x_nom", "mm", "the nominal (model) point: x");
    /// Nominal `y`.
    pub const Y_NOM: Column = Column::new("y_nom", "mm", "the nominal (model) point: y");
    /// Nominal `z`.
    pub const Z_NOM: Column = Column::new("z_nom", "mm", "the nominal (model) point: z");
    /// Actual `x`.
    pub const X_ACT: Column = Column::new("x_act", "mm", "the measured (or predicted) point: x");
    /// Actual `y`.
    pub const Y_ACT: Column = Column::new("y_act", "mm", "the measured (or predicted) point: y");
    /// Actual `z`.
    pub const Z_ACT: Column = Column::new("z_act", "mm", "the measured (or predicted) point: z");
    /// Normal `x`.
    pub const NX: Column = Column::optional(
        "nx",
        "",
        "the nominal surface normal: x (when the measurements gave normals; always in `cmm-<k>.csv`)",
    );
    /// Normal `y`.
    pub const NY: Column = Column::optional("ny", "", "the nominal surface normal: y");
    /// Normal `z`.
    pub const NZ: Column = Column::optional("nz", "", "the nominal surface normal: z");
}
