//! What a cloud's sensors saw free: the voxels their laser rays crossed. A hypothesis that
//! puts one cloud's points where the other's rays passed contradicts what was measured (a
//! wall where the other scan looked through a doorway); what the other never saw is no
//! evidence either way (a scan that sees new rooms must not be held to the map).
//!
//! Three guards keep the free space honest: a ray frees nothing within one voxel of its
//! return (quantisation), a voxel holding one of the cloud's own points is never free, and a
//! voxel is free only when its six face neighbours were crossed too. Far from the sensor a
//! surface's returns are sparse and rays to its far parts graze its near parts between
//! returns; but a surface always borders the unseen space behind it, so its voxels do not
//! survive the last guard.

use glam::Vec3;
use std::collections::HashSet;

/// The voxels a cloud's sensors saw free.
pub(crate) struct SeenFree {
    voxel_m: f32,
    free: HashSet<(i32, i32, i32)>,
}

impl SeenFree {
    /// The free space of `points` (one per voxel of `voxel_m` is enough), each seen from its
    /// sensor `sensors[i]`, in one frame. Rays longer than `max_ray_m` are cut there (they
    /// would only cost time).
    pub(crate) fn new(points: &[Vec3], sensors: &[Vec3], voxel_m: f64, max_ray_m: f64) -> Self {
        let voxel = voxel_m as f32;
        let key = |p: Vec3| {
            let c = (p / voxel).floor();
            (c.x as i32, c.y as i32, c.z as i32)
        };
        let step = voxel / 2.0;
        let mut crossed = HashSet::new();
        for (p, s) in points.iter().zip(sensors) {
            let length = (*p - *s).length();
            let stop = (length - voxel).min(max_ray_m as f32);
            if stop.is_nan() || stop <= 0.0 {
                continue;
            }
            let dir = (*p - *s) / length;
            let steps = (stop / step) as usize;
            for k in 0..steps {
                crossed.insert(key(*s + dir * (k as f32 * step)));
            }
        }
        let own: HashSet<(i32, i32, i32)> = points.iter().map(|p| key(*p)).collect();
        let near_own = |v: (i32, i32, i32)| own.contains(&v);
        let faces = [
            (1, 0, 0),
            (-1, 0, 0),
            (0, 1, 0),
            (0, -1, 0),
            (0, 0, 1),
            (0, 0, -1),
        ];
        let free = crossed
            .iter()
            .copied()
            .filter(|&(x, y, z)| {
                faces
                    .iter()
                    .all(|(dx, dy, dz)| crossed.contains(&(x + dx, y + dy, z + dz)))
                    && !near_own((x, y, z))
            })
            .collect();
        SeenFree {
            voxel_m: voxel,
            free,
        }
    }

    /// Whether `p` lies in a voxel seen free.
    pub(crate) fn is_free(&self, p: Vec3) -> bool {
        let c = (p / self.voxel_m).floor();
        self.free.contains(&(c.x as i32, c.y as i32, c.z as i32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_clear_their_path_but_not_surfaces_or_beyond() {
        // A wall at x = 4 m seen from the origin, every 5 cm in y and z.
        let mut wall = Vec::new();
        for j in -40..=40 {
            for k in -40..=40 {
                wall.push(Vec3::new(4.0, j as f32 * 0.05, k as f32 * 0.05));
            }
        }
        let seen = SeenFree::new(&wall, &vec![Vec3::ZERO; wall.len()], 0.25, 100.0);
        assert!(seen.is_free(Vec3::new(2.0, 0.1, 0.1)));
        assert!(!seen.is_free(Vec3::new(3.9, 0.1, 0.1)), "next to the wall");
        assert!(!seen.is_free(Vec3::new(5.0, 0.1, 0.1)), "behind the wall");
        assert!(!seen.is_free(Vec3::new(2.0, 5.0, 0.1)), "never seen");
    }
}
