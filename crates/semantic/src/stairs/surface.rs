//! Returns that lie on surfaces. A real laser's beam has a footprint; where it straddles a
//! depth edge (a step's nosing, the corner where a staircase's side face steps up) the sensor
//! can report a range between the two surfaces: a "mixed pixel" floating in the air in front
//! of the edge, up to the height of the edge above the lower tread (Ye and Borenstein, ICRA
//! 2002, for the SICK LMS 200). A staircase's profile takes the highest point along its
//! direction, so a few such returns raise a tread's level by a whole step and shift its edge.
//!
//! A surface is sampled at the cloud's own spacing: a return on one (a tread, a riser, a side
//! face, even its top edge or corner) has neighbours within twice that spacing, a mixed pixel
//! (scattered along its ray between foreground and background) has hardly any. The spacing is
//! measured on the candidate's own points (the distance to the nearest neighbour, 90th percentile), so
//! the rule holds for a dense close scan as for a voxel-downsampled map or a far, sparse one.

use glam::Vec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Points sampled to measure the spacing.
const SPACING_SAMPLES: usize = 512;

/// The members (indexes into `points`) with at least `min_neighbours` other members within
/// `radius_spacings` times the members' spacing (the 90th percentile of their nearest-neighbour
/// distances, capped at `max_radius_m`).
pub(super) fn on_surfaces(
    points: &[Vec3],
    members: &[usize],
    min_neighbours: usize,
    radius_spacings: f64,
    max_radius_m: f64,
) -> Vec<usize> {
    if min_neighbours == 0 || members.len() <= min_neighbours {
        return members.to_vec();
    }
    // 1. The spacing: the median nearest-neighbour distance of a sample, searched within
    //    the cap (a sample with no neighbour that close counts as the cap).
    let cap = max_radius_m as f32;
    let coarse = Grid::new(points, members, cap);
    let stride = (members.len() / SPACING_SAMPLES).max(1);
    let mut nearest: Vec<f32> = members
        .iter()
        .step_by(stride)
        .map(|&i| coarse.nearest(points, i, cap))
        .collect();
    nearest.sort_by(f32::total_cmp);
    // (the 90th percentile: a candidate's spacing varies, treads seen at grazing angles are
    // sampled sparser than the riser in front of the laser, and they must stay)
    let spacing = nearest[nearest.len() * 9 / 10];
    // 2. The members with enough neighbours within the radius.
    let radius = (radius_spacings as f32 * spacing).clamp(1e-3, cap);
    let grid = Grid::new(points, members, radius);
    members
        .par_iter()
        .copied()
        .filter(|&i| grid.has_neighbours(points, i, radius, min_neighbours))
        .collect()
}

/// Members hashed into cubes of one edge.
struct Grid {
    edge: f32,
    cells: HashMap<(i32, i32, i32), Vec<usize>, BuildHasherDefault<CellHasher>>,
}

/// A multiplicative hash of a cube's three small integer coordinates: the map is built and
/// probed 27 times per member, and the keys need no protection from chosen collisions.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        bytes.iter().for_each(|&b| self.write_u8(b));
    }

    fn write_u8(&mut self, b: u8) {
        self.write_u64(u64::from(b));
    }

    fn write_i32(&mut self, v: i32) {
        self.write_u64(u64::from(v as u32));
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(21) ^ v).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }

    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 29)
    }
}

impl Grid {
    fn new(points: &[Vec3], members: &[usize], edge: f32) -> Grid {
        let mut cells: HashMap<(i32, i32, i32), Vec<usize>, BuildHasherDefault<CellHasher>> =
            HashMap::default();
        for &i in members {
            cells.entry(cell(points[i], edge)).or_default().push(i);
        }
        Grid { edge, cells }
    }

    /// The distance from member `i` to its nearest other member, if under `cap` (at most one
    /// edge; else `cap`): its own cube is searched first, then those of the 26 around it
    /// that come nearer than the nearest found so far.
    fn nearest(&self, points: &[Vec3], i: usize, cap: f32) -> f32 {
        let p = points[i];
        let (x, y, z) = cell(p, self.edge);
        // The distance from `p` to the cube `(x, y, z) + d` along one axis.
        let gap = |v: f32, c: i32, d: i32| match d {
            -1 => v - c as f32 * self.edge,
            1 => (c + 1) as f32 * self.edge - v,
            _ => 0.0,
        };
        let mut best = cap;
        for (dx, dy, dz) in own_cube_first() {
            let g = Vec3::new(gap(p.x, x, dx), gap(p.y, y, dy), gap(p.z, z, dz));
            // (a millimetre's margin for the rounding of a point into its cube)
            if g.length() - 1e-3 >= best {
                continue;
            }
            if let Some(v) = self.cells.get(&(x + dx, y + dy, z + dz)) {
                for &j in v {
                    if j != i {
                        best = best.min(p.distance(points[j]));
                    }
                }
            }
        }
        best
    }
}

impl Grid {
    /// Whether member `i` has at least `n` other members within `radius` (at most one edge):
    /// the cubes around it are searched, its own first (where most of them lie), until that
    /// many are found.
    fn has_neighbours(&self, points: &[Vec3], i: usize, radius: f32, n: usize) -> bool {
        let p = points[i];
        let (x, y, z) = cell(p, self.edge);
        let mut found = 0usize;
        own_cube_first()
            .filter_map(|(dx, dy, dz)| self.cells.get(&(x + dx, y + dy, z + dz)))
            .any(|v| {
                v.iter().any(|&j| {
                    found += usize::from(j != i && p.distance(points[j]) <= radius);
                    found >= n
                })
            })
    }
}

/// The offsets of a cube and the 26 around it, the cube itself first.
fn own_cube_first() -> impl Iterator<Item = (i32, i32, i32)> {
    let around =
        (-1..=1).flat_map(|dx| (-1..=1).flat_map(move |dy| (-1..=1).map(move |dz| (dx, dy, dz))));
    std::iter::once((0, 0, 0)).chain(around.filter(|&d| d != (0, 0, 0)))
}

fn cell(p: Vec3, edge: f32) -> (i32, i32, i32) {
    let c = |v: f32| (v / edge).floor().clamp(-1e9, 1e9) as i32;
    (c(p.x), c(p.y), c(p.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A riser-like vertical face sampled every 5 cm (a voxel map's spacing) and mixed pixels
    /// scattered along rays in front of its top edge: the face is kept whole, its top edge and
    /// corners included, and the mixed pixels are left out.
    #[test]
    fn mixed_pixels_in_front_of_an_edge_are_on_no_surface() {
        let mut points = Vec::new();
        for i in 0..20 {
            for k in 0..4 {
                points.push(Vec3::new(0.05 * i as f32, 0.0, 0.05 * k as f32));
            }
        }
        let face = points.len();
        for j in 0..6 {
            let f = j as f32;
            points.push(Vec3::new(0.17 * f, 0.12 + 0.13 * f, 0.2 + 0.07 * (f % 3.0)));
        }
        let members: Vec<usize> = (0..points.len()).collect();
        let kept = on_surfaces(&points, &members, 3, 2.0, 0.15);
        assert_eq!(kept, (0..face).collect::<Vec<_>>());
    }

    /// The same face sampled ten times more densely (a close scan, no voxels) keeps all its
    /// points: the radius follows the spacing.
    #[test]
    fn the_neighbourhood_follows_the_point_spacing() {
        let points: Vec<Vec3> = (0..200)
            .flat_map(|i| (0..30).map(move |k| Vec3::new(0.005 * i as f32, 0.0, 0.005 * k as f32)))
            .collect();
        let members: Vec<usize> = (0..points.len()).collect();
        assert_eq!(
            on_surfaces(&points, &members, 3, 2.0, 0.15).len(),
            points.len()
        );
    }
    /// Members in clusters and scattered alone, cubes of several sizes: the nearest member
    /// found with the farther cubes skipped is the nearest of all (within the cap).
    #[test]
    fn the_nearest_member_is_the_nearest_of_all() {
        let mut rng = crate::test_rng::TestRng::new(0x9e37_79b9_7f4a_7c15);
        let mut rand = move || rng.next_f32();
        let mut points = Vec::new();
        for _ in 0..40 {
            let c = Vec3::new(rand(), rand(), rand()) * 2.0 - Vec3::ONE;
            for _ in 0..10 {
                points.push(c + (Vec3::new(rand(), rand(), rand()) - Vec3::splat(0.5)) * 0.1);
            }
            points.push(Vec3::new(rand(), rand(), rand()) * 2.0 - Vec3::ONE);
        }
        let members: Vec<usize> = (0..points.len()).collect();
        for cap in [0.02f32, 0.05, 0.15, 0.4] {
            let grid = Grid::new(&points, &members, cap);
            for &i in &members {
                let want = members
                    .iter()
                    .filter(|&&j| j != i)
                    .map(|&j| points[i].distance(points[j]))
                    .fold(cap, f32::min);
                assert_eq!(grid.nearest(&points, i, cap), want, "member {i}, cap {cap}");
            }
        }
    }
}
