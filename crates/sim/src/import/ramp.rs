//! Ramps in the world, whose boxes turn about z only: a run of blocks following the ramp's
//! slope within [`RAMP_STEP_M`], a building's pitched slab (`building`) or a semantic map's
//! ramp, which rises along its box's x axis from the floor to the box's top.

use crate::spec::BoxSpec;

/// The most blocks a ramp becomes.
pub(crate) const MAX_RAMP_BLOCKS: f64 = 2000.0;
/// The height of one block's step along a ramp (m): a centimetre is below what a wheel of any
/// robot feels (kerbs and door sills are 2 cm and more).
pub(crate) const RAMP_STEP_M: f64 = 0.01;

/// The blocks of a ramp whose top rises along its box's x axis from the box's bottom at its
/// -x end to its top at its +x end (a semantic map's ramp): solid from the bottom, each block's
/// top at the slope's height in its middle.
#[cfg_attr(not(feature = "semantic"), allow(dead_code))]
pub(crate) fn wedge_blocks(b: &BoxSpec) -> Vec<BoxSpec> {
    let [hx, hy, hz] = b.half_extents_m;
    let (s, c) = b.yaw_deg.to_radians().sin_cos();
    let bottom = b.center_m[2] - hz;
    let rise = 2.0 * hz;
    let n = (rise / RAMP_STEP_M).ceil().clamp(1.0, MAX_RAMP_BLOCKS) as usize;
    (0..n)
        .map(|k| {
            let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
            // Along x from -hx to hx; the block's top at the slope's height at its middle.
            let along = -hx + hx * (t0 + t1);
            let top = bottom + rise * (t0 + t1) / 2.0;
            BoxSpec {
                center_m: [
                    b.center_m[0] + c * along,
                    b.center_m[1] + s * along,
                    (bottom + top) / 2.0,
                ],
                half_extents_m: [
                    hx * (t1 - t0),
                    hy,
                    ((top - bottom) / 2.0).max(RAMP_STEP_M / 4.0),
                ],
                yaw_deg: b.yaw_deg,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wedge_rises_along_its_box_within_a_centimetre() {
        // 4 m long, 1.5 m wide, rising 0.5 m towards +y (yaw 90 degrees) from z = 0.
        let b = BoxSpec {
            center_m: [1.0, 2.0, 0.25],
            half_extents_m: [2.0, 0.75, 0.25],
            yaw_deg: 90.0,
        };
        let blocks = wedge_blocks(&b);
        assert_eq!(blocks.len(), 50);
        for k in blocks.windows(2) {
            assert!(k[1].center_m[1] > k[0].center_m[1], "rises towards +y");
        }
        for q in &blocks {
            let top = q.center_m[2] + q.half_extents_m[2];
            let slope_z = 0.5 * (q.center_m[1] - 0.0) / 4.0;
            assert!((top - slope_z).abs() <= RAMP_STEP_M, "{top} vs {slope_z}");
            assert!(
                (q.center_m[2] - q.half_extents_m[2]).abs() < 1e-9,
                "stands on z = 0"
            );
            assert!((q.center_m[0] - 1.0).abs() < 1e-9);
        }
        // The blocks cover the box's length once.
        let length: f64 = blocks.iter().map(|q| 2.0 * q.half_extents_m[0]).sum();
        assert!((length - 4.0).abs() < 1e-9);
    }
}
