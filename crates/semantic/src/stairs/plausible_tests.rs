//! Tests of `finish`: the checks that make a profile a staircase, and the regressions they pin.

use super::*;
use crate::points::XyIndex;
use crate::stairs::tests::over_floor;
use glam::Vec3;

/// A profile along `dir` of `steps` steps of `rise` x `run` from 0, `found` of its levels seen.
fn flight(dir: DVec2, (rise, run, steps): (f64, f64, u32), found: u32) -> Profile {
    Profile {
        dir,
        rise,
        run,
        front1: 0.0,
        steps,
        found,
        score: f64::from(found),
        fit_score: 0.0,
    }
}

/// Regression: office-6's upper flight (4 steps on a mid landing) was refused: a desk
/// beside it, 0.9 m off, had parts at step heights, so the width across the points on the
/// steps spanned both (3.1 m), and the floor seen under the desk read as floor under the
/// flight. The run of those points without a 0.3 m gap holding most of them is the flight.
#[test]
fn the_flight_is_the_densest_run_across_it() {
    let flight = (0..120).map(|i| -6.0 + 0.011 * i as f64);
    let desk = (0..40).map(|i| -3.7 + 0.02 * i as f64);
    let t: Vec<f64> = flight.chain([-4.1]).chain(desk).collect();
    let run = densest_run(t);
    assert_eq!(run.len(), 120);
    assert!(run.iter().all(|&t| t < -4.6));
}

/// Regression: office-3's 8-step flight joined one blob with a desk and its chairs 0.4 m
/// beside it; its width, taken over all of the blob's points, spanned the desk, and the
/// floor seen under the desk read as floor under the flight, so it was no staircase.
#[test]
fn a_desk_beside_a_flight_does_not_widen_it() {
    let (rise, run) = (0.17, 0.27);
    // The flight: 4 steps climbing +X from x = 0, 1 m wide (y 0..1); treads and risers
    // every 2 cm.
    let mut blob: Vec<(DVec2, f64)> = Vec::new();
    for k in 0..4 {
        let (x0, top) = (k as f64 * run, (k + 1) as f64 * rise);
        for j in 0..50 {
            let y = 0.01 + 0.02 * j as f64;
            for i in 0..(rise / 0.02) as usize {
                blob.push((DVec2::new(x0, y), top - rise + 0.02 * i as f64));
            }
            for i in 0..(run / 0.02) as usize {
                blob.push((DVec2::new(x0 + 0.02 * i as f64, y), top));
            }
        }
    }
    // A desk beside it (y -1.2..-0.4, top 0.72 m) on four legs.
    for i in 0..54 {
        for j in 0..40 {
            blob.push((DVec2::new(0.02 * i as f64, -1.2 + 0.02 * j as f64), 0.72));
        }
    }
    for (x, y) in [(0.0, -1.2), (1.06, -1.2), (0.0, -0.42), (1.06, -0.42)] {
        for i in 0..35 {
            blob.push((DVec2::new(x, y), 0.02 * i as f64));
        }
    }
    // The cloud: the blob over a floor seen everywhere but under the flight.
    let points = over_floor(
        &blob,
        DVec2::new(-1.0, -2.0),
        (100, 100),
        DVec2::new(1.08, 1.0),
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(4.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
    let p = flight(DVec2::X, (rise, run, 4), 4);
    let stairs = finish(&blob, p, &sc, &StairsConfig::default()).expect("a staircase");
    assert!((stairs.width - 1.0).abs() < 0.05, "width {}", stairs.width);
}

/// A flight's side face at y = 0 climbing +X, seen alone (its treads above the laser):
/// `steps` steps of `rise` x `run` and a landing 1.1 m deep, sampled every 1 cm along and
/// 2 cm up; step `k`'s face sampled on `columns(k)` of its columns (all of them: `None`) up
/// to `z_top(k)`, with `extra` returns. Returns the face and the cloud: the face over a
/// floor seen everywhere but under the flight (y > 0).
fn side_face(
    (rise, run, steps): (f64, f64, u32),
    face: impl Fn(u32, f64) -> (Option<usize>, f64),
    extra: &[(DVec2, f64)],
) -> (Vec<(DVec2, f64)>, Vec<Vec3>) {
    let mut side: Vec<(DVec2, f64)> = extra.to_vec();
    for k in 0..steps {
        let (x0, top) = (f64::from(k) * run, f64::from(k + 1) * rise);
        let depth = if k + 1 == steps { run + 1.1 } else { run };
        let (columns, z_top) = face(k, top);
        for i in 0..columns.unwrap_or((depth / 0.01) as usize) {
            let mut z = 0.02;
            while z <= z_top + 1e-9 {
                side.push((DVec2::new(x0 + 0.01 * i as f64, 0.0), z));
                z += 0.02;
            }
        }
    }
    let length = f64::from(steps) * run + 1.1;
    let points = over_floor(
        &side,
        DVec2::new(-1.5, -2.0),
        (150, 100),
        DVec2::new(length, 1.3),
    );
    (side, points)
}

/// Regression: office-3's 8-step flight, seen only along its side face from its top end
/// (its treads above the laser): the two lowest steps' top edges were the farthest, lowest
/// strips at grazing angles, almost unseen, so its levels started at the third step; it
/// was no staircase. Six levels step by step from the third are a flight's.
#[test]
fn a_long_flight_seen_from_its_top_end_keeps_its_unseen_lowest_levels() {
    let (rise, run, steps) = (0.17, 0.26, 8u32);
    // The first step's face: only 2 returns on its top edge; the second's: not its top
    // 8 cm.
    let first = [0.1, 0.15].map(|x| (DVec2::new(x, 0.0), rise));
    let (side, points) = side_face(
        (rise, run, steps),
        |k, top| match k {
            0 => (Some(0), top),
            1 => (None, top - 0.08),
            _ => (None, top),
        },
        &first,
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
    let c = StairsConfig::default();
    let p = crate::stairs::profile::profile(&side, &side, DVec2::X, &c).expect("a profile");
    assert_eq!(p.steps, steps);
    let stairs = finish(&side, p, &sc, &c).expect("a staircase");
    assert_eq!(stairs.steps, steps);
    assert!((stairs.rise - rise).abs() < 0.01, "rise {}", stairs.rise);
    assert!((stairs.run - run).abs() < 0.02, "run {}", stairs.run);
}

/// Regression: on office-3's flight (above) the fit also missed one level, and the third
/// step's face held 3 returns; one thin step was allowed only where every level was seen.
/// With all but one level seen it is allowed too, wherever it stands (here the lowest step
/// checked: the first one's face is not, seen from the side); with two levels unseen, at the
/// end of the flight it is not.
#[test]
fn one_thin_step_is_allowed_with_all_levels_seen_but_one() {
    let (rise, run, steps) = (0.17, 0.26, 8u32);
    // The second step's face: 3 returns at its top.
    let thin = [0.1, 0.13, 0.16].map(|x| (DVec2::new(run + x, 0.0), 2.0 * rise));
    let (side, points) = side_face(
        (rise, run, steps),
        |k, top| (if k == 1 { Some(0) } else { None }, top),
        &thin,
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
    let c = StairsConfig::default();
    let profile = |found| flight(DVec2::X, (rise, run, steps), found);
    assert!(finish(&side, profile(steps - 1), &sc, &c).is_some());
    assert!(finish(&side, profile(steps - 2), &sc, &c).is_none());
}

/// Regression: office-3's 8-step flight, surveyed clear of its doors' swings, showed 7 of its
/// 8 steps' side faces: the third held no return (clutter in front of it), and 5 of the 8
/// levels were in the envelope. It was no staircase: a step could be thin, not unseen. A
/// flight does not skip a step: one unseen between two that are seen is still there; two
/// are not, nor one at the flight's end.
#[test]
fn one_unseen_step_between_two_seen_ones_is_still_a_step() {
    let (rise, run, steps) = (0.17, 0.26, 8u32);
    let c = StairsConfig::default();
    let finds = |unseen: &[u32]| {
        let (side, points) = side_face(
            (rise, run, steps),
            |k, top| (unseen.contains(&k).then_some(0), top),
            &[],
        );
        let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
        finish(&side, flight(DVec2::X, (rise, run, steps), 5), &sc, &c)
    };
    let stairs = finds(&[2]).expect("one step unseen between two seen ones");
    assert_eq!(stairs.steps, steps);
    assert!(stairs.rules.iter().any(|r| r.contains("step 3 short")));
    assert!(finds(&[2, 5]).is_none(), "two steps unseen");
    assert!(finds(&[1]).is_none(), "the lowest step checked unseen");
    assert!(finds(&[7]).is_none(), "the top step unseen");
}

/// Regression: on mixed-26 a crate's edge, a person's streak crossing over it diagonally and
/// returns beside it stood at three heights 0.2 m apart along one direction, within 0.6 m
/// across it: a 3-step flight seen from its side only, on no staircase. Its steps' returns
/// lay 0.17-0.18 m apart across the direction by turns; a side face is one plane.
#[test]
fn steps_on_no_one_plane_are_no_side_face() {
    let (rise, run, steps) = (0.2, 0.24, 3u32);
    let (side, points) = side_face((rise, run, steps), |_, top| (None, top), &[]);
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
    let c = StairsConfig::default();
    let profile = |dir| flight(dir, (rise, run, steps), steps);
    // The side face itself is a staircase; along a direction 3 degrees off the face (its
    // steps' returns drifting across it step by step) still.
    assert!(finish(&side, profile(DVec2::X), &sc, &c).is_some());
    let turned = DVec2::from_angle(3f64.to_radians());
    assert!(finish(&side, profile(turned), &sc, &c).is_some());
    // The other steps' returns 0.17 m across from the middle one's, the floor hidden beside
    // them as under the rest: no staircase.
    // (Their lowest returns, 2 cm up, would read as floor seen beside the middle step.)
    let bent: Vec<(DVec2, f64)> = side
        .iter()
        .filter(|(_, z)| *z > 0.05)
        .map(|&(q, z)| {
            let middle = (run..2.0 * run).contains(&q.x);
            (q + DVec2::Y * if middle { 0.0 } else { 0.17 }, z)
        })
        .collect();
    let points = over_floor(
        &bent,
        DVec2::new(-1.5, -2.0),
        (150, 100),
        DVec2::new(1.82, 1.3),
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
    assert!(finish(&bent, profile(DVec2::X), &sc, &c).is_none());
}

/// Regression: fresh office-41's upper flight (5 steps on a mid landing, seen from the floor
/// below as its side face) was refused: 5 % of its returns lay up to 0.4 m beyond the face
/// (mixed pixels, a registration's smear), the 1-99 % span put the face 0.13 m out, and the
/// width assumed from there reached over the floor seen in front of it. The face stands where
/// its returns pile up.
#[test]
fn stray_returns_beyond_a_side_face_do_not_move_it() {
    let (rise, run, steps) = (0.17, 0.26, 5u32);
    // Strays 0.15-0.4 m in front of the face (y < 0, over the floor seen), at the steps'
    // heights: one per 2 x 3.5 cm along each tread, 6 % of the returns.
    let strays: Vec<(DVec2, f64)> = (0..steps)
        .flat_map(|k| {
            (0..13).flat_map(move |i| {
                (0..8).map(move |j| {
                    (
                        DVec2::new(
                            f64::from(k) * run + 0.01 + 0.02 * f64::from(i),
                            -0.15 - 0.035 * f64::from(j),
                        ),
                        f64::from(k + 1) * rise - 0.01,
                    )
                })
            })
        })
        .collect();
    let (side, points) = side_face((rise, run, steps), |_, top| (None, top), &strays);
    assert!(
        strays.len() * 100 > 2 * side.len(),
        "{} of {}",
        strays.len(),
        side.len()
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
    let c = StairsConfig::default();
    let p = flight(DVec2::X, (rise, run, steps), steps);
    let stairs = finish(&side, p, &sc, &c).expect("a staircase");
    // Its width from the face (y = 0) away from the floor seen: centred 0.5 m in.
    assert!((stairs.start.y - 0.5).abs() < 0.03, "{:?}", stairs.start);
}

/// A flight of `steps` steps of `rise` x `run` climbing +X from x = 0, 1 m wide, its treads
/// and risers every 2 cm, over a floor seen everywhere but under it; `finish` on its profile.
fn finished(rise: f64, run: f64, steps: u32) -> Option<DetectedStairs> {
    let mut blob: Vec<(DVec2, f64)> = Vec::new();
    for k in 0..steps {
        let (x0, top) = (f64::from(k) * run, f64::from(k + 1) * rise);
        for j in 0..50 {
            let y = 0.01 + 0.02 * f64::from(j);
            for i in 0..(rise / 0.02) as usize {
                blob.push((DVec2::new(x0, y), top - rise + 0.02 * i as f64));
            }
            for i in 0..(run / 0.02) as usize {
                blob.push((DVec2::new(x0 + 0.02 * i as f64, y), top));
            }
        }
    }
    let length = f64::from(steps) * run;
    let points = over_floor(
        &blob,
        DVec2::new(-1.0, -2.0),
        (150, 100),
        DVec2::new(length, 1.0),
    );
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
    finish(
        &blob,
        flight(DVec2::X, (rise, run, steps), steps),
        &sc,
        &StairsConfig::default(),
    )
}

/// Regression (garage-100 of seeds 96-100): an 8-step flight of 0.159 m x 0.289 m seen from
/// its side only, its top edge sampled sparsely, read as 6 steps of 0.219 m x 0.423 m: each
/// in the codes' range, but together a pace (2 x rise + run) of 0.86 m, which no code allows
/// and no one climbs.
#[test]
fn a_rise_and_a_run_each_in_range_must_make_a_stair_together() {
    assert!(finished(0.219, 0.42, 6).is_none());
    let stairs = finished(0.159, 0.29, 8).expect("a staircase");
    assert_eq!(stairs.steps, 8);
    // The steepest and the shallowest the codes allow are stairs.
    assert!(finished(0.22, 0.24, 5).is_some());
    assert!(finished(0.12, 0.45, 5).is_some());
}

/// Regression (garage-255 of seeds 251-255): a ramp's side face (its 0.2 m slab's edge rising
/// 1:7.5 along +Y) read along the ramp's part's own axis, 22 degrees off the face, as 4 steps
/// of 0.123 x 0.447 m, 0.70 m wide across the face's oblique extent, with the floor beside it
/// seen and none under the ramp. A side face climbs along its own line.
#[test]
fn a_ramps_side_face_read_obliquely_is_no_staircase() {
    let mut face: Vec<(DVec2, f64)> = Vec::new();
    for i in 0..350 {
        let y = 0.01 * i as f64;
        let top = 0.133 * (y + 1.3);
        for j in 0..10 {
            let z = top - 0.02 * j as f64;
            if z > 0.04 {
                face.push((DVec2::new(0.0, y), z));
            }
        }
    }
    let mut points = over_floor(
        &face,
        DVec2::new(-2.0, -2.0),
        (125, 250),
        DVec2::new(3.0, 8.0),
    );
    points.retain(|p| p.x < 0.0 || p.y < -1.3 || p.z > 0.0);
    let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(9.0), 0.25);
    let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
    let dir = DVec2::from_angle(68f64.to_radians());
    let p = flight(dir, (0.123, 0.447, 4), 4);
    let c = StairsConfig::default();
    assert_eq!(finish(&face, p, &sc, &c), None);
    // Read along its own line, the face is a side face, and climbs on as a ramp's.
    let p = flight(DVec2::Y, (0.123, 0.447, 4), 4);
    assert_eq!(finish(&face, p, &sc, &c), None);
}
