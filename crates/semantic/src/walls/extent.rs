//! Wall extent: the runs of a wall's face points along its plane, with the corners (where
//! another wall's face crosses the plane) left out (see the `walls` module).

use super::WallConfig;
use crate::points::Line2;
use crate::scene::Scene;

/// A crossing surface this near a wall's end is where it ends (the hidden bins beside the
/// surface keep the face points a few centimetres off it) ...
const CORNER_M: f64 = 0.15;
/// ... if it covers this much of the wall's height in one run: another wall's face, not a duct
/// or a pipe crossing the plane up high, nor a beam's underside over a parked car's return
/// (garage-305 of seeds 301-305: the lobby's east wall ran on 0.77 m along a beam past its
/// corner, a return off a car at 0.70 m under the beam's underside at 2.56 m spanning 1.9 m).
const CORNER_HEIGHT_M: f64 = 1.5;
/// ... where gaps up to this long between the heights it is seen at are joined (a wall's face
/// across the plane is hidden in stretches by what stands before it, or seen in sparse rows
/// from afar).
const CORNER_GAP_M: f64 = 0.5;
/// A crossing surface's heights are marked in this many bands from the floor to the ceiling
/// ...
const BANDS: usize = 64;
/// ... each at least this tall.
const MIN_BAND_M: f64 = 0.05;

/// The corner regions along a wall where a crossing surface hides the face points: per 3 cm
/// bin of the searched range, the heights `(z0, z1)` it covers, if any, and the tallest run
/// of heights it is seen in there and in the bins beside it (see [`CORNER_GAP_M`]; noise
/// spreads a surface into the neighbouring bins, and a door leaf ajar, crossing the plane at a
/// slant, is seen in each bin at a few heights only: the default building's stair room door
/// open 15 degrees was missed without them).
pub(crate) struct Crossings {
    r0: f64,
    bin: f64,
    heights: Vec<Option<(f64, f64)>>,
    tallest: Vec<f64>,
}

impl Crossings {
    /// Whether a crossing surface hides the point at `s` along the wall, height `z`.
    pub fn hides(&self, s: f64, z: f64) -> bool {
        let k = (s - self.r0) / self.bin;
        if k.is_nan() || k < 0.0 {
            return false;
        }
        matches!(self.heights.get(k as usize), Some(Some((z0, z1))) if z >= *z0 && z <= *z1)
    }

    /// The crossing surface nearest `end` within [`CORNER_M`] of it that covers a wall's
    /// height in one run ([`CORNER_HEIGHT_M`]): the face of a wall this one meets there, a
    /// corner.
    pub fn corner_near(&self, end: f64) -> Option<f64> {
        self.centres()
            .filter(|&(m, height)| height >= CORNER_HEIGHT_M && (m - end).abs() <= CORNER_M)
            .map(|(m, _)| m)
            .min_by(|p, q| (p - end).abs().total_cmp(&(q - end).abs()))
    }

    /// The crossing bins' centres along the wall and their tallest runs of heights.
    fn centres(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.heights
            .iter()
            .zip(&self.tallest)
            .enumerate()
            .filter(|(_, (h, _))| h.is_some())
            .map(|(k, (_, &t))| (self.r0 + (k as f64 + 0.5) * self.bin, t))
    }
}

/// A wall's extent along `line` from `[a, b]` (see the module docs), grown while it reaches the
/// searched range's ends, and the corners where a crossing surface hides the face points.
pub(crate) fn find_extent(
    line: &Line2,
    faces: &[f64],
    a: f64,
    b: f64,
    sc: &Scene,
    c: &WallConfig,
) -> Option<(f64, f64, Crossings)> {
    let hw = c.search_half_width_m;
    let tol = c.face_tolerance_m;
    let on_face = |d: f64| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let (f_lo, f_hi) = (faces[0] - 2.0 * tol, faces[faces.len() - 1] + 2.0 * tol);
    let band_m = ((sc.ceiling - sc.floor) / BANDS as f64).max(MIN_BAND_M);
    let band_of = |z: f64| (((z - sc.floor) / band_m).max(0.0) as usize).min(BANDS - 1);
    let (mut e0, mut e1) = (0.5f64, 0.5f64);
    // The points between the wall's heights within the searched range, walked once (a grown
    // range walks only the stretches it adds): `(along, height)` on a face, and
    // `(along, across, height)` off the faces (see below).
    type Seen = (Vec<(f64, f64)>, Vec<(f64, f64, f64)>);
    let mut seen: Seen = (Vec::new(), Vec::new());
    let mut walked: Option<(f64, f64)> = None;
    let walk = |seen: &mut Seen, s0: f64, s1: f64, keep: &dyn Fn(f64) -> bool| {
        sc.upright
            .for_each_near_line(line, s0, s1, hw, |_, s, d, z| {
                if z < z_lo || z > z_hi || !keep(s) {
                    return;
                }
                if on_face(d) {
                    seen.0.push((s, z));
                } else if d < f_lo || d > f_hi {
                    seen.1.push((s, d, z));
                }
            });
    };
    let mut found = None;
    for _ in 0..8 {
        let (r0, r1) = (a - e0, b + e1);
        match walked {
            None => walk(&mut seen, r0, r1, &|_| true),
            Some((w0, w1)) => {
                if r0 < w0 {
                    walk(&mut seen, r0, w0, &|s| s < w0);
                }
                if r1 > w1 {
                    walk(&mut seen, w1, r1, &|s| s > w1);
                }
            }
        }
        walked = Some((r0, r1));
        let (on_faces, off_faces) = &seen;
        // Per 3 cm of the line the spread of the points off the faces: a surface across the
        // line (another wall's face at a corner or junction) covers many distances; the face
        // points there belong to the corner, not to this wall's extent.
        let bin = 0.03;
        let nb = (((r1 - r0) / bin).ceil() as usize + 1).min(10_000_000);
        let bin_of = |s: f64| (((s - r0) / bin) as usize).min(nb - 1);
        let mut across = vec![(0u32, f64::INFINITY, f64::NEG_INFINITY); nb];
        let mut bands = vec![0u64; nb];
        for &(s, d, z) in off_faces {
            let k = bin_of(s);
            let x = &mut across[k];
            x.0 |= across_mark(d, hw);
            x.1 = x.1.min(z);
            x.2 = x.2.max(z);
            bands[k] |= 1 << band_of(z);
        }
        // A crossing surface hides the face points at its own heights only (a cupboard in
        // front of a wall leaves the wall above it).
        // Noise spreads a crossing surface into the neighbouring bins: they are hidden too.
        // (most bins have no crossing surface beside them: their points are not hidden)
        let near = |k: usize| k.saturating_sub(1)..(k + 2).min(nb);
        let beside: Vec<bool> = (0..nb)
            .map(|k| near(k).any(|j| crossing(across[j].0)))
            .collect();
        let hidden = |k: usize, z: f64| {
            beside[k]
                && near(k).any(|j| {
                    let x = &across[j];
                    crossing(x.0) && z >= x.1 - 0.1 && z <= x.2 + 0.1
                })
        };
        let s_vals: Vec<f64> = on_faces
            .iter()
            .filter(|&&(s, z)| !hidden(bin_of(s), z))
            .map(|p| p.0)
            .collect();
        let (lo, hi) = extent(&s_vals, a, b, c.max_gap_m)?;
        let grow_lo = lo <= r0 + c.max_gap_m;
        let grow_hi = hi >= r1 - c.max_gap_m;
        let crossing = Crossings {
            r0,
            bin,
            heights: across
                .iter()
                .map(|m| crossing(m.0).then_some((m.1 - 0.1, m.2 + 0.1)))
                .collect(),
            tallest: (0..nb)
                .map(|k| {
                    let m = bands[near(k)].iter().fold(0, |m, b| m | b);
                    tallest_run(m, band_m, CORNER_GAP_M)
                })
                .collect(),
        };
        // An end next to a wall-high crossing surface (the hidden bins keep it a few
        // centimetres off) is a corner: the wall ends at the surface.
        let snap = |end: f64| crossing.corner_near(end).unwrap_or(end);
        let (lo, hi) = (snap(lo), snap(hi));
        found = Some((lo, hi, crossing));
        if !grow_lo && !grow_hi {
            break;
        }
        if grow_lo {
            e0 *= 3.0;
        }
        if grow_hi {
            e1 *= 3.0;
        }
    }
    found
}

/// The bit of a point `d` off the plane (within `hw` of it) in a mask of 3 cm distance bins.
pub(crate) fn across_mark(d: f64, hw: f64) -> u32 {
    1 << ((((d + hw) / 0.03) as usize).min(31))
}

/// Whether the points off the plane marked in `mask` (see [`across_mark`]) spread over 15 cm or
/// more across it: a surface crossing the plane (another wall's face), not noise.
pub(crate) fn crossing(mask: u32) -> bool {
    mask.count_ones() >= 5
}

/// The tallest run of the height bands (each `band_m` tall) marked in `mask`, gaps of at most
/// `max_gap_m` joined.
fn tallest_run(mask: u64, band_m: f64, max_gap_m: f64) -> f64 {
    let max_gap = (max_gap_m / band_m + 1e-9).floor() as u32;
    // (the run so far: its first and last band)
    let (mut best, mut run) = (0u32, None::<(u32, u32)>);
    for k in (0..64).filter(|&k| mask & (1u64 << k) != 0) {
        let first = match run {
            Some((first, last)) if k - last - 1 <= max_gap => first,
            _ => k,
        };
        run = Some((first, k));
        best = best.max(k - first + 1);
    }
    best as f64 * band_m
}

/// The union of the runs of the values `s` (gaps at most `max_gap`) that overlap `[a, b]`.
/// Linear time: the values go into 1 cm bins that keep their least and greatest value.
fn extent(s: &[f64], a: f64, b: f64, max_gap: f64) -> Option<(f64, f64)> {
    let lo = s.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = s.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    let n = (((hi - lo) / 0.01) as usize + 1).min(10_000_000);
    let mut bins = vec![(f64::INFINITY, f64::NEG_INFINITY); n];
    for &v in s {
        let bin = &mut bins[(((v - lo) / 0.01) as usize).min(n - 1)];
        bin.0 = bin.0.min(v);
        bin.1 = bin.1.max(v);
    }
    let mut runs: Vec<(f64, f64)> = Vec::new();
    for &(b0, b1) in bins.iter().filter(|x| x.0 <= x.1) {
        match runs.last_mut() {
            Some(r) if b0 - r.1 <= max_gap => r.1 = b1,
            _ => runs.push((b0, b1)),
        }
    }
    let hits: Vec<&(f64, f64)> = runs.iter().filter(|r| r.1 >= a && r.0 <= b).collect();
    let lo = hits.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let hi = hits.iter().map(|r| r.1).fold(f64::NEG_INFINITY, f64::max);
    (lo < hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// A wall's face along +Y at x = 0 from y = 0 to 3 (ceiling 3 m), a beam's underside
    /// across its plane at 2.55 m from y = 3.0 to 3.5 and one return off a car under it at
    /// 0.70 m; `crossing_wall`: the face of a wall across the plane at y = 3.05 too, seen in
    /// rows 0.17 m apart.
    fn face_beam_and_car(crossing_wall: bool) -> Vec<Vec3> {
        let steps = |from: f32, to: f32, step: f32| {
            (0..=((to - from) / step).round() as usize).map(move |i| from + step * i as f32)
        };
        let mut points: Vec<Vec3> = steps(0.0, 3.0, 0.03)
            .flat_map(|y| steps(0.1, 2.9, 0.1).map(move |z| Vec3::new(0.0, y, z)))
            .collect();
        points.extend(
            steps(-0.3, 0.3, 0.03)
                .flat_map(|x| steps(3.0, 3.5, 0.03).map(move |y| Vec3::new(x, y, 2.55))),
        );
        points.push(Vec3::new(0.25, 3.05, 0.7));
        if crossing_wall {
            points.extend(
                steps(-0.3, 0.3, 0.03)
                    .flat_map(|x| steps(0.1, 2.9, 0.17).map(move |z| Vec3::new(x, 3.05, z))),
            );
        }
        points
    }

    /// Regression: garage-305 (seeds 301-305): a beam's underside over a parked car's return
    /// spans 1.85 m of height across the lobby's east wall's plane and read as the face of a
    /// wall it meets, a corner, where no cut of the wall running on along the beam is made. A
    /// wall's face across the plane covers its heights in one run.
    #[test]
    fn a_beams_underside_over_a_cars_return_is_no_corner() {
        let corner_at_the_end = |crossing_wall: bool| {
            let points = face_beam_and_car(crossing_wall);
            let index = XyIndex::new(&points, DVec2::new(-1.0, -1.0), DVec2::new(1.0, 5.0), 0.25);
            let sc = Scene::with_one_index(&points, &index, 0.0, 3.0);
            let line = Line2::through(DVec2::new(0.0, 0.0), DVec2::new(0.0, 1.0));
            let c = WallConfig::default();
            let (_, hi, crossings) =
                find_extent(&line, &[0.0], 0.2, 2.8, &sc, &c).expect("the face has an extent");
            assert!((hi - 3.0).abs() < 0.1, "{hi}");
            crossings.corner_near(hi)
        };
        assert_eq!(corner_at_the_end(false), None);
        let corner = corner_at_the_end(true).expect("a wall's face crosses the plane");
        // (at its bin or the one beside it: a bin's neighbours' heights count with its own)
        assert!((corner - 3.05).abs() < 0.06, "{corner}");
    }

    #[test]
    fn the_tallest_run_joins_bands_across_short_gaps_only() {
        // Bands 0.1 m: 0-3 and 6-9 (a gap of 0.2 m) joined, 20 (0.1 m) apart.
        let mask = 0b1111 | 0b1111 << 6 | 1 << 20;
        assert!((tallest_run(mask, 0.1, 0.2) - 1.0).abs() < 1e-9);
        assert!((tallest_run(mask, 0.1, 0.1) - 0.4).abs() < 1e-9);
        assert!((tallest_run(1 << 63, 0.1, 0.5) - 0.1).abs() < 1e-9);
        assert_eq!(tallest_run(0, 0.1, 0.5), 0.0);
    }

    #[test]
    fn extent_joins_runs_over_the_segment_only() {
        let s = [-3.0, -2.9, 0.1, 0.2, 0.4, 1.0, 1.1, 2.5, 2.6];
        assert_eq!(extent(&s, 0.0, 1.0, 0.35), Some((0.1, 1.1)));
        assert_eq!(extent(&s, 0.0, 2.55, 0.35), Some((0.1, 2.6)));
        assert_eq!(extent(&[], 0.0, 1.0, 0.35), None);
    }
}
