//! G codes by what they do, and the modal state the G-code readers keep
//! between lines (the motion mode, absolute or incremental distances, arc
//! centres, the arc plane, units, the feed mode).
//!
//! Both readers classify a `G` word with [`GCode::of`] and apply it to their
//! [`Modal`] with [`Modal::apply`]; each refuses what it does not support
//! before that (the program reader: arcs, inches, feed per revolution; the
//! milling reader: coordinate-system changes, canned cycles, polar
//! coordinates).

/// A motion mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MotionMode {
    /// `G0`.
    Rapid,
    /// `G1`.
    Linear,
    /// `G2`.
    ArcCw,
    /// `G3`.
    ArcCcw,
}

/// An arc plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ArcPlane {
    /// `G17`.
    Xy,
    /// `G18`.
    Zx,
    /// `G19`.
    Yz,
}

impl ArcPlane {
    /// The axes (0 = X) of the plane's first and second coordinates and of
    /// its normal.
    pub(crate) fn axes(self) -> (usize, usize, usize) {
        match self {
            ArcPlane::Xy => (0, 1, 2),
            ArcPlane::Zx => (2, 0, 1),
            ArcPlane::Yz => (1, 2, 0),
        }
    }
}

/// What a G code does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GCode {
    /// `G0..G3`.
    Motion(MotionMode),
    /// `G4`: dwell (its words are its arguments).
    Dwell,
    /// `G17..G19`.
    Plane(ArcPlane),
    /// `G20` (Sinumerik also `G70`, `G700`): inches.
    Inch,
    /// `G21` (Sinumerik also `G71`, `G710`): mm.
    Metric,
    /// `G90`.
    Absolute,
    /// `G91`.
    Incremental,
    /// `G90.1`: arc centres absolute.
    CentreAbsolute,
    /// `G91.1`: arc centres incremental.
    CentreIncremental,
    /// `G93`: inverse-time feed.
    InverseTime,
    /// `G94`: feed per minute.
    PerMinute,
    /// `G95`: feed per revolution.
    PerRevolution,
    /// `G28`, `G30`, `G53` (any sub-code): moves in machine coordinates or
    /// home; the number.
    Home(u32),
    /// `G92` (sub-code 0): sets axis values without moving.
    Preset,
    /// `G92.1`, `G92.2`, `G92.3`.
    PresetOther,
    /// `G10`, `G51`, `G52`, `G68`: other coordinate-system changes; the number.
    CoordinateSystem(u32),
    /// `G16`: polar coordinates.
    Polar,
    /// `G73`, `G74`, `G76`, `G81..G89`: canned cycles; the number.
    Cycle(u32),
    /// Anything else (work offsets, cutter compensation, …).
    Other,
}

impl GCode {
    /// The code of `G<value>`; `None` when `value` is no G code (negative,
    /// or more than one decimal). `sinumerik` adds its unit codes.
    pub(crate) fn of(value: f64, sinumerik: bool) -> Option<Self> {
        let whole = value.trunc();
        let frac = ((value - whole) * 10.0).round();
        if !(value >= 0.0 && (value - whole - frac / 10.0).abs() < 1e-9) {
            return None;
        }
        let (g, sub) = (whole as u32, frac as u32);
        Some(match (g, sub) {
            (0, 0) => Self::Motion(MotionMode::Rapid),
            (1, 0) => Self::Motion(MotionMode::Linear),
            (2, 0) => Self::Motion(MotionMode::ArcCw),
            (3, 0) => Self::Motion(MotionMode::ArcCcw),
            (4, 0) => Self::Dwell,
            (17, 0) => Self::Plane(ArcPlane::Xy),
            (18, 0) => Self::Plane(ArcPlane::Zx),
            (19, 0) => Self::Plane(ArcPlane::Yz),
            (20, 0) => Self::Inch,
            (21, 0) => Self::Metric,
            (70 | 700, 0) if sinumerik => Self::Inch,
            (71 | 710, 0) if sinumerik => Self::Metric,
            (90, 0) => Self::Absolute,
            (91, 0) => Self::Incremental,
            (90, 1) => Self::CentreAbsolute,
            (91, 1) => Self::CentreIncremental,
            (93, 0) => Self::InverseTime,
            (94, 0) => Self::PerMinute,
            (95, 0) => Self::PerRevolution,
            (28 | 30 | 53, _) => Self::Home(g),
            (92, 0) => Self::Preset,
            (92, _) => Self::PresetOther,
            (10 | 51 | 52 | 68, _) => Self::CoordinateSystem(g),
            (16, 0) => Self::Polar,
            (73 | 74 | 76 | 81..=89, _) => Self::Cycle(g),
            _ => Self::Other,
        })
    }
}

/// The modal state of a G-code reader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Modal {
    /// The motion mode; `None` before the first `G0..G3`.
    pub(crate) motion: Option<MotionMode>,
    /// `G91`.
    pub(crate) incremental: bool,
    /// `G90.1` (the default is incremental centres).
    pub(crate) centre_absolute: bool,
    /// The arc plane (`G17` by default).
    pub(crate) plane: ArcPlane,
    /// `G20`.
    pub(crate) inch: bool,
    /// `G93`.
    pub(crate) inverse_time: bool,
}

impl Default for Modal {
    fn default() -> Self {
        Self {
            motion: None,
            incremental: false,
            centre_absolute: false,
            plane: ArcPlane::Xy,
            inch: false,
            inverse_time: false,
        }
    }
}

impl Modal {
    /// Takes on `code`'s mode (codes that set no mode change nothing).
    pub(crate) fn apply(&mut self, code: GCode) {
        match code {
            GCode::Motion(m) => self.motion = Some(m),
            GCode::Plane(p) => self.plane = p,
            GCode::Inch => self.inch = true,
            GCode::Metric => self.inch = false,
            GCode::Absolute => self.incremental = false,
            GCode::Incremental => self.incremental = true,
            GCode::CentreAbsolute => self.centre_absolute = true,
            GCode::CentreIncremental => self.centre_absolute = false,
            GCode::InverseTime => self.inverse_time = true,
            GCode::PerMinute | GCode::PerRevolution => self.inverse_time = false,
            _ => {}
        }
    }

    /// mm per program unit.
    pub(crate) fn scale(&self) -> f64 {
        if self.inch { 25.4 } else { 1.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_and_modes() {
        assert_eq!(
            GCode::of(1.0, false),
            Some(GCode::Motion(MotionMode::Linear))
        );
        assert_eq!(GCode::of(91.1, false), Some(GCode::CentreIncremental));
        assert_eq!(GCode::of(92.1, false), Some(GCode::PresetOther));
        assert_eq!(GCode::of(70.0, false), Some(GCode::Other));
        assert_eq!(GCode::of(70.0, true), Some(GCode::Inch));
        assert_eq!(GCode::of(1.25, false), None);
        assert_eq!(GCode::of(-1.0, false), None);
        let mut m = Modal::default();
        for g in [20.0, 91.0, 18.0, 93.0, 2.0] {
            m.apply(GCode::of(g, false).unwrap_or(GCode::Other));
        }
        assert_eq!(m.scale(), 25.4);
        assert_eq!(m.plane.axes(), (2, 0, 1));
        assert!(m.incremental && m.inverse_time);
        assert_eq!(m.motion, Some(MotionMode::ArcCw));
        m.apply(GCode::PerRevolution);
        assert!(!m.inverse_time);
    }
}
