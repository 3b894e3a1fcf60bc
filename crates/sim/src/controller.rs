//! Commands and the controller: timed velocity commands take precedence; otherwise the robot
//! follows its waypoints in order (turn in place when far off heading, else drive with a
//! proportional heading correction); with nothing to do it stands still (motors braking).

use crate::error::{check_finite, check_range, Result};
use crate::world::robot::RobotPose;
use serde::{Deserialize, Serialize};

/// Drive at a velocity from `from_s` to `to_s` (simulated seconds).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityCommand {
    /// Start time (s).
    pub from_s: f64,
    /// End time (s, exclusive).
    pub to_s: f64,
    /// Forward speed (m/s, negative backwards).
    #[serde(default)]
    pub linear_mps: f64,
    /// Yaw rate (rad/s, counter-clockwise positive).
    #[serde(default)]
    pub angular_radps: f64,
}

/// A point to drive to.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Waypoint {
    /// x (m).
    pub x_m: f64,
    /// y (m).
    pub y_m: f64,
    /// Cruise speed towards it (m/s); absent = the controller's default.
    #[serde(default)]
    pub speed_mps: Option<f64>,
    /// Reached within this distance (m); absent = the controller's default.
    #[serde(default)]
    pub tolerance_m: Option<f64>,
}

/// The waypoint follower's gains.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ControllerConfig {
    /// Default cruise speed (m/s).
    pub speed_mps: f64,
    /// Default waypoint tolerance (m).
    pub tolerance_m: f64,
    /// Turn in place when the heading error exceeds this (degrees).
    pub turn_in_place_deg: f64,
    /// Yaw-rate gain (rad/s per rad of heading error).
    pub heading_gain: f64,
    /// Yaw rate when turning in place (rad/s).
    pub turn_rate_radps: f64,
    /// Slow down within this distance of the last waypoint (m).
    pub slowdown_m: f64,
}

impl Default for ControllerConfig {
    fn default() -> Self {
        ControllerConfig {
            speed_mps: 0.5,
            tolerance_m: 0.15,
            turn_in_place_deg: 35.0,
            heading_gain: 2.0,
            turn_rate_radps: 0.8,
            slowdown_m: 0.5,
        }
    }
}

impl ControllerConfig {
    /// Checks the gains.
    pub fn validate(&self) -> Result<()> {
        let el = "controller";
        check_range(
            el,
            "speed_mps",
            self.speed_mps,
            0.01,
            20.0,
            "0.01 to 20 m/s",
        )?;
        check_range(
            el,
            "tolerance_m",
            self.tolerance_m,
            0.01,
            10.0,
            "0.01 to 10 m",
        )?;
        check_range(
            el,
            "turn_in_place_deg",
            self.turn_in_place_deg,
            1.0,
            180.0,
            "1 to 180",
        )?;
        check_range(
            el,
            "heading_gain",
            self.heading_gain,
            0.0,
            100.0,
            "0 to 100",
        )?;
        check_range(
            el,
            "turn_rate_radps",
            self.turn_rate_radps,
            0.01,
            20.0,
            "0.01 to 20",
        )?;
        check_range(el, "slowdown_m", self.slowdown_m, 0.0, 100.0, "0 to 100 m")?;
        Ok(())
    }
}

pub(crate) fn validate_commands(
    velocity: &[VelocityCommand],
    waypoints: &[Waypoint],
) -> Result<()> {
    for (i, v) in velocity.iter().enumerate() {
        let el = format!("velocity[{i}]");
        check_finite(
            &el,
            "linear_mps, angular_radps",
            &[v.linear_mps, v.angular_radps],
        )?;
        check_range(
            &el,
            "from_s",
            v.from_s,
            0.0,
            1.0e7,
            "a time from 0 to 1e7 s",
        )?;
        check_range(
            &el,
            "to_s",
            v.to_s,
            v.from_s,
            1.0e7,
            &format!("a time from from_s ({} s) to 1e7 s", v.from_s),
        )?;
    }
    for (i, w) in waypoints.iter().enumerate() {
        let el = format!("waypoints[{i}]");
        check_finite(&el, "x_m, y_m", &[w.x_m, w.y_m])?;
        if let Some(s) = w.speed_mps {
            check_range(&el, "speed_mps", s, 0.01, 20.0, "0.01 to 20 m/s")?;
        }
        if let Some(t) = w.tolerance_m {
            check_range(&el, "tolerance_m", t, 0.01, 10.0, "0.01 to 10 m")?;
        }
    }
    Ok(())
}

/// The scenario's scripted controller: timed velocity commands first, else the waypoints in
/// order (turn in place towards the next one, then drive with a heading gain). Its state is
/// the cursor: which waypoint is next. Public so that a driver outside the simulation (an
/// operator console's test driving through its protocol) computes exactly what the scenario
/// would command.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Controller {
    pub(crate) next_waypoint: usize,
    turning: bool,
}

impl Controller {
    /// The (linear m/s, angular rad/s) command at time `t_s` for a robot at `pose`.
    pub fn command(
        &mut self,
        t_s: f64,
        pose: &RobotPose,
        velocity: &[VelocityCommand],
        waypoints: &[Waypoint],
        cfg: &ControllerConfig,
    ) -> (f64, f64) {
        if let Some(v) = velocity.iter().find(|v| t_s >= v.from_s && t_s < v.to_s) {
            return (v.linear_mps, v.angular_radps);
        }
        while let Some(w) = waypoints.get(self.next_waypoint) {
            let (dx, dy) = (w.x_m - pose.x_m, w.y_m - pose.y_m);
            let dist = dx.hypot(dy);
            if dist <= w.tolerance_m.unwrap_or(cfg.tolerance_m) {
                self.next_waypoint += 1;
                self.turning = false;
                continue;
            }
            let err = wrap_rad(dy.atan2(dx) - pose.yaw_deg.to_radians());
            let limit = cfg.turn_in_place_deg.to_radians();
            // Hysteresis: once turning in place, turn until well aligned.
            if err.abs() > limit || (self.turning && err.abs() > limit * 0.3) {
                self.turning = true;
                return (0.0, cfg.turn_rate_radps.copysign(err));
            }
            self.turning = false;
            let cruise = w.speed_mps.unwrap_or(cfg.speed_mps);
            let last = self.next_waypoint + 1 == waypoints.len();
            let speed = if last && cfg.slowdown_m > 0.0 {
                cruise * (dist / cfg.slowdown_m).clamp(0.3, 1.0)
            } else {
                cruise
            };
            return (speed * err.cos().max(0.0), cfg.heading_gain * err);
        }
        (0.0, 0.0)
    }
}

/// An angle wrapped to (-pi, pi].
pub(crate) fn wrap_rad(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let mut a = a % two_pi;
    if a > std::f64::consts::PI {
        a -= two_pi;
    } else if a <= -std::f64::consts::PI {
        a += two_pi;
    }
    a
}
