//! The risers' evidence for a stair model (the paper's "parallel lines at equal spacing"): a
//! riser seen from in front of the flight is a vertical face across its width, so its points
//! pile up in a narrow band along the direction of ascent, at the heights between its step and
//! the one below. The upper envelope (see `envelope`) keeps one point per bin and loses that
//! pile; worse, where several scans see a flight, the side face's stepped edge is smeared along
//! the direction by the range noise at grazing incidence (a few centimetres before each edge),
//! and those returns, above a model with the true edges, make an earlier and shorter-run model
//! fit the envelope better. The heights between `k rise` and `(k + 1) rise` holding points
//! within [`HALF_WIDTH_M`] of the model's `k`-th front edge (a riser spans them; a tread, or
//! clutter's top, at one height does not) pin the edges where the risers are. (Seen from its
//! side only, a flight's side face spans a riser's heights from its edge on, and nothing before
//! it: there the envelope's violations keep the edges from sliding late.)

use glam::DVec2;

/// Half the width of the band around a front edge in which a riser's points are counted: the
/// range noise of a face seen head-on, and the registration's spread between scans.
const HALF_WIDTH_M: f64 = 0.02;

/// Bins along the direction (m).
const BIN_M: f64 = 0.01;

/// A riser is a vertical face: its points span the heights of its band, counted in cells of
/// this height (m). A tread's edge, or clutter's top, at one height fills one or two.
const CELL_M: f64 = 0.02;

/// Height cells a tread (and its noise) fills: a riser shows more.
const TREAD_CELLS: u32 = 2;

/// Height cells at which a riser's evidence saturates (10 cm of its height seen).
const SATURATION_CELLS: u32 = 5;

/// The weight of a saturated riser in a fit's score, in envelope bins (a level's support
/// counts up to 5 bins, a violation -3): a seen riser outweighs the few bins of smear before it.
pub(super) const RISER_WEIGHT: f64 = 10.0;

/// The height cells each riser's band holds, per bin along the direction.
pub(super) struct RiserBands {
    s_lo: f64,
    /// Band `k` (heights from `k rise + 3 cm`, over the tread below, which runs on before the
    /// edge, to `(k + 1) rise + 2 cm`): per bin, a bit per height cell holding a point.
    masks: Vec<Vec<u32>>,
}

impl RiserBands {
    /// The bands of `n` risers of `rise` from points `(xy, height above the foot)`.
    pub(super) fn new(pts: &[(DVec2, f64)], dir: DVec2, n: u32, rise: f64) -> RiserBands {
        let (mut s_lo, mut s_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (q, _) in pts {
            s_lo = s_lo.min(q.dot(dir));
            s_hi = s_hi.max(q.dot(dir));
        }
        // (the number of bins from the points' own extent, at most 100 m of them)
        let nb = if s_hi >= s_lo {
            ((s_hi - s_lo) / BIN_M) as usize + 1
        } else {
            0
        }
        .min(10_000);
        let mut masks = vec![vec![0u32; nb]; n as usize];
        for (q, z) in pts {
            let k = ((z - 0.03) / rise).floor();
            if k < 0.0 || k >= f64::from(n) || *z > (k + 1.0) * rise + 0.02 {
                continue;
            }
            let cell = (((z - 0.03 - k * rise) / CELL_M) as u32).min(31);
            let bin = ((q.dot(dir) - s_lo) / BIN_M) as usize;
            if let Some(m) = masks[k as usize].get_mut(bin) {
                *m |= 1 << cell;
            }
        }
        RiserBands { s_lo, masks }
    }

    /// The evidence for front edges at `s0 + k run` (see the module docs).
    pub(super) fn score(&self, run: f64, s0: f64) -> f64 {
        let per_cell = RISER_WEIGHT / f64::from(SATURATION_CELLS - TREAD_CELLS);
        self.masks
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let edge = s0 + k as f64 * run - self.s_lo;
                let lo = ((edge - HALF_WIDTH_M) / BIN_M).floor().max(0.0) as usize;
                let hi = (((edge + HALF_WIDTH_M) / BIN_M).floor().max(-1.0) + 1.0) as usize;
                let cells = m
                    .get(lo..hi.min(m.len()))
                    .unwrap_or(&[])
                    .iter()
                    .fold(0u32, |a, b| a | b)
                    .count_ones();
                f64::from(cells.clamp(TREAD_CELLS, SATURATION_CELLS) - TREAD_CELLS) * per_cell
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three risers of 0.17 m every 0.28 m from x = 0.5, sampled every 2 cm in height and
    /// 5 cm across: the true edges score all of them, edges half a run early none.
    #[test]
    fn the_true_edges_collect_every_riser() {
        let (rise, run) = (0.17, 0.28);
        let mut pts = Vec::new();
        for k in 0..3 {
            for i in 0..8 {
                for j in 0..4 {
                    let z = k as f64 * rise + 0.01 + 0.02 * i as f64;
                    pts.push((DVec2::new(0.5 + k as f64 * run, 0.05 * j as f64), z));
                }
            }
        }
        let bands = RiserBands::new(&pts, DVec2::X, 3, rise);
        assert!((bands.score(run, 0.5) - 3.0 * RISER_WEIGHT).abs() < 1e-9);
        assert_eq!(bands.score(run, 0.5 - run / 2.0), 0.0);
        // Treads at the risers' tops (one height each) are no risers.
        let treads: Vec<(DVec2, f64)> = (0..3)
            .flat_map(|k| {
                (0..20).map(move |i| {
                    let x = 0.5 + k as f64 * run + 0.01 * i as f64;
                    (DVec2::new(x, 0.0), (k + 1) as f64 * rise)
                })
            })
            .collect();
        let bands = RiserBands::new(&treads, DVec2::X, 3, rise);
        assert_eq!(bands.score(run, 0.5), 0.0);
    }
}
