//! A wall's points binned along it for its door openings ([`super::openings`]): per bin, the
//! face returns at door level that block it, the lintel above, and what the scans saw through.

use super::OpeningConfig;
use crate::scene::Scene;
use crate::walls::WallFit;

/// Face points above door level count as lintel up to this far below the wall's top.
const LINTEL_TOP_MARGIN_M: f64 = 0.02;
/// Points this near the floor height are floor points (seen through an opening).
const FLOOR_POINT_TOLERANCE_M: f64 = 0.04;
/// Points behind a one-sided wall's face count as seen through from this far above the floor
/// to this far below the wall's top.
const BEHIND_SLAB_MARGIN_M: f64 = 0.05;
/// The most bins along one wall (a cap against absurd lengths).
const MAX_BINS: usize = 10_000_000;

#[derive(Clone, Default)]
pub(super) struct Bin {
    pub(super) blocked: bool,
    pub(super) face_s: (f64, f64),
    pub(super) lintel: bool,
    pub(super) lintel_low_z: f64,
    pub(super) lintel_points: u64,
    pub(super) evidence: bool,
    /// Face points at door level near enough a face to block (see `bin_wall`).
    pub(super) door_face: u16,
    /// The faces with returns in the bin at any height, a bit per [`side`].
    pub(super) faces_seen: u8,
    /// Two-sided walls: whether the scans saw through the wall from each [`side`]: returns
    /// beyond the other face (up to `behind_m`), up to door level or on the floor.
    pub(super) seen_from: [bool; 2],
}

/// The side of the centre line of offset `d`: 0 negative, 1 positive (the index of
/// [`Bin::seen_from`] and the bit of [`Bin::faces_seen`]).
pub(super) fn side(d: f64) -> usize {
    usize::from(d >= 0.0)
}

/// Door level `[lo, hi]` (absolute z) of the wall's openings.
#[derive(Clone, Copy)]
pub(super) struct DoorLevel {
    pub(super) lo: f64,
    pub(super) hi: f64,
}

impl DoorLevel {
    pub(super) fn contains(&self, z: f64) -> bool {
        z >= self.lo && z <= self.hi
    }
}

/// Bins the points near wall `w` along it (`bin_m`): face points at door level, the lintel
/// above, and evidence of the scans seeing through. Also returns, per bin, the door-level
/// points within half a wall of a face; a bin's `blocked` is set from both.
pub(super) fn bin_wall(
    w: &WallFit,
    sc: &Scene,
    c: &OpeningConfig,
    face_tol: f64,
    level: DoorLevel,
) -> (Vec<Bin>, Vec<u16>) {
    let n = ((w.length / c.bin_m).ceil() as usize).clamp(1, MAX_BINS);
    let mut bins = vec![
        Bin {
            face_s: (f64::INFINITY, f64::NEG_INFINITY),
            lintel_low_z: f64::INFINITY,
            ..Bin::default()
        };
        n
    ];
    let half_t = w.thickness / 2.0;
    let two_sided = w.measured;
    let sigma = w.free_side;
    let top = w.z_range.1;
    let (reach, block_tol) = reach_and_block_tol(w, c, face_tol);
    let mut blocking = vec![0u16; n];
    // Of them, those in the door level's upper half (see the end of this function).
    let mut blocking_high = vec![0u16; n];
    let mid_level = (level.lo + level.hi) / 2.0;
    // Door-level points within half a wall of a face, behind or in front of it: a bin's wall
    // surface, a closed leaf recessed behind it (whose noise tail reaches the face), or a leaf
    // open at a small angle, crossing the face plane near its hinge.
    let mut at_wall = vec![0u16; n];

    let near_wall = face_tol.max(half_t);
    sc.index
        .for_each_near_line(&w.line, 0.0, w.length, reach, |_, s, d, z| {
            let b = ((s / c.bin_m) as usize).min(n - 1);
            if level.contains(z) && w.faces.iter().any(|f| (d - f).abs() <= near_wall) {
                at_wall[b] = at_wall[b].saturating_add(1);
            }
            let bin = &mut bins[b];
            let on_face = w.faces.iter().any(|f| (d - f).abs() <= face_tol);
            if on_face {
                bin.faces_seen |= 1 << side(d);
                if level.contains(z) {
                    if w.faces.iter().any(|f| (d - f).abs() <= block_tol) {
                        blocking[b] = blocking[b].saturating_add(1);
                        if z >= mid_level {
                            blocking_high[b] = blocking_high[b].saturating_add(1);
                        }
                        bin.face_s = (bin.face_s.0.min(s), bin.face_s.1.max(s));
                    }
                } else if z > level.hi && z < top - LINTEL_TOP_MARGIN_M {
                    bin.lintel = true;
                    bin.lintel_points += 1;
                }
                // The lintel's underside: the lowest face point above door level (below it,
                // face points in an opening are the noise tail of a closed leaf).
                if z > level.hi {
                    bin.lintel_low_z = bin.lintel_low_z.min(z);
                }
                return;
            }
            let floor_pt = (z - sc.floor).abs() <= FLOOR_POINT_TOLERANCE_M;
            let inside = d.abs() < half_t - face_tol;
            if two_sided
                && d.abs() > half_t + face_tol
                && (floor_pt
                    || (z > sc.floor - BEHIND_SLAB_MARGIN_M
                        && z < level.hi.min(top - BEHIND_SLAB_MARGIN_M)))
            {
                // Beyond the face on the side of `d`: seen through from the other side.
                bin.seen_from[1 - side(d)] = true;
            }
            let seen_through = if two_sided {
                inside && (floor_pt || level.contains(z))
            } else {
                // Behind the face (away from the free side) up to door level, or on the floor
                // within the footprint. Higher up, what lies behind the face is the noise of
                // the face itself (seen above what hid it below, at range and grazing
                // incidence), not a view through an opening.
                let depth = half_t - sigma * d; // 0 at the face, growing behind it
                (depth > face_tol
                    && z > sc.floor - BEHIND_SLAB_MARGIN_M
                    && z < level.hi.min(top - BEHIND_SLAB_MARGIN_M))
                    || (floor_pt && inside)
            };
            if seen_through {
                bin.evidence = true;
            }
        });
    // A bin is blocked by three face points at door level (one is noise) that are at least a
    // third of its door-level points at the wall (else they are the noise tail of a closed
    // leaf recessed behind the face), one of them in the door level's upper half: a wall's
    // face is seen up to door height, while clutter standing in a doorway against its jamb (a
    // crate, a bin: office-123's 0.69 m crate set its door's edge 0.32 m into the opening, and
    // its leaf, searched from there, was missed) stands lower. (Over clutter in front of a
    // wall, the face is seen above it.)
    for (b, bin) in bins.iter_mut().enumerate() {
        let (k, m) = (blocking[b], at_wall[b]);
        bin.door_face = k;
        bin.blocked = k >= 3 && 3 * k >= m && blocking_high[b] > 0;
    }
    (bins, at_wall)
}

/// How far from wall `w`'s centre line its points are binned (out to half a wall in front of
/// the faces too: see `at_wall` in `bin_wall`; behind a face, `behind_m`),
/// and how near a face a door-level point must be to block a bin.
fn reach_and_block_tol(w: &WallFit, c: &OpeningConfig, face_tol: f64) -> (f64, f64) {
    let half_t = w.thickness / 2.0;
    let two_sided = w.measured;
    let reach = (half_t + c.behind_m + face_tol).max(2.0 * half_t + face_tol);
    // A closed leaf is recessed from the faces by half the wall less half the leaf: at door
    // level, only points nearer the face than half that recess block a bin.
    let block_tol = if two_sided {
        face_tol.min(((half_t - 0.02) / 2.0).max(0.01))
    } else {
        face_tol
    };
    (reach, block_tol)
}
