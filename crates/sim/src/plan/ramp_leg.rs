//! The drive up a ramp (from a run-up before its foot to its upper end, the robot's half
//! length short of its head), or why the robot cannot: too steep for the plan, too narrow or
//! too short to take the robot, something over the slope lower than the robot or standing on
//! it in the robot's way, or no room (or no floor) before its foot.

use super::footprint::Footprint;
use super::goals::{add, ClimbLeg, RUN_UP_M};
use super::grid::{FreeGrid, HEAD_MARGIN_M};
use super::{Goal, PlanConfig, Unreachable};
use crate::ramps::{corners, RampGeometry};
use crate::spec::WorldSpec;
use cloud::EntityClass;

/// Whether `p` lies over one of the world's floor boxes.
fn on_floor(world: &WorldSpec, p: [f64; 2]) -> bool {
    world
        .fixed
        .iter()
        .filter(|f| f.class == EntityClass::Floor)
        .any(|f| {
            let b = &f.geometry;
            let (s, c) = b.yaw_deg.to_radians().sin_cos();
            let d = [p[0] - b.center_m[0], p[1] - b.center_m[1]];
            (d[0] * c + d[1] * s).abs() <= b.half_extents_m[0]
                && (-d[0] * s + d[1] * c).abs() <= b.half_extents_m[1]
        })
}

/// The drive up a ramp, or why the robot cannot (see the module docs). The top is the robot's
/// half length and the margin short of the head (a ramp's head may end in a drop).
pub(crate) fn ramp_leg(
    world: &WorldSpec,
    grid: &FreeGrid,
    fp: &Footprint,
    cfg: &PlanConfig,
    r: &RampGeometry,
) -> Result<ClimbLeg, Unreachable> {
    let fail = |reason: String| Unreachable {
        goal: Goal::Ramp(r.name.clone()),
        reason,
    };
    let pitch = r.pitch_deg();
    if pitch > cfg.max_ramp_pitch_deg + 1e-9 {
        return Err(fail(format!(
            "the ramp climbs {pitch:.1} degrees, steeper than the plan's max_ramp_pitch_deg \
             ({:.1})",
            cfg.max_ramp_pitch_deg
        )));
    }
    let needed = 2.0 * (fp.half_width_m + cfg.margin_m);
    if r.width_m < needed {
        return Err(fail(format!(
            "the ramp is {:.2} m wide, the robot needs {needed:.2} m",
            r.width_m
        )));
    }
    let long = 2.0 * fp.half_length_m + cfg.margin_m;
    if r.length_m < long {
        return Err(fail(format!(
            "the ramp is {:.2} m long, the robot needs {long:.2} m to stand on it",
            r.length_m
        )));
    }
    let top_t = r.length_m - fp.half_length_m - cfg.margin_m;
    if let Some(why) = in_the_way(world, fp, cfg, r, top_t) {
        return Err(fail(why));
    }
    let foot = add(r.foot_m, r.uphill, -(fp.half_length_m + cfg.margin_m));
    // A car-park ramp often starts near a wall, entered from the side: the run-up shortens
    // to nothing there (the robot turns at the foot to face up the slope).
    let run_up = [RUN_UP_M, RUN_UP_M / 2.0, 0.0]
        .into_iter()
        .map(|d| add(foot, r.uphill, -d))
        .find(|&p| grid.free_at(foot) && grid.segment_free(p, foot))
        .ok_or_else(|| {
            fail(if on_floor(world, foot) {
                "no room for the robot before the foot of the ramp".into()
            } else {
                "no floor in the world before the foot of the ramp (a map has floor only \
                 where its scans saw it)"
                    .into()
            })
        })?;
    Ok(ClimbLeg {
        goal: Goal::Ramp(r.name.clone()),
        run_up,
        foot,
        top: r.centre_at(top_t),
    })
}

/// What stops the robot on its way up the ramp's centre line to `top_t` (m up from the foot),
/// if anything: a fixed box (not floor, not the ramp) over the robot's lane, from the foot to
/// the top plus its half length, whose bottom is below the slope plus the robot's height and
/// margin where the slope is highest under it: standing on the ramp (its bottom within the
/// head margin of the slope or under it: a car parked on it, a person) or hanging too low over
/// it (a beam).
fn in_the_way(
    world: &WorldSpec,
    fp: &Footprint,
    cfg: &PlanConfig,
    r: &RampGeometry,
    top_t: f64,
) -> Option<String> {
    let across = [-r.uphill[1], r.uphill[0]];
    let half_lane = fp.half_width_m + cfg.margin_m;
    let (t0, t1) = (0.0, (top_t + fp.half_length_m).min(r.length_m));
    let slope_at = |t: f64| r.foot_z_m + r.rise_m * (t / r.length_m.max(1e-9)).clamp(0.0, 1.0);
    world
        .fixed
        .iter()
        .filter(|f| !matches!(f.class, EntityClass::Floor | EntityClass::Ramp))
        .find_map(|f| {
            let b = &f.geometry;
            // The box's corners along and across the slope (from the foot's middle).
            let local = corners(b).map(|q| {
                let d = [q[0] - r.foot_m[0], q[1] - r.foot_m[1]];
                [
                    d[0] * r.uphill[0] + d[1] * r.uphill[1],
                    d[0] * across[0] + d[1] * across[1],
                ]
            });
            if !overlaps(&local, [t0, t1], half_lane) {
                return None;
            }
            // The box's extent along the slope.
            let (lo, hi) = local
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                    (l.min(q[0]), h.max(q[0]))
                });
            let surface = slope_at(hi.min(t1));
            let (bottom, top) = (
                b.center_m[2] - b.half_extents_m[2],
                b.center_m[2] + b.half_extents_m[2],
            );
            let needed = fp.height_m + HEAD_MARGIN_M;
            if top <= slope_at(lo.max(t0)) + 1e-6 || bottom >= surface + needed {
                return None;
            }
            // Within the head margin of the slope is standing on it (a map's slope is
            // centimetres off; a person's legs on it are no beam).
            Some(if bottom <= surface + HEAD_MARGIN_M {
                format!("{} stands on the ramp in the robot's way", f.name)
            } else {
                format!(
                    "{} is {:.2} m over the slope, the robot needs {needed:.2} m",
                    f.name,
                    bottom - surface
                )
            })
        })
}

/// Whether a box's footprint (its corners, in the lane's frame: along, across) overlaps the
/// lane `t` along, `half_lane` either side across (separating axes: the lane's two and the
/// box's two edge normals).
fn overlaps(q: &[[f64; 2]; 4], t: [f64; 2], half_lane: f64) -> bool {
    let lane = [
        [t[0], -half_lane],
        [t[1], -half_lane],
        [t[1], half_lane],
        [t[0], half_lane],
    ];
    let edges = [
        [1.0, 0.0],
        [0.0, 1.0],
        [q[1][0] - q[0][0], q[1][1] - q[0][1]],
        [q[2][0] - q[1][0], q[2][1] - q[1][1]],
    ];
    edges.iter().all(|a| {
        let span = |ps: &[[f64; 2]]| {
            ps.iter()
                .map(|p| p[0] * a[0] + p[1] * a[1])
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                })
        };
        let ((l1, h1), (l2, h2)) = (span(q), span(&lane));
        h1 >= l2 && h2 >= l1
    })
}
