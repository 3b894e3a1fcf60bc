//! Two faces of one small thing: a chair whose seat the laser saw only along its front and back
//! edges (and the legs under them), a crate seen on two opposite sides from two stops while its
//! top was out of sight. No cell between the faces holds a return, so they are two thin
//! clusters side by side along one direction, a thing's depth apart, standing on the floor to
//! the same height, each too thin to be the thing; their union's box is the thing.

use super::classify::set_box_rule;
use super::merge::absorb;
use super::{DetectedObstacle, ObstacleConfig};
use glam::DVec2;

/// A face is at most this thick (a seat's edge and the leg under it, blurred by the smear of a
/// registration; a thing seen whole is thicker).
const FACE_MAX_ACROSS_M: f64 = 0.3;
/// Two faces of one thing span at most this across, outer side to outer side (a chair's seat,
/// 0.45 m, its two edges' thickness and the smear; two cabinets' fronts across an aisle span
/// more).
const FACES_MAX_DEPTH_M: f64 = 0.75;
/// A backrest rises at most this over its seat (0.3-0.5 m; an office chair's up to 0.6 m).
const BACKREST_MAX_RISE_M: f64 = 0.6;
/// A seat's top is at least this high over the floor (chairs 0.4-0.5 m, stools up to 0.8 m;
/// lower is a crate or a footrest).
const MIN_SEAT_HEIGHT_M: f64 = 0.3;
/// A backrest is at most this long: a chair's width (office chairs 0.45-0.7 m) and what its
/// cluster takes in beside it (seen up to 0.82 m on the styles bench). A board longer than
/// this with a seat before it is a partition or a screen with a chair at it
/// (office-201 of seeds 201-205: a partial-height partition 1.49 m long and a chair's seat
/// 0.29 m long beside it were boxed as one chair, and the partition was lost).
const BACKREST_MAX_LENGTH_M: f64 = 1.0;
/// A backrest standing free of a desk is at most this thick (a board or a mesh 2-8 cm thick,
/// blurred by the range noise and a registration's smear).
const BACKREST_MAX_ACROSS_M: f64 = 0.15;

/// The clusters, pairs of faces of one thing (see the module docs) joined into one box: their
/// footprints (hulls, not boxes: the box of a blob 0.2 m thick may lie at any angle) overlapping
/// along the longer one's direction by at least half of the shorter extent, spanning at most
/// `FACES_MAX_DEPTH_M` across it, bottoms and tops within `max_top_step_m`. A joined pair is
/// thicker than a face and joins nothing more.
pub(super) fn join_faces(
    mut found: Vec<DetectedObstacle>,
    c: &ObstacleConfig,
) -> Vec<DetectedObstacle> {
    loop {
        // (the faces only: a building holds hundreds of clusters)
        let faces: Vec<usize> = (0..found.len()).filter(|&i| is_face(&found[i])).collect();
        let pair = faces
            .iter()
            .enumerate()
            .flat_map(|(n, &i)| faces[n + 1..].iter().map(move |&j| (i, j)))
            .find_map(|(i, j)| {
                if faces_of_one_thing(&found[i], &found[j], c.max_top_step_m) {
                    Some((i, j, false))
                } else {
                    corner_of_one_thing(&found[i], &found[j], c).then_some((i, j, true))
                }
            });
        let Some((i, j, corner)) = pair else {
            return found;
        };
        // (j > i: removing j leaves i in place)
        let other = found.swap_remove(j);
        // (along the longer face)
        let dir = if found[i].size[0] >= other.size[0] {
            found[i].dir
        } else {
            other.dir
        };
        let why = format!(
            "box: around two faces of one thing {:.2} and {:.2} m long {}",
            found[i].size[0].max(other.size[0]),
            found[i].size[0].min(other.size[0]),
            if corner {
                "meeting at a corner, its top unseen"
            } else {
                "side by side, the cells between them unseen"
            }
        );
        absorb(&mut found[i], &other, dir);
        set_box_rule(&mut found[i], why);
    }
}

fn is_face(o: &DetectedObstacle) -> bool {
    !o.overhead && o.size[1] <= FACE_MAX_ACROSS_M
}

fn faces_of_one_thing(a: &DetectedObstacle, b: &DetectedObstacle, max_step_m: f64) -> bool {
    let (a, b) = if a.size[0] >= b.size[0] {
        (a, b)
    } else {
        (b, a)
    };
    let extent = |o: &DetectedObstacle, d: DVec2| {
        o.hull.iter().fold((f64::MAX, f64::MIN), |(lo, hi), q| {
            (lo.min(q.dot(d)), hi.max(q.dot(d)))
        })
    };
    let (d, n) = (a.dir, a.dir.perp());
    let ((a0, a1), (b0, b1)) = (extent(a, d), extent(b, d));
    let overlap = a1.min(b1) - a0.max(b0);
    let ((c0, c1), (e0, e1)) = (extent(a, n), extent(b, n));
    let depth = c1.max(e1) - c0.min(e0);
    overlap >= 0.5 * (a1 - a0).min(b1 - b0)
        && depth <= FACES_MAX_DEPTH_M
        && (a.z_range.0 - b.z_range.0).abs() <= max_step_m
        && ((a.z_range.1 - b.z_range.1).abs() <= max_step_m || backrest_and_seat(a, b, max_step_m))
}

/// Two faces of a thing seen from its corner meet within this of each one's end (m): the cell
/// at the corner, seen by grazing rays from both sides, may hold no return, and the two are
/// parted there ([`super::necks`]: the corner reads as a neck across the diagonal).
const CORNER_REACH_M: f64 = 0.25;
/// Two faces meeting at a corner stand square to each other within this (the cosine of the
/// angle between them: 15 degrees off square).
const CORNER_MAX_COS: f64 = 0.26;
/// A face meeting another at a corner is a plane seen edge-on from above: at most this thick
/// (a board's: the range noise and a registration's smear). A thicker cluster under a desk
/// (its legs and what the mixed pixels join to them) is no face (office-443 of seeds 441-445:
/// 0.23 m thick, it took a backrest at the desk's edge into a box over the desk).
const CORNER_FACE_MAX_ACROSS_M: f64 = BACKREST_MAX_ACROSS_M;
/// ... and at least this long (a thing's side; a leg's cells or a speck are shorter).
const CORNER_FACE_MIN_LENGTH_M: f64 = 0.2;

/// Whether `a` and `b` are two faces of one thing seen from its corner, its top out of sight
/// (hall-445 of seeds 441-445: a crate 0.59 x 0.69 m, 0.67 m tall, seen as its south face and
/// its west face, two boxes 0.09 and 0.05 m thick, neither the crate): each a face (at most
/// [`CORNER_FACE_MAX_ACROSS_M`] thick, at least [`CORNER_FACE_MIN_LENGTH_M`] long), square to each other,
/// their lines crossing within [`CORNER_REACH_M`] of an end of each, bottoms and tops within
/// `max_top_step_m`, and neither a partition's face (at least `partition_min_length_m` long
/// and `partition_min_height_m` tall: two partitions meet at corners too, and each is a wall).
fn corner_of_one_thing(a: &DetectedObstacle, b: &DetectedObstacle, c: &ObstacleConfig) -> bool {
    let may_be_partition = |o: &DetectedObstacle| {
        o.size[0] >= c.partition_min_length_m
            && o.z_range.1 - o.z_range.0 >= c.partition_min_height_m
    };
    let face = |o: &DetectedObstacle| {
        o.size[1] <= CORNER_FACE_MAX_ACROSS_M && o.size[0] >= CORNER_FACE_MIN_LENGTH_M
    };
    if !face(a)
        || !face(b)
        || a.dir.dot(b.dir).abs() > CORNER_MAX_COS
        || (a.z_range.0 - b.z_range.0).abs() > c.max_top_step_m
        || (a.z_range.1 - b.z_range.1).abs() > c.max_top_step_m
        || may_be_partition(a)
        || may_be_partition(b)
    {
        return false;
    }
    // Where their centre lines cross: `a.center + t * a.dir`, `b.center + u * b.dir`.
    let denom = a.dir.perp_dot(b.dir);
    let t = (b.center - a.center).perp_dot(b.dir) / denom;
    let u = (b.center - a.center).perp_dot(a.dir) / denom;
    let near_an_end =
        |o: &DetectedObstacle, s: f64| (s.abs() - o.size[0] / 2.0).abs() <= CORNER_REACH_M;
    near_an_end(a, t) && near_an_end(b, u)
}

/// Whether one of `a` and `b` is a backrest and the other, lower, a seat in front of it: the
/// seat's top at a seat's height over the floor, the backrest no longer than
/// [`BACKREST_MAX_LENGTH_M`] and rising over it by a step to [`BACKREST_MAX_RISE_M`]. The
/// backrest was cut off a desk's edge ([`super::tops`]), or, standing free, is a board at most
/// [`BACKREST_MAX_ACROSS_M`] thick (a desk's or cabinet's edge seen beside a seat is a thing's
/// side, thicker).
fn backrest_and_seat(a: &DetectedObstacle, b: &DetectedObstacle, max_step_m: f64) -> bool {
    let (back, seat) = if a.z_range.1 >= b.z_range.1 {
        (a, b)
    } else {
        (b, a)
    };
    let cut_off = back.beside_top && !seat.beside_top;
    let board = !back.beside_top && !seat.beside_top && back.size[1] <= BACKREST_MAX_ACROSS_M;
    let rise = back.z_range.1 - seat.z_range.1;
    let seat_height = seat.z_range.1 - seat.z_range.0;
    (cut_off || board)
        && back.size[0] <= BACKREST_MAX_LENGTH_M
        && rise > max_step_m
        && rise <= BACKREST_MAX_RISE_M
        && seat_height >= MIN_SEAT_HEIGHT_M
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::test_cluster as cluster;

    /// Regression (office-35 of seeds 31-35): a chair seen as its seat's front and back edges,
    /// 0.75 x 0.28 and 0.62 x 0.23 m, 0.41 m apart, the second's box turned by 24 degrees, was
    /// two boxes neither of which is the chair.
    #[test]
    fn a_seat_seen_along_its_two_edges_is_one_thing() {
        let front = cluster([9.95, -3.58], DVec2::X, [0.75, 0.28], (0.0, 0.52), false);
        let mut back = cluster([9.94, -3.99], DVec2::X, [0.62, 0.23], (0.0, 0.47), false);
        let out = join_faces(
            vec![front.clone(), back.clone()],
            &ObstacleConfig::default(),
        );
        assert_eq!(out.len(), 1, "{out:#?}");
        assert!((out[0].size[1] - 0.665).abs() < 1e-6, "{:?}", out[0].size);
        assert!((out[0].z_range.1 - 0.52).abs() < 1e-9);
        // The same cells, their box turned.
        back.dir = DVec2::from_angle(24f64.to_radians());
        let out = join_faces(vec![front, back], &ObstacleConfig::default());
        assert_eq!(out.len(), 1, "{out:#?}");
    }

    #[test]
    fn a_backrest_cut_off_a_desk_and_the_seat_before_it_are_one_chair() {
        // The backrest (to 0.83 m) cut off the desk's edge, the seat's far edge (0.42 m) 0.3 m
        // in front of it.
        let mut back = cluster([0.0, 0.0], DVec2::X, [0.45, 0.1], (0.0, 0.83), false);
        let seat = cluster([0.02, 0.3], DVec2::X, [0.5, 0.15], (0.0, 0.42), false);
        let c = ObstacleConfig::default();
        // Not cut off a top and thicker than a backrest: a desk's side and a seat, two things.
        let mut side = back.clone();
        side.size[1] = 0.2;
        assert_eq!(join_faces(vec![side, seat.clone()], &c).len(), 2);
        back.beside_top = true;
        let out = join_faces(vec![back.clone(), seat.clone()], &c);
        assert_eq!(out.len(), 1, "{out:#?}");
        assert!((out[0].z_range.1 - 0.83).abs() < 1e-9);
        assert!(out[0].size[1] > 0.4, "{:?}", out[0].size);
        // A crate's lid (0.25 m) is no seat; a cabinet (1.9 m) is no backrest.
        let lid = cluster([0.02, 0.3], DVec2::X, [0.5, 0.15], (0.0, 0.25), false);
        assert_eq!(join_faces(vec![back.clone(), lid], &c).len(), 2);
        let mut tall = back;
        tall.z_range.1 = 1.9;
        assert_eq!(join_faces(vec![tall, seat], &c).len(), 2);
    }

    /// Regression (office-141 of seeds 141-145, and others): a chair whose backrest, standing
    /// free of any desk, was seen as a board 0.09 m thick to 0.86 m, and its seat as a strip
    /// 0.19 m wide to 0.48 m in front of it, was two boxes, each half outside the chair.
    #[test]
    fn a_free_standing_backrest_and_the_seat_before_it_are_one_chair() {
        let back = cluster([0.0, 0.0], DVec2::X, [0.56, 0.09], (0.0, 0.86), false);
        let seat = cluster([0.0, 0.25], DVec2::X, [0.55, 0.19], (0.0, 0.48), false);
        let c = ObstacleConfig::default();
        let out = join_faces(vec![back.clone(), seat.clone()], &c);
        assert_eq!(out.len(), 1, "{out:#?}");
        assert!((out[0].z_range.1 - 0.86).abs() < 1e-9);
        // A cabinet's side (1.9 m) is no backrest, a crate's lid (0.25 m) no seat.
        let mut tall = back.clone();
        tall.z_range.1 = 1.9;
        assert_eq!(join_faces(vec![tall, seat], &c).len(), 2);
        let lid = cluster([0.0, 0.25], DVec2::X, [0.55, 0.19], (0.0, 0.25), false);
        assert_eq!(join_faces(vec![back, lid], &c).len(), 2);
    }

    /// Regression (office-201 of seeds 201-205): a partial-height partition 1.49 m long, 1.21 m
    /// tall, and the seat of a chair at it, 0.29 m long, were joined as a backrest and its seat,
    /// and the partition was lost in the chair's box.
    #[test]
    fn a_partition_and_a_seat_beside_it_are_no_chair() {
        let partition = cluster([0.0, 0.0], DVec2::X, [1.49, 0.08], (0.0, 1.21), false);
        let seat = cluster([0.3, 0.12], DVec2::X, [0.29, 0.12], (0.0, 0.7), false);
        let c = ObstacleConfig::default();
        assert_eq!(
            join_faces(vec![partition.clone(), seat.clone()], &c).len(),
            2
        );
        // (a backrest as long as a chair is wide, with the same seat, is one chair)
        let back = cluster([0.3, 0.0], DVec2::X, [0.5, 0.08], (0.0, 1.21), false);
        assert_eq!(join_faces(vec![back, seat], &c).len(), 1);
    }

    /// Regression (hall-445 of seeds 441-445): a crate 0.59 x 0.69 m, 0.67 m tall, seen as
    /// its south and west faces meeting at its corner (the corner cell unseen), was two thin
    /// boxes, neither the crate. Faces crossing in their middles, meeting off square, of other
    /// heights, or one a partition's, stay apart.
    #[test]
    fn two_faces_meeting_at_a_corner_are_one_thing() {
        let south = || cluster([14.90, 16.075], DVec2::X, [0.58, 0.09], (0.0, 0.66), false);
        let west = |x: f64, y: f64, top: f64, length: f64, dir: DVec2| {
            cluster([x, y], dir, [length, 0.05], (0.0, top), false)
        };
        let c = ObstacleConfig::default();
        let out = join_faces(vec![south(), west(14.575, 16.44, 0.66, 0.66, DVec2::Y)], &c);
        assert_eq!(out.len(), 1, "{out:#?}");
        let (lo, hi) = out[0].hull.iter().fold(
            (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN)),
            |(lo, hi), q| (lo.min(*q), hi.max(*q)),
        );
        assert!((hi.x - lo.x - 0.64).abs() < 0.02, "{lo} {hi}");
        assert!((hi.y - lo.y - 0.74).abs() < 0.02, "{lo} {hi}");
        assert!(
            out[0].rules.iter().any(|r| r.contains("corner")),
            "{:?}",
            out[0].rules
        );
        let apart = |w: DetectedObstacle| join_faces(vec![south(), w], &c).len() == 2;
        // Crossing the south face's middle (a T), off square, a step taller, too thick (a
        // desk's legs and what joins them), too short (a leg).
        let thick = cluster([14.6, 16.44], DVec2::Y, [0.66, 0.23], (0.0, 0.66), false);
        assert!(!corner_of_one_thing(&south(), &thick, &c));
        assert!(apart(west(14.575, 16.2, 0.66, 0.15, DVec2::Y)));
        assert!(apart(west(14.9, 16.44, 0.66, 0.66, DVec2::Y)));
        let off_square = west(14.575, 16.44, 0.66, 0.66, DVec2::from_angle(1.2));
        assert!(!corner_of_one_thing(&south(), &off_square, &c));
        assert!(apart(west(14.575, 16.44, 0.9, 0.66, DVec2::Y)));
        // A partition 1.5 m long and 1.2 m tall meeting a partition of its height at a corner.
        let tall = cluster([15.6, 16.075], DVec2::X, [1.5, 0.09], (0.0, 1.2), false);
        let tall_west = west(14.8, 16.44, 1.2, 0.66, DVec2::Y);
        assert_eq!(join_faces(vec![tall, tall_west], &c).len(), 2);
    }

    #[test]
    fn faces_too_far_apart_off_each_other_or_of_other_heights_stay_apart() {
        let front = || cluster([0.0, 0.0], DVec2::X, [0.6, 0.2], (0.0, 0.5), false);
        let at =
            |y: f64, x: f64, top: f64| cluster([x, y], DVec2::X, [0.6, 0.2], (0.0, top), false);
        let c = ObstacleConfig::default();
        // Two cabinets' fronts across a 0.9 m aisle.
        assert_eq!(join_faces(vec![front(), at(0.9, 0.0, 0.5)], &c).len(), 2);
        // Side by side, not facing each other.
        assert_eq!(join_faces(vec![front(), at(0.4, 0.5, 0.5)], &c).len(), 2);
        // A seat's edge and a desk's.
        assert_eq!(join_faces(vec![front(), at(0.4, 0.0, 0.75)], &c).len(), 2);
        // A thing seen whole beside a face.
        let whole = cluster([0.0, 0.4], DVec2::X, [0.6, 0.45], (0.0, 0.5), false);
        assert_eq!(join_faces(vec![front(), whole], &c).len(), 2);
        // Three faces: the first pair joins, the joined box is no face.
        let three = join_faces(vec![front(), at(0.4, 0.0, 0.5), at(0.8, 0.0, 0.5)], &c);
        assert_eq!(three.len(), 2, "{three:#?}");
    }
}
