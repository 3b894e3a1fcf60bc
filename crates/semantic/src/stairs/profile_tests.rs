//! Tests of `profile`: fits to synthetic flights and the regressions they pin.

use super::*;

/// A straight flight climbing +X from x = 0: `steps` steps of `rise` x `run`, a landing
/// 1.1 m deep, 1.2 m wide; points every 2 cm on treads and risers, 10 cm across.
fn flight(steps: u32, rise: f64, run: f64) -> Vec<(DVec2, f64)> {
    let mut pts = Vec::new();
    let across = |pts: &mut Vec<(DVec2, f64)>, x: f64, z: f64| {
        for k in 0..12 {
            pts.push((DVec2::new(x, -0.6 + 0.1 * k as f64), z));
        }
    };
    for k in 0..steps {
        let (x0, top) = (k as f64 * run, (k + 1) as f64 * rise);
        let depth = if k + 1 == steps { run + 1.1 } else { run };
        for i in 0..(rise / 0.02) as usize {
            across(&mut pts, x0, top - rise + 0.02 * i as f64);
        }
        for i in 0..(depth / 0.02) as usize {
            across(&mut pts, x0 + 0.02 * i as f64, top);
        }
    }
    pts
}

/// Regression: office-1's 10-step flight (rise 0.16 m) was not found at all: mixed pixels
/// along rays rising past its landing's edge stood 0.05-0.4 m above the landing, so the top
/// height read as 12 steps, whose fit left the upper levels empty and was refused.
#[test]
fn returns_above_the_landing_do_not_add_steps() {
    let c = StairsConfig::default();
    let mut pts = flight(10, 0.16, 0.27);
    // A veil over the landing: streaks of returns along rays rising past its edge, each
    // return 1 cm above and 2 cm along the one before (so they continue each other as a
    // surface's returns do), 0.2-0.26 m above it, between the heights an 11th and a 12th
    // step would have.
    for k in 0..6 {
        let x = 2.9 + 0.12 * k as f64;
        for i in 0..7 {
            let q = DVec2::new(x + 0.02 * i as f64, -0.2 + 0.05 * k as f64);
            pts.push((q, 1.8 + 0.01 * i as f64));
        }
    }
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, 10);
    assert!((p.rise - 0.16).abs() < 0.01, "rise {}", p.rise);
    assert!((p.run - 0.27).abs() < 0.02, "run {}", p.run);
    // The same flight without the veil, for reference.
    let bare = flight(10, 0.16, 0.27);
    let clean = profile(&bare, &bare, DVec2::X, &c).expect("a staircase");
    assert_eq!(clean.steps, 10);
}

/// Regression: hall-9's 11-step flight (rise 0.158 m), scanned from 23 poses, was not
/// found: sparse returns 0.2-0.45 m over its top landing (mixed pixels between the
/// landing's edge and the wall behind it; on no surface, so they set neither the levels
/// nor the top) each counted as a violation of every fit, and outweighed the steps' support.
#[test]
fn returns_high_over_the_landing_do_not_refuse_the_flight() {
    let c = StairsConfig::default();
    let pts = flight(11, 0.158, 0.28);
    let mut all = pts.clone();
    // 30 bins along the landing (x 3.1-3.7), each with a return 0.2-0.45 m over it.
    for k in 0..30 {
        let q = DVec2::new(3.1 + 0.02 * k as f64, 0.1);
        all.push((q, 11.0 * 0.158 + 0.2 + 0.25 * ((k * 7) % 10) as f64 / 10.0));
    }
    let p = profile(&pts, &all, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, 11);
    assert!((p.rise - 0.158).abs() < 0.01, "rise {}", p.rise);
}

/// A flight's profile as a side face's sparsely sampled top edge shows it: `steps` steps of
/// `rise` x `run` climbing +X from x = 0 (the last with a 1.1 m landing), every 2 cm along and
/// 10 cm across, each step's first 8 cm at the level of a `grid` between its foot and its tread.
fn levels_between(steps: u32, rise: f64, run: f64, grid: f64) -> Vec<(DVec2, f64)> {
    let mut pts = Vec::new();
    for k in 0..steps {
        let (x0, top) = (f64::from(k) * run, f64::from(k + 1) * rise);
        // The grid's level between this step's foot and its tread, over its first 8 cm.
        let between = ((top - rise) / grid).floor() * grid + grid;
        let depth = if k + 1 == steps { run + 1.1 } else { run };
        let mut x = x0;
        while x < x0 + depth {
            let z = if x < x0 + 0.08 && between < top - 0.02 {
                between
            } else {
                top
            };
            for j in 0..12 {
                pts.push((DVec2::new(x, -0.6 + 0.1 * j as f64), z));
            }
            x += 0.02;
        }
    }
    pts
}

/// Regression: hall-4's upper flight (4 steps of 0.17 m, seen on its side face from the
/// floor) was not found: the side face's top edge, sampled sparsely, stood at heights
/// between the treads' in the first centimetres of each step, and the grid of levels locked
/// onto two thirds of the rise (its levels hold every true one but the odd ones), so the
/// counts fitted were 5 to 7, all refused.
#[test]
fn levels_between_the_treads_do_not_hide_the_rise() {
    let c = StairsConfig::default();
    let (rise, run) = (0.17, 0.27);
    let pts = levels_between(4, rise, run, rise * 2.0 / 3.0);
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, 4);
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
}

/// Regression: the upper flights of hall-3's and hall-8's mid-landing staircases (4 steps of
/// 0.16 m, 3 of 0.18 m), seen from the floor below on their risers and side faces only, fitted
/// one step more better; the lower flight's rise decides (a staircase's risers are uniform).
#[test]
fn the_rise_of_the_flight_below_decides_between_counts_that_fit_alike() {
    let c = StairsConfig::default();
    // A side face's stepped top edge, 3 steps of 0.18 x 0.26 m and a 1.1 m landing, sampled
    // every 2 cm along; over the first `lead` of each step the edge shows at the level a
    // 4-step flight to the same top would have there (a riser's foot, clutter).
    let (rise, run): (f64, f64) = (0.18, 0.26);
    let four = 3.0 * rise / 4.0;
    let lead = 0.08;
    let mut pts = Vec::new();
    let mut x: f64 = 0.0;
    while x < 3.0 * run + 1.1 {
        let k = (x / run).floor().min(2.0);
        let top = (k + 1.0) * rise;
        let between = ((k * rise) / four).floor() * four + four;
        let z = if x - k * run < lead && between < top - 0.02 {
            between
        } else {
            top
        };
        for j in 0..10 {
            pts.push((DVec2::new(x, 0.1 * j as f64), z));
        }
        x += 0.02;
    }
    let p = profile_near(&pts, &pts, DVec2::X, &c, Some(0.175)).expect("a flight");
    assert_eq!(p.steps, 3);
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
    // A hint no count fits within 15 % of leaves the choice to the fits' scores.
    let far = profile_near(&pts, &pts, DVec2::X, &c, Some(0.30)).map(|p| p.steps);
    assert_eq!(far, profile(&pts, &pts, DVec2::X, &c).map(|p| p.steps));
}

/// Regression: office-1's 10-step flight (0.16 m x 0.267 m), seen by nine scans from a laser
/// 0.5 m up, was fitted 15 cm early with a 0.252 m run and refused (its top steps held no
/// points of the model): its side face's stepped edge, smeared a few centimetres before each
/// front edge by the range noise at grazing incidence, stood above the true model (violations),
/// and an earlier, shorter model lost only support, which counts a few bins per level. The
/// risers seen at the true edges now hold the fit there.
#[test]
fn a_side_face_smeared_before_each_edge_does_not_shorten_the_run() {
    let c = StairsConfig::default();
    let (steps, rise, run) = (10u32, 0.16, 0.267);
    let mut pts = Vec::new();
    for k in 0..steps {
        let (x0, top) = (k as f64 * run, (k + 1) as f64 * rise);
        // The riser across the width (every 2 cm up, 10 cm across).
        for i in 0..8 {
            for j in 0..12 {
                pts.push((
                    DVec2::new(x0, -0.6 + 0.1 * j as f64),
                    top - rise + 0.02 * i as f64,
                ));
            }
        }
        // Treads under the laser (0.5 m) only; the top one is the landing.
        let depth = if k + 1 == steps { run + 1.1 } else { run };
        if top < 0.5 || k + 1 == steps {
            let mut x = x0;
            while x < x0 + depth {
                for j in 0..12 {
                    pts.push((DVec2::new(x, -0.6 + 0.1 * j as f64), top));
                }
                x += 0.02;
            }
        }
        // The side face (y = -0.6) up to the step's top, every 2 cm, its upper 8 cm smeared
        // up to 4 cm before the step's front edge.
        let mut x = x0;
        while x < x0 + run {
            let mut z = 0.01;
            while z <= top {
                let smear = if top - z < 0.08 && x < x0 + 0.03 {
                    0.04
                } else {
                    0.0
                };
                pts.push((DVec2::new(x - smear, -0.6), z));
                z += 0.02;
            }
            x += 0.02;
        }
    }
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, steps);
    assert!((p.run - run).abs() < 0.005, "run {}", p.run);
    // (the smear still pulls the edges early, within the band a riser is counted in)
    assert!(p.front1.abs() < 0.035, "first edge at {}", p.front1);
}

/// Regression: office-6's 6-step flight (rise 0.18 m) read as 3 steps on a "landing": a person
/// walking past its foot left returns 0.5 m up just in front of the first riser, the running
/// maximum started at that height and hid the first two levels. The profile starts at the
/// flight's foot, its first bin at most a rise high.
#[test]
fn something_high_in_front_of_the_foot_does_not_hide_the_lower_steps() {
    let c = StairsConfig::default();
    let mut pts = flight(6, 0.18, 0.28);
    // A person's streak 2-6 cm in front of the first riser, 0.48-0.52 m up.
    for k in 0..12 {
        let q = DVec2::new(-0.06 + 0.004 * k as f64, -0.5 + 0.02 * k as f64);
        pts.push((q, 0.48 + 0.004 * (k % 10) as f64));
    }
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, 6);
    assert!((p.rise - 0.18).abs() < 0.01, "rise {}", p.rise);
    assert!(p.front1.abs() < 0.03, "first front edge at {}", p.front1);
}

/// Regression: held-out hall-14's straight 10-step flight (rise 0.159 m) read as 9 steps: its
/// grid of levels locked onto 0.109 m, 3 % over two thirds of the rise, so the top stood 14.4
/// grid levels up; rounded to 14 and then taken two thirds of, that gave 9. Two thirds of the
/// unrounded 14.4 is 10. (Here the levels between the treads stand on a grid 5 % over two
/// thirds of the rise; the grid fitted to them puts the top 14.4 of its levels up.)
#[test]
fn a_grid_a_little_off_two_thirds_of_the_rise_still_counts_every_step() {
    let c = StairsConfig::default();
    let (rise, run, steps) = (0.159, 0.28, 10);
    let pts = levels_between(steps, rise, run, rise * 2.0 / 3.0 * 1.05);
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, steps);
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
}

/// Regression (hall-17, fresh seed 17): the upper flight of a staircase with a mid landing, 4
/// steps seen from the floor below, read as 5: a person walking past beside it, over its top
/// step, stood 0.2-0.3 m above its top landing, and the count from the top height climbed to
/// the person. Its points end with its top landing, whose height is counted to as well.
#[test]
fn a_person_beside_an_upper_flight_does_not_add_a_step() {
    let c = StairsConfig::default();
    let (rise, run) = (0.179, 0.256);
    let mut pts = flight(4, rise, run);
    // The person: 0.5 m along, from the middle of the top step on, 0.2 m above the landing
    // (over a rise: the count from the top height is one more, the grid of levels no higher).
    for i in 0..25 {
        for j in 0..4 {
            let q = DVec2::new(3.5 * run + 0.02 * i as f64, 0.7 + 0.05 * j as f64);
            pts.push((q, 4.0 * rise + 0.2 + 0.01 * ((i + j) % 3) as f64));
        }
    }
    let p = profile_near(&pts, &pts, DVec2::X, &c, Some(0.177)).expect("a flight");
    assert_eq!(
        p.steps, 4,
        "rise {} run {} found {}",
        p.rise, p.run, p.found
    );
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
}

/// Regression (office-17, held-out seed 17): the 3-step upper flight of a staircase with a mid
/// landing, seen from the floor below, was not found. The rays grazing its second step's nosing
/// left mixed pixels over that tread, rising towards the next riser (0.05-0.09 m over the
/// tread), so the profile's running maximum climbed through them and showed no level at the
/// second step: no grid of levels, no staircase. The rise of the flight below stands in.
#[test]
fn mixed_pixels_over_an_upper_flights_tread_do_not_hide_it() {
    let c = StairsConfig::default();
    let (rise, run) = (0.185, 0.30);
    let mut pts = flight(3, rise, run);
    // The veil: from the second step's nosing (x = run) to 4 cm short of the next riser, from
    // 5 cm over the tread up, 2 cm apart along and 0.6 cm up (one surface, as far as
    // continuation goes), 10 cm across.
    for i in 0..13 {
        for k in 0..12 {
            let q = DVec2::new(run + 0.02 * i as f64, -0.6 + 0.1 * k as f64);
            pts.push((q, 2.0 * rise + 0.05 + 0.006 * i as f64));
        }
    }
    // On its own, the profile shows no staircase with the flight's count.
    let alone = profile(&pts, &pts, DVec2::X, &c);
    assert!(
        alone.as_ref().is_none_or(|p| p.steps != 3),
        "found without the hint: {:?}",
        alone.map(|p| (p.steps, p.rise))
    );
    // With the rise of the flight below, it is the flight.
    let p = profile_near(&pts, &pts, DVec2::X, &c, Some(0.18)).expect("a flight");
    assert_eq!(
        p.steps, 3,
        "rise {} run {} found {}",
        p.rise, p.run, p.found
    );
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
    // (the veil, over the tread by more than the fit's tolerance, still pulls the third
    // step's edge in front of it: the run comes out short, as office-17's did, 0.23 m for
    // 0.30 m; the count is what the flight is judged by)
    assert!(p.run >= c.run_m[0] && p.run < run, "run {}", p.run);
}

/// Regression: hall-82's 8-step flight (seeds 81-85; rise 0.188 m), seen from the floor in
/// front of it: its risers dense, its treads by a few returns each, its top riser (the
/// landing's front edge) hardly at all. The grid of levels found 8 levels at 0.186 m and the
/// fit of 8 steps found all 8; a fit of 7 steps (0.217 m) scored more, its riser bands holding
/// the 7 risers seen, while missing one of its 7 levels, and won. Another count replaces the
/// best so far only where it misses no more of its levels.
#[test]
fn a_count_that_misses_a_level_does_not_replace_one_that_finds_every_level() {
    let c = StairsConfig::default();
    let (steps, rise, run) = (8u32, 0.188, 0.319);
    let mut pts = Vec::new();
    for k in 0..steps {
        let (x0, top) = (f64::from(k) * run, f64::from(k + 1) * rise);
        if k + 1 < steps {
            // The riser, dense (the top one, the landing's edge, unseen).
            for i in 0..(rise / 0.02) as usize {
                for j in 0..12 {
                    pts.push((
                        DVec2::new(x0, -0.6 + 0.1 * j as f64),
                        top - rise + 0.02 * i as f64,
                    ));
                }
            }
        }
        // The tread by a return every 10 cm along its middle.
        for i in 0..3 {
            pts.push((DVec2::new(x0 + 0.06 + 0.1 * i as f64, 0.0), top));
        }
        // Mixed pixels over its last 12 cm, up to two thirds of a rise towards the next
        // tread (rays grazing the nosing above).
        if k + 1 < steps {
            for i in 0..6 {
                let x = x0 + run - 0.12 + 0.02 * i as f64;
                pts.push((DVec2::new(x, 0.0), top + rise * (0.15 + 0.1 * i as f64)));
            }
        }
    }
    // The landing, dense.
    let x_top = f64::from(steps) * run;
    for i in 0..50 {
        for j in 0..12 {
            pts.push((
                DVec2::new(x_top + 0.02 * i as f64, -0.6 + 0.1 * j as f64),
                f64::from(steps) * rise,
            ));
        }
    }
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!(p.steps, steps, "rise {}", p.rise);
}

/// Regression (office-165 of seeds 161-165): a 3-step flight (0.178 m x 0.282 m) whose top
/// riser had returns 0.07-0.15 m over its landing along 0.2 m (mixed pixels over the nosing and
/// the landing's front) read as 4 steps of 0.164 m climbing to them, one level missing. The
/// profile ends in the landing, 1.1 m long, with nothing over it beyond a tread's depth: its
/// height is counted to as well, fitted to the envelope under it, and finds every level.
#[test]
fn returns_over_the_top_riser_do_not_add_a_step() {
    let c = StairsConfig::default();
    let (rise, run) = (0.178, 0.282);
    let mut pts = flight(3, rise, run);
    for i in 0..10 {
        for k in 0..12 {
            let q = DVec2::new(
                2.0 * run - 0.06 + 0.02 * f64::from(i),
                -0.6 + 0.1 * f64::from(k),
            );
            let over = 0.15 * (0.5 + 0.05 * f64::from((i + k) % 10));
            pts.push((q, 3.0 * rise + over));
        }
    }
    let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
    assert_eq!((p.steps, p.found), (3, 3), "rise {} run {}", p.rise, p.run);
    assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
    assert!((p.run - run).abs() < 0.01, "run {}", p.run);
}
