//! The goals a tour can include, each with its legs: a door opening the robot fits through
//! (a straight leg along its normal from an approach point on one side to a point past its free
//! space on the other, as far towards the latch as the robot fits), a staircase it can climb
//! (from a run-up before its foot to the middle of its landing); or why it cannot. Ramps are
//! in [`super::ramp_leg`].

use super::footprint::Footprint;
use super::grid::FreeGrid;
use super::{Goal, PlanConfig, Unreachable};
use crate::spec::{BoxSpec, FreeSpaceSpec, StairsSpec, WorldSpec};

/// The run-up before a staircase's foot (m), so the robot arrives facing up the stairs.
pub(crate) const RUN_UP_M: f64 = 0.5;

/// A door opening the robot fits through: its two sides.
pub(crate) struct DoorLeg {
    pub name: String,
    /// Per side: (approach point, exit point on the other side, whether entering from this
    /// side pushes the leaf), for the sides where both points are free.
    pub sides: Vec<([f64; 2], [f64; 2], bool)>,
    /// Why the side the leaf swings to is no entry (the robot cannot pull the leaf), if so.
    pub pull_refused: Option<String>,
    /// The free space: centre, unit vector along the opening, unit normal, half extents.
    centre: [f64; 2],
    along: [f64; 2],
    normal: [f64; 2],
    half_m: [f64; 2],
}

impl DoorLeg {
    /// Where a point is relative to the opening: (along, across) in metres.
    pub(crate) fn local(&self, p: [f64; 2]) -> (f64, f64) {
        let d = [p[0] - self.centre[0], p[1] - self.centre[1]];
        (
            d[0] * self.along[0] + d[1] * self.along[1],
            d[0] * self.normal[0] + d[1] * self.normal[1],
        )
    }

    pub(crate) fn inside(&self, p: [f64; 2]) -> bool {
        let (u, v) = self.local(p);
        u.abs() <= self.half_m[0] && v.abs() <= self.half_m[1]
    }

    /// The straight leg through the opening entered from the side of `p`, if it has one.
    pub(crate) fn leg_from(&self, p: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
        let side = self.local(p).1;
        self.sides
            .iter()
            .find(|(a, _, _)| self.local(*a).1 * side > 0.0)
            .map(|&(a, e, _)| (a, e))
    }
}

/// A staircase or ramp the robot can climb: up from `run_up` through `foot` to `top`.
pub(crate) struct ClimbLeg {
    pub goal: Goal,
    pub run_up: [f64; 2],
    pub foot: [f64; 2],
    pub top: [f64; 2],
}

fn unit(v: [f64; 2]) -> Option<[f64; 2]> {
    let n = v[0].hypot(v[1]);
    (n > 1e-9).then(|| [v[0] / n, v[1] / n])
}

pub(crate) fn add(p: [f64; 2], d: [f64; 2], s: f64) -> [f64; 2] {
    [p[0] + d[0] * s, p[1] + d[1] * s]
}

/// Half the extent of a box along a horizontal unit direction.
fn half_along(b: &BoxSpec, d: [f64; 2]) -> f64 {
    let (c, s) = (b.yaw_deg.to_radians().cos(), b.yaw_deg.to_radians().sin());
    (d[0] * c + d[1] * s).abs() * b.half_extents_m[0]
        + (-d[0] * s + d[1] * c).abs() * b.half_extents_m[1]
}

/// The legs through an opening, or why the robot cannot pass it.
pub(crate) fn door_leg(
    world: &WorldSpec,
    grid: &FreeGrid,
    fp: &Footprint,
    cfg: &PlanConfig,
    fs: &FreeSpaceSpec,
) -> Result<DoorLeg, Unreachable> {
    let leaf = fs
        .door
        .and_then(|id| world.doors.iter().find(|d| d.entity == id));
    let name = leaf.map_or(fs.name.clone(), |d| d.name.clone());
    let fail = |reason: String| Unreachable {
        goal: Goal::Door(name.clone()),
        reason,
    };
    let g = &fs.geometry;
    let yaw = g.yaw_deg.to_radians();
    let normal = [-yaw.sin(), yaw.cos()];
    let (width, needed) = (
        2.0 * g.half_extents_m[0],
        2.0 * (fp.half_width_m + cfg.margin_m),
    );
    if width < needed {
        return Err(fail(format!(
            "the opening is {width:.2} m wide, the robot needs {needed:.2} m"
        )));
    }
    // The side the leaf swings to (+1/-1 along the normal); entering from the other pushes it.
    let swing = leaf.and_then(|d| {
        let towards_free_end = unit([
            d.leaf.center_m[0] - d.hinge_m[0],
            d.leaf.center_m[1] - d.hinge_m[1],
        ])?;
        let s = d.opens.sign();
        let moves = [-towards_free_end[1] * s, towards_free_end[0] * s];
        Some((moves[0] * normal[0] + moves[1] * normal[1]).signum())
    });
    // Through the opening's middle, or with a leaf, as far to its latch side as the robot fits:
    // a leaf pushed near its hinge takes a large force (a short lever), which breaks hinges.
    let latch = leaf.and_then(|d| {
        unit([
            d.leaf.center_m[0] - d.hinge_m[0],
            d.leaf.center_m[1] - d.hinge_m[1],
        ])
    });
    // From the side the leaf swings to, the robot must get past the leaf's free edge as the
    // map has it: the gap between that edge and the far jamb, 2 w sin(angle / 2), must take
    // the robot (it pushes a leaf, it cannot pull one: one ajar towards it is pushed shut).
    let pull_gap = leaf.map(|d| {
        let w = 2.0 * d.leaf.half_extents_m[0];
        2.0 * w * (d.initial_deg.to_radians() / 2.0).sin().abs()
    });
    let pull_ok = pull_gap.is_none_or(|gap| gap >= needed);
    let centre = [g.center_m[0], g.center_m[1]];
    let play = (g.half_extents_m[0] - fp.half_width_m - cfg.margin_m).max(0.0);
    let hy = g.half_extents_m[1];
    // Out of the free space: the chassis' half length beyond it, ideally the whole robot's
    // half length plus the margin (room to turn there); on the side the leaf swings to, so
    // far that turning there cannot sweep the leaf (the leaf's length plus the turning
    // radius from the hinge, which sits at a jamb).
    let near = hy + fp.chassis_half_length_m + cfg.margin_m;
    let turn = fp.half_length_m.max(fp.turn_radius_m()) + cfg.margin_m;
    let leaf_m = leaf.map_or(0.0, |d| 2.0 * d.leaf.half_extents_m[0]);
    let far = |side: f64| {
        let clear_of_leaf = ((leaf_m + turn).powi(2) - g.half_extents_m[0].powi(2))
            .max(0.0)
            .sqrt();
        let swung = swing.is_some_and(|w| w == side);
        if swung {
            (hy + turn).max(clear_of_leaf)
        } else {
            hy + turn
        }
    };
    let point = |c: [f64; 2], side: f64| -> Option<[f64; 2]> {
        let far = far(side);
        let steps = ((far - near) / grid.cell_m()).ceil().max(0.0) as usize;
        (0..=steps.min(1000))
            .map(|k| (far - k as f64 * grid.cell_m()).max(near))
            .map(|off| add(c, normal, side * off))
            .find(|p| grid.free_at(*p))
    };
    // The largest shift towards the latch that leaves a free way through.
    let shifts = (play / grid.cell_m()).floor().min(100.0) as usize;
    let mut sides = vec![];
    let mut room = [false; 2];
    let mut pull_only = false;
    for k in (0..=shifts).rev() {
        let c = add(
            centre,
            latch.unwrap_or([0.0, 0.0]),
            k as f64 * grid.cell_m(),
        );
        for (i, side) in [1.0, -1.0].into_iter().enumerate() {
            let (a, e) = (point(c, side), point(c, -side));
            room[i] |= a.is_some();
            let (Some(a), Some(e)) = (a, e) else {
                continue;
            };
            if grid.segment_free(a, e) {
                let push = swing.is_none_or(|w| w != side);
                if push || pull_ok {
                    sides.push((a, e, push));
                } else {
                    pull_only = true;
                }
            }
        }
        if !sides.is_empty() {
            break;
        }
    }
    let pull_refused = pull_only.then(|| {
        let (gap, deg) = (pull_gap.unwrap_or(0.0), leaf.map_or(0.0, |d| d.initial_deg));
        format!(
            "the leaf swings towards the other side, and the robot cannot pull it: ajar \
             {deg:.0} deg, it leaves {gap:.2} m past its free edge, the robot needs {needed:.2} m"
        )
    });
    if sides.is_empty() {
        if let Some(why) = pull_refused {
            return Err(fail(format!(
                "no room on the side that pushes the leaf; {why}"
            )));
        }
    }
    if sides.is_empty() {
        return Err(fail(match room {
            [false, false] => "no room for the robot on either side of the opening".into(),
            [true, true] => "no free way for the robot straight through the opening".into(),
            _ => "no room for the robot on one side of the opening (nothing mapped there, or \
                  something in the way)"
                .into(),
        }));
    }
    Ok(DoorLeg {
        name,
        sides,
        pull_refused,
        centre,
        along: [yaw.cos(), yaw.sin()],
        normal,
        half_m: [g.half_extents_m[0], hy],
    })
}

/// The climb of a staircase, or why the robot cannot climb it.
pub(crate) fn stairs_leg(
    grid: &FreeGrid,
    fp: &Footprint,
    robot_name: &str,
    cfg: &PlanConfig,
    s: &StairsSpec,
) -> Result<ClimbLeg, Unreachable> {
    let fail = |reason: String| Unreachable {
        goal: Goal::Stairs(s.name.clone()),
        reason,
    };
    let (Some(first), Some(last)) = (s.steps.first(), s.steps.last()) else {
        return Err(fail("the staircase has no steps".into()));
    };
    let (b0, bl) = (&first.geometry, &last.geometry);
    let top_box = s.landing.as_ref().unwrap_or(bl);
    // Up the stairs: from the first step's centre towards the top.
    let dir = unit([
        top_box.center_m[0] - b0.center_m[0],
        top_box.center_m[1] - b0.center_m[1],
    ])
    .unwrap_or([b0.yaw_deg.to_radians().cos(), b0.yaw_deg.to_radians().sin()]);
    let tops: Vec<f64> = s
        .steps
        .iter()
        .map(|st| st.geometry.center_m[2] + st.geometry.half_extents_m[2])
        .chain(
            s.landing
                .iter()
                .map(|l| l.center_m[2] + l.half_extents_m[2]),
        )
        .collect();
    let rise = tops
        .iter()
        .scan(grid.floor_z_m(), |prev, &t| {
            let r = t - *prev;
            *prev = t;
            Some(r)
        })
        .fold(0.0, f64::max);
    if rise > fp.max_rise_m + 1e-6 {
        return Err(fail(format!(
            "rise {rise:.2} m above what {robot_name} climbs ({:.2} m)",
            fp.max_rise_m
        )));
    }
    let across = [-dir[1], dir[0]];
    let (width, needed) = (
        2.0 * half_along(b0, across),
        2.0 * (fp.half_width_m + cfg.margin_m),
    );
    if width < needed {
        return Err(fail(format!(
            "the stairs are {width:.2} m wide, the robot needs {needed:.2} m"
        )));
    }
    let c0 = [b0.center_m[0], b0.center_m[1]];
    let foot = add(
        c0,
        dir,
        -(half_along(b0, dir) + fp.half_length_m + cfg.margin_m),
    );
    let run_up = add(foot, dir, -RUN_UP_M);
    if !(grid.free_at(foot) && grid.segment_free(run_up, foot)) {
        return Err(fail(
            "no room for the robot before the foot of the stairs".into(),
        ));
    }
    Ok(ClimbLeg {
        goal: Goal::Stairs(s.name.clone()),
        run_up,
        foot,
        top: [top_box.center_m[0], top_box.center_m[1]],
    })
}
