//! One pass over the points near a wall prerequisite's faces, over an extent along its line:
//! what `fit` judges the prerequisite by (support, orientation, heights, coverage, top reach,
//! free sides).

use super::extent::Crossings;
use super::orientation::FaceOrientation;
use super::support::{SupportProfile, BIN_M, HEAD_HEIGHT_M};
use super::top::TopReach;
use super::WallConfig;
use crate::points::Line2;
use crate::scene::Scene;

/// The strip in front of (and behind) each face where floor and ceiling points show free
/// space: from 2 cm (beyond the face's own noise) to 10 cm.
const FREE_STRIP_M: (f64, f64) = (0.02, 0.10);

/// What one pass over the extent `[lo, hi]` along `line` saw (corners left out).
pub(super) struct FacePass {
    /// Heights of the face points between floor and ceiling.
    pub zs: Vec<f64>,
    /// Per 10 cm stretch: whether it holds a face point.
    pub covered: Vec<bool>,
    pub reach: TopReach,
    /// Per face: floor and ceiling points in the strip right of it and left of it.
    pub front: Vec<[usize; 2]>,
    /// Per face: the face points on it.
    pub on_each: Vec<usize>,
    pub profile: SupportProfile,
    pub orientation: FaceOrientation,
}

/// Walks the points near `line` from `lo` to `hi` once (see [`FacePass`]).
pub(super) fn measure(
    line: &Line2,
    (lo, hi): (f64, f64),
    faces: &[f64],
    crossing: &Crossings,
    sc: &Scene,
    c: &WallConfig,
) -> FacePass {
    let tol = c.face_tolerance_m;
    let on_face = |d: f64| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let stretches = (((hi - lo) / 0.1).ceil() as usize).clamp(1, 1_000_000);
    let mut pass = FacePass {
        zs: Vec::new(),
        covered: vec![false; stretches],
        reach: TopReach::new(stretches, z_lo, sc.ceiling - c.max_top_below_ceiling_m),
        front: vec![[0usize; 2]; faces.len()],
        on_each: vec![0usize; faces.len()],
        profile: SupportProfile::new(
            ((hi - lo) / BIN_M).ceil().max(1.0) as usize,
            faces,
            sc.floor,
        ),
        orientation: FaceOrientation::new(hi - lo, faces),
    };
    let (s0, s1) = FREE_STRIP_M;
    sc.index
        .for_each_near_line(line, lo, hi, c.search_half_width_m + s1, |_, s, d, z| {
            let crossed = crossing.hides(s, z);
            let face = z >= z_lo && z <= z_hi && on_face(d);
            if !crossed {
                pass.profile.add(((s - lo) / BIN_M) as usize, d, z, face);
                if z > sc.floor + 0.1 && z < sc.floor + HEAD_HEIGHT_M {
                    pass.orientation.add(s - lo, d);
                }
                if face {
                    pass.zs.push(z);
                    for (k, f) in faces.iter().enumerate() {
                        pass.on_each[k] += usize::from((d - f).abs() <= tol);
                    }
                    let b = (((s - lo) / 0.1) as usize).min(stretches - 1);
                    pass.covered[b] = true;
                    pass.reach.add(b, z);
                }
            }
            if sc.on_slab(z, 0.04) {
                for (k, f) in faces.iter().enumerate() {
                    let off = d - f;
                    if off.abs() >= s0 && off.abs() <= s1 {
                        pass.front[k][usize::from(off > 0.0)] += 1;
                    }
                }
            }
        });
    pass
}
