//! `semsim simulate --map` (or `--building`) with no scenario plans one in the map's (or the
//! building's) world; a map with no free space for the robot is bad input (exit 2) with a
//! message naming the map.

mod util;

use util::Dir;

/// A semantic map (format 2) holding only a floor of `size_m` x `size_m` metres.
fn floor_only_map(size_m: f64) -> String {
    format!(
        r#"{{"format":"semsim.semantic_map","version":2,
        "input_from_map":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],
        "entities":[{{"id":1,"class":"floor","geometry":{{"center_m":[0,0,-0.1],
        "size_m":[{size_m},{size_m},0.2],"yaw_deg":0}},"support_points":100,"confidence":1.0,
        "rules":[]}}],"relations":[]}}"#
    )
}

#[test]
fn simulate_map_without_a_scenario_plans_one_and_writes_it() {
    let dir = Dir::new();
    dir.write("room.json", floor_only_map(4.0));
    let out = dir
        .run(&["simulate", "--map", "room.json", "--out", "sim"])
        .ok();
    assert!(
        out.contains("planned tour: 0 doors, 0 stairs, 0 unreachable"),
        "{out}"
    );
    let scenario = sim::Scenario::load(&dir.join("sim/scenario.toml")).expect("parses");
    // The start: the middle of the only free region, the floor's centre.
    assert!(scenario.start.x_m.abs() < 0.1 && scenario.start.y_m.abs() < 0.1);
    let report = std::fs::read_to_string(dir.join("sim/report.md")).expect("report.md");
    assert!(report.contains("## Not reachable") && report.contains("no door opening"));
}

#[test]
fn simulate_map_with_no_free_space_is_bad_input_naming_the_map() {
    let dir = Dir::new();
    // A floor 0.3 m square: the narrowest robot (0.5 m wide) fits nowhere on it.
    dir.write("tiny.json", floor_only_map(0.3));
    dir.run(&["simulate", "--map", "tiny.json", "--out", "sim"])
        .bad_input(&["no free space for the robot in tiny.json"]);
}

/// A building file and no scenario: the built-in scenario names places in the built-in
/// building only, so a tour is planned in this one's world, up its ramp.
#[test]
fn simulate_building_without_a_scenario_plans_a_tour_up_its_ramp() {
    let dir = Dir::new();
    dir.write(
        "ramp_room.toml",
        fixtures::RoomToml::new([0.0, -2.0], [6.0, 2.0], 2.5).toml(
            "[[ramps]]\nstart_m = [1.5, 0.0]\ndirection_deg = 0.0\nlength_m = 3.5\n\
             width_m = 1.5\nrise_m = 0.35\n",
        ),
    );
    let out = dir
        .run(&["simulate", "--building", "ramp_room.toml", "--out", "sim"])
        .ok();
    assert!(
        out.contains("planned tour: 0 doors, 0 stairs, 1 ramps, 0 unreachable"),
        "{out}"
    );
    let scenario = sim::Scenario::load(&dir.join("sim/scenario.toml")).expect("parses");
    assert_eq!(
        scenario.rules.reach_top_of_ramps,
        vec!["ramps[0]".to_string()]
    );
    assert_eq!(scenario.building, "ramp_room.toml");
    let events = std::fs::read_to_string(dir.join("sim/events.jsonl")).expect("events");
    assert!(events.contains("\"ramp_climbing_finished\""), "{events}");
}
