//! Vertical structure seen from above: the points of walls, furniture sides and columns
//! projected to the horizontal plane, one per occupied vertical column of the search grid.
//!
//! Gravity is known (scanners are levelled), so the horizontal layout of what stands upright
//! is the same in two scans up to a yaw and a horizontal translation; floors and ceilings
//! cover every column and would only blur the comparison. A column (a square of the cell's
//! edge, as tall as the scene) counts as structure when its points fill at least
//! [`MIN_RUN_CELLS`] consecutive cells of the same edge in height: a floor or ceiling fills
//! one (two where its noise straddles a cell boundary), and a column that sees both the floor
//! and the ceiling of a room fills two apart, while a wall fills every cell up to its height.

use glam::{Vec2, Vec3};
use std::collections::HashMap;

/// Consecutive filled height cells that make a column structure (3: at 0.25 m cells anything
/// upright and at least half a metre tall; a horizontal surface fills at most 2).
pub(crate) const MIN_RUN_CELLS: u32 = 3;
/// Height cells tracked per column, centred on the sensor's height (64 bits of a mask: at
/// 0.25 m cells, 8 m above and below the sensor; what lies beyond is not used).
const HEIGHT_CELLS: i64 = 64;

/// The structure columns of `points` (already levelled: z up, and relative to a sensor, so
/// that heights are heights above or below it), as the centroid of each structure column's
/// points in x, y.
pub(crate) fn structure_columns(points: impl Iterator<Item = Vec3>, cell_m: f32) -> Vec<Vec2> {
    struct Column {
        heights: u64,
        sum: Vec2,
        count: u32,
    }
    let mut columns: HashMap<(i32, i32), Column> = HashMap::new();
    for p in points {
        let h = (p.z / cell_m).floor() as i64 + HEIGHT_CELLS / 2;
        if !(0..HEIGHT_CELLS).contains(&h) {
            continue;
        }
        let key = ((p.x / cell_m).floor() as i32, (p.y / cell_m).floor() as i32);
        let c = columns.entry(key).or_insert(Column {
            heights: 0,
            sum: Vec2::ZERO,
            count: 0,
        });
        c.heights |= 1 << h;
        c.sum += Vec2::new(p.x, p.y);
        c.count += 1;
    }
    let mut out: Vec<((i32, i32), Vec2)> = columns
        .into_iter()
        .filter(|(_, c)| longest_run_at_least(c.heights, MIN_RUN_CELLS))
        .map(|(key, c)| (key, c.sum / c.count as f32))
        .collect();
    // A HashMap's order varies between runs: sort so that the search is deterministic.
    out.sort_unstable_by_key(|(key, _)| *key);
    out.into_iter().map(|(_, p)| p).collect()
}

/// Whether `mask` holds `run` consecutive set bits.
fn longest_run_at_least(mask: u64, run: u32) -> bool {
    let mut m = mask;
    for _ in 1..run {
        m &= m >> 1;
    }
    m != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_set_bits_are_counted() {
        assert!(longest_run_at_least(0b0111_0000, 3));
        assert!(!longest_run_at_least(0b0110_0110, 3));
        assert!(!longest_run_at_least(0, 1));
        assert!(longest_run_at_least(1 << 63, 1));
    }

    #[test]
    fn walls_are_structure_and_floor_with_ceiling_is_not() {
        let mut points = Vec::new();
        // A floor 1.5 m below the sensor and a ceiling 1.2 m above it, 4 x 4 m, every 5 cm.
        for i in 0..80 {
            for j in 0..80 {
                let (x, y) = (i as f32 * 0.05 - 2.0, j as f32 * 0.05 - 2.0);
                points.push(Vec3::new(x, y, -1.5));
                points.push(Vec3::new(x, y, 1.2));
            }
        }
        // A wall at x = 2.1 m, from the floor to the ceiling.
        for j in 0..80 {
            for k in 0..54 {
                points.push(Vec3::new(2.1, j as f32 * 0.05 - 2.0, k as f32 * 0.05 - 1.5));
            }
        }
        let columns = structure_columns(points.into_iter(), 0.25);
        assert_eq!(columns.len(), 16, "the wall's 16 columns only");
        assert!(columns.iter().all(|c| (c.x - 2.1).abs() < 1e-4));
    }
}
