/// Value and first two derivatives of `r(z)` at one `z`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet {
    /// Radius `r(z)`, mm.
    pub r: f64,
    /// Slope `r'(z)`.
    pub dr: f64,
    /// Second derivative `r''(z)`, 1/mm.
    pub d2r: f64,
}

/// The generating curve `r = r(z)` of a surface of revolution about the `z` axis.
///
/// `eval` must return exact derivatives for analytic shapes. Shapes may be
/// evaluated a little outside `[z_start, z_end]` (integrators probe there while
/// locating events); they then continue their analytic form where it exists and
/// return NaN where it does not.
///
/// Meridians are plain data, shared between threads (`Sync`) by the algorithms
/// that split their work.
pub trait Meridian: Sync {
    /// The meridian's domain `(z_start, z_end)`, `z_start < z_end`.
    fn z_range(&self) -> (f64, f64);

    /// `r`, `r'` and `r''` at `z`.
    fn eval(&self, z: f64) -> Jet;

    /// Interior `z` values where `r''` (or a higher derivative) jumps, in
    /// increasing order; integrators stop exactly on them.
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Radius at `z`, mm.
    fn r(&self, z: f64) -> f64 {
        self.eval(z).r
    }

    /// First derivative `dr/dz`.
    fn dr(&self, z: f64) -> f64 {
        self.eval(z).dr
    }

    /// Second derivative `d2r/dz2`, 1/mm.
    fn d2r(&self, z: f64) -> f64 {
        self.eval(z).d2r
    }

    /// `z_start`.
    fn z_start(&self) -> f64 {
        self.z_range().0
    }

    /// `z_end`.
    fn z_end(&self) -> f64 {
        self.z_range().1
    }
}

impl<M: Meridian + ?Sized> Meridian for &M {
    fn z_range(&self) -> (f64, f64) {
        (**self).z_range()
    }
    fn eval(&self, z: f64) -> Jet {
        (**self).eval(z)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
}

impl<M: Meridian + ?Sized> Meridian for Box<M> {
    fn z_range(&self) -> (f64, f64) {
        (**self).z_range()
    }
    fn eval(&self, z: f64) -> Jet {
        (**self).eval(z)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
}
