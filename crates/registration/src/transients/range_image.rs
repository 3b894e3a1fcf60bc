//! A scan's view of its surroundings: the nearest return per direction bin round its sensor,
//! from which it tells whether it saw past a point of another scan.

use super::TransientConfig;
use cloud::PointCloud;
use glam::Vec3;

/// A scan's nearest return per direction bin around its sensor (`INFINITY`: no return).
pub(crate) struct RangeImage {
    origin: Vec3,
    bin_rad: f32,
    cols: usize,
    rows: usize,
    range: Vec<f32>,
}

impl RangeImage {
    pub(crate) fn build(scan: &PointCloud, bin_deg: f64) -> RangeImage {
        let bin_rad = (bin_deg.to_radians()) as f32;
        let cols = (std::f32::consts::TAU / bin_rad).ceil() as usize;
        let rows = (std::f32::consts::PI / bin_rad).ceil() as usize + 1;
        let mut im = RangeImage {
            origin: scan.sensor_origin,
            bin_rad,
            cols,
            rows,
            range: vec![f32::INFINITY; cols * rows],
        };
        for p in scan.points.iter().filter(|p| p.is_finite()) {
            if let Some((col, row, r)) = im.bin_of(*p) {
                let cell = &mut im.range[row * cols + col];
                *cell = cell.min(r);
            }
        }
        im
    }

    /// The bin of the direction of `p` from the sensor, and its range.
    fn bin_of(&self, p: Vec3) -> Option<(usize, usize, f32)> {
        let d = p - self.origin;
        let r = d.length();
        // At the sensor (or NaN): no direction.
        if r.is_nan() || r <= 1e-3 {
            return None;
        }
        let az = d.y.atan2(d.x) + std::f32::consts::PI;
        let el = (d.z / r).clamp(-1.0, 1.0).asin() + std::f32::consts::FRAC_PI_2;
        let col = ((az / self.bin_rad) as usize).min(self.cols - 1);
        let row = ((el / self.bin_rad) as usize).min(self.rows - 1);
        Some((col, row, r))
    }

    /// Whether this scan saw past `p`: the point's bin and its neighbours with a return (at
    /// least `min_bins_seen` of them) all hold returns beyond it by the margin.
    pub(crate) fn sees_through(&self, p: Vec3, c: &TransientConfig) -> bool {
        let Some((col, row, r)) = self.bin_of(p) else {
            return false;
        };
        let beyond = r + (c.margin_m + c.margin_per_m * r as f64) as f32;
        let mut seen = 0;
        for dr in -1i64..=1 {
            let rr = row as i64 + dr;
            if rr < 0 || rr >= self.rows as i64 {
                continue;
            }
            for dc in -1i64..=1 {
                // Azimuth wraps round.
                let cc = (col as i64 + dc).rem_euclid(self.cols as i64) as usize;
                let v = self.range[rr as usize * self.cols + cc];
                if v.is_finite() {
                    if v <= beyond {
                        return false;
                    }
                    seen += 1;
                }
            }
        }
        seen >= c.min_bins_seen
    }
}
