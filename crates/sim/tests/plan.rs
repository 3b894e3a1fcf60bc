//! The scenario planner against ground truth: the default building's tour from the demo's
//! start, a door walled off, a world that is all wall, a world without doors.

mod common;

use common::{default_world, room, world};
use fixtures::Side;
use sim::{plan_scenario, Goal, PlanConfig, RobotModel, Scenario, SimError, StartPose};

fn robot(name: &str) -> (RobotModel, PlanConfig) {
    let cfg = PlanConfig {
        robot: name.into(),
        ..PlanConfig::default()
    };
    (RobotModel::builtin(name).expect("built in"), cfg)
}

fn demo_start() -> StartPose {
    Scenario::default_scenario()
        .expect("the demo scenario")
        .start
}

#[test]
fn the_default_building_tour_passes_the_stair_room_door_and_climbs_the_stairs_and_passes() {
    let w = default_world();
    let (model, cfg) = robot("inspection");
    let p = plan_scenario(&w, &model, Some(demo_start()), &cfg).expect("planned");
    // Ground truth: five openings off the corridor, the stairs behind the stair room's door
    // (walls[4].doors[2]); the inspection robot fits every opening and climbs the 0.15 m rise.
    assert_eq!((p.doors(), p.stairs()), (5, 1), "{}", p.summary());
    assert!(p.unreachable.is_empty(), "{:?}", p.unreachable);
    assert!(p
        .tour
        .contains(&Goal::Door("walls[4].doors[2].leaf".into())));
    assert_eq!(p.tour.last(), Some(&Goal::Stairs("stairs[0]".into())));
    let s = &p.scenario;
    assert_eq!(s.robot, "inspection");
    assert!((s.start.x_m - 1.5).abs() < 0.05, "{:?}", s.start);
    assert_eq!(s.rules.max_wall_contact_s, Some(0.5));
    assert!(s.rules.no_tipping);
    // The time limit covers the tour at the cruise speed, with slack.
    assert!(
        s.time_limit_s > p.tour_length_m / cfg.cruise_speed_mps,
        "{}",
        s.time_limit_s
    );
    // The planned scenario reads back equal from the TOML written beside the outputs.
    let text = p.to_toml().expect("toml");
    assert!(text.starts_with("# Planned by semsim"), "{text}");
    let back = Scenario::from_toml_str(&text, "planned").expect("parses");
    assert_eq!(&back, s);
    // Run and judged with the planned rules: every rule passes.
    let outcome = sim::run_scenario(&w, s, &model).expect("runs");
    let v = &outcome.verdict;
    assert!(v.passed, "{:#?}\n{}", v.rules, common::timeline(&outcome));
    assert_eq!(v.rules.len(), 5 + 1 + 2);
}

#[test]
fn the_pioneer_cannot_climb_the_default_stairs_and_the_report_says_why() {
    let w = default_world();
    let (model, cfg) = robot("pioneer3at");
    let p = plan_scenario(&w, &model, Some(demo_start()), &cfg).expect("planned");
    assert_eq!(p.stairs(), 0);
    assert_eq!(p.doors(), 5, "{} {:?}", p.summary(), p.unreachable);
    let u = p
        .unreachable
        .iter()
        .find(|u| u.goal == Goal::Stairs("stairs[0]".into()))
        .expect("the stairs are listed");
    // The default stairs rise 0.15 m; the Pioneer's plain tyres climb about 0.03 m.
    assert!(
        u.reason
            .starts_with("rise 0.15 m above what pioneer3at climbs (0.03 m)"),
        "{}",
        u.reason
    );
    let section = p.report_section();
    assert!(section.starts_with("## Not reachable") && section.contains("`stairs[0]`"));
}

#[test]
fn a_walled_off_door_is_listed_unreachable_and_the_run_still_gets_a_verdict() {
    // A room (x 0..6) whose east wall's door opens onto another wall 0.5 m behind it: the
    // robot fits through the opening but has no room on the far side.
    let text = fixtures::walled_off_room();
    let w = world(&text);
    let (model, cfg) = robot("pioneer3at");
    let p = plan_scenario(&w, &model, None, &cfg).expect("planned");
    assert!(p.tour.is_empty(), "{:?}", p.tour);
    assert_eq!(p.unreachable.len(), 1, "{:?}", p.unreachable);
    assert_eq!(
        p.unreachable[0].goal,
        Goal::Door("walls[3].doors[0].free_space".into())
    );
    assert!(p.report_section().contains("nothing was reachable"));
    // The start: the free cell nearest the middle of the room (x 0.1..5.9, y -1.9..1.9).
    let s = &p.scenario.start;
    assert!((s.x_m - 3.0).abs() < 0.1 && s.y_m.abs() < 0.1, "{s:?}");
    // No door to pass: the robot sweeps the room instead, to its farthest free point and on
    // to the point farthest from there (two far corners of the free x 0.35..5.65, y
    // -1.65..1.65), and must reach the sweep's far end; plus the two constraints.
    let end = p.sweep_end_m.expect("a sweep");
    assert!(!p.scenario.waypoints.is_empty());
    assert!(end[0] < 1.0 || end[0] > 5.0, "{end:?}");
    assert!(p.tour_length_m > 5.0, "{}", p.summary());
    assert!(p.summary().ends_with(" sweep"), "{}", p.summary());
    let reach = p.scenario.rules.reach.expect("a reach rule");
    assert_eq!([reach.x_m, reach.y_m], end);
    let outcome = sim::run_scenario(&w, &p.scenario, &model).expect("runs");
    assert!(outcome.verdict.passed, "{:#?}", outcome.verdict.rules);
    assert_eq!(outcome.verdict.rules.len(), 3);
}

#[test]
fn a_sweep_ends_where_the_robot_can_turn() {
    // Regression (the 3DTK corridor's planned sweep): the farthest free cell from where the
    // robot stood lay in a doorway with nothing mapped beyond, where the robot turned into the
    // jamb. Here it was a corner, 0.28 m from both walls. The room's inner faces: x 0.1 and
    // 5.9, y -1.9 and 1.9.
    let w = world(&fixtures::walled_off_room());
    let (model, cfg) = robot("pioneer3at");
    let p = plan_scenario(&w, &model, None, &cfg).expect("planned");
    let end = p.sweep_end_m.expect("a sweep");
    let clearance = (end[0] - 0.1).min(5.9 - end[0]).min(1.9 - end[1].abs());
    // The Pioneer 3-AT turns in a circle of 0.36 m radius (its half diagonal).
    assert!(
        clearance >= 0.36,
        "sweep end {end:?}: {clearance:.2} m from a wall"
    );
}

#[test]
fn the_same_door_without_the_wall_behind_is_passed() {
    // The control for the test above: the door itself is passable.
    let text = fixtures::RoomToml::new([0.0, -2.0], [6.0, 2.0], 2.5)
        .walls(&[Side::South, Side::North, Side::West])
        .floor_to_x(9.2)
        .toml(fixtures::EAST_DOOR_WALL);
    let w = world(&text);
    let (model, cfg) = robot("pioneer3at");
    let p = plan_scenario(&w, &model, None, &cfg).expect("planned");
    assert_eq!(
        p.tour,
        vec![Goal::Door("walls[3].doors[0].free_space".into())]
    );
    let outcome = sim::run_scenario(&w, &p.scenario, &model).expect("runs");
    assert!(outcome.verdict.passed, "{:#?}", outcome.verdict.rules);
}

#[test]
fn a_world_that_is_all_wall_is_a_clear_error() {
    let text = room(
        r#"
[[boxes]]
name = "solid"
center_m = [3.0, 0.0, 1.0]
size_m = [6.4, 4.4, 2.0]
"#,
    );
    let w = world(&text);
    let (model, cfg) = robot("pioneer3at");
    let e = plan_scenario(&w, &model, None, &cfg).expect_err("no free space");
    assert!(
        e.to_string() == "plan: no free space for the robot in test room",
        "{e}"
    );
    assert!(matches!(e, SimError::Invalid { .. }));
    assert!(cloud::BadInput::is_bad_input(&e));
    let e = plan_scenario(&w, &model, Some(demo_start()), &cfg).expect_err("with a hint too");
    assert!(e.to_string().contains("no free space"), "{e}");
}

#[test]
fn beams_above_the_robot_and_flat_mats_do_not_block_but_a_crate_does() {
    // Each box spans the room from wall to wall at x = 3: the largest free region (and so the
    // start without a hint) is the whole room where the box does not block, half of it where
    // it does.
    let across = |class: &str, z_m: f64, h_m: f64| {
        room(&format!(
            "[[boxes]]\nclass = \"{class}\"\ncenter_m = [3.0, 0.0, {z_m}]\nsize_m = [0.3, 4.4, {h_m}]\n"
        ))
    };
    let (model, cfg) = robot("pioneer3at");
    let start_x = |text: &str| {
        let p = plan_scenario(&world(text), &model, None, &cfg).expect("planned");
        p.scenario.start.x_m
    };
    let whole = |x: f64| (x - 3.0).abs() < 0.2;
    let half = |x: f64| (x - 1.5).abs() < 0.3 || (x - 4.5).abs() < 0.3;
    // A beam 2.05..2.35 m up: far above the Pioneer (0.28 m).
    assert!(whole(start_x(&across("beam", 2.2, 0.3))));
    // A mat 2 cm high: below the 0.028 m its tyres drive over.
    assert!(whole(start_x(&across("furniture", 0.01, 0.02))));
    // A crate 0.5 m high, and a beam hanging down to 0.2 m: they block.
    assert!(half(start_x(&across("furniture", 0.25, 0.5))));
    assert!(half(start_x(&across("beam", 1.2, 2.0))));
}
