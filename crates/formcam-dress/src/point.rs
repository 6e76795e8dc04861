//! A point (or vector) of the wheel's axial section.

use std::ops::{Add, Mul, Neg, Sub};

/// A point or vector in the axial section of the wheel, mm: `x` along the
/// wheel's axis (the machine's Z), `y` radial, outward (the machine's X).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point {
    /// Along the wheel's axis, mm.
    pub x: f64,
    /// Radial, away from the wheel's axis, mm.
    pub y: f64,
}

impl Point {
    /// The point `(x, y)`.
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }

    /// The unit vector at angle `a` (rad) from the x axis, counter-clockwise.
    pub fn polar(a: f64) -> Self {
        let (s, c) = a.sin_cos();
        Self { x: c, y: s }
    }

    /// The Euclidean length.
    pub fn hypot(self) -> f64 {
        self.x.hypot(self.y)
    }

    /// The distance to `other`.
    pub fn distance(self, other: Point) -> f64 {
        (self - other).hypot()
    }

    /// The angle from the x axis, rad in `(-pi, pi]`.
    pub fn atan2(self) -> f64 {
        self.y.atan2(self.x)
    }

    /// The dot product.
    pub fn dot(self, other: Point) -> f64 {
        self.x * other.x + self.y * other.y
    }

    /// The z component of the cross product `self x other`.
    pub fn cross(self, other: Point) -> f64 {
        self.x * other.y - self.y * other.x
    }

    /// The mirror image in the y axis (`x -> -x`).
    pub fn mirrored(self) -> Self {
        Self {
            x: -self.x,
            y: self.y,
        }
    }

    /// Both coordinates finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl Add for Point {
    type Output = Point;
    fn add(self, o: Point) -> Point {
        Point::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Point {
    type Output = Point;
    fn sub(self, o: Point) -> Point {
        Point::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f64> for Point {
    type Output = Point;
    fn mul(self, k: f64) -> Point {
        Point::new(self.x * k, self.y * k)
    }
}

impl Neg for Point {
    type Output = Point;
    fn neg(self) -> Point {
        Point::new(-self.x, -self.y)
    }
}
