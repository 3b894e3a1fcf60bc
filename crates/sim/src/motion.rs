//! The robot's own motion: movement events at a fixed rate, tipping (roll or pitch over the
//! limit, reported again only after recovering) and being stuck (commanded to move, not moving).

use crate::doors::entity_refs;
use crate::events::{Emitter, EventConfig, EventKind};
use crate::robot::robot_pose;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// Per-robot motion state.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct RobotMotion {
    next_movement_s: f64,
    tipped: bool,
    still_s: f64,
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
        self.robots.resize_with(world.robots.len(), RobotMotion::default);
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
            let (v, w) = robot.command;
            let commanded = v.abs() > 0.05 || w.abs() > 0.2;
            let moving = p.ground_speed_mps > cfg.stuck_speed_mps || p.yaw_rate_radps.abs() > 0.05;
            if commanded && !moving {
                m.still_s += world.dt_secs();
                if !m.stuck && m.still_s >= cfg.stuck_after_s {
                    m.stuck = true;
                    out.emit(
                        EventKind::RobotStuck,
                        entity_refs(world, &ids),
                        "",
                        &[("x_m", p.x_m), ("y_m", p.y_m), ("still_s", m.still_s)],
                    );
                }
            } else {
                m.still_s = 0.0;
                m.stuck = false;
            }
        }
    }
}
