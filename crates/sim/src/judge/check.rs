//! What the judge watches for each rule, and the rules that name an entity resolved against the
//! world (a door or its free space to pass through, a staircase or a ramp to climb).

use crate::error::{Result, SimError};
use crate::ramps::ramps_of;
use crate::scenario::ReachGoal;
use crate::spec::WorldSpec;
use cloud::EntityClass;
use serde::{Deserialize, Serialize};

/// One rule's check, with what it has seen so far.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) enum Check {
    PassThrough {
        free_space: u32,
        entered: u32,
    },
    ReachTop {
        stairs: u32,
        steps: u32,
        highest: i64,
    },
    RampTop {
        ramp: u32,
        rise_m: f64,
        /// How high up the slope the robot got in its best aborted climb (m), if it started.
        highest_m: Option<f64>,
    },
    OpenDoor {
        door: u32,
        initial_deg: f64,
        widest_deg: f64,
        by_deg: f64,
    },
    Reach {
        goal: ReachGoal,
        closest_m: f64,
    },
    MaxWall {
        max_s: f64,
    },
    NoBrokenJoint,
    NoTipping {
        max_tilt_deg: f64,
    },
    NoStuck,
}

/// The check of passing through a door (or an opening's free space) named `r` under `key`.
pub(super) fn pass_through(spec: &WorldSpec, key: &str, r: &str) -> Result<Check> {
    let el = format!("rules.{key}");
    let e = spec.resolve(r, &el)?;
    let free_space = match e.class {
        EntityClass::FreeSpaceForDoor => e.id,
        EntityClass::Door => spec
            .free_spaces
            .iter()
            .find(|f| f.door == Some(e.id))
            .map(|f| f.entity)
            .ok_or_else(|| SimError::Invalid {
                element: el.clone(),
                msg: format!("door {} has no free space to pass through", e.name),
            })?,
        c => return Err(wrong(&el, r, c, "door or free_space_for_door")),
    };
    Ok(Check::PassThrough {
        free_space,
        entered: 0,
    })
}

/// The check of climbing to the top of the staircase named `r` under `key`.
pub(super) fn reach_top(spec: &WorldSpec, key: &str, r: &str) -> Result<Check> {
    let el = format!("rules.{key}");
    let e = spec.resolve(r, &el)?;
    let s = spec
        .stairs
        .iter()
        .find(|s| s.entity == e.id)
        .ok_or_else(|| wrong(&el, r, e.class, "stairs"))?;
    let steps = s.steps.len() as u32 + u32::from(s.landing.is_some());
    Ok(Check::ReachTop {
        stairs: e.id,
        steps,
        highest: -1,
    })
}

/// The check of driving up the ramp named `r` under `key`.
pub(super) fn ramp_top(spec: &WorldSpec, key: &str, r: &str) -> Result<Check> {
    let el = format!("rules.{key}");
    let e = spec.resolve(r, &el)?;
    if e.class != EntityClass::Ramp {
        return Err(wrong(&el, r, e.class, "ramp"));
    }
    let ramp = ramps_of(spec)
        .into_iter()
        .find(|g| g.entity == e.id)
        .ok_or_else(|| SimError::Invalid {
            element: el.clone(),
            msg: format!("ramp {} has no slope to drive up", e.name),
        })?;
    Ok(Check::RampTop {
        ramp: e.id,
        rise_m: ramp.rise_m,
        highest_m: None,
    })
}

pub(super) fn wrong(
    element: &str,
    reference: &str,
    found: EntityClass,
    expected: &str,
) -> SimError {
    SimError::WrongEntityClass {
        element: element.into(),
        reference: reference.into(),
        found: found.name().into(),
        expected: expected.into(),
    }
}
