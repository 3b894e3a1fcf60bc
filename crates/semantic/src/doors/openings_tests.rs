//! Tests of door openings' runs and faces (`openings`).

use super::*;

/// Bins with these door-level face returns, blocked where a bin would be (three or more).
fn bins(face: &[u16]) -> Vec<Bin> {
    face.iter()
        .map(|&k| Bin {
            blocked: k >= 3,
            door_face: k,
            ..Bin::default()
        })
        .collect()
}

/// Regression: mixed-100 of seeds 96-100: a person crossing a 0.99 m doorway in the face
/// plane left 2-10 door-level returns per bin over 0.3 m of it, in a wall of 20-59 per bin;
/// the doorway is one run. A pier as dense as the wall between two doorways parts them.
#[test]
fn a_sparse_streak_across_a_doorway_is_no_pier_between_two() {
    let c = OpeningConfig::default();
    let row = |sliver: &[u16]| {
        let mut face = vec![30u16, 45, 25, 50, 40, 35, 55, 20];
        face.extend([0, 1, 0, 0, 2, 0, 0]);
        face.extend(sliver);
        face.extend([0, 0, 1, 0, 0, 0]);
        face.extend([40, 30, 50, 35, 25, 45, 30, 20]);
        face
    };
    let streak = row(&[5, 7, 4, 10, 5, 2]);
    assert_eq!(open_runs(&bins(&streak), &streak, &c), vec![(8, 27)]);
    let pier = row(&[30, 45, 25, 40, 35, 50]);
    assert_eq!(open_runs(&bins(&pier), &pier, &c), vec![(8, 15), (21, 27)]);
}

/// A glass pane (office-54 of the bench's seeds 51-55: 1-6 returns per bin, a few bins
/// blocking) is its wall's face going on; a doorway with a leaf ajar crossing the face
/// plane over three bins (20-40 returns) in a wall of 50 per bin is no face.
#[test]
fn a_glass_pane_is_the_face_going_on_a_doorway_with_a_leaf_is_not() {
    let c = OpeningConfig::default();
    let mut glass = vec![5u16, 4, 6, 5, 3, 5];
    glass.extend([1, 0, 2, 1, 2, 1, 0, 1, 2, 1, 0, 1]);
    glass.extend([4, 5, 6, 3, 5, 5]);
    assert!(face_goes_on(&bins(&glass), 6, 18, &c));
    let mut doorway = vec![50u16; 20];
    doorway.extend([0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 20, 40, 30, 0, 0]);
    doorway.extend([50; 20]);
    assert!(!face_goes_on(&bins(&doorway), 20, 36, &c));
    // A doorway (0.35 m with no face return, a leaf's edge) beside a stretch of wall seen
    // sparsely, in one run (the 3DTK corridor's, as `semsim run` maps it).
    let mut beside = vec![8u16, 5, 4, 15, 10, 5, 5, 17, 4, 3];
    beside.extend([
        2, 3, 2, 4, 3, 7, 4, 2, 4, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 11, 16, 4, 0, 1,
    ]);
    beside.extend([6, 7, 7, 12, 8, 7, 4, 5, 5, 10]);
    assert!(!face_goes_on(&bins(&beside), 10, 34, &c));
    // A run with nothing in most bins is a gap, however sparse the wall around it.
    let mut gap = vec![4u16; 10];
    gap.extend([0, 0, 1, 0, 0, 2, 0, 0]);
    gap.extend([4; 10]);
    assert!(!face_goes_on(&bins(&gap), 10, 18, &c));
}
