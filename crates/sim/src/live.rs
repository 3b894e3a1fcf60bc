//! The live state of a running simulation, for viewers: the robot's pose and orientation, its
//! wheel and arm joint angles, the doors' angles, what the robot touches now, and each rule of
//! the scenario with its state so far (pending, passed or failed).

use crate::detect::contacts;
use crate::simulation::Simulation;
use crate::world::robot::RobotPose;
use rapier3d::prelude::{ImpulseJointHandle, PhysicsWorld};
use serde::{Deserialize, Serialize};

/// Where a rule stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RuleState {
    /// Not decided yet.
    Pending,
    /// Decided: passed.
    Passed,
    /// Decided: failed.
    Failed,
}

/// One rule of the scenario, live.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LiveRule {
    /// The rule as written, e.g. `pass_through_door = door@14.5,1.3`.
    pub rule: String,
    /// Where it stands.
    pub state: RuleState,
    /// Why (for a pending rule: what has been seen so far, or what it would be judged at the
    /// end as things are).
    pub reason: String,
    /// When it was decided (s), if it was.
    pub decided_s: Option<f64>,
}

/// The robot, live.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LiveRobot {
    /// Its entity id.
    pub entity: u32,
    /// Pose and speeds.
    pub pose: RobotPose,
    /// The chassis' orientation as a quaternion `[x, y, z, w]` (semsim's frame, z up).
    pub rotation_xyzw: [f64; 4],
    /// Each wheel's angle about its axle (radians, positive about the chassis' +y), in the
    /// model's order.
    pub wheel_angles_rad: Vec<f64>,
    /// Each arm joint's angle (degrees, about the joint's axis as the model gives it), in the
    /// model's order; `None` for a broken joint.
    pub arm_angles_deg: Vec<Option<f64>>,
}

/// A door, live.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LiveDoor {
    /// The door's entity id.
    pub entity: u32,
    /// Its opening angle (degrees, 0 = closed).
    pub angle_deg: f64,
    /// Whether its hinge is intact.
    pub attached: bool,
}

/// A snapshot of the simulation for viewers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LiveState {
    /// Steps taken.
    pub step: u64,
    /// Simulated time (s).
    pub time_s: f64,
    /// The robot (absent in a world without one).
    pub robot: Option<LiveRobot>,
    /// Every door.
    pub doors: Vec<LiveDoor>,
    /// The entities the robot touches now (floor under its wheels and stairs under its wheels
    /// excluded, as for collision events), ascending.
    pub contacts: Vec<u32>,
}

/// A revolute joint's angle (radians, about its axis: rapier's convention), if it exists.
fn revolute_angle(physics: &PhysicsWorld, joint: ImpulseJointHandle) -> Option<f64> {
    let j = physics.impulse_joints.get(joint)?;
    let rot1 = *physics.bodies.get(j.body1())?.rotation() * j.data.local_frame1.rotation;
    let rot2 = *physics.bodies.get(j.body2())?.rotation() * j.data.local_frame2.rotation;
    let err = rot1.inverse() * rot2;
    let half = (err.x as f64).clamp(-1.0, 1.0).asin();
    Some(if rot1.dot(rot2) < 0.0 {
        -2.0 * half
    } else {
        2.0 * half
    })
}

impl Simulation {
    /// The robot, doors and contacts now.
    pub fn live_state(&self) -> LiveState {
        let world = &self.world;
        let physics = &world.physics;
        let robot = world.robots.first().map(|r| {
            let rotation_xyzw = physics
                .bodies
                .get(r.chassis)
                .map(|b| {
                    let q = b.rotation();
                    [q.x as f64, q.y as f64, q.z as f64, q.w as f64]
                })
                .unwrap_or([0.0, 0.0, 0.0, 1.0]);
            LiveRobot {
                entity: r.entity,
                pose: self.robot_pose(),
                rotation_xyzw,
                wheel_angles_rad: r
                    .wheels
                    .iter()
                    .map(|w| revolute_angle(physics, w.joint).unwrap_or(0.0))
                    .collect(),
                arm_angles_deg: r
                    .arm
                    .iter()
                    .map(|l| Some(revolute_angle(physics, l.joint?)?.to_degrees()))
                    .collect(),
            }
        });
        let doors = world
            .doors
            .iter()
            .map(|d| LiveDoor {
                entity: d.entity,
                angle_deg: d.angle_deg(physics),
                attached: d.joint.is_some(),
            })
            .collect();
        let contacts = contacts::scan(world)
            .pairs
            .into_iter()
            .filter(|(robot, _)| *robot == 0)
            .map(|(_, entity)| entity)
            .collect();
        LiveState {
            step: world.steps,
            time_s: world.time_s(),
            robot,
            doors,
            contacts,
        }
    }

    /// Each rule of the scenario, in the verdict's order, with where it stands now.
    pub fn live_rules(&self) -> Vec<LiveRule> {
        let verdict = self.verdict();
        let decided = self.judge.decided();
        verdict
            .rules
            .into_iter()
            .zip(decided)
            .map(|(r, decided)| LiveRule {
                state: match (decided, r.passed) {
                    (false, _) => RuleState::Pending,
                    (true, true) => RuleState::Passed,
                    (true, false) => RuleState::Failed,
                },
                decided_s: decided.then_some(r.decided_s),
                rule: r.rule,
                reason: r.reason,
            })
            .collect()
    }
}
