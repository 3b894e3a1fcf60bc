//! The floor around and under a flight (see the `stairs` module): a staircase hides the floor
//! under it, and the floor seen around it tells the local density of the scans.

use crate::scene::Scene;
use glam::DVec2;

/// Floor returns within `half.0` along `dir` and `half.1` across it of `centre` (along, across).
pub(super) fn floor_in_strip(
    sc: &Scene,
    dir: DVec2,
    centre: (f64, f64),
    half: (f64, f64),
) -> usize {
    let line = crate::points::Line2 {
        origin: dir * centre.0 + dir.perp() * centre.1,
        dir,
    };
    let mut n = 0usize;
    sc.index
        .for_each_near_line(&line, -half.0, half.0, half.1, |_, _, _, z| {
            n += usize::from((z - sc.floor).abs() <= 0.03);
        });
    n
}

/// Points per m² of the floor seen in a ring 0.3-1.3 m around a footprint (`s` along `dir`,
/// `t` across it): the local density of the scans, counted over the 10 cm cells where the
/// floor was seen.
pub(super) fn floor_density(sc: &Scene, dir: DVec2, s: (f64, f64), t: (f64, f64)) -> f64 {
    let (inner, outer) = (0.3, 1.3);
    let line = crate::points::Line2 {
        origin: dir.perp() * ((t.0 + t.1) / 2.0),
        dir,
    };
    let half = (t.1 - t.0) / 2.0;
    let mut cells = std::collections::HashSet::new();
    let mut n = 0usize;
    sc.index.for_each_near_line(
        &line,
        s.0 - outer,
        s.1 + outer,
        half + outer,
        |_, a, d, z| {
            let near = a > s.0 - inner && a < s.1 + inner && d.abs() < half + inner;
            if near || (z - sc.floor).abs() > 0.03 {
                return;
            }
            n += 1;
            cells.insert(((a / 0.1).floor() as i64, (d / 0.1).floor() as i64));
        },
    );
    if cells.is_empty() {
        0.0
    } else {
        n as f64 / (cells.len() as f64 * 0.01)
    }
}
