//! Shared helpers for the sim integration tests.
#![allow(dead_code)]

use fixtures::Side;
use sim::{Event, EventKind, Outcome, RobotModel, Scenario, WorldSpec};
use std::path::Path;

/// A world from a building TOML string.
pub fn world(building_toml: &str) -> WorldSpec {
    let b = scanner::Building::from_toml_str(building_toml, Path::new("test.toml")).unwrap();
    WorldSpec::from_building(&b).unwrap()
}

/// The default building's world.
pub fn default_world() -> WorldSpec {
    WorldSpec::from_building(&scanner::Building::default_building().unwrap()).unwrap()
}

/// Runs a scenario (TOML) in a world.
pub fn run(spec: &WorldSpec, scenario_toml: &str) -> Outcome {
    let sc = Scenario::from_toml_str(scenario_toml, "test scenario").unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    sim::run_scenario(spec, &sc, &model).unwrap()
}

/// The events of a kind.
pub fn of(o: &Outcome, kind: EventKind) -> Vec<&Event> {
    o.events.iter().filter(|e| e.kind == kind).collect()
}

/// Whether an event of `kind` names the entity `name`.
pub fn has(o: &Outcome, kind: EventKind, name: &str) -> bool {
    o.events
        .iter()
        .any(|e| e.kind == kind && e.entities.iter().any(|x| x.name == name))
}

/// The significant events, one JSON line each (for failure messages).
pub fn timeline(o: &Outcome) -> String {
    o.events
        .iter()
        .filter(|e| e.kind.is_significant())
        .map(|e| e.to_json_line())
        .collect::<Vec<_>>()
        .join("\n")
}

/// A 6 m x 4 m room (x 0..6, y -2..2), 2.5 m high, named "test room", with its south, north
/// and west walls (`walls[0..3]`) and the given extra walls/boxes appended.
pub fn room(extra: &str) -> String {
    fixtures::RoomToml::new([0.0, -2.0], [6.0, 2.0], 2.5)
        .walls(&[Side::South, Side::North, Side::West])
        .toml(extra)
}

/// [`room`] closed by its east wall at x = 6 (`walls[3]`).
pub fn closed_room() -> String {
    fixtures::RoomToml::new([0.0, -2.0], [6.0, 2.0], 2.5).toml("")
}
