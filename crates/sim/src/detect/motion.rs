//! The robot's own motion: movement events at a fixed rate, tipping (roll or pitch over the
//! limit, reported again only after recovering) and being stuck (commanded to move, not moving).

use crate::events::{Emitter, EventConfig, EventKind};
use crate::world::robot::robot_pose;
use crate::world::{entity_refs, World};
use serde::{Deserialize, Serialize};

/// Per-robot motion state.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct RobotMotion {
    next_movement_s: f64,
    tipped: bool,
    /// Where and when the robot last made progress (moved more than the stuck distance).
    anchor: [f64; 2],
    anchor_s: f64,
    stuck: bool,
}

/// Movement, tipping and stuck detection for every robot.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct MotionDetector {
    robots: Vec<RobotMotion>,
}

impl MotionDetector {
    pub(crate) fn update(&mut self, world: &World, cfg: &EventConfig, out: &mut Emitter) {
        let t = out.time_s;
        self.robots
            .resize_with(world.robots.len(), RobotMotion::default);
        for (robot, m) in world.robots.iter().zip(self.robots.iter_mut()) {
            let p = robot_pose(&world.physics, robot);
            let ids = [robot.entity];
            if cfg.movement_rate_hz > 0.0 && t + 1e-9 >= m.next_movement_s {
                m.next_movement_s = t + 1.0 / cfg.movement_rate_hz;
                out.emit(
                    EventKind::Movement,
                    entity_refs(world, &ids),
                    "",
                    &[
                        ("x_m", p.x_m),
                        ("y_m", p.y_m),
                        ("z_m", p.z_m),
                        ("roll_deg", p.roll_deg),
                        ("pitch_deg", p.pitch_deg),
                        ("yaw_deg", p.yaw_deg),
                        ("speed_mps", p.speed_mps),
                    ],
                );
            }
            let tilt = p.roll_deg.abs().max(p.pitch_deg.abs());
            if !m.tipped && tilt > cfg.tip_limit_deg {
                m.tipped = true;
                out.emit(
                    EventKind::RobotTipped,
                    entity_refs(world, &ids),
                    "",
                    &[("roll_deg", p.roll_deg), ("pitch_deg", p.pitch_deg)],
                );
            } else if m.tipped && tilt < cfg.tip_limit_deg - cfg.tip_rearm_deg {
                m.tipped = false;
            }
            // Stuck: commanded to drive, yet within `stuck_distance_m` of where it was
            // `stuck_after_s` ago (turning in place is not checked).
            let (v, _) = robot.command;
            let moved = (p.x_m - m.anchor[0]).hypot(p.y_m - m.anchor[1]);
            if v.abs() <= 0.05 || moved > cfg.stuck_distance_m {
                m.anchor = [p.x_m, p.y_m];
                m.anchor_s = t;
                m.stuck = false;
            } else if !m.stuck && t - m.anchor_s >= cfg.stuck_after_s {
                m.stuck = true;
                out.emit(
                    EventKind::RobotStuck,
                    entity_refs(world, &ids),
                    "",
                    &[("x_m", p.x_m), ("y_m", p.y_m), ("still_s", t - m.anchor_s)],
                );
            }
        }
    }
}
