use crate::{Jet, Meridian};

/// A meridian seen from its other end: `r~(z) = r(z_start + z_end - z)`.
///
/// Used to run an algorithm "from the other end" and compare.
#[derive(Debug, Clone, Copy)]
pub struct Mirrored<M>(pub M);

impl<M: Meridian> Meridian for Mirrored<M> {
    fn z_range(&self) -> (f64, f64) {
        self.0.z_range()
    }
    fn eval(&self, z: f64) -> Jet {
        let (a, b) = self.0.z_range();
        let j = self.0.eval(a + b - z);
        Jet {
            r: j.r,
            dr: -j.dr,
            d2r: j.d2r,
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.0.z_range();
        let mut v: Vec<f64> = self
            .0
            .breakpoints()
            .into_iter()
            .map(|z| a + b - z)
            .collect();
        v.reverse();
        v
    }
}
