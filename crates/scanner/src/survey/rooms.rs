//! Step 3b of the survey (see the module docs): at least one pose inside every room reached,
//! since a doorway's view of a room is not a survey of it.

/// Adds to `chosen` a pose in every room (`room(k)` of candidate `k`, `None` outside any)
/// that has none yet: the room's candidate sharing most with what was seen (`shared(k)`:
/// registration needs that overlap), linked to a chosen pose (`linked(chosen, k)`), one room
/// at a time. Where no such room is linked directly (its door is narrow or ajar, the poses
/// outside stand too far or at the wrong angle), a surveyor first stands in front of the door,
/// or in it: a stepping stone linked to a chosen pose, from which a pose in the room is linked;
/// the room's pose sharing most with what was seen, then the stone doing so; where no one
/// stone does and the survey is `stuck` (most of the floor unseen), the shortest walk of stones
/// (see [`walk_to_room`]; a room entered that way shares little with what was seen, and its
/// scan may not register: generated mixed-3's did not, 0.84 m off, when every room was walked
/// to). Each time, a room's pose standing `clear(k)` of the doors' swings comes first, through
/// a stone where none is linked directly. Stops when no room without a pose can be reached
/// that way.
pub(super) fn enter_rooms(
    chosen: &mut Vec<usize>,
    candidates: usize,
    room: impl Fn(usize) -> Option<usize>,
    linked: impl Fn(&[usize], usize) -> bool,
    shared: impl Fn(usize) -> usize,
    clear: impl Fn(usize) -> bool,
    stuck: bool,
) {
    loop {
        let mut has_pose: Vec<Option<usize>> = chosen.iter().map(|&c| room(c)).collect();
        has_pose.sort_unstable();
        has_pose.dedup();
        let in_room: Vec<usize> = (0..candidates)
            .filter(|&k| room(k).is_some() && has_pose.binary_search(&room(k)).is_err())
            .collect();
        let next = in_room
            .iter()
            .copied()
            .filter(|&k| linked(chosen, k))
            .max_by_key(|&k| (clear(k), shared(k)));
        if let Some(k) = next.filter(|&k| clear(k)) {
            chosen.push(k);
            continue;
        }
        // (A pose clear of the swings through a stone before one in a swing linked directly.)
        let stone = (0..candidates)
            .filter(|&s| linked(chosen, s))
            .flat_map(|s| {
                in_room
                    .iter()
                    .filter(|&&k| linked(&[s], k))
                    .map(move |&k| (s, k))
                    .collect::<Vec<_>>()
            })
            .max_by_key(|&(s, k)| (clear(k), shared(k), clear(s), shared(s)));
        match (next, stone) {
            (Some(k), Some((_, j))) if !clear(j) => chosen.push(k),
            (Some(k), None) => chosen.push(k),
            (_, Some((s, k))) => chosen.extend([s, k]),
            (None, None) if stuck => {
                match walk_to_room(chosen, candidates, &in_room, &linked, &|k| {
                    (clear(k), shared(k))
                }) {
                    Some(walk) => chosen.extend(walk),
                    None => break,
                }
            }
            (None, None) => break,
        }
    }
}

/// Where no one stone reaches a room (the first pose stands deep in a room whose door, ajar,
/// shows little of the corridor, with a desk between it and the door): the shortest walk of
/// stones, each linked to the one before, from a chosen pose to a candidate in a room without
/// a pose (`in_room`), breadth first; of the rooms' candidates reached in the fewest steps, the
/// one ranking first (`rank`: clear of the doors' swings, then sharing most with what was
/// seen). Returns the stones and that candidate, in walking order.
fn walk_to_room<K: Ord>(
    chosen: &[usize],
    candidates: usize,
    in_room: &[usize],
    linked: &impl Fn(&[usize], usize) -> bool,
    rank: &impl Fn(usize) -> K,
) -> Option<Vec<usize>> {
    let mut from: Vec<Option<usize>> = vec![None; candidates];
    let mut reached = vec![false; candidates];
    chosen.iter().for_each(|&c| reached[c] = true);
    let mut front: Vec<usize> = (0..candidates)
        .filter(|&k| !reached[k] && linked(chosen, k))
        .collect();
    front.iter().for_each(|&k| reached[k] = true);
    while !front.is_empty() {
        if let Some(&k) = front
            .iter()
            .filter(|k| in_room.contains(k))
            .max_by_key(|&&k| rank(k))
        {
            let mut walk = vec![k];
            while let Some(s) = from[walk[walk.len() - 1]] {
                walk.push(s);
            }
            walk.reverse();
            return Some(walk);
        }
        let mut next = Vec::new();
        for &s in &front {
            for k in 0..candidates {
                if !reached[k] && linked(&[s], k) {
                    reached[k] = true;
                    from[k] = Some(s);
                    next.push(k);
                }
            }
        }
        front = next;
    }
    None
}

/// How much of what each candidate sees (`sees`, target indices) was seen (`seen`).
pub(super) fn shared<'a>(sees: &'a [Vec<u32>], seen: &'a [bool]) -> impl Fn(usize) -> usize + 'a {
    move |k| sees[k].iter().filter(|&&t| seen[t as usize]).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Candidates 0..4 on a line, each linked to its neighbours: 0 in room 0 (chosen), 1 in
    /// no room (a doorway), 2 and 3 in room 1: the doorway is the stone, then room 1's pose
    /// sharing most (here the nearer one).
    #[test]
    fn a_room_beyond_a_doorway_gets_a_stone_and_a_pose() {
        let room = |k: usize| match k {
            0 => Some(0),
            1 => None,
            _ => Some(1),
        };
        let linked = |chosen: &[usize], k: usize| chosen.iter().any(|&c| c.abs_diff(k) <= 1);
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 4, room, linked, |k| 10 - k, |_| true, false);
        assert_eq!(chosen, vec![0, 1, 2]);
        // (a room linked to a chosen pose directly needs no stone)
        let mut chosen = vec![1];
        enter_rooms(&mut chosen, 4, room, linked, |k| 10 - k, |_| true, false);
        assert_eq!(chosen, vec![1, 0, 2]);
    }

    /// Candidates 0..4 on a line, each linked to those up to two away: 0 in room 0 (chosen), 1
    /// in no room (a doorway), 2 and 3 in room 1, 2 in a door's swing: room 1's pose is 3,
    /// through the stone 1, though 2 is linked directly and shares more.
    #[test]
    fn a_rooms_pose_in_a_doors_swing_gives_way_to_one_clear_of_it() {
        let room = |k: usize| match k {
            0 => Some(0),
            1 => None,
            _ => Some(1),
        };
        let linked = |chosen: &[usize], k: usize| chosen.iter().any(|&c| c.abs_diff(k) <= 2);
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 4, room, linked, |k| 10 - k, |k| k != 2, false);
        assert_eq!(chosen, vec![0, 1, 3]);
        // (with no swing, the one linked directly)
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 4, room, linked, |k| 10 - k, |_| true, false);
        assert_eq!(chosen, vec![0, 2]);
    }

    /// Candidates 0..6 on a line, each linked to its neighbours: 0 in room 0 (chosen), 1-3 in
    /// no room (its far side behind a desk, the doorway, the corridor's edge), 4 and 5 in room
    /// 1: no one stone reaches room 1, the walk of three does (where the survey is stuck).
    #[test]
    fn a_room_three_stones_away_is_walked_to() {
        let room = |k: usize| match k {
            0 => Some(0),
            1..=3 => None,
            _ => Some(1),
        };
        let linked = |chosen: &[usize], k: usize| chosen.iter().any(|&c| c.abs_diff(k) <= 1);
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 6, room, linked, |k| 10 - k, |_| true, true);
        assert_eq!(chosen, vec![0, 1, 2, 3, 4]);
        // (only where the survey is stuck)
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 6, room, linked, |k| 10 - k, |_| true, false);
        assert_eq!(chosen, vec![0]);
        // (a room beyond no walk at all is left)
        let unlinked =
            |chosen: &[usize], k: usize| chosen.iter().any(|&c| c.abs_diff(k) <= 1 && k != 3);
        let mut chosen = vec![0];
        enter_rooms(&mut chosen, 6, room, unlinked, |k| 10 - k, |_| true, true);
        assert_eq!(chosen, vec![0]);
    }
}
