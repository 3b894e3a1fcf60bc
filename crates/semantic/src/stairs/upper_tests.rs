//! Regressions of upper flights: parted from the flight below them (`upper`), and counted at
//! its rise (`profile`).

use super::profile::{profile_near, Profile};
use super::tests::{over_floor, returns_and_surface, returns_by_part};
use super::*;
use crate::points::XyIndex;
use glam::Vec3;

/// The stairs stage's last steps on `returns` parted as `part_of` (each part searched along
/// and across X, as walls would give, then the upper flights joined), in a cloud of them over
/// a floor seen everywhere but under the staircase (x 0..`hidden_x`, y 0..1.3).
fn search_parts(
    returns: &[(DVec2, f64)],
    part_of: &[usize],
    hidden_x: f64,
) -> Vec<Option<Vec<DetectedStairs>>> {
    let points = over_floor(
        returns,
        DVec2::new(-1.5, -2.0),
        (250, 100),
        DVec2::new(hidden_x, 1.3),
    );
    search_parts_in(&points, returns.len(), part_of)
}

/// [`search_parts`] in a cloud of `points`: the parts' returns (`count` of them, first), then
/// the floor and what else the scene holds.
fn search_parts_in(
    points: &[Vec3],
    count: usize,
    part_of: &[usize],
) -> Vec<Option<Vec<DetectedStairs>>> {
    let c = StairsConfig::default();
    let index = XyIndex::new(points, DVec2::splat(-3.0), DVec2::splat(9.0), 0.25);
    let sc = Scene::with_one_index(points, &index, 0.0, 2.6);
    let n = part_of.iter().max().map_or(0, |m| m + 1);
    let parts: Vec<parts::Part> = (0..n)
        .map(|k| {
            let members: Vec<usize> = (0..count).filter(|&i| part_of[i] == k).collect();
            let surface = surface::on_surfaces(
                points,
                &members,
                c.min_surface_neighbours,
                c.surface_radius_spacings,
                3.0 * c.cell_m,
            );
            parts::Part {
                pixels: members.len(),
                members,
                surface,
            }
        })
        .collect();
    // (one wall along x: the directions along x and y)
    let walls = directions::WallFamilies::new([(DVec2::ZERO, DVec2::X)].into_iter());
    let mut found: Vec<_> = parts
        .iter()
        .map(|p| search_part(p, &walls, &sc, &c))
        .collect();
    upper::join_upper_flights(&parts, &mut found, &sc, &c);
    found
}

/// Regression: fresh office-66's staircase with a mid landing (flights of 3 and 4 steps of
/// 0.179 m; the landing 0.54 m up, above the laser) showed its lower flight alone: the upper
/// flight's risers, seen from below a run apart with no tread between them, were parts of
/// their own (three risers with the landing's side face, and the top riser), each too few
/// levels to be a flight. Read together, from the lower flight's landing, they are its upper
/// flight. (The parts' returns, from the bench's map.)
#[test]
fn an_upper_flights_risers_parted_from_the_lower_flight_are_its_flight() {
    let (lower, upper) = two_flights_of(
        include_str!("../../tests/data/office66_upper_flight.txt"),
        868,
        4.0,
    );
    assert_eq!((lower.steps, upper.steps), (3, 4), "{lower:?} {upper:?}");
    assert!((upper.rise - 0.179).abs() < 0.01, "rise {}", upper.rise);
    // Its first riser 2.25 m along, past the landing.
    assert_on_landing(&upper, 0.537, 2.25);
}

/// `upper` stands on a landing `base_m` up (within 3 cm), its first riser `start_x_m` along
/// (within 6 cm).
fn assert_on_landing(upper: &DetectedStairs, base_m: f64, start_x_m: f64) {
    assert!((upper.base - base_m).abs() < 0.03, "base {}", upper.base);
    assert!(
        (upper.start.x - start_x_m).abs() < 0.06,
        "start {}",
        upper.start
    );
}

/// The two flights read from the parts' returns in `text` (`count` of them; the staircase
/// over x 0..`hidden_x`): both of the first part's, none of the others'.
fn two_flights_of(text: &str, count: usize, hidden_x: f64) -> (DetectedStairs, DetectedStairs) {
    let (returns, part_of) = returns_by_part(text);
    assert_eq!(returns.len(), count);
    let found = search_parts(&returns, &part_of, hidden_x);
    assert!(found[1..].iter().all(Option::is_none), "{found:?}");
    match found[0].as_deref() {
        Some([lower, upper]) => (lower.clone(), upper.clone()),
        other => panic!("not two flights: {other:?}"),
    }
}

/// The same risers beside the lower flight's line (moved 1.5 m across it) are no flight of it.
#[test]
fn risers_beside_a_flights_line_are_no_flight_on_its_landing() {
    let (mut returns, part_of) =
        returns_by_part(include_str!("../../tests/data/office66_upper_flight.txt"));
    for (p, &k) in returns.iter_mut().zip(&part_of) {
        if k > 0 {
            p.0.y += 1.5;
        }
    }
    let found = search_parts(&returns, &part_of, 4.0);
    let flights = found[0].as_ref().expect("the lower flight");
    assert_eq!(flights.len(), 1, "{flights:?}");
    assert_eq!(flights[0].steps, 3);
}

/// A face along the flight's line beyond its landing, a tall cabinet's with its shelves a rise
/// apart (bench office-61), is no flight on the landing: the same returns squeezed into 0.2 m
/// across the flight's width, as a face along it, are no risers spanning it.
#[test]
fn a_face_along_a_flights_line_beyond_its_landing_is_no_flight_on_it() {
    let (mut returns, part_of) =
        returns_by_part(include_str!("../../tests/data/office66_upper_flight.txt"));
    for (p, &k) in returns.iter_mut().zip(&part_of) {
        if k > 0 {
            p.0.y = 0.1 + 0.2 * (p.0.y / 1.3).clamp(0.0, 1.0);
        }
    }
    let found = search_parts(&returns, &part_of, 4.0);
    let flights = found[0].as_ref().expect("the lower flight");
    assert_eq!(flights.len(), 1, "{flights:?}");
}

/// Regression: fresh office-74's staircase with a mid landing (two flights of 4 steps of
/// 0.158 m; the landing 0.63 m up, 1.25 m deep, above the laser), seen from its side past a
/// desk whose top hid the side face's top edge over half the landing, was missed whole: the
/// profile rose to the lower flight's top step and fell back under it past the desk, so the
/// landing was read low (0.48 m), under the lower flight's top (0.58 m), and neither was
/// kept. The lower flight climbs to its top step: that is the landing (see
/// `flights::LANDING_UNDER_TOP`). The upper flight, its first riser in the lower flight's part
/// and the others a part of their own, all seen from below a few centimetres low, is still
/// not found. (The parts' returns, from the bench's map.)
#[test]
fn a_landing_read_under_its_flights_top_step_leaves_the_flight() {
    let (returns, part_of) =
        returns_by_part(include_str!("../../tests/data/office74_two_flights.txt"));
    assert_eq!(returns.len(), 1591);
    let found = search_parts(&returns, &part_of, 4.4);
    let flights = found[0].as_ref().expect("the lower flight");
    assert_eq!(flights.len(), 1, "{flights:?}");
    let lower = &flights[0];
    assert_eq!(lower.steps, 4, "{lower:?}");
    assert!(
        lower.dir.x > 0.99 && lower.start.x.abs() < 0.06,
        "{lower:?}"
    );
    assert!(found[1..].iter().all(Option::is_none));
}

/// Regression: fresh office-126's staircase with a mid landing (flights of 4 and 5 steps of
/// 0.158 m; the landing 0.63 m up, above the laser), seen from its side, showed its lower
/// flight alone: the upper flight's first riser joined the lower flight's part (with the
/// landing's side face), and read from the other parts' returns alone its first step had none
/// and the flight was dropped. With the lower flight's part's own returns beyond its top step,
/// every step of it is seen. (The parts' returns, from the bench's map.)
#[test]
fn an_upper_flights_first_riser_in_the_lower_flights_part_is_one_of_its_steps() {
    let (lower, upper) = two_flights_of(
        include_str!("../../tests/data/office126_upper_flight.txt"),
        739,
        4.8,
    );
    assert_eq!((lower.steps, upper.steps), (4, 5), "{lower:?} {upper:?}");
    assert!((upper.rise - 0.158).abs() < 0.01, "rise {}", upper.rise);
    // Its first riser 2.26 m along (17.90 m in the map), past the landing.
    assert!((upper.start.x - 2.26).abs() < 0.06, "start {}", upper.start);
}

/// Regression (office-311 of seeds 311-315, blind): the upper flight of a staircase with a mid
/// landing, 4 steps of 0.156 m, read as 5. The lower flight's rise, read 1 cm low (0.146 m),
/// lay between the rises of 4 steps (0.163 m, every level found) and of 5 (0.131 m, one level
/// empty), 0.5 % of the rise nearer the latter. A count that finds every level now comes before
/// a nearer rise that leaves one empty. (The flight's returns, from the bench's map.)
#[test]
fn a_hint_between_two_counts_does_not_pick_the_one_that_misses_a_level() {
    let text = include_str!("../../tests/data/office311_upper_flight.txt");
    let (_, p) = upper_flight_at(text, 619, 0.1464, 4);
    assert!((p.rise - 0.156).abs() < 0.01, "rise {}", p.rise);
}

/// The profile along +X of the upper flight's returns in `text` (`count` of them; the fourth
/// column 1 on a surface) at the lower flight's rise `hint`, with every one of its `steps`
/// levels found; and its returns.
fn upper_flight_at(
    text: &str,
    count: usize,
    hint: f64,
    steps: u32,
) -> (Vec<(DVec2, f64)>, Profile) {
    let (all, pts) = returns_and_surface(text);
    assert_eq!(all.len(), count);
    let c = StairsConfig::default();
    let p = profile_near(&pts, &all, DVec2::X, &c, Some(hint)).expect("a flight");
    assert_eq!(
        (p.steps, p.found),
        (steps, steps),
        "rise {} run {} found {}",
        p.rise,
        p.run,
        p.found
    );
    (all, p)
}

/// Regression: office-441 of seeds 441-445, a staircase with a mid landing (two flights of 4
/// steps of 0.170 m x 0.254 m, the landing 0.68 m up) seen from its side only through a
/// doorway, the landing's side face hidden by the door's frame. The lower flight's top step,
/// its side face's top edge seen 9 cm past it, was read as something standing at the top (3
/// steps, "landing" on the fourth step's side face under its top edge); the upper flight's side
/// face, a part of its own, was left out of the map. A person standing on the landing is a
/// part of its own, off the side face's plane, and no step of either. (The parts' returns, from
/// the bench's map.)
#[test]
fn a_staircase_seen_from_its_side_through_a_doorway_keeps_both_flights() {
    let (lower, upper) = two_flights_of(
        include_str!("../../tests/data/office441_side_flights.txt"),
        705,
        4.5,
    );
    assert_eq!((lower.steps, upper.steps), (4, 4), "{lower:?} {upper:?}");
    assert!((lower.rise - 0.170).abs() < 0.01, "rise {}", lower.rise);
    // The upper flight's first riser 2.37 m along, past the landing.
    assert_on_landing(&upper, 0.68, 2.37);
}

/// Regression: office-462 of seeds 461-465, a staircase with a mid landing (two flights of 4
/// steps of 0.184 m, the landing 0.74 m up) seen from its side only, from across a room where
/// a desk and a chair stand by its side face: one part. Along the part's own axis, 16 degrees
/// off the walls (the clutter's), it read as its upper flight alone; its side face alone shows
/// both flights climbing square to the walls, which win (see `search`). (The part's returns,
/// from the bench's map.)
#[test]
fn a_staircase_seen_from_its_side_past_clutter_climbs_square_to_the_walls() {
    let (returns, part_of) =
        returns_by_part(include_str!("../../tests/data/office462_side_clutter.txt"));
    assert_eq!(returns.len(), 2899);
    // The floor the map saw round it (the file's floor returns, x y).
    let mut points: Vec<Vec3> = returns
        .iter()
        .map(|(q, z)| Vec3::new(q.x as f32, q.y as f32, *z as f32))
        .collect();
    points.extend(
        include_str!("../../tests/data/office462_floor.txt")
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| {
                let v: Vec<f32> = l.split(' ').map(|x| x.parse().expect("a number")).collect();
                Vec3::new(v[0], v[1], 0.0)
            }),
    );
    let found = search_parts_in(&points, returns.len(), &part_of);
    let (lower, upper) = match found[0].as_deref() {
        Some([lower, upper]) => (lower.clone(), upper.clone()),
        other => panic!("not two flights: {other:?}"),
    };
    assert_eq!((lower.steps, upper.steps), (4, 4), "{lower:?} {upper:?}");
    for flight in [&lower, &upper] {
        assert!(flight.dir.x > 0.9999, "direction {}", flight.dir);
        assert!((flight.rise - 0.184).abs() < 0.01, "rise {}", flight.rise);
    }
    // The lower flight's first riser at 1.11 m (its foot seen across the room at grazing
    // incidence: within 8 cm), the upper flight's at 3.49 m on the landing.
    assert!((lower.start.x - 1.11).abs() < 0.08, "start {}", lower.start);
    assert_on_landing(&upper, 0.737, 3.49);
}

/// Regression (office-482 of seeds 481-485, blind): the upper flight of a staircase with a mid
/// landing, 4 steps of 0.176 m, read as 5 of 0.171 m. A person standing beside its top step in
/// one scan, seen up to 0.53 m over its top landing, lifted the flight's top height, and every
/// level of 5 steps up to it found a bin; the 4 steps up to the landing's plateau found every
/// level too and fitted far better, but the 5 lay nearer the lower flight's rise (0.172 m).
/// Within `SAME_RISE` of that rise, the better fit now wins. (The flight's returns, from the
/// bench's map.)
#[test]
fn a_person_over_the_top_step_does_not_add_a_step_nearer_the_hint() {
    let text = include_str!("../../tests/data/office482_upper_flight.txt");
    let (all, p) = upper_flight_at(text, 1044, 0.1718, 4);
    // (the person's returns are there: the top landing stands 0.70 m over the landing)
    assert!(all.iter().any(|p| p.1 > 1.2));
    assert!((p.rise - 0.176).abs() < 0.01, "rise {}", p.rise);
    assert!((p.run - 0.273).abs() < 0.02, "run {}", p.run);
}
