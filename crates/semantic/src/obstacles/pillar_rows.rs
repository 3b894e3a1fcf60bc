//! A row of pillars with gaps narrower than two cells between them (hall-30 and hall-10 of the
//! bench: pillars 0.58 m square, 0.25 m apart) is one cluster, and no neck shows in its cells:
//! the laser sees a pillar's faces, not its inside, so a slice through a pillar holds a cell or
//! two (its front and back faces), as many as a slice through the gap holds of the mixed
//! pixels strung across it. The returns show the gaps: a pillar's faces stack returns from
//! the floor up, the gap holds stray ones (on hall-30, 131-169 returns per 10 cm slice through
//! a pillar, 31-68 through a gap). So a cluster standing on the floor whose top climbs to the
//! ceiling and which is longer than a column may be across (a row of pillars; not a desk, a
//! chair, a car or a cabinet under the ceiling, whose returns thin out where its shelves are
//! open) is cut where its slices hold under half the returns of its typical slice; each part
//! is then fitted and classed on its own (a column if it is one).

use super::classify::reaches;
use super::cluster::BandGrid;
use super::necks::{split_at_weighed_necks, Necks, MIN_SIDE_M};
use super::{DetectedObstacle, ObstacleConfig};
use crate::image_frame::ImageFrame;

/// A gap between pillars holds at most this share of the returns of a slice through a pillar
/// (a pillar's faces are seen from the floor up, the gap's mixed pixels are strays; on the
/// bench's rows, under 0.45).
const GAP_SHARE: f64 = 0.5;

/// True if the low cluster `o` (its top climbed into the band above) may be a row of pillars:
/// it stands on the floor, reaches the ceiling (as `classify` tells both) and is longer than a
/// column may be across.
pub(super) fn may_be_a_pillar_row(
    o: &DetectedObstacle,
    floor: f64,
    ceiling: f64,
    c: &ObstacleConfig,
) -> bool {
    let (on_floor, to_ceiling) = reaches(o, floor, ceiling, c);
    on_floor && to_ceiling && o.size[0] > c.column_max_across_m
}

/// `cells` of the low band `grid` cut where their slices hold under [`GAP_SHARE`] of the
/// returns of their typical slice (the gaps of a row of pillars, see the module docs).
pub(super) fn split_pillar_row(
    cells: Vec<usize>,
    grid: &BandGrid,
    frame: &ImageFrame,
) -> Vec<Vec<usize>> {
    let by_returns = Necks {
        weight: &|k| grid.count(k),
        share: GAP_SHARE,
        min_side_m: MIN_SIDE_M,
        min_width_m: 0.0,
    };
    split_at_weighed_necks(cells, frame, &by_returns)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;

    /// Cells of the test grid and their returns: `returns(along, across)` for the cell centres
    /// along x from x = 2 m and across y from y = 3 m (0 for an empty cell).
    fn cells_of(returns: impl Fn(f64, f64) -> usize) -> (Vec<usize>, Vec<usize>) {
        let frame = crate::obstacles::test_grid();
        let w = frame.width_px as usize;
        let mut cells = Vec::new();
        let mut counts = vec![0usize; frame.len()];
        for (k, count) in counts.iter_mut().enumerate() {
            let p = pixel_center(&frame, (k % w) as f64, (k / w) as f64);
            let n = returns(p.x - 2.0, p.y - 3.0);
            if n > 0 {
                cells.push(k);
                *count = n;
            }
        }
        (cells, counts)
    }

    /// A row of four hollow pillars 0.6 m square, 0.3 m apart, along x: each pillar's front
    /// and back faces hold `face` returns per cell, its side faces `side`; the gaps' cells
    /// (one along the row's middle: mixed pixels) hold `gap`.
    fn row(face: usize, side: usize, gap: usize) -> (Vec<usize>, Vec<usize>) {
        cells_of(|along, across| {
            if !(0.0..3.3).contains(&along) || across.abs() > 0.35 {
                return 0;
            }
            let at = along % 0.9;
            let in_pillar = at < 0.6;
            if in_pillar && (across.abs() - 0.3).abs() < 0.05 {
                face
            } else if in_pillar && !(0.05..=0.55).contains(&at) {
                side
            } else if !in_pillar && across.abs() < 0.05 {
                gap
            } else {
                0
            }
        })
    }

    /// The cells cut as a row of pillars would be, with `counts` returns each.
    fn cut(cells: Vec<usize>, counts: &[usize]) -> Vec<Vec<usize>> {
        let frame = crate::obstacles::test_grid();
        // (one point per return, each in its cell)
        let cell_of: Vec<u32> = cells
            .iter()
            .flat_map(|&k| std::iter::repeat_n(k as u32, counts[k]))
            .collect();
        let ids: Vec<u32> = (0..cell_of.len() as u32).collect();
        let grid = BandGrid::new(&frame, &ids, &cell_of);
        split_pillar_row(cells, &grid, &frame)
    }

    #[test]
    fn a_row_of_hollow_pillars_is_cut_at_its_gaps() {
        let (cells, counts) = row(30, 60, 12);
        let parts = cut(cells, &counts);
        assert_eq!(
            parts.len(),
            4,
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
    }

    #[test]
    fn a_shelf_as_dense_all_along_stays_whole() {
        // A shelf 3.3 x 0.4 m seen from its front: its front face as dense all along, a few
        // returns on its shelves behind.
        let (cells, counts) = cells_of(|along, across| {
            if !(0.0..3.3).contains(&along) || !(-0.2..0.2).contains(&across) {
                0
            } else if across < -0.1 {
                30
            } else {
                3
            }
        });
        assert_eq!(cut(cells, &counts).len(), 1);
    }

    #[test]
    fn only_what_stands_from_floor_to_ceiling_longer_than_a_column_may_be_a_row() {
        let c = ObstacleConfig::default();
        let thing = |z_range: (f64, f64), length: f64, overhead: bool| DetectedObstacle {
            class: cloud::EntityClass::Obstacle,
            center: glam::DVec2::ZERO,
            dir: glam::DVec2::X,
            size: [length, 0.6],
            z_range,
            hull: Vec::new(),
            fill: 1.0,
            support: 100,
            overhead,
            beside_top: false,
            rules: Vec::new(),
        };
        let (floor, ceiling) = (0.0, 3.0);
        assert!(may_be_a_pillar_row(
            &thing((0.05, 2.9), 3.4, false),
            floor,
            ceiling,
            &c
        ));
        // A cabinet 2.2 m tall, a single pillar, something hanging from the ceiling.
        assert!(!may_be_a_pillar_row(
            &thing((0.05, 2.2), 3.4, false),
            floor,
            ceiling,
            &c
        ));
        assert!(!may_be_a_pillar_row(
            &thing((0.05, 2.9), 0.6, false),
            floor,
            ceiling,
            &c
        ));
        assert!(!may_be_a_pillar_row(
            &thing((1.0, 2.9), 3.4, false),
            floor,
            ceiling,
            &c
        ));
        assert!(!may_be_a_pillar_row(
            &thing((2.0, 2.9), 3.4, true),
            floor,
            ceiling,
            &c
        ));
    }
}
