//! `semsim simulate --map` on semantic maps whose obstacles overlap walls, columns and each
//! other (a hand-edited or foreign map, issue #15's bad input): the world is built and a
//! scenario planned around them (no panic, never bad input); obstacles leaving the robot no
//! room at all are bad input with a message naming the map.

mod util;

use util::Dir;

/// A semantic map (format 2): a 6 m floor, a wall along x = 0 and the entities `extra` (JSON
/// objects, comma-separated).
fn map_with(extra: &str) -> String {
    format!(
        r#"{{"format":"semsim.semantic_map","version":2,
        "input_from_map":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],
        "entities":[
        {{"id":1,"class":"floor","geometry":{{"center_m":[0,0,-0.1],"size_m":[6,6,0.2],
          "yaw_deg":0}},"support_points":100,"confidence":1.0,"rules":[]}},
        {{"id":2,"class":"wall","geometry":{{"center_m":[0,0,1.25],"size_m":[0.2,6,2.5],
          "yaw_deg":0}},"support_points":100,"confidence":1.0,"rules":[],
          "wall":{{"segment_m":[[0,-3],[0,3]],"thickness_m":0.2,"thickness_measured":true,
          "z_range_m":[0,2.5],"solid_boxes":[]}}}},
        {extra}],"relations":[]}}"#
    )
}

/// An obstacle, column or beam entity of `class` with id `id`.
fn entity(id: u32, class: &str, center: [f64; 3], size: [f64; 3], yaw_deg: f64) -> String {
    let (z0, z1) = (center[2] - size[2] / 2.0, center[2] + size[2] / 2.0);
    format!(
        r#"{{"id":{id},"class":"{class}","geometry":{{"center_m":[{},{},{}],
        "size_m":[{},{},{}],"yaw_deg":{yaw_deg}}},"support_points":50,"confidence":0.5,
        "rules":[],"obstacle":{{"z_range_m":[{z0},{z1}],"clearance_m":{z0},"hull_m":[],
        "fill":1.0}}}}"#,
        center[0], center[1], center[2], size[0], size[1], size[2]
    )
}

#[test]
fn obstacles_overlapping_a_wall_and_each_other_are_simulated_around() {
    let dir = Dir::new();
    let extra = [
        // Through the wall, a column in it, and a second obstacle overlapping the first.
        entity(3, "obstacle", [0.0, 1.0, 0.5], [1.0, 1.0, 1.0], 30.0),
        entity(4, "column", [0.05, -1.5, 1.25], [0.4, 0.4, 2.5], 0.0),
        entity(5, "obstacle", [0.4, 1.3, 0.4], [0.8, 0.6, 0.8], 0.0),
        // A beam over the wall's top.
        entity(6, "beam", [0.0, 0.0, 2.3], [0.3, 6.0, 0.4], 90.0),
    ]
    .join(",");
    dir.write("overlap.json", map_with(&extra));
    let r = dir.run(&["simulate", "--map", "overlap.json", "--out", "sim"]);
    let (code, stdout, stderr) = (r.code(), r.stdout(), r.stderr());
    assert!(
        code == 0 || code == 1,
        "exit {code}\nstdout: {stdout}\nstderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stdout.contains("planned tour: "), "{stdout}");
    assert!(dir.join("sim/report.md").exists());
}

#[test]
fn obstacles_covering_the_whole_floor_are_bad_input_naming_the_map() {
    let dir = Dir::new();
    let extra = [
        entity(3, "obstacle", [-1.5, 0.0, 0.5], [3.2, 6.2, 1.0], 0.0),
        entity(4, "obstacle", [1.5, 0.0, 0.5], [3.2, 6.2, 1.0], 0.0),
    ]
    .join(",");
    dir.write("full.json", map_with(&extra));
    dir.run(&["simulate", "--map", "full.json", "--out", "sim"])
        .bad_input(&["no free space for the robot in full.json"]);
}
