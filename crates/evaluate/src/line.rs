//! A 2D line in the map frame, as the matching measures along and across true walls.

use glam::DVec2;

/// A 2D line through `origin` with unit direction `dir`; `normal` is `dir` turned left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Line2 {
    pub origin: DVec2,
    pub dir: DVec2,
}

impl Line2 {
    /// The line from `a` towards `b` (x axis if they coincide).
    pub fn through(a: DVec2, b: DVec2) -> Line2 {
        let d = b - a;
        let dir = if d.length() > 1e-12 {
            d.normalize()
        } else {
            DVec2::X
        };
        Line2 { origin: a, dir }
    }

    /// The left normal.
    pub fn normal(&self) -> DVec2 {
        self.dir.perp()
    }

    /// The point at along-coordinate `s`.
    pub fn at(&self, s: f64) -> DVec2 {
        self.origin + self.dir * s
    }

    /// Along- and across- (left positive) coordinates of `q`.
    pub fn coords(&self, q: DVec2) -> (f64, f64) {
        let v = q - self.origin;
        (v.dot(self.dir), v.dot(self.normal()))
    }
}

/// The angle between two undirected directions, in degrees (0..=90).
pub(crate) fn undirected_angle_deg(a: DVec2, b: DVec2) -> f64 {
    let c = a
        .normalize_or_zero()
        .dot(b.normalize_or_zero())
        .abs()
        .min(1.0);
    c.acos().to_degrees()
}
