//! Validation of a building description: every number finite and sensible, every door
//! inside its wall and clear of its neighbours, every staircase and ramp buildable.

use crate::building::{Building, Door, Wall};
use crate::error::{Result, ScannerError};
use std::path::Path;

/// The most parts (boxes) a building may produce; guards against absurd descriptions.
const MAX_PARTS: usize = 200_000;
/// How far outside the floor's rectangle an element may reach (walls stand on its edges,
/// clutter may stand outside); anything farther is a mistake, not a building.
const MAX_OUTSIDE_FLOOR_M: f64 = 100.0;
/// The steepest ramp accepted (degrees): the steepest car-park ramps are about 20 % (11
/// degrees) and wheelchair ramps 1:12 (5 degrees); beyond 20 degrees a slope is no longer
/// something a wheeled robot drives up, it is a wall or a staircase.
const MAX_RAMP_PITCH_DEG: f64 = 20.0;

impl Building {
    /// Checks the description; the error names `path` and the offending element.
    pub fn validate(&self, path: &Path) -> Result<()> {
        let bad = |element: String, msg: String| ScannerError::InvalidBuilding {
            path: path.to_path_buf(),
            element,
            msg,
        };
        let f = &self.floor;
        all_finite(&[
            f.min_m[0],
            f.min_m[1],
            f.max_m[0],
            f.max_m[1],
            f.thickness_m,
        ])
        .map_err(|m| bad("floor".into(), m))?;
        if f.max_m[0] - f.min_m[0] < 0.1 || f.max_m[1] - f.min_m[1] < 0.1 {
            return Err(bad(
                "floor".into(),
                "max_m must exceed min_m by at least 0.1 m in x and y".into(),
            ));
        }
        if (f.max_m[0] - f.min_m[0]).max(f.max_m[1] - f.min_m[1]) > 10_000.0 {
            return Err(bad(
                "floor".into(),
                "a building over 10 km wide is not supported".into(),
            ));
        }
        positive("floor.thickness_m", f.thickness_m).map_err(|m| bad("floor".into(), m))?;
        let c = &self.ceiling;
        all_finite(&[c.height_m, c.thickness_m]).map_err(|m| bad("ceiling".into(), m))?;
        if !(0.5..=100.0).contains(&c.height_m) {
            return Err(bad(
                "ceiling".into(),
                format!("height_m = {} must be between 0.5 and 100", c.height_m),
            ));
        }
        positive("ceiling.thickness_m", c.thickness_m).map_err(|m| bad("ceiling".into(), m))?;
        let reach = Reach::of(self);
        let mut parts = 2usize;
        for (i, w) in self.walls.iter().enumerate() {
            reach
                .points(&[w.start_m, w.end_m], 0.0)
                .map_err(|m| bad(format!("walls[{i}]{}", named(&w.name)), m))?;
            parts += self
                .check_wall(w)
                .map_err(|m| bad(format!("walls[{i}]{}", named(&w.name)), m))?;
            for (j, d) in w.doors.iter().enumerate() {
                check_door(w, d, self.wall_height_m(w), &w.doors[..j])
                    .map_err(|m| bad(format!("walls[{i}]{}.doors[{j}]", named(&w.name)), m))?;
            }
        }
        for (i, s) in self.stairs.iter().enumerate() {
            let el = || format!("stairs[{i}]{}", named(&s.name));
            all_finite(&[
                s.start_m[0],
                s.start_m[1],
                s.direction_deg,
                s.rise_m,
                s.run_m,
                s.width_m,
                s.landing_m,
                s.base_m,
            ])
            .map_err(|m| bad(el(), m))?;
            if s.steps == 0 || s.steps > 1000 {
                return Err(bad(
                    el(),
                    format!("steps = {} must be between 1 and 1000", s.steps),
                ));
            }
            if !(0.01..=0.5).contains(&s.rise_m) || !(0.05..=2.0).contains(&s.run_m) {
                return Err(bad(
                    el(),
                    "rise_m must be within 0.01..0.5 and run_m within 0.05..2".into(),
                ));
            }
            positive("width_m", s.width_m).map_err(|m| bad(el(), m))?;
            if s.landing_m < 0.0 {
                return Err(bad(el(), "landing_m must not be negative".into()));
            }
            if s.base_m < 0.0 {
                return Err(bad(el(), "base_m must not be negative".into()));
            }
            if s.base_m + s.rise_m * s.steps as f64 >= c.height_m {
                return Err(bad(el(), "the staircase rises through the ceiling".into()));
            }
            let length_m = s.run_m * s.steps as f64 + s.landing_m;
            reach
                .points(&[s.start_m], length_m.max(s.width_m))
                .map_err(|m| bad(el(), m))?;
            parts += s.steps as usize + 1;
        }
        for (i, b) in self.boxes.iter().enumerate() {
            let el = || format!("boxes[{i}]{}", named(&b.name));
            all_finite(&[b.center_m[0], b.center_m[1], b.center_m[2], b.yaw_deg])
                .map_err(|m| bad(el(), m))?;
            if !crate::building::BOX_CLASSES.contains(&b.class) {
                return Err(bad(
                    el(),
                    format!(
                        "class `{}` is not one a box may have (furniture, obstacle, column, beam)",
                        b.class
                    ),
                ));
            }
            for s in b.size_m {
                positive("size_m", s).map_err(|m| bad(el(), m))?;
            }
            let size_m = b.size_m[0].max(b.size_m[1]).max(b.size_m[2]);
            reach
                .points(&[[b.center_m[0], b.center_m[1]]], size_m)
                .map_err(|m| bad(el(), m))?;
            if b.center_m[2].abs() > MAX_OUTSIDE_FLOOR_M + c.height_m {
                return Err(bad(
                    el(),
                    format!(
                        "center_m z = {} m is far outside the building",
                        b.center_m[2]
                    ),
                ));
            }
            parts += 1;
        }
        for (i, r) in self.ramps.iter().enumerate() {
            let el = || format!("ramps[{i}]{}", named(&r.name));
            check_ramp(r, c.height_m).map_err(|m| bad(el(), m))?;
            reach
                .points(&[r.start_m], r.length_m.max(r.width_m))
                .map_err(|m| bad(el(), m))?;
            parts += 1;
        }
        if parts > MAX_PARTS {
            return Err(bad(
                "building".into(),
                format!("{parts} parts is more than the {MAX_PARTS} supported"),
            ));
        }
        Ok(())
    }

    fn check_wall(&self, w: &Wall) -> Result<usize, String> {
        all_finite(&[
            w.start_m[0],
            w.start_m[1],
            w.end_m[0],
            w.end_m[1],
            w.thickness_m,
        ])?;
        let len = w.length_m();
        if len < 0.01 {
            return Err("start_m and end_m must be at least 1 cm apart".into());
        }
        if !(w.thickness_m > 0.0 && w.thickness_m <= 5.0) {
            return Err(format!(
                "thickness_m = {} must be within (0, 5]",
                w.thickness_m
            ));
        }
        let h = self.wall_height_m(w);
        if !(h.is_finite() && h > 0.0 && h <= 100.0) {
            return Err(format!("height_m = {h} must be within (0, 100]"));
        }
        Ok(2 * w.doors.len() + w.doors.len() + 1)
    }
}

/// The region elements must lie in: the floor's rectangle grown by [`MAX_OUTSIDE_FLOOR_M`].
struct Reach {
    min_m: [f64; 2],
    max_m: [f64; 2],
}

impl Reach {
    fn of(b: &Building) -> Reach {
        let grow = |v: f64, sign: f64| v + sign * MAX_OUTSIDE_FLOOR_M;
        Reach {
            min_m: [grow(b.floor.min_m[0], -1.0), grow(b.floor.min_m[1], -1.0)],
            max_m: [grow(b.floor.max_m[0], 1.0), grow(b.floor.max_m[1], 1.0)],
        }
    }

    /// `Ok` if every point lies within the region and `size_m` is no larger than the region.
    fn points(&self, points: &[[f64; 2]], size_m: f64) -> Result<(), String> {
        for p in points {
            if p[0] < self.min_m[0]
                || p[0] > self.max_m[0]
                || p[1] < self.min_m[1]
                || p[1] > self.max_m[1]
            {
                return Err(format!(
                    "({}, {}) lies more than {MAX_OUTSIDE_FLOOR_M} m outside the floor",
                    p[0], p[1]
                ));
            }
        }
        let span = (self.max_m[0] - self.min_m[0]).max(self.max_m[1] - self.min_m[1]);
        if size_m > span {
            return Err(format!(
                "a size of {size_m} m is larger than the building ({span} m with the margin)"
            ));
        }
        Ok(())
    }
}

fn check_door(w: &Wall, d: &Door, wall_h: f64, earlier: &[Door]) -> Result<(), String> {
    all_finite(&[d.offset_m, d.width_m, d.height_m])?;
    let len = w.length_m();
    positive("width_m", d.width_m)?;
    positive("height_m", d.height_m)?;
    if d.width_m > len {
        return Err(format!(
            "the door ({} m) is wider than its wall ({len:.3} m)",
            d.width_m
        ));
    }
    if d.offset_m < 0.0 || d.offset_m + d.width_m > len + 1e-9 {
        return Err(format!(
            "the opening {:.3}..{:.3} m lies outside the wall (0..{len:.3} m)",
            d.offset_m,
            d.offset_m + d.width_m
        ));
    }
    if d.height_m > wall_h + 1e-9 {
        return Err(format!(
            "the door ({} m) is taller than its wall ({wall_h} m)",
            d.height_m
        ));
    }
    if let Some(o) = earlier
        .iter()
        .find(|o| d.offset_m < o.offset_m + o.width_m && o.offset_m < d.offset_m + d.width_m)
    {
        return Err(format!(
            "the opening overlaps the door at offset_m = {}",
            o.offset_m
        ));
    }
    if let Some(l) = &d.leaf {
        all_finite(&[l.open_deg, l.thickness_m])?;
        if !(0.0..=180.0).contains(&l.open_deg) {
            return Err(format!(
                "leaf.open_deg = {} must be within 0..180",
                l.open_deg
            ));
        }
        if !(l.thickness_m > 0.0 && l.thickness_m <= w.thickness_m) {
            return Err(format!(
                "leaf.thickness_m = {} must be positive and no thicker than the wall",
                l.thickness_m
            ));
        }
    }
    Ok(())
}

fn check_ramp(r: &crate::building::Ramp, ceiling_m: f64) -> Result<(), String> {
    all_finite(&[
        r.start_m[0],
        r.start_m[1],
        r.direction_deg,
        r.length_m,
        r.width_m,
        r.rise_m,
        r.thickness_m,
    ])?;
    positive("length_m", r.length_m)?;
    positive("width_m", r.width_m)?;
    positive("rise_m", r.rise_m)?;
    if !(r.thickness_m > 0.0 && r.thickness_m <= 2.0) {
        return Err(format!(
            "thickness_m = {} must be within (0, 2]",
            r.thickness_m
        ));
    }
    let pitch_deg = r.pitch_rad().to_degrees();
    if pitch_deg > MAX_RAMP_PITCH_DEG {
        return Err(format!(
            "a slope of {pitch_deg:.1} degrees (rise_m {} over length_m {}) is steeper than the \
             {MAX_RAMP_PITCH_DEG} degrees a ramp may have",
            r.rise_m, r.length_m
        ));
    }
    if r.rise_m >= ceiling_m {
        return Err("the ramp rises through the ceiling".into());
    }
    Ok(())
}

fn named(name: &str) -> String {
    if name.is_empty() {
        String::new()
    } else {
        format!(" ('{name}')")
    }
}

fn all_finite(values: &[f64]) -> Result<(), String> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(format!("{v} is not a finite number")),
        None => Ok(()),
    }
}

fn positive(name: &str, v: f64) -> Result<(), String> {
    if v > 0.0 {
        Ok(())
    } else {
        Err(format!("{name} = {v} must be positive"))
    }
}

#[cfg(test)]
#[path = "validate_tests.rs"]
mod tests;
