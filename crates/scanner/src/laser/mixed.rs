//! Mixed pixels at depth edges. A beam has a footprint (its divergence times the range); where
//! that footprint straddles a depth edge, part of the light comes back from the foreground and
//! part from the background, and a time-of-flight sensor that cannot separate the two echoes
//! reports a range in between: points floating between the two surfaces (Ye and Borenstein,
//! "Characterization of a 2-D laser scanner for mobile robot obstacle negotiation", ICRA 2002,
//! analyse them for the SICK LMS 200). Echoes far enough apart are resolved: the sensor keeps
//! the first.
//!
//! Cost: only beams next to a depth jump in the organised grid (a neighbour's first surface
//! differs by more than `min_separation_m`) are looked at again, with four extra rays on the
//! rim of the footprint; only where those disagree does the footprint straddle the edge.

use cloud::{check_range, Rng};
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Mixed pixels where a footprint straddles a depth edge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MixedPixels {
    /// Chance that a footprint straddling an edge returns a mixed range (0: never).
    pub probability: f64,
    /// Depth differences within a footprint smaller than this are no edge (metres).
    pub min_separation_m: f64,
    /// Echoes farther apart than this are resolved by the sensor: no mixing (metres).
    pub max_separation_m: f64,
}

impl Default for MixedPixels {
    fn default() -> Self {
        MixedPixels::off()
    }
}

/// Rays cast per re-examined beam: its centre and four on the footprint's rim.
const FOOTPRINT_RAYS: usize = 5;

impl MixedPixels {
    /// No mixed pixels.
    pub fn off() -> MixedPixels {
        MixedPixels {
            probability: 0.0,
            ..MixedPixels::real()
        }
    }

    /// The preset: 70 % of straddling footprints mix (in the rest one echo dominates), edges
    /// from 5 cm (five times the laser's 1 cm noise) up to 2 m: a pulsed sensor whose pulse is
    /// a few nanoseconds long (about a metre of light) merges echoes closer than about that,
    /// and its receiver's filtering widens it (a modelling choice, not a data sheet value).
    pub fn real() -> MixedPixels {
        MixedPixels {
            probability: 0.7,
            min_separation_m: 0.05,
            max_separation_m: 2.0,
        }
    }

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range(
            "realism.mixed.probability",
            self.probability,
            0.0,
            1.0,
            "a probability within 0..1",
        )?;
        check_range(
            "realism.mixed.min_separation_m",
            self.min_separation_m,
            1e-3,
            100.0,
            "within 1 mm..100 m",
        )?;
        check_range(
            "realism.mixed.max_separation_m",
            self.max_separation_m,
            self.min_separation_m,
            1000.0,
            "within min_separation_m..1000 m",
        )?;
        Ok(())
    }

    /// The beams (row-major indices of a `rows x cols` grid) next to a depth edge: a
    /// 4-neighbour whose first surface is another one (`first_id`) and nearer or farther
    /// (`first_t`, NaN where none) by more than `min_separation_m`. One surface seen at a
    /// grazing angle has large range steps between beams too, but no edge.
    pub(crate) fn edge_candidates(
        &self,
        first_t: &[f32],
        first_id: &[u32],
        rows: usize,
        cols: usize,
    ) -> Vec<usize> {
        let jump = self.min_separation_m as f32;
        let edge = |k: usize, n: usize| {
            first_id[n] != first_id[k] && (first_t[k] - first_t[n]).abs() > jump
        };
        (0..rows * cols)
            .filter(|&k| {
                let (j, i) = (k / cols, k % cols);
                first_t[k].is_finite()
                    && ((i > 0 && edge(k, k - 1))
                        || (i + 1 < cols && edge(k, k + 1))
                        || (j > 0 && edge(k, k - cols))
                        || (j + 1 < rows && edge(k, k + cols)))
            })
            .collect()
    }

    /// The four rim directions of the footprint of unit beam `d` whose full divergence is
    /// `divergence_rad`.
    pub(crate) fn footprint_rim(d: Vec3, divergence_rad: f32) -> [Vec3; 4] {
        let u = d.any_orthonormal_vector();
        let v = d.cross(u);
        let h = (divergence_rad / 2.0).tan();
        [u, -u, v, -v].map(|e| (d + e * h).normalize())
    }

    /// The mixed range of a footprint whose centre and rim rays meet their first surfaces
    /// `ids` at `t` (centre first), if it straddles an edge (two surfaces) within the
    /// separations and the draw says so: between the nearest and farthest surface, weighted by
    /// the share of the footprint on the far one (jittered within one ray's share).
    pub(crate) fn mixed_range(
        &self,
        t: &[f32; FOOTPRINT_RAYS],
        ids: &[u32; FOOTPRINT_RAYS],
        rng: &mut Rng,
    ) -> Option<f32> {
        if ids.iter().all(|&id| id == ids[0]) {
            return None;
        }
        let near = t.iter().copied().fold(f32::INFINITY, f32::min);
        let far = t.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        let gap = far - near;
        if !(gap.is_finite()
            && gap >= self.min_separation_m as f32
            && gap <= self.max_separation_m as f32)
        {
            return None;
        }
        if !rng.chance(self.probability) {
            return None;
        }
        let far_rays = t.iter().filter(|&&x| x > near + gap / 2.0).count();
        let share = far_rays as f64 / FOOTPRINT_RAYS as f64;
        let jitter = (rng.unit() - 0.5) / FOOTPRINT_RAYS as f64;
        let w = (share + jitter).clamp(0.05, 0.95) as f32;
        Some(near + w * gap)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_footprints_across_two_surfaces_within_the_separations_mix_between_them() {
        let m = MixedPixels {
            probability: 1.0,
            ..MixedPixels::real()
        };
        let mut rng = Rng::new(5);
        let two = [0, 0, 1, 0, 1];
        for _ in 0..100 {
            let r = m
                .mixed_range(&[2.0, 2.0, 3.0, 2.0, 3.0], &two, &mut rng)
                .expect("mixes");
            assert!(r > 2.0 && r < 3.0, "{r}");
        }
        // One surface (even at a grazing angle, its ranges spread), two too far apart, or too
        // close: no mixing.
        assert_eq!(m.mixed_range(&[2.0; 5], &two, &mut rng), None);
        assert_eq!(
            m.mixed_range(&[2.0, 2.0, 3.0, 2.0, 3.0], &[4; 5], &mut rng),
            None
        );
        assert_eq!(
            m.mixed_range(&[2.0, 2.0, 9.0, 2.0, 9.0], &two, &mut rng),
            None
        );
        assert_eq!(
            m.mixed_range(&[2.0, 2.0, 2.01, 2.0, 2.0], &two, &mut rng),
            None
        );
        let off = MixedPixels::off();
        assert_eq!(
            off.mixed_range(&[2.0, 2.0, 3.0, 2.0, 3.0], &two, &mut rng),
            None
        );
        // Candidates: the beams either side of the jump between two surfaces in a 2 x 4
        // grid; one surface with the same jumps has none.
        let t = [1.0, 1.0, 5.0, 5.0, 1.0, 1.0, 5.0, 5.0];
        let ids = [0, 0, 1, 1, 0, 0, 1, 1];
        assert_eq!(m.edge_candidates(&t, &ids, 2, 4), vec![1, 2, 5, 6]);
        assert!(m.edge_candidates(&t, &[3; 8], 2, 4).is_empty());
        let rim = MixedPixels::footprint_rim(Vec3::X, 0.01);
        for r in rim {
            assert!((r.angle_between(Vec3::X) - 0.005).abs() < 1e-4);
        }
    }
}
