//! Tests of `validate`.

use crate::Building;
use std::path::Path;

const SMALL: &str = r#"
    [floor]
    min_m = [0.0, 0.0]
    max_m = [4.0, 4.0]
    [ceiling]
    height_m = 2.5
    [[walls]]
    start_m = [0.0, 0.0]
    end_m = [4.0, 0.0]
    thickness_m = 0.2
    [[walls.doors]]
    offset_m = 1.0
    width_m = 0.9
    height_m = 2.0
"#;

fn with(from: &str, to: &str) -> String {
    assert!(SMALL.contains(from), "{from}");
    SMALL.replace(from, to)
}

#[test]
fn a_box_of_1e30_m_or_far_outside_the_floor_is_rejected() {
    for (extra, why) in [
        (
            "[[boxes]]\ncenter_m = [1.0, 1.0, 0.5]\nsize_m = [1e30, 1.0, 1.0]\n",
            "larger than the building",
        ),
        (
            "[[boxes]]\ncenter_m = [1e30, 1.0, 0.5]\nsize_m = [1.0, 1.0, 1.0]\n",
            "outside the floor",
        ),
        (
            "[[boxes]]\ncenter_m = [1.0, 1.0, 1e9]\nsize_m = [1.0, 1.0, 1.0]\n",
            "far outside the building",
        ),
    ] {
        let e = Building::from_toml_str(&format!("{SMALL}\n{extra}"), Path::new("b.toml"))
            .expect_err(why)
            .to_string();
        assert!(
            e.contains("b.toml") && e.contains("boxes[0]") && e.contains(why),
            "{e}"
        );
    }
    let far_wall = with("end_m = [4.0, 0.0]", "end_m = [4.0e6, 0.0]");
    let e = Building::from_toml_str(&far_wall, Path::new("b.toml")).expect_err("far wall");
    assert!(e.to_string().contains("walls[0]"), "{e}");
}

#[test]
fn a_valid_building_parses() {
    let b = Building::from_toml_str(SMALL, Path::new("b.toml")).expect("valid");
    assert_eq!(b.walls[0].doors.len(), 1);
}

#[test]
fn door_wider_than_its_wall_is_rejected_with_file_and_element() {
    let e = Building::from_toml_str(&with("width_m = 0.9", "width_m = 5.0"), Path::new("b.toml"))
        .expect_err("must fail")
        .to_string();
    assert!(
        e.contains("b.toml")
            && e.contains("walls[0].doors[0]")
            && e.contains("wider than its wall"),
        "{e}"
    );
}

#[test]
fn absurd_values_are_rejected() {
    for (from, to) in [
        ("offset_m = 1.0", "offset_m = 3.5"),
        ("height_m = 2.0", "height_m = 3.0"),
        ("height_m = 2.5", "height_m = -1.0"),
        ("thickness_m = 0.2", "thickness_m = 0.0"),
        ("max_m = [4.0, 4.0]", "max_m = [40000.0, 4.0]"),
        ("offset_m = 1.0", "offset_m = nan"),
    ] {
        let r = Building::from_toml_str(&with(from, to), Path::new("b.toml"));
        assert!(r.is_err(), "{from} -> {to} accepted");
    }
}

#[test]
fn a_ramp_steeper_than_20_degrees_or_through_the_ceiling_is_rejected() {
    let ramp = |length: &str, rise: &str| {
        format!(
            "{SMALL}\n[[ramps]]\nstart_m = [1.0, 2.0]\ndirection_deg = 0.0\n\
             length_m = {length}\nwidth_m = 1.5\nrise_m = {rise}\n"
        )
    };
    let b = Building::from_toml_str(&ramp("3.0", "0.5"), Path::new("b.toml")).expect("9.5 deg");
    assert_eq!(b.ramps.len(), 1);
    for (length, rise, why) in [
        ("1.0", "0.5", "steeper than"),
        ("10.0", "2.6", "through the ceiling"),
        ("3.0", "-0.5", "must be positive"),
        ("3.0", "nan", "not a finite number"),
    ] {
        let e = Building::from_toml_str(&ramp(length, rise), Path::new("b.toml"))
            .expect_err(why)
            .to_string();
        assert!(e.contains("ramps[0]") && e.contains(why), "{e}");
    }
}

#[test]
fn unknown_keys_and_syntax_errors_name_the_file() {
    let e = Building::from_toml_str(
        &with("[ceiling]", "[ceiling]\ncolour = 3"),
        Path::new("b.toml"),
    )
    .expect_err("unknown key")
    .to_string();
    assert!(e.contains("b.toml") && e.contains("colour"), "{e}");
}
