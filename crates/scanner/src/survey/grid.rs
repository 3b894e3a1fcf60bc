//! The survey's floor grid: cells blocked by what stands on the floor, free cells clear of
//! them, connected regions and line of sight.

use crate::building::{Building, Swing};
use crate::geometry::BuildingGeometry;
use cloud::EntityClass;

/// Things whose bottom is above this height (m) are walked under: beams and ducts hang
/// higher, a person and a tripod are lower.
pub const BLOCKING_TOP_M: f32 = 1.9;
/// The most grid cells a survey grid may have; a larger floor gets coarser cells.
const MAX_CELLS: f64 = 4.0e6;

/// The floor as a grid of cells, blocked or not.
pub(super) struct Grid {
    pub origin: [f64; 2],
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    pub blocked: Vec<bool>,
}

impl Grid {
    fn new(b: &Building, cell_m: f64) -> Grid {
        let f = &b.floor;
        let (w, h) = (f.max_m[0] - f.min_m[0], f.max_m[1] - f.min_m[1]);
        let cell = cell_m.max((w * h / MAX_CELLS).sqrt());
        let (nx, ny) = ((w / cell).ceil() as usize, (h / cell).ceil() as usize);
        Grid {
            origin: f.min_m,
            cell,
            nx,
            ny,
            blocked: vec![false; nx * ny],
        }
    }

    pub fn centre(&self, i: usize) -> [f64; 2] {
        [
            self.origin[0] + (i % self.nx) as f64 * self.cell + self.cell / 2.0,
            self.origin[1] + (i / self.nx) as f64 * self.cell + self.cell / 2.0,
        ]
    }

    pub fn index(&self, p: [f64; 2]) -> Option<usize> {
        let x = ((p[0] - self.origin[0]) / self.cell).floor();
        let y = ((p[1] - self.origin[1]) / self.cell).floor();
        (x >= 0.0 && y >= 0.0 && (x as usize) < self.nx && (y as usize) < self.ny)
            .then(|| y as usize * self.nx + x as usize)
    }

    /// Marks the cells the oriented rectangle touches (grown by half a cell, so that a
    /// closed 4 cm door leaf or a chair leg between cell centres still blocks).
    fn block(&mut self, c: [f64; 2], half: [f64; 2], yaw: f64) {
        let half = [half[0] + self.cell / 2.0, half[1] + self.cell / 2.0];
        let (s, co) = yaw.sin_cos();
        for (i, d) in self.cells_around(c, half[0].hypot(half[1])) {
            if (d[0] * co + d[1] * s).abs() <= half[0] && (-d[0] * s + d[1] * co).abs() <= half[1] {
                self.blocked[i] = true;
            }
        }
    }

    /// The cells of the square of half-edge `r` round `c` (clamped to the grid), each with its
    /// centre's offset from `c`.
    fn cells_around(&self, c: [f64; 2], r: f64) -> Vec<(usize, [f64; 2])> {
        let lo = self.index_clamped([c[0] - r, c[1] - r]);
        let hi = self.index_clamped([c[0] + r, c[1] + r]);
        (lo[1]..=hi[1])
            .flat_map(|y| (lo[0]..=hi[0]).map(move |x| y * self.nx + x))
            .map(|i| {
                let p = self.centre(i);
                (i, [p[0] - c[0], p[1] - c[1]])
            })
            .collect()
    }

    fn index_clamped(&self, p: [f64; 2]) -> [usize; 2] {
        let f = |v: f64, n: usize| (v.max(0.0).floor() as usize).min(n.saturating_sub(1));
        [
            f((p[0] - self.origin[0]) / self.cell, self.nx),
            f((p[1] - self.origin[1]) / self.cell, self.ny),
        ]
    }

    /// True if the straight line between cell centres crosses no blocked cell.
    pub fn sight(&self, a: usize, b: usize) -> bool {
        let (pa, pb) = (self.centre(a), self.centre(b));
        let d = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        let n = (d / (self.cell * 0.5)).ceil() as usize;
        (1..n).all(|k| {
            let t = k as f64 / n as f64;
            let p = [pa[0] + (pb[0] - pa[0]) * t, pa[1] + (pb[1] - pa[1]) * t];
            self.index(p).is_some_and(|i| !self.blocked[i])
        })
    }

    /// The cells farther than `r` from every blocked cell (and not on the grid's edge).
    pub fn clear_of(&self, r: f64) -> Vec<bool> {
        let k = (r / self.cell).ceil() as isize;
        let offsets: Vec<(isize, isize)> = (-k..=k)
            .flat_map(|dy| (-k..=k).map(move |dx| (dx, dy)))
            .filter(|(dx, dy)| ((dx * dx + dy * dy) as f64).sqrt() * self.cell <= r)
            .collect();
        let mut free = vec![true; self.blocked.len()];
        for (i, f) in free.iter_mut().enumerate() {
            let (x, y) = ((i % self.nx) as isize, (i / self.nx) as isize);
            *f = offsets.iter().all(|(dx, dy)| {
                let (u, v) = (x + dx, y + dy);
                u >= 0
                    && v >= 0
                    && (u as usize) < self.nx
                    && (v as usize) < self.ny
                    && !self.blocked[v as usize * self.nx + u as usize]
            });
        }
        free
    }

    /// Connected regions (4-neighbours) of the `free` cells: a region index per cell.
    pub fn regions(&self, free: &[bool]) -> (Vec<Option<usize>>, Vec<Vec<usize>>) {
        let mut of = vec![None; free.len()];
        let mut regions: Vec<Vec<usize>> = Vec::new();
        for start in 0..free.len() {
            if !free[start] || of[start].is_some() {
                continue;
            }
            let id = regions.len();
            let mut cells = vec![start];
            of[start] = Some(id);
            let mut k = 0;
            while k < cells.len() {
                let i = cells[k];
                k += 1;
                let (x, y) = (i % self.nx, i / self.nx);
                let mut next = Vec::with_capacity(4);
                if x > 0 {
                    next.push(i - 1);
                }
                if x + 1 < self.nx {
                    next.push(i + 1);
                }
                if y > 0 {
                    next.push(i - self.nx);
                }
                if y + 1 < self.ny {
                    next.push(i + self.nx);
                }
                for j in next {
                    if free[j] && of[j].is_none() {
                        of[j] = Some(id);
                        cells.push(j);
                    }
                }
            }
            regions.push(cells);
        }
        (of, regions)
    }

    /// The cells where a door's leaf swings: within the door's width of its hinge (and the
    /// tripod's `clearance_m` beyond it), on the side the leaf opens to. A surveyor sets no
    /// tripod there: whoever opens or closes the door knocks it, and standing beside an open
    /// leaf, the leaf hides a wide sector of the room (garage-301's lobby pose, 0.46 m beside
    /// its leaf, never saw 0.52 m of the wall behind it).
    pub fn door_swings(&self, b: &Building, clearance_m: f64) -> Vec<bool> {
        let mut swing = vec![false; self.blocked.len()];
        for w in b.walls.iter().filter(|w| w.length_m() > 0.0) {
            let len = w.length_m();
            let u = [
                (w.end_m[0] - w.start_m[0]) / len,
                (w.end_m[1] - w.start_m[1]) / len,
            ];
            for d in &w.doors {
                let (Some(leaf), Some(s)) = (&d.leaf, d.hinge_offset_m()) else {
                    continue;
                };
                // The normal on the side the leaf opens to (left of the wall's direction for
                // `Swing::Left`).
                let side = match leaf.swing {
                    Swing::Left => [-u[1], u[0]],
                    Swing::Right => [u[1], -u[0]],
                };
                let r = d.width_m + clearance_m;
                for (i, v) in self.cells_around(w.point_at_m(s), r) {
                    if v[0].hypot(v[1]) <= r && v[0] * side[0] + v[1] * side[1] >= 0.0 {
                        swing[i] = true;
                    }
                }
            }
        }
        swing
    }

    pub fn touches_edge(&self, cells: &[usize]) -> bool {
        cells.iter().any(|&i| {
            let (x, y) = (i % self.nx, i / self.nx);
            x <= 1 || y <= 1 || x + 2 >= self.nx || y + 2 >= self.ny
        })
    }
}

/// The floor grid of `b`: blocked where a solid stands below [`BLOCKING_TOP_M`]; with
/// `doors_shut`, every door opening is blocked too (to tell rooms apart).
pub(super) fn floor_grid(
    b: &Building,
    g: &BuildingGeometry,
    cell_m: f64,
    doors_shut: bool,
) -> Grid {
    let mut grid = Grid::new(b, cell_m);
    for p in g.parts() {
        let class = p.label.class;
        let is_slab =
            matches!(class, EntityClass::Floor | EntityClass::Ceiling) && p.pitch_rad == 0.0;
        // A pitched part's vertical extent is bounded by its bounding sphere.
        let reach = if p.pitch_rad == 0.0 {
            p.half_extents_m.z
        } else {
            p.half_extents_m.length()
        };
        let bottom = p.center_m.z - reach;
        if is_slab || bottom > BLOCKING_TOP_M || p.center_m.z + reach < 0.02 {
            continue;
        }
        let (c, h) = (p.center_m, p.half_extents_m);
        let along = if p.pitch_rad == 0.0 {
            f64::from(h.x)
        } else {
            f64::from(h.x * p.pitch_rad.cos() + h.z * p.pitch_rad.sin().abs())
        };
        grid.block(
            [f64::from(c.x), f64::from(c.y)],
            [along, f64::from(h.y)],
            f64::from(p.yaw_rad),
        );
    }
    if doors_shut {
        for w in &b.walls {
            let len = w.length_m();
            let u = [
                (w.end_m[0] - w.start_m[0]) / len,
                (w.end_m[1] - w.start_m[1]) / len,
            ];
            for d in &w.doors {
                let s = d.offset_m + d.width_m / 2.0;
                grid.block(
                    [w.start_m[0] + u[0] * s, w.start_m[1] + u[1] * s],
                    [d.width_m / 2.0 + 0.05, w.thickness_m / 2.0 + 0.05],
                    u[1].atan2(u[0]),
                );
            }
        }
    }
    grid
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// A wall along x (0..4 m) with a 1 m door at 1..2 m whose leaf, hinged at `hinge`,
    /// swings to `swing`.
    fn swings_of(hinge: &str, swing: &str) -> (Grid, Vec<bool>) {
        let toml = format!(
            r#"
            [floor]
            min_m = [-1.0, -2.0]
            max_m = [5.0, 2.0]
            [ceiling]
            height_m = 2.5
            [[walls]]
            start_m = [0.0, 0.0]
            end_m = [4.0, 0.0]
            thickness_m = 0.1
            [[walls.doors]]
            offset_m = 1.0
            width_m = 1.0
            height_m = 2.0
            [walls.doors.leaf]
            hinge = "{hinge}"
            swing = "{swing}"
            open_deg = 90.0
            "#
        );
        let b = Building::from_toml_str(&toml, Path::new("door.toml")).expect("valid");
        let grid = floor_grid(&b, &BuildingGeometry::new(&b), 0.1, false);
        let swings = grid.door_swings(&b, 0.3);
        (grid, swings)
    }

    #[test]
    fn a_doors_swing_is_the_half_disc_its_leaf_sweeps_and_the_tripods_clearance() {
        let at = |(grid, swings): &(Grid, Vec<bool>), p: [f64; 2]| {
            swings[grid.index(p).expect("on the grid")]
        };
        // Hinged at the opening's start (1, 0), opening to the left (+y).
        let left = swings_of("start", "left");
        assert!(at(&left, [1.55, 0.55]));
        assert!(at(&left, [1.05, 1.25]), "within the leaf and the clearance");
        assert!(
            !at(&left, [1.05, 1.45]),
            "beyond the leaf and the clearance"
        );
        assert!(
            !at(&left, [1.55, -0.55]),
            "the side the leaf does not open to"
        );
        // Hinged at its end (2, 0), opening to the right (-y).
        let right = swings_of("end", "right");
        assert!(at(&right, [1.55, -0.55]));
        assert!(!at(&right, [1.55, 0.55]));
        assert!(!at(&right, [0.55, -0.55]), "1.5 m from the hinge");
    }
}
