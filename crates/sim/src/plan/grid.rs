//! The 2D free-space grid: which cells the robot's centre may occupy. A cell is blocked where a
//! fixed box (wall, lintel, obstacle, column, furniture, ...) reaches into the robot's height
//! band (above the step it drives over, below its top plus a head margin: beams and lintels
//! above it do not block), where a stair step or landing stands (stairs are driven only
//! along their own legs of the tour), and, in a world with a floor, where there is no floor.
//! Door leaves and free-space sensors never block. Each cell's clearance (the distance to the
//! nearest blocked cell, an exact Euclidean distance transform) decides whether it is free:
//! at least the robot's half width plus the margin.

use super::distance::distance_transform;
use super::footprint::Footprint;
use super::PlanConfig;
use crate::error::{Result, SimError};
use crate::spec::{BoxSpec, WorldSpec};
use cloud::EntityClass;

/// Boxes whose bottom is this far above the robot's top do not block (m): sensor masts and
/// the sway of a tall chassis on a bump.
pub(crate) const HEAD_MARGIN_M: f64 = 0.1;
/// The grid reaches this far beyond the world's boxes (m).
const BORDER_M: f64 = 0.5;

/// The free-space grid of a world for one robot.
#[derive(Debug, Clone)]
pub(crate) struct FreeGrid {
    /// The lower-left corner of cell (0, 0) (m).
    origin_m: [f64; 2],
    cell_m: f64,
    nx: usize,
    ny: usize,
    /// Distance from each cell's centre to the nearest blocked cell's centre (m; 0 blocked).
    clearance_m: Vec<f32>,
    /// The clearance a cell needs to be free (m).
    needed_m: f64,
    floor_z_m: f64,
}

impl FreeGrid {
    /// The grid of `world` for a robot of footprint `fp`.
    pub(crate) fn build(world: &WorldSpec, fp: &Footprint, cfg: &PlanConfig) -> Result<FreeGrid> {
        // 1. The floor the robot stands on: the top of the largest floor box (else z = 0).
        let floors: Vec<&BoxSpec> = world
            .fixed
            .iter()
            .filter(|f| f.class == EntityClass::Floor)
            .map(|f| &f.geometry)
            .collect();
        let floor_z_m = floors
            .iter()
            .max_by(|a, b| area(a).total_cmp(&area(b)))
            .map_or(0.0, |b| b.center_m[2] + b.half_extents_m[2]);
        // 2. The extent: the floor's, else every box's, plus a border.
        let bounds = extent(world, &floors).ok_or_else(|| SimError::Invalid {
            element: "plan".into(),
            msg: "the world has no finite extent to plan in".into(),
        })?;
        let (w, h) = (
            bounds[2] - bounds[0] + 2.0 * BORDER_M,
            bounds[3] - bounds[1] + 2.0 * BORDER_M,
        );
        // Coarser cells where the world is too large for `max_cells` at the asked size.
        let cell_m = cfg.cell_m.max((w * h / cfg.max_cells as f64).sqrt() * 1.01);
        let (nx, ny) = ((w / cell_m).ceil() as usize, (h / cell_m).ceil() as usize);
        let (nx, ny) = (nx.max(1), ny.max(1));
        if nx.saturating_mul(ny) > cfg.max_cells.saturating_mul(2) {
            return Err(SimError::TooMany {
                element: "plan".into(),
                what: "grid cells".into(),
                count: nx.saturating_mul(ny),
                limit: cfg.max_cells,
            });
        }
        let mut g = FreeGrid {
            origin_m: [bounds[0] - BORDER_M, bounds[1] - BORDER_M],
            cell_m,
            nx,
            ny,
            clearance_m: vec![],
            // Blocked cells are painted up to half a cell beyond their boxes: a robot centre
            // this far from the nearest blocked cell centre is within half a cell of the
            // half width + margin from the box itself.
            needed_m: fp.half_width_m + cfg.margin_m,
            floor_z_m,
        };
        // 3. Blocked cells: no floor, boxes in the height band, stairs.
        let mut blocked = vec![!floors.is_empty(); nx * ny];
        for f in &floors {
            g.paint(&mut blocked, f, false);
        }
        let (low, high) = (
            floor_z_m + fp.max_rise_m,
            floor_z_m + fp.height_m + HEAD_MARGIN_M,
        );
        for f in world.fixed.iter().filter(|f| f.class != EntityClass::Floor) {
            let b = &f.geometry;
            let (bottom, top) = (
                b.center_m[2] - b.half_extents_m[2],
                b.center_m[2] + b.half_extents_m[2],
            );
            if top > low && bottom < high {
                g.paint(&mut blocked, b, true);
            }
        }
        for s in &world.stairs {
            for b in s.steps.iter().map(|st| &st.geometry).chain(&s.landing) {
                g.paint(&mut blocked, b, true);
            }
        }
        // 4. Clearance: the exact Euclidean distance transform of the blocked cells.
        g.clearance_m = distance_transform(&blocked, nx, ny)
            .into_iter()
            .map(|d2| (d2.sqrt() * cell_m) as f32)
            .collect();
        Ok(g)
    }

    /// Sets every cell whose centre lies in `b` (grown by half a cell, so that thin walls
    /// still cover the cells they cross) to `value`.
    fn paint(&self, cells: &mut [bool], b: &BoxSpec, value: bool) {
        let (c, s) = (b.yaw_deg.to_radians().cos(), b.yaw_deg.to_radians().sin());
        let grow = self.cell_m / 2.0;
        let (hx, hy) = (b.half_extents_m[0] + grow, b.half_extents_m[1] + grow);
        let (ex, ey) = (hx * c.abs() + hy * s.abs(), hx * s.abs() + hy * c.abs());
        let [x0, y0] = [b.center_m[0] - ex, b.center_m[1] - ey];
        let [x1, y1] = [b.center_m[0] + ex, b.center_m[1] + ey];
        let ix = |x: f64| ((x - self.origin_m[0]) / self.cell_m).floor();
        let iy = |y: f64| ((y - self.origin_m[1]) / self.cell_m).floor();
        let clamp_x = |v: f64| v.clamp(0.0, (self.nx - 1) as f64) as usize;
        let clamp_y = |v: f64| v.clamp(0.0, (self.ny - 1) as f64) as usize;
        if ix(x1) < 0.0 || iy(y1) < 0.0 || ix(x0) >= self.nx as f64 || iy(y0) >= self.ny as f64 {
            return;
        }
        for j in clamp_y(iy(y0))..=clamp_y(iy(y1)) {
            for i in clamp_x(ix(x0))..=clamp_x(ix(x1)) {
                let p = self.centre(j * self.nx + i);
                let (dx, dy) = (p[0] - b.center_m[0], p[1] - b.center_m[1]);
                let (u, v) = (dx * c + dy * s, -dx * s + dy * c);
                if u.abs() <= hx && v.abs() <= hy {
                    cells[j * self.nx + i] = value;
                }
            }
        }
    }

    /// The cell size (m).
    pub(crate) fn cell_m(&self) -> f64 {
        self.cell_m
    }

    /// The height of the floor the robot stands on (m).
    pub(crate) fn floor_z_m(&self) -> f64 {
        self.floor_z_m
    }

    /// Cells along x and y.
    pub(crate) fn dims(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Number of cells.
    pub(crate) fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// A cell's centre (m).
    pub(crate) fn centre(&self, cell: usize) -> [f64; 2] {
        let (i, j) = (cell % self.nx, cell / self.nx);
        [
            self.origin_m[0] + (i as f64 + 0.5) * self.cell_m,
            self.origin_m[1] + (j as f64 + 0.5) * self.cell_m,
        ]
    }

    /// The cell holding a point, if it is on the grid.
    pub(crate) fn cell_of(&self, p: [f64; 2]) -> Option<usize> {
        let i = ((p[0] - self.origin_m[0]) / self.cell_m).floor();
        let j = ((p[1] - self.origin_m[1]) / self.cell_m).floor();
        let inside = i >= 0.0 && j >= 0.0 && i < self.nx as f64 && j < self.ny as f64;
        inside.then(|| j as usize * self.nx + i as usize)
    }

    /// The distance from a cell's centre to the nearest blocked cell (m).
    pub(crate) fn clearance_m(&self, cell: usize) -> f64 {
        self.clearance_m[cell] as f64
    }

    /// Whether the robot's centre may be in this cell.
    pub(crate) fn is_free(&self, cell: usize) -> bool {
        self.clearance_m(cell) >= self.needed_m
    }

    /// Whether a point is on a free cell.
    pub(crate) fn free_at(&self, p: [f64; 2]) -> bool {
        self.cell_of(p).is_some_and(|c| self.is_free(c))
    }

    /// Whether every point of the segment from `a` to `b` is on a free cell.
    pub(crate) fn segment_free(&self, a: [f64; 2], b: [f64; 2]) -> bool {
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let n = (len / (self.cell_m / 2.0)).ceil().min(1.0e7) as usize;
        (0..=n.max(1)).all(|k| {
            let t = k as f64 / n.max(1) as f64;
            self.free_at([a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t])
        })
    }

    /// The free cell nearest to `p`, if any cell is free.
    pub(crate) fn nearest_free(&self, p: [f64; 2]) -> Option<usize> {
        (0..self.len())
            .filter(|&c| self.is_free(c))
            .min_by(|&a, &b| {
                let (pa, pb) = (self.centre(a), self.centre(b));
                let da = (pa[0] - p[0]).hypot(pa[1] - p[1]);
                let db = (pb[0] - p[0]).hypot(pb[1] - p[1]);
                da.total_cmp(&db).then(a.cmp(&b))
            })
    }

    /// The free cell nearest the centroid of the largest connected free region, if any.
    pub(crate) fn centre_of_largest_region(&self) -> Option<usize> {
        let mut label = vec![u32::MAX; self.len()];
        let (mut best, mut best_size) = (None, 0usize);
        let mut stack = vec![];
        let mut next = 0u32;
        for seed in 0..self.len() {
            if !self.is_free(seed) || label[seed] != u32::MAX {
                continue;
            }
            let (mut size, mut sum) = (0usize, [0.0f64; 2]);
            label[seed] = next;
            stack.push(seed);
            while let Some(c) = stack.pop() {
                size += 1;
                let p = self.centre(c);
                sum = [sum[0] + p[0], sum[1] + p[1]];
                for n in self.neighbours4(c) {
                    if self.is_free(n) && label[n] == u32::MAX {
                        label[n] = next;
                        stack.push(n);
                    }
                }
            }
            if size > best_size {
                best_size = size;
                best = Some((next, [sum[0] / size as f64, sum[1] / size as f64]));
            }
            next += 1;
        }
        let (region, centroid) = best?;
        (0..self.len())
            .filter(|&c| label[c] == region)
            .min_by(|&a, &b| {
                let (pa, pb) = (self.centre(a), self.centre(b));
                let da = (pa[0] - centroid[0]).hypot(pa[1] - centroid[1]);
                let db = (pb[0] - centroid[0]).hypot(pb[1] - centroid[1]);
                da.total_cmp(&db).then(a.cmp(&b))
            })
    }

    /// The 4 neighbours of a cell on the grid.
    pub(crate) fn neighbours4(&self, c: usize) -> impl Iterator<Item = usize> {
        let (i, j, nx, ny) = (c % self.nx, c / self.nx, self.nx, self.ny);
        [
            (i > 0).then(|| c - 1),
            (i + 1 < nx).then(|| c + 1),
            (j > 0).then(|| c - nx),
            (j + 1 < ny).then(|| c + nx),
        ]
        .into_iter()
        .flatten()
    }
}

fn area(b: &BoxSpec) -> f64 {
    b.half_extents_m[0] * b.half_extents_m[1]
}

/// [min x, min y, max x, max y] of the floor boxes, else of every fixed box, stair and opening.
fn extent(world: &WorldSpec, floors: &[&BoxSpec]) -> Option<[f64; 4]> {
    let mut boxes: Vec<&BoxSpec> = floors.to_vec();
    if boxes.is_empty() {
        boxes.extend(world.fixed.iter().map(|f| &f.geometry));
        boxes.extend(world.free_spaces.iter().map(|f| &f.geometry));
        for s in &world.stairs {
            boxes.extend(s.steps.iter().map(|st| &st.geometry));
            boxes.extend(&s.landing);
        }
    }
    let mut e = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for b in boxes {
        let (c, s) = (b.yaw_deg.to_radians().cos(), b.yaw_deg.to_radians().sin());
        let (hx, hy) = (b.half_extents_m[0], b.half_extents_m[1]);
        let (ex, ey) = (hx * c.abs() + hy * s.abs(), hx * s.abs() + hy * c.abs());
        e = [
            e[0].min(b.center_m[0] - ex),
            e[1].min(b.center_m[1] - ey),
            e[2].max(b.center_m[0] + ex),
            e[3].max(b.center_m[1] + ey),
        ];
    }
    e.iter().all(|v| v.is_finite()).then_some(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_cells_keep_the_half_width_and_margin_from_walls() {
        // A corridor x 0..10, walls at y = +-1.0 (0.2 m thick: faces at +-0.9).
        let b = scanner::Building::from_toml_str(
            r#"
            [floor]
            min_m = [0.0, -1.5]
            max_m = [10.0, 1.5]
            [ceiling]
            height_m = 2.5
            [[walls]]
            start_m = [0.0, -1.0]
            end_m = [10.0, -1.0]
            thickness_m = 0.2
            [[walls]]
            start_m = [0.0, 1.0]
            end_m = [10.0, 1.0]
            thickness_m = 0.2
            "#,
            std::path::Path::new("corridor.toml"),
        )
        .expect("building");
        let w = WorldSpec::from_building(&b).expect("world");
        let model = crate::RobotModel::builtin("pioneer3at").expect("built in");
        let fp = Footprint::of(&model);
        let cfg = PlanConfig::default();
        let g = FreeGrid::build(&w, &fp, &cfg).expect("grid");
        // The robot's centre keeps half its width (0.2475 m) + the 5 cm margin from each face,
        // within a cell either way.
        let edge = 0.9 - fp.half_width_m - cfg.margin_m;
        for y in [-edge + cfg.cell_m, 0.0, edge - cfg.cell_m] {
            assert!(g.free_at([5.0, y]), "free at y = {y}");
        }
        for y in [-edge - cfg.cell_m, edge + cfg.cell_m, 0.95, 1.2] {
            assert!(!g.free_at([5.0, y]), "blocked at y = {y}");
        }
        // Off the floor's end nothing is free.
        assert!(!g.free_at([10.3, 0.0]));
        assert_eq!(g.floor_z_m(), 0.0);
    }
}
