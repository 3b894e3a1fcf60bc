//! Where a stray face's points bridge a wall's face (see [`super::faces::Faces::stray`]):
//! something standing against a wall hides its face, so its returns carry the wall's extent
//! across what it hides, but only where nothing shows the wall absent: the floor seen within
//! the wall's body (in the 3DTK corridor, pilasters and a ledge under the ceiling hide the
//! wall's face; in garage-193, a person and a car stand where the floor shows that the wall
//! has ended).

use super::faces::Faces;
use super::WallConfig;
use crate::points::Line2;
use crate::scene::Scene;

/// The floor is looked for in stretches this long along the wall ...
const BIN_M: f64 = 0.1;
/// ... and is seen within the wall's body where a stretch and its two neighbours hold this
/// many floor returns there.
const MIN_FLOOR_RETURNS: usize = 5;
/// A floor return is one within this of the floor's height.
const FLOOR_TOL_M: f64 = 0.05;
/// The body of a wall seen from one side is looked at this far behind its face.
const BODY_DEPTH_M: f64 = 0.1;

/// The stretches of `[r0, r1]` along a wall where its stray face's points may bridge its face.
pub(crate) struct StrayBridges {
    r0: f64,
    /// Per stretch: the floor seen within the wall's body there (or beside it).
    floor_seen: Vec<bool>,
}

impl StrayBridges {
    /// The stretches of `[r0, r1]` along the wall on `line` with `faces` where the floor is
    /// seen within its body: between its two faces, or up to [`BODY_DEPTH_M`] behind its one
    /// face (away from the stray face). `None` where the wall has no stray face.
    pub fn new(
        line: &Line2,
        faces: &Faces,
        (r0, r1): (f64, f64),
        sc: &Scene,
        c: &WallConfig,
    ) -> Option<StrayBridges> {
        let stray = faces.stray?;
        let tol = c.face_tolerance_m;
        let (f0, f1) = (*faces.wall.first()?, *faces.wall.last()?);
        let body = if faces.wall.len() >= 2 {
            (f0 + tol, f1 - tol)
        } else if stray < f0 {
            (f0 + tol, f0 + BODY_DEPTH_M)
        } else {
            (f0 - BODY_DEPTH_M, f0 - tol)
        };
        let n = (((r1 - r0) / BIN_M).ceil() as usize + 1).min(10_000_000);
        let mut floor = vec![0usize; n];
        // (only the strip of the body is walked: the floor's returns are most of a wall's)
        let half_width = body.0.abs().max(body.1.abs()) + 0.01;
        sc.index
            .for_each_near_line(line, r0, r1, half_width, |_, s, d, z| {
                if (z - sc.floor).abs() <= FLOOR_TOL_M && d >= body.0 && d <= body.1 {
                    floor[(((s - r0) / BIN_M).max(0.0) as usize).min(n - 1)] += 1;
                }
            });
        let floor_seen = (0..n)
            .map(|k| {
                floor[k.saturating_sub(1)..(k + 2).min(n)]
                    .iter()
                    .sum::<usize>()
            })
            .map(|sum| sum >= MIN_FLOOR_RETURNS)
            .collect();
        Some(StrayBridges { r0, floor_seen })
    }

    /// Whether a stray face's point at `s` along the wall bridges its face: the floor is not
    /// seen within the wall's body there.
    pub fn bridges(&self, s: f64) -> bool {
        let k = ((s - self.r0) / BIN_M).max(0.0) as usize;
        !self.floor_seen.get(k).copied().unwrap_or(false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// Regression (garage-193): a person standing beside a wall's end, where the floor shows
    /// that the wall has ended, carried the wall on into the garage.
    #[test]
    fn a_stray_face_bridges_only_where_the_floor_in_the_walls_body_is_unseen() {
        // The floor seen 5 cm behind the wall's face (x along the wall) over [2, 3] m.
        let points: Vec<Vec3> = (0..50)
            .map(|i| Vec3::new(2.0 + i as f32 * 0.02, 0.05, 0.0))
            .collect();
        let index = XyIndex::new(&points, DVec2::splat(-10.0), DVec2::splat(10.0), 0.5);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
        let c = WallConfig::default();
        let line = Line2::through(DVec2::ZERO, DVec2::X);
        let faces = |stray| Faces {
            wall: vec![0.0],
            stray,
        };
        // Something stands 0.28 m in front of the face: the wall's body is behind it.
        let b = StrayBridges::new(&line, &faces(Some(-0.28)), (0.0, 5.0), &sc, &c)
            .expect("a stray face");
        assert!(b.bridges(1.0) && b.bridges(4.0));
        assert!(!b.bridges(2.5) && !b.bridges(2.95));
        // Standing behind the face instead, the floor seen is in front of it: no evidence.
        let b = StrayBridges::new(&line, &faces(Some(0.28)), (0.0, 5.0), &sc, &c)
            .expect("a stray face");
        assert!(b.bridges(2.5));
        assert!(StrayBridges::new(&line, &faces(None), (0.0, 5.0), &sc, &c).is_none());
    }
}
