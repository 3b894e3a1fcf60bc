//! The foot of a staircase, as the survey sees it: a pose in front of the first riser sees the
//! flight's risers (from the side or from above, its steps hide each other).

use super::grid::Grid;
use crate::building::Staircase;

/// The foot of a staircase: where its first riser stands and which way it climbs.
pub(super) struct Foot {
    start: [f64; 2],
    sin_cos: (f64, f64),
    /// The grid cell 0.3 m in front of the first riser.
    cell: usize,
}

impl Foot {
    pub(super) fn new(grid: &Grid, s: &Staircase) -> Option<Foot> {
        let (sin, cos) = s.direction_deg.to_radians().sin_cos();
        let cell = grid.index([s.start_m[0] - cos * 0.3, s.start_m[1] - sin * 0.3])?;
        Some(Foot {
            start: s.start_m,
            sin_cos: (sin, cos),
            cell,
        })
    }

    /// True if a pose at cell `i` sees the flight from its foot: within `view_m` of the first
    /// riser, within 60 degrees of the flight's axis in front of it, and in sight of the foot.
    pub(super) fn seen_from(&self, grid: &Grid, i: usize, view_m: f64) -> bool {
        let p = grid.centre(i);
        let v = [p[0] - self.start[0], p[1] - self.start[1]];
        let (sin, cos) = self.sin_cos;
        let (d, ahead) = (v[0].hypot(v[1]), -(v[0] * cos + v[1] * sin));
        d <= view_m && ahead >= 0.5 * d && grid.sight(i, self.cell)
    }
}
