//! Ramps in the simulation: the planned tour drives up them, the wheels on them are no
//! collision, the climb is an event, and the rule `reach_top_of_ramps` judges it.

mod common;

use common::{has, of, room, timeline, world};
use sim::{plan_scenario, EventKind, Goal, PlanConfig, RobotModel, Scenario};

/// The test room (x 0..6, y -2..2) with a ramp from x = 1.5 up to x = 5 along +x, 1.5 m wide,
/// rising `rise_m` (0.35 m: 5.7 degrees).
fn ramp_room(rise_m: f64, width_m: f64) -> String {
    room(&format!(
        "[[ramps]]\nstart_m = [1.5, 0.0]\ndirection_deg = 0.0\nlength_m = 3.5\n\
         width_m = {width_m}\nrise_m = {rise_m}\n"
    ))
}

fn pioneer() -> (RobotModel, PlanConfig) {
    (
        RobotModel::builtin("pioneer3at").expect("built in"),
        PlanConfig::default(),
    )
}

#[test]
fn the_planned_tour_drives_up_a_ramp_and_every_rule_passes() {
    let w = world(&ramp_room(0.35, 1.5));
    let (model, cfg) = pioneer();
    let p = plan_scenario(&w, &model, None, &cfg).expect("planned");
    assert_eq!(p.tour, vec![Goal::Ramp("ramps[0]".into())], "{:?}", p);
    assert!(p.unreachable.is_empty(), "{:?}", p.unreachable);
    assert!(
        p.summary().contains("0 stairs, 1 ramps,"),
        "{}",
        p.summary()
    );
    let s = &p.scenario;
    assert_eq!(s.rules.reach_top_of_ramps, vec!["ramps[0]".to_string()]);
    // The planned scenario reads back equal from its TOML.
    let back = Scenario::from_toml_str(&p.to_toml().expect("toml"), "planned").expect("parses");
    assert_eq!(&back, s);
    let o = sim::run_scenario(&w, s, &model).expect("runs");
    let t = timeline(&o);
    assert!(o.verdict.passed, "{:#?}\n{t}", o.verdict.rules);
    assert!(has(&o, EventKind::RampClimbingStarted, "ramps[0]"), "{t}");
    assert!(has(&o, EventKind::RampClimbingFinished, "ramps[0]"), "{t}");
    // Driving on the ramp is no collision with it.
    assert!(!has(&o, EventKind::CollisionStarted, "ramps[0]"), "{t}");
    // The robot ends up the slope: its upper end is 0.35 m x (3.5 - 0.3) / 3.5 up at the
    // robot's centre, less the robot's own half length's worth of slope at most.
    let (first, last) = (
        o.trajectory[0].pose,
        o.trajectory.last().expect("samples").pose,
    );
    let climbed = last.z_m - first.z_m;
    assert!(climbed > 0.25 && climbed < 0.36, "climbed {climbed} m\n{t}");
}

#[test]
fn a_robot_that_turns_back_halfway_up_fails_the_ramp_rule_saying_how_high_it_got() {
    let w = world(&ramp_room(0.35, 1.5));
    let o = common::run(
        &w,
        r#"
        robot = "pioneer3at"
        time_limit_s = 40.0
        start = { x_m = 0.6, y_m = 0.0, yaw_deg = 0.0 }
        [[waypoints]]
        x_m = 3.25
        y_m = 0.0
        speed_mps = 0.4
        [[waypoints]]
        x_m = 0.6
        y_m = 0.0
        speed_mps = 0.4
        [rules]
        reach_top_of_ramps = ["ramps[0]"]
        no_tipping = true
        "#,
    );
    let t = timeline(&o);
    assert!(!o.verdict.passed, "{t}");
    let aborted = of(&o, EventKind::RampClimbingAborted);
    assert_eq!(aborted.len(), 1, "{t}");
    assert!(of(&o, EventKind::RampClimbingFinished).is_empty(), "{t}");
    // Its centre got to x = 3.25, half way up: 0.35 x 1.75 / 3.5 = 0.175 m.
    let h = aborted[0].value("height_m").expect("height");
    assert!((h - 0.175).abs() < 0.04, "{h}\n{t}");
    let r = o
        .verdict
        .rules
        .iter()
        .find(|r| r.rule.starts_with("reach_top_of_ramps"))
        .expect("the ramp rule");
    assert!(!r.passed);
    assert!(
        r.reason.contains("never stood at its top, 0.35 m up"),
        "{}",
        r.reason
    );
}

#[test]
fn ramps_too_steep_or_too_narrow_are_listed_with_the_reason() {
    let (model, cfg) = pioneer();
    // 1.1 m over 3.5 m: 17.4 degrees.
    let steep = world(&ramp_room(1.1, 1.5));
    let p = plan_scenario(&steep, &model, None, &cfg).expect("planned");
    assert_eq!(p.ramps(), 0);
    let u = &p.unreachable;
    assert_eq!(u.len(), 1, "{u:?}");
    assert_eq!(u[0].goal, Goal::Ramp("ramps[0]".into()));
    assert!(
        u[0].reason
            .starts_with("the ramp climbs 17.4 degrees, steeper than the plan's"),
        "{}",
        u[0].reason
    );
    assert!(p.report_section().contains("| `ramps[0]` | ramp |"));
    // Allowed steeper, the same ramp is on the tour.
    let steeper = PlanConfig {
        max_ramp_pitch_deg: 20.0,
        ..cfg.clone()
    };
    let p = plan_scenario(&steep, &model, None, &steeper).expect("planned");
    assert_eq!(p.tour, vec![Goal::Ramp("ramps[0]".into())]);
    // 0.5 m wide: the Pioneer (0.5 m over its wheels) needs 0.6 m with the margins.
    let narrow = world(&ramp_room(0.35, 0.5));
    let p = plan_scenario(&narrow, &model, None, &cfg).expect("planned");
    assert_eq!(p.ramps(), 0);
    assert!(
        p.unreachable[0]
            .reason
            .starts_with("the ramp is 0.50 m wide"),
        "{:?}",
        p.unreachable
    );
}

#[test]
fn a_crate_on_the_ramp_or_a_beam_low_over_it_keeps_the_tour_off_it() {
    let (model, cfg) = pioneer();
    let with = |extra: &str| {
        let text = format!("{}{extra}", ramp_room(0.35, 1.5));
        let p = plan_scenario(&world(&text), &model, None, &cfg).expect("planned");
        assert_eq!(p.ramps(), 0, "{:?}", p.tour);
        p.unreachable[0].reason.clone()
    };
    // A crate standing on the slope half way up (x = 3.25, the slope 0.175 m up there).
    let on = with(
        "[[boxes]]\nname = \"crate\"\ncenter_m = [3.25, 0.0, 0.4]\nsize_m = [0.4, 0.4, 0.5]\n",
    );
    assert_eq!(on, "boxes[0] stands on the ramp in the robot's way");
    // A beam across the ramp 0.45 m up at x = 4 (the slope 0.25 m up): 0.2 m over it, less
    // than the Pioneer's height and margin.
    let low = with(
        "[[boxes]]\nclass = \"beam\"\ncenter_m = [4.0, 0.0, 0.55]\nsize_m = [0.2, 4.4, 0.2]\n",
    );
    assert!(
        low.starts_with("boxes[0] is 0.19 m over the slope, the robot needs"),
        "{low}"
    );
    // The same beam 1 m higher is no obstacle: the tour goes up.
    let text = format!(
        "{}[[boxes]]\nclass = \"beam\"\ncenter_m = [4.0, 0.0, 1.55]\nsize_m = [0.2, 4.4, 0.2]\n",
        ramp_room(0.35, 1.5)
    );
    let p = plan_scenario(&world(&text), &model, None, &cfg).expect("planned");
    assert_eq!(p.ramps(), 1, "{:?}", p.unreachable);
}
