//! Semantic events: what happened, when, to which entities, with which values; written as JSON
//! lines with a fixed field order and fixed float formatting, so runs compare byte for byte.

use crate::error::{check_range, Result};
use crate::spec::EntityInfo;
use cloud::EntityClass;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// The kinds of semantic events.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// The robot's pose, at the configured rate.
    Movement,
    /// A robot started touching an entity (floor excluded; stairs only with chassis or arm).
    CollisionStarted,
    /// Still touching, at the configured rate.
    CollisionContinued,
    /// No longer touching (after the release delay).
    CollisionStopped,
    /// A robot started touching a wall or the wall above a door.
    WallTouched,
    /// A robot's chassis entered a door's free space.
    DoorFreeSpaceEntered,
    /// A robot's chassis left a door's free space (`crossed` = 1 if on the other side).
    DoorFreeSpaceLeft,
    /// A door's angle rose above the "open" threshold.
    DoorOpened,
    /// A door's angle fell below the "closed" threshold.
    DoorClosed,
    /// A robot's wheel first stood on a step.
    StairsClimbingStarted,
    /// A robot reached a step (`step` = index, the landing's is the number of steps).
    StairsStepReached,
    /// A robot stands on the top (landing or top step) with all its touching wheels.
    StairsClimbingFinished,
    /// A climbing robot is back on the floor without having finished.
    StairsClimbingAborted,
    /// A robot stands on a ramp with a wheel, its centre `ramp_start_height_m` up the slope.
    RampClimbingStarted,
    /// A robot stands on a ramp's upper end with all its touching wheels (`height_m`: the
    /// ramp's rise).
    RampClimbingFinished,
    /// A climbing robot is back on the floor without having reached the ramp's upper end
    /// (`height_m`: how high up the slope its centre got).
    RampClimbingAborted,
    /// A door hinge or an arm joint broke.
    JointBroken,
    /// A robot's roll or pitch exceeded the limit.
    RobotTipped,
    /// A robot commanded to move has not moved for a while.
    RobotStuck,
}

impl EventKind {
    /// The snake_case name used in files.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Movement => "movement",
            EventKind::CollisionStarted => "collision_started",
            EventKind::CollisionContinued => "collision_continued",
            EventKind::CollisionStopped => "collision_stopped",
            EventKind::WallTouched => "wall_touched",
            EventKind::DoorFreeSpaceEntered => "door_free_space_entered",
            EventKind::DoorFreeSpaceLeft => "door_free_space_left",
            EventKind::DoorOpened => "door_opened",
            EventKind::DoorClosed => "door_closed",
            EventKind::StairsClimbingStarted => "stairs_climbing_started",
            EventKind::StairsStepReached => "stairs_step_reached",
            EventKind::StairsClimbingFinished => "stairs_climbing_finished",
            EventKind::StairsClimbingAborted => "stairs_climbing_aborted",
            EventKind::RampClimbingStarted => "ramp_climbing_started",
            EventKind::RampClimbingFinished => "ramp_climbing_finished",
            EventKind::RampClimbingAborted => "ramp_climbing_aborted",
            EventKind::JointBroken => "joint_broken",
            EventKind::RobotTipped => "robot_tipped",
            EventKind::RobotStuck => "robot_stuck",
        }
    }

    /// Whether a report's timeline shows it (all but movement and continued collisions).
    pub fn is_significant(self) -> bool {
        !matches!(self, EventKind::Movement | EventKind::CollisionContinued)
    }
}

/// An entity taking part in an event.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct EntityRef {
    /// Entity id.
    pub id: u32,
    /// Its class.
    pub class: EntityClass,
    /// Its machine name (robots: the scenario's robot name).
    pub name: String,
}

impl From<&EntityInfo> for EntityRef {
    fn from(e: &EntityInfo) -> Self {
        EntityRef {
            id: e.id,
            class: e.class,
            name: e.name.clone(),
        }
    }
}

/// One semantic event.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Simulated time (s).
    pub time_s: f64,
    /// What happened.
    pub kind: EventKind,
    /// The entities involved (the robot first).
    pub entities: Vec<EntityRef>,
    /// A word on it (e.g. the broken joint's name); may be empty.
    pub detail: String,
    /// Named values with units in the names, in a fixed order.
    pub values: Vec<(String, f64)>,
}

impl Event {
    /// A value by name.
    pub fn value(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|v| v.0 == name).map(|v| v.1)
    }

    /// Whether an entity takes part.
    pub fn involves(&self, id: u32) -> bool {
        self.entities.iter().any(|e| e.id == id)
    }

    /// One JSON object on one line: `time_s`, `kind`, `entities`, `detail`, `values`, in this
    /// order; numbers with 4 decimals (non-finite ones as `null`).
    pub fn to_json_line(&self) -> String {
        let mut s = String::with_capacity(160);
        let _ = write!(
            s,
            "{{\"time_s\":{},\"kind\":\"{}\",\"entities\":[",
            fmt_f(self.time_s),
            self.kind.name()
        );
        for (i, e) in self.entities.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            let _ = write!(
                s,
                "{{\"id\":{},\"class\":\"{}\",\"name\":{}}}",
                e.id,
                e.class.name(),
                json_str(&e.name)
            );
        }
        let _ = write!(s, "],\"detail\":{},\"values\":{{", json_str(&self.detail));
        for (i, (k, v)) in self.values.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            let _ = write!(s, "{}:{}", json_str(k), fmt_f(*v));
        }
        s.push_str("}}");
        s
    }
}

/// Every event as a JSON line (each ending with a newline).
pub fn events_to_jsonl(events: &[Event]) -> String {
    let mut s = String::with_capacity(events.len() * 160);
    for e in events {
        s.push_str(&e.to_json_line());
        s.push('\n');
    }
    s
}

/// Fixed formatting: 4 decimals, no negative zero, `null` for non-finite values.
pub(crate) fn fmt_f(v: f64) -> String {
    if !v.is_finite() {
        return "null".into();
    }
    let s = format!("{v:.4}");
    if s == "-0.0000" {
        "0.0000".into()
    } else {
        s
    }
}

fn json_str(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

/// Event detection settings (rates, thresholds).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EventConfig {
    /// Movement events per second (0 = none).
    pub movement_rate_hz: f64,
    /// Collision-continued events per second per touching pair (0 = none).
    pub contact_rate_hz: f64,
    /// A contact gap shorter than this does not stop a collision (s).
    pub contact_release_s: f64,
    /// A door is opened above this angle (degrees).
    pub door_opened_deg: f64,
    /// A door is closed below this angle (degrees).
    pub door_closed_deg: f64,
    /// Roll or pitch beyond this is tipping (degrees).
    pub tip_limit_deg: f64,
    /// Tipping is reported again only after the robot came back this far below the limit.
    pub tip_rearm_deg: f64,
    /// A robot commanded to drive that moves less than this (m) ...
    pub stuck_distance_m: f64,
    /// ... in this long is stuck (s).
    pub stuck_after_s: f64,
    /// A step tread is stood on when the contact normal's z is above this.
    pub tread_normal_z: f64,
    /// A climb is aborted when all touching wheels have been on the floor this long (s).
    pub stairs_abort_s: f64,
    /// A ramp is climbed when the robot's centre is within this of its head, along the slope,
    /// with every touching wheel on the ramp (m): a robot stops a body length or so short of a
    /// head that ends in a drop.
    pub ramp_top_within_m: f64,
    /// A ramp climb starts when the robot's centre is this high up the slope (m): below it
    /// the ramp's foot is a kerb the robot drives over.
    pub ramp_start_height_m: f64,
}

impl Default for EventConfig {
    fn default() -> Self {
        EventConfig {
            movement_rate_hz: 2.0,
            contact_rate_hz: 2.0,
            contact_release_s: 0.1,
            door_opened_deg: 10.0,
            door_closed_deg: 3.0,
            tip_limit_deg: 45.0,
            tip_rearm_deg: 10.0,
            stuck_distance_m: 0.05,
            stuck_after_s: 3.0,
            tread_normal_z: 0.7,
            stairs_abort_s: 1.0,
            // Twice the Pioneer 3-AT's length: its planned stop is its half length plus a
            // margin short of the head.
            ramp_top_within_m: 1.0,
            ramp_start_height_m: 0.05,
        }
    }
}

impl EventConfig {
    /// Checks rates and thresholds.
    pub fn validate(&self) -> Result<()> {
        let el = "events";
        check_range(
            el,
            "movement_rate_hz",
            self.movement_rate_hz,
            0.0,
            1000.0,
            "0 to 1000",
        )?;
        check_range(
            el,
            "contact_rate_hz",
            self.contact_rate_hz,
            0.0,
            1000.0,
            "0 to 1000",
        )?;
        check_range(
            el,
            "contact_release_s",
            self.contact_release_s,
            0.0,
            10.0,
            "0 to 10 s",
        )?;
        check_range(
            el,
            "door_closed_deg",
            self.door_closed_deg,
            0.0,
            90.0,
            "0 to 90",
        )?;
        check_range(
            el,
            "door_opened_deg",
            self.door_opened_deg,
            self.door_closed_deg,
            180.0,
            "door_closed_deg to 180",
        )?;
        check_range(
            el,
            "tip_limit_deg",
            self.tip_limit_deg,
            1.0,
            180.0,
            "1 to 180",
        )?;
        check_range(
            el,
            "tip_rearm_deg",
            self.tip_rearm_deg,
            0.0,
            self.tip_limit_deg,
            "0 to tip_limit_deg",
        )?;
        for (name, v, hi, range) in [
            (
                "stuck_distance_m",
                self.stuck_distance_m,
                100.0,
                "0 to 100 m",
            ),
            ("tread_normal_z", self.tread_normal_z, 1.0, "0 to 1"),
            (
                "ramp_top_within_m",
                self.ramp_top_within_m,
                100.0,
                "0 to 100 m",
            ),
            (
                "ramp_start_height_m",
                self.ramp_start_height_m,
                10.0,
                "0 to 10 m",
            ),
        ] {
            check_range(el, name, v, 0.0, hi, range)?;
        }
        check_range(
            el,
            "stuck_after_s",
            self.stuck_after_s,
            0.1,
            1.0e6,
            "0.1 s to 1e6 s",
        )?;
        Ok(())
    }
}

/// Builds events and pushes them to the log; the detectors share it.
pub(crate) struct Emitter<'a> {
    pub time_s: f64,
    pub log: &'a mut Vec<Event>,
}

impl Emitter<'_> {
    pub(crate) fn emit(
        &mut self,
        kind: EventKind,
        entities: Vec<EntityRef>,
        detail: &str,
        values: &[(&str, f64)],
    ) {
        self.log.push(Event {
            time_s: self.time_s,
            kind,
            entities,
            detail: detail.to_string(),
            values: values.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_line_has_fixed_order_and_format() {
        let e = Event {
            time_s: 1.0 / 3.0,
            kind: EventKind::WallTouched,
            entities: vec![EntityRef {
                id: 3,
                class: EntityClass::WallAboveDoor,
                name: "walls[1].doors[0].lintel".into(),
            }],
            detail: String::new(),
            values: vec![("x_m".into(), -0.00001), ("bad".into(), f64::NAN)],
        };
        assert_eq!(
            e.to_json_line(),
            r#"{"time_s":0.3333,"kind":"wall_touched","entities":[{"id":3,"class":"wall_above_door","name":"walls[1].doors[0].lintel"}],"detail":"","values":{"x_m":0.0000,"bad":null}}"#
        );
    }
}
