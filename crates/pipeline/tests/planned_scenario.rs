//! The simulation stage with no scenario given: one is planned in the world, run, judged and
//! written, and a world with no reachable door still gives a verdict (not an error).

use pipeline::{simulate, write_simulation, Config, ScenarioChoice};
use sim::{Scenario, WorldSpec};
use std::ops::ControlFlow;
use std::path::Path;

/// In a 6 x 4 m room whose only door (`walls[3].doors[0]`) opens onto a wall 0.5 m behind it
/// (`fixtures::walled_off_room`), the plan reaches nothing.
#[test]
fn a_world_with_no_reachable_door_gets_a_planned_scenario_and_a_verdict() {
    let b = scanner::Building::from_toml_str(&fixtures::walled_off_room(), Path::new("room.toml"))
        .expect("building");
    let world = WorldSpec::from_building(&b).expect("world");
    let choice = ScenarioChoice::from_file_or_plan(None, &Config::default().plan).expect("plan");
    let source = choice.resolve(&world, None).expect("planned, not an error");
    let planned = source.planned.as_ref().expect("a planned scenario");
    assert!(planned.tour.is_empty());
    assert_eq!(planned.unreachable.len(), 1);
    let outcome = simulate(&world, &source, &mut |_| ControlFlow::Continue(())).expect("runs");
    assert!(outcome.verdict.passed, "{:#?}", outcome.verdict.rules);
    let dir = tempfile::tempdir().expect("temp dir");
    let report = write_simulation(&outcome, &source, dir.path()).expect("written");
    // The report lists what was not reachable, and so does the file.
    let file = std::fs::read_to_string(dir.path().join("report.md")).expect("report.md");
    assert_eq!(file, report);
    assert!(
        file.contains("## Not reachable")
            && file.contains("nothing was reachable")
            && file.contains("`walls[3].doors[0].free_space`"),
        "{file}"
    );
    // scenario.toml beside it is the planned scenario, which reads back equal.
    let back = Scenario::load(&dir.path().join("scenario.toml")).expect("scenario.toml parses");
    assert_eq!(back, source.scenario);
}

#[test]
fn a_given_scenario_is_not_planned_and_writes_no_section() {
    let choice = ScenarioChoice::Given(Box::new(
        pipeline::ScenarioSource::load(None).expect("built in"),
    ));
    let world = WorldSpec::from_building(&scanner::Building::default_building().expect("b"))
        .expect("world");
    let source = choice.resolve(&world, None).expect("given");
    assert!(source.planned.is_none());
    assert_eq!(
        source.scenario,
        Scenario::default_scenario().expect("default")
    );
}

#[test]
fn a_bad_plan_robot_fails_up_front_as_bad_input() {
    let mut cfg = Config::default().plan;
    cfg.robot = "no-such-robot".into();
    let e = ScenarioChoice::from_file_or_plan(None, &cfg).expect_err("unknown robot");
    assert!(cloud::BadInput::is_bad_input(&e), "{e}");
    assert!(e.to_string().contains("no-such-robot"), "{e}");
}
