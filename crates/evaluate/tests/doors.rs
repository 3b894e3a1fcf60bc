//! Door openings against the default building's ground truth, where a leaf makes them hard.

use evaluate::evaluate;
use scanner::Building;
use semantic::{build_semantic_map, SemanticConfig};

/// Regression: a leaf ajar crosses the face plane over 20 cm (open 30 degrees) to 40 cm (open
/// 15 degrees) near its hinge; those bins counted as wall, so at 30 degrees the opening was
/// found 35 cm narrow on the hinge side (the hinge was put there and the angle came out 19
/// degrees too wide), and at 15 degrees it was not found at all.
#[test]
fn a_leaf_ajar_leaves_the_opening_its_full_width() {
    for open_deg in [15.0, 30.0] {
        let mut b = Building::default_building().expect("default building");
        let leaf = b.walls[4].doors[2]
            .leaf
            .as_mut()
            .expect("the stair room's door has a leaf");
        leaf.open_deg = open_deg;
        stair_room_door_measured(&b, &format!("{open_deg} deg"));
    }
}

/// The demo's scans (full resolution) of `b` mapped and scored; asserts that the stair room's
/// door is found with its width within 0.1 m and its leaf's angle within 5 degrees (`case`
/// names the building in failures), and returns the evaluation.
fn stair_room_door_measured(b: &Building, case: &str) -> evaluate::Evaluation {
    let poses = Building::default_survey_poses();
    let cloud = fixtures::scan_building(b, &poses, &scanner::LaserConfig::default(), 0.03);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    let ev = evaluate(&out.map, b, Some(&cloud));
    let m = ev
        .door_matches
        .iter()
        .find(|m| m.truth == "walls[4].doors[2]")
        .unwrap_or_else(|| panic!("{case}: the door is found: missed {:?}", ev.missed));
    eprintln!("{case}: {m:?}");
    assert!(
        m.width_error_m.abs() < 0.1,
        "{case}: width off by {}",
        m.width_error_m
    );
    let angle = m
        .open_angle_error_deg
        .expect("the leaf's angle is measured");
    assert!(angle.abs() < 5.0, "{case}: angle off by {angle} deg");
    ev
}

/// Regression: the free edge of a leaf standing open (the stair room's, at 60 degrees) was
/// left unlabelled by the door and became a 5 cm x 2 m `obstacle` at the leaf's tip; in the
/// simulation it stood fixed where the leaf swings, and the robot pushing the door open got
/// stuck on it (the demo's verdict failed). Nothing of a leaf is an obstacle at any angle.
#[test]
fn no_obstacle_stands_where_a_leaf_swings() {
    for open_deg in [0.0, 30.0, 60.0, 90.0] {
        let mut b = Building::default_building().expect("default building");
        let wall = &mut b.walls[4];
        let (start, end) = (wall.start_m, wall.end_m);
        let door = &mut wall.doors[2];
        let leaf = door
            .leaf
            .as_mut()
            .expect("the stair room's door has a leaf");
        leaf.open_deg = open_deg;
        let (hinge_offset, width) = (door.offset_m, door.width_m);
        let poses = Building::default_survey_poses();
        let cloud = fixtures::scan_building(&b, &poses, &scanner::LaserConfig::default(), 0.03);
        let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
        // The leaf's quarter circle on its swing side (hinge at the opening's start edge,
        // swinging left of the wall's direction), in the truth's frame (the map's, here).
        let len = ((end[0] - start[0]).powi(2) + (end[1] - start[1]).powi(2)).sqrt();
        let u = [(end[0] - start[0]) / len, (end[1] - start[1]) / len];
        let hinge = [
            start[0] + u[0] * hinge_offset,
            start[1] + u[1] * hinge_offset,
        ];
        for e in &out.map.entities {
            if !matches!(
                e.class,
                cloud::EntityClass::Obstacle | cloud::EntityClass::Column
            ) {
                continue;
            }
            let r = [
                e.geometry.center_m[0] - hinge[0],
                e.geometry.center_m[1] - hinge[1],
            ];
            let (along, left) = (r[0] * u[0] + r[1] * u[1], -r[0] * u[1] + r[1] * u[0]);
            let in_swing = (r[0].hypot(r[1]) < width + 0.1) && along > -0.1 && left > -0.1;
            assert!(
                !in_swing,
                "leaf open {open_deg} deg: {} {} at {:?} stands where the leaf swings",
                e.class, e.id, e.geometry.center_m
            );
        }
    }
}

/// Regression: a glass partition read as a row of door openings (bench office-54 of seeds
/// 51-55: three in one pane; 8 of the bench's buildings had such openings): the realistic laser's
/// glass returns some beams, in most 5 cm bins fewer than block one at door level, and its upper
/// part reads as a lintel. That building scanned along its survey poses with the realistic
/// laser (at the tests' resolution, true poses): no opening in its glass, every doorway of its
/// other walls found.
#[test]
fn a_glass_partition_is_no_row_of_door_openings() {
    let config = scanner::GeneratorConfig {
        style: scanner::Style::Office,
        ..Default::default()
    };
    let b = scanner::generate_building(54, &config).expect("office-54");
    assert!(
        b.walls
            .iter()
            .any(|w| w.material == scanner::Material::Glass),
        "office-54 has a glass partition"
    );
    let poses = scanner::survey_poses(&b, &scanner::SurveyConfig::default()).expect("poses");
    let cloud = fixtures::scan_building(&b, &poses, &fixtures::real_test_laser(), 0.03);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    let ev = evaluate(&out.map, &b, Some(&cloud));
    eprintln!(
        "door openings {:?}, missed {:?}",
        ev.door_openings, ev.missed
    );
    assert_eq!(
        ev.door_openings.detected, ev.door_openings.matched,
        "no opening where there is none: {:?}",
        ev.door_openings
    );
    assert!(ev.door_openings.recall >= 0.9, "{:?}", ev.door_openings);
}

/// Regression: office-123 of seeds 121-125: a 0.69 m crate standing in a doorway against its
/// hinge-side jamb blocked the bins it stands in (its top and back face lie within half a wall
/// of the face), so the opening's edge was put at the crate's far side, 0.32 m into it; the
/// leaf, open 98 degrees, was looked for from there and missed, and became a 2 m tall
/// partial-height wall. A wall's face is seen up to door height; the crate stands lower.
#[test]
fn a_crate_against_a_doorways_jamb_leaves_the_opening_its_full_width() {
    let mut b = Building::default_building().expect("default building");
    let wall = &mut b.walls[4];
    let (start, face_y) = (wall.start_m, wall.start_m[1] - wall.thickness_m / 2.0);
    let door = &mut wall.doors[2];
    let leaf = door
        .leaf
        .as_mut()
        .expect("the stair room's door has a leaf");
    leaf.open_deg = 95.0;
    // The crate: in the corridor, 2 cm off the wall's face, from 2 cm past the hinge jamb.
    let (jamb_x, size) = (start[0] + door.offset_m, 0.3);
    b.boxes.push(scanner::Furniture {
        name: "doorway crate".into(),
        class: cloud::EntityClass::Furniture,
        material: scanner::Material::default(),
        center_m: [
            jamb_x + 0.02 + size / 2.0,
            face_y - 0.02 - size / 2.0,
            0.345,
        ],
        size_m: [size, size, 0.69],
        yaw_deg: 0.0,
    });
    let ev = stair_room_door_measured(&b, "a crate against its jamb");
    assert_eq!(
        ev.walls.detected, ev.walls.matched,
        "no wall where the leaf stands: {:?}",
        ev.spurious
    );
}
