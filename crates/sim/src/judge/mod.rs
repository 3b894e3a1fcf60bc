//! The judge: a scenario's rules resolved against the world, watched after every step, and the
//! verdict (each rule passed or failed, with a one-line reason and the time it was decided).

use crate::error::Result;
use crate::events::{fmt_f, Event, EventKind};
use crate::scenario::Rules;
use crate::spec::WorldSpec;
use crate::verdict::{RuleResult, Verdict};
use crate::world::robot::RobotPose;
use check::{pass_through, ramp_top, reach_top, wrong, Check};
use serde::{Deserialize, Serialize};

mod check;

#[derive(Debug, Clone, Serialize, Deserialize)]
struct Tracked {
    rule: String,
    check: Check,
    result: Option<RuleResult>,
}

impl Tracked {
    fn is_goal(&self) -> bool {
        matches!(
            self.check,
            Check::PassThrough { .. }
                | Check::ReachTop { .. }
                | Check::RampTop { .. }
                | Check::OpenDoor { .. }
                | Check::Reach { .. }
        )
    }
}

/// Watches the rules during a run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct Judge {
    rules: Vec<Tracked>,
}

/// What the judge sees after a step besides the new events.
pub(crate) struct Observation<'a> {
    pub time_s: f64,
    pub events: &'a [Event],
    pub robot_entity: u32,
    pub pose: RobotPose,
    pub wall_contact_s: f64,
    /// (door entity, angle in degrees) for every attached door.
    pub door_angles: &'a [(u32, f64)],
}

impl Judge {
    /// Resolves every entity reference; unknown or wrong-class names are errors.
    pub(crate) fn new(rules: &Rules, spec: &WorldSpec) -> Result<Judge> {
        let mut out = vec![];
        let mut push = |rule: String, check: Check| {
            out.push(Tracked {
                rule,
                check,
                result: None,
            })
        };
        let doors = rules
            .pass_through_door
            .iter()
            .map(|r| ("pass_through_door", r));
        let more_doors = rules
            .pass_through_doors
            .iter()
            .map(|r| ("pass_through_doors", r));
        for (key, r) in doors.chain(more_doors) {
            push(format!("{key} = {r}"), pass_through(spec, key, r)?);
        }
        let stairs = rules
            .reach_top_of_stairs
            .iter()
            .map(|r| ("reach_top_of_stairs", r));
        let more_stairs = rules
            .reach_top_of_stairs_all
            .iter()
            .map(|r| ("reach_top_of_stairs_all", r));
        for (key, r) in stairs.chain(more_stairs) {
            push(format!("{key} = {r}"), reach_top(spec, key, r)?);
        }
        for r in &rules.reach_top_of_ramps {
            let key = "reach_top_of_ramps";
            push(format!("{key} = {r}"), ramp_top(spec, key, r)?);
        }
        if let Some(r) = &rules.open_door {
            let el = "rules.open_door";
            let e = spec.resolve(r, el)?;
            let d = spec
                .doors
                .iter()
                .find(|d| d.entity == e.id)
                .ok_or_else(|| wrong(el, r, e.class, "door"))?;
            push(
                format!("open_door = {r}"),
                Check::OpenDoor {
                    door: e.id,
                    initial_deg: d.initial_deg,
                    widest_deg: d.initial_deg,
                    by_deg: rules.open_door_by_deg,
                },
            );
        }
        if let Some(g) = rules.reach {
            push(
                format!("reach = ({}, {}) within {} m", g.x_m, g.y_m, g.radius_m),
                Check::Reach {
                    goal: g,
                    closest_m: f64::INFINITY,
                },
            );
        }
        if let Some(m) = rules.max_wall_contact_s {
            push(
                format!("max_wall_contact_s = {m}"),
                Check::MaxWall { max_s: m },
            );
        }
        if rules.no_broken_joint {
            push("no_broken_joint".into(), Check::NoBrokenJoint);
        }
        if rules.no_tipping {
            push("no_tipping".into(), Check::NoTipping { max_tilt_deg: 0.0 });
        }
        if rules.no_stuck {
            push("no_stuck".into(), Check::NoStuck);
        }
        Ok(Judge { rules: out })
    }

    /// Decides what can be decided after a step.
    pub(crate) fn observe(&mut self, o: &Observation) {
        let t = o.time_s;
        for r in self.rules.iter_mut().filter(|r| r.result.is_none()) {
            let mut decide = |passed: bool, reason: String| {
                r.result = Some(RuleResult {
                    rule: r.rule.clone(),
                    passed,
                    reason,
                    decided_s: t,
                    undecided: false,
                });
            };
            match &mut r.check {
                Check::PassThrough {
                    free_space,
                    entered,
                } => {
                    for e in o
                        .events
                        .iter()
                        .filter(|e| e.involves(*free_space) && e.involves(o.robot_entity))
                    {
                        if e.kind == EventKind::DoorFreeSpaceEntered {
                            *entered += 1;
                        }
                        if e.kind == EventKind::DoorFreeSpaceLeft && e.value("crossed") == Some(1.0)
                        {
                            decide(
                                true,
                                format!("passed through the opening at {} s", fmt_f(e.time_s)),
                            );
                            break;
                        }
                    }
                }
                Check::ReachTop {
                    stairs,
                    steps,
                    highest,
                } => {
                    for e in o
                        .events
                        .iter()
                        .filter(|e| e.involves(*stairs) && e.involves(o.robot_entity))
                    {
                        if e.kind == EventKind::StairsStepReached {
                            *highest = (*highest).max(e.value("step").unwrap_or(-1.0) as i64);
                        }
                        if e.kind == EventKind::StairsClimbingFinished {
                            decide(
                                true,
                                format!(
                                    "stood on the top ({steps} treads incl. landing) at {} s",
                                    fmt_f(e.time_s)
                                ),
                            );
                            break;
                        }
                    }
                }
                Check::RampTop {
                    ramp,
                    rise_m,
                    highest_m,
                } => {
                    for e in o
                        .events
                        .iter()
                        .filter(|e| e.involves(*ramp) && e.involves(o.robot_entity))
                    {
                        if e.kind == EventKind::RampClimbingStarted {
                            highest_m.get_or_insert(0.0);
                        }
                        if e.kind == EventKind::RampClimbingAborted {
                            let h = e.value("height_m").unwrap_or(0.0);
                            *highest_m = Some(highest_m.unwrap_or(0.0).max(h));
                        }
                        if e.kind == EventKind::RampClimbingFinished {
                            decide(
                                true,
                                format!(
                                    "drove up to the top ({rise_m:.2} m up) at {} s",
                                    fmt_f(e.time_s)
                                ),
                            );
                            break;
                        }
                    }
                }
                Check::OpenDoor {
                    door,
                    initial_deg,
                    widest_deg,
                    by_deg,
                } => {
                    if let Some(&(_, a)) = o.door_angles.iter().find(|d| d.0 == *door) {
                        *widest_deg = widest_deg.max(a);
                    }
                    let opened_event = o
                        .events
                        .iter()
                        .any(|e| e.kind == EventKind::DoorOpened && e.involves(*door));
                    if opened_event || *widest_deg >= *initial_deg + *by_deg {
                        decide(
                            true,
                            format!(
                                "opened from {:.1} to {:.1} degrees",
                                initial_deg, widest_deg
                            ),
                        );
                    }
                }
                Check::Reach { goal, closest_m } => {
                    let d = (o.pose.x_m - goal.x_m).hypot(o.pose.y_m - goal.y_m);
                    *closest_m = closest_m.min(d);
                    if d <= goal.radius_m {
                        decide(
                            true,
                            format!("reached ({:.2}, {:.2})", o.pose.x_m, o.pose.y_m),
                        );
                    }
                }
                Check::MaxWall { max_s } => {
                    if o.wall_contact_s > *max_s {
                        decide(false, format!("touched walls for more than {max_s} s"));
                    }
                }
                Check::NoBrokenJoint => {
                    if let Some(e) = o.events.iter().find(|e| e.kind == EventKind::JointBroken) {
                        let who = e
                            .entities
                            .first()
                            .map(|x| x.name.clone())
                            .unwrap_or_default();
                        let f = e.value("force_n").unwrap_or(f64::NAN);
                        decide(false, format!("{} of {who} broke ({f:.0} N)", e.detail));
                    }
                }
                Check::NoTipping { max_tilt_deg } => {
                    *max_tilt_deg =
                        max_tilt_deg.max(o.pose.roll_deg.abs().max(o.pose.pitch_deg.abs()));
                    if let Some(e) = o
                        .events
                        .iter()
                        .find(|e| e.kind == EventKind::RobotTipped && e.involves(o.robot_entity))
                    {
                        let (r, p) = (
                            e.value("roll_deg").unwrap_or(0.0),
                            e.value("pitch_deg").unwrap_or(0.0),
                        );
                        decide(
                            false,
                            format!("tipped over (roll {r:.0}, pitch {p:.0} degrees)"),
                        );
                    }
                }
                Check::NoStuck => {
                    if let Some(e) = o
                        .events
                        .iter()
                        .find(|e| e.kind == EventKind::RobotStuck && e.involves(o.robot_entity))
                    {
                        let (x, y) = (e.value("x_m").unwrap_or(0.0), e.value("y_m").unwrap_or(0.0));
                        decide(false, format!("stuck at ({x:.2}, {y:.2})"));
                    }
                }
            }
        }
    }

    /// Whether each rule (in the verdict's order) has been decided yet.
    pub(crate) fn decided(&self) -> Vec<bool> {
        self.rules.iter().map(|r| r.result.is_some()).collect()
    }

    /// Whether every goal rule has passed (false when there are none).
    pub(crate) fn goals_met(&self) -> bool {
        let mut goals = self.rules.iter().filter(|r| r.is_goal()).peekable();
        goals.peek().is_some() && goals.all(|r| r.result.as_ref().is_some_and(|x| x.passed))
    }

    /// The verdict at `end_s`: undecided goals fail, undecided constraints pass; or, when the
    /// run was `interrupted` at `end_s`, undecided rules fail as not decided.
    pub(crate) fn verdict(&self, end_s: f64, wall_contact_s: f64, interrupted: bool) -> Verdict {
        let rules: Vec<RuleResult> = self
            .rules
            .iter()
            .map(|r| {
                if let Some(x) = &r.result {
                    return x.clone();
                }
                let (passed, reason) = match &r.check {
                    Check::PassThrough { entered: 0, .. } => (false, "never entered the door's free space".into()),
                    Check::PassThrough { entered, .. } => {
                        (false, format!("entered the free space {entered} time(s) but never came out on the other side"))
                    }
                    Check::ReachTop { highest, steps, .. } if *highest < 0 => {
                        (false, format!("never stood on a step (0 of {steps} treads)"))
                    }
                    Check::ReachTop { highest, steps, .. } => {
                        (false, format!("got as far as tread {} of {steps} but not fully onto the top", highest + 1))
                    }
                    Check::RampTop { highest_m: None, .. } => {
                        (false, "never drove onto the ramp".into())
                    }
                    Check::RampTop { highest_m: Some(h), rise_m, .. } => {
                        let off = if *h > 0.0 { format!(" (at most {h:.2} m up before it drove back off)") } else { String::new() };
                        (false, format!("drove onto the ramp but never stood at its top, {rise_m:.2} m up{off}"))
                    }
                    Check::OpenDoor { initial_deg, widest_deg, .. } => {
                        (false, format!("the door opened at most {widest_deg:.1} degrees (from {initial_deg:.1})"))
                    }
                    Check::Reach { closest_m, .. } => (false, format!("came no closer than {closest_m:.2} m")),
                    Check::MaxWall { max_s } => {
                        (true, format!("touched walls for {wall_contact_s:.2} s (allowed {max_s} s)"))
                    }
                    Check::NoBrokenJoint => (true, "no joint broke".into()),
                    Check::NoTipping { max_tilt_deg } => {
                        (true, format!("never tipped (largest roll or pitch {max_tilt_deg:.1} degrees)"))
                    }
                    Check::NoStuck => (true, "never stuck".into()),
                };
                if interrupted {
                    let reason = format!("not decided: the run was interrupted at {end_s:.2} s (so far: {reason})");
                    return RuleResult { rule: r.rule.clone(), passed: false, reason, decided_s: end_s, undecided: true };
                }
                RuleResult { rule: r.rule.clone(), passed, reason, decided_s: end_s, undecided: false }
            })
            .collect();
        Verdict {
            passed: !interrupted && rules.iter().all(|r| r.passed),
            rules,
            end_time_s: end_s,
            interrupted_at_s: interrupted.then_some(end_s),
        }
    }
}
