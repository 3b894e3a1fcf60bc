//! Stop-and-scan poses chosen as a surveyor would, from a building alone.
//!
//! 1. A 2D grid of the floor: a cell is blocked where anything stands between the floor and
//!    head height (walls, door leaves where they are, boxes, stairs, ramps; beams above
//!    [`BLOCKING_TOP_M`] are walked under); free cells are those farther than the tripod's
//!    clearance from any blocked one. Free space touching the floor's edge lies outside the
//!    walls and is dropped.
//! 2. The reachable space: the largest connected region the surveyor passes through (with
//!    `pass_clearance_m`, less than a standing tripod's: a door left ajar lets a person
//!    through; a closed door cuts its room off); poses stand on its free cells.
//! 3. Poses, greedily: first the candidate (cells every `candidate_step_m`) that sees the most
//!    free floor within `cover_radius_m`, then always the candidate seeing most floor not yet
//!    seen, among those within `max_step_m` of a chosen pose and in its line of sight and
//!    sharing at least `min_overlap` of their floor with what was seen, until the gain is
//!    under `min_gain_m2`. Then every room (a region of free floor with the doors shut)
//!    reached through an open door and still without a pose gets one: the pose in it that
//!    shares most with what was seen (clear of its doors' swings where it can be: a tripod
//!    beside an open leaf has a wide sector of the room hidden by it, and whoever uses the
//!    door knocks it), linked to a chosen one or, where none is (a door
//!    ajar, poses outside at the wrong angle), to a stepping stone linked to a chosen one
//!    (a surveyor stands in front of the door first; see `rooms`). Where the poses leave
//!    more than half of the reachable floor unseen, the survey is stuck, not done (its first
//!    pose in a room whose door, ajar, shows little of the corridor beyond): the greedy
//!    choice goes on from the rooms' poses, and so on. Last, every staircase that starts on
//!    the floor is seen from its foot (a pose in front of its first riser) where a candidate
//!    there is linked to a chosen pose.
//! 4. Ordered as a walk: always on to the nearest pose that has an earlier one close by and
//!    in sight (what registering scan k against scans 0..k-1 needs), so that consecutive
//!    poses stay close (odometry drifts with distance); each yaw points the way walked.

mod foot;
mod grid;
mod rooms;

use crate::building::Building;
use crate::error::{Result, ScannerError};
use crate::geometry::BuildingGeometry;
use crate::pose::ScanPose;
use cloud::check_range;
use foot::Foot;
use grid::floor_grid;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

pub use grid::BLOCKING_TOP_M;

/// A survey is stuck, not done, where its poses leave more than this share of the reachable
/// floor unseen. (Surveys that end normally leave corners behind furniture and rooms seen only
/// through their doors: a quarter of the floor at most on the styles benches' 100 buildings.)
const STUCK_UNSEEN: f64 = 0.5;

/// How poses are chosen (`[survey]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SurveyConfig {
    /// The grid's cell edge (m).
    pub cell_m: f64,
    /// How far a pose stays from anything solid (m): a tripod's legs spread about 0.3 m.
    pub clearance_m: f64,
    /// How far the surveyor walking between poses stays from anything solid (m): a person
    /// carrying a folded tripod passes sideways through a door left ajar.
    pub pass_clearance_m: f64,
    /// How far from the foot of a staircase a pose may stand to count as seeing it from
    /// there (m); one more pose stands there if none does.
    pub stairs_view_m: f64,
    /// How far a scan is counted as covering the floor (m). The laser reaches 30 m, but at
    /// 4 m its 0.5 degree beam spacing already leaves 3.5 cm between points, about what the
    /// semantic stage's grid resolves, and walls farther away are seen at grazing angles.
    pub cover_radius_m: f64,
    /// The farthest a new pose may stand from the nearest earlier one (m). Registration
    /// matches a scan against the earlier ones: scans 2.5 m apart inside the 4 m cover
    /// radius share most of what they see (the default building's hand-made survey steps
    /// 2.5 m along its corridor).
    pub max_step_m: f64,
    /// Spacing of the candidate poses (m).
    pub candidate_step_m: f64,
    /// Stop when the best new pose sees less unseen floor than this (m²).
    pub min_gain_m2: f64,
    /// The least share of a new pose's floor that earlier poses saw. Registration matches a
    /// scan against the map of the earlier ones, and ICP needs a good part of the scan to
    /// lie on that map: a room scanned first from deep inside shares only a doorway's glimpse
    /// with the corridor, so a surveyor stands in the doorway first.
    pub min_overlap: f64,
}

impl Default for SurveyConfig {
    fn default() -> Self {
        SurveyConfig {
            cell_m: 0.1,
            clearance_m: 0.3,
            pass_clearance_m: 0.2,
            stairs_view_m: 3.0,
            cover_radius_m: 4.0,
            max_step_m: 2.5,
            candidate_step_m: 0.5,
            min_gain_m2: 1.5,
            min_overlap: 0.5,
        }
    }
}

impl SurveyConfig {
    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<()> {
        check_range("survey.cell_m", self.cell_m, 0.02, 1.0, "within 2 cm..1 m")?;
        check_range(
            "survey.clearance_m",
            self.clearance_m,
            0.0,
            2.0,
            "within 0..2 m",
        )?;
        check_range(
            "survey.pass_clearance_m",
            self.pass_clearance_m,
            0.0,
            self.clearance_m,
            "within 0..clearance_m",
        )?;
        check_range(
            "survey.stairs_view_m",
            self.stairs_view_m,
            0.5,
            30.0,
            "within 0.5..30 m",
        )?;
        check_range(
            "survey.cover_radius_m",
            self.cover_radius_m,
            0.5,
            30.0,
            "within 0.5..30 m",
        )?;
        check_range(
            "survey.max_step_m",
            self.max_step_m,
            0.5,
            30.0,
            "within 0.5..30 m",
        )?;
        check_range(
            "survey.candidate_step_m",
            self.candidate_step_m,
            self.cell_m,
            5.0,
            "within cell_m..5 m",
        )?;
        check_range(
            "survey.min_overlap",
            self.min_overlap,
            0.0,
            0.95,
            "within 0..0.95",
        )?;
        check_range(
            "survey.min_gain_m2",
            self.min_gain_m2,
            0.0,
            1000.0,
            "within 0..1000 m²",
        )?;
        Ok(())
    }
}

/// Stop-and-scan poses for `b`, in walking order (see the module's documentation).
/// An error names the building when it has no free floor for the tripod.
pub fn survey_poses(b: &Building, cfg: &SurveyConfig) -> Result<Vec<ScanPose>> {
    cfg.validate()?;
    let no_space = |msg: &str| ScannerError::Survey {
        building: if b.name.is_empty() {
            "the building".into()
        } else {
            format!("building '{}'", b.name)
        },
        msg: msg.into(),
    };
    // 1. The floor grid, the cells a pose may stand on and those the surveyor passes.
    let g = BuildingGeometry::new(b);
    let grid = floor_grid(b, &g, cfg.cell_m, false);
    let free = grid.clear_of(cfg.clearance_m);
    let passable = grid.clear_of(cfg.pass_clearance_m);
    // 2. The reachable space: the largest passable region inside the walls.
    let (_, regions) = grid.regions(&passable);
    let Some(reach) = regions
        .into_iter()
        .filter(|r| !grid.touches_edge(r))
        .max_by_key(Vec::len)
    else {
        return Err(no_space(&format!(
            "no free floor inside the walls for a survey: nowhere is {} m clear of walls, \
             boxes and stairs",
            cfg.pass_clearance_m
        )));
    };
    // 3. Candidates and what each sees of the reachable floor.
    let stride = ((cfg.candidate_step_m / grid.cell).round() as usize).max(1);
    let feet: Vec<Foot> = b
        .stairs
        .iter()
        .filter(|s| s.base_m == 0.0)
        .filter_map(|s| Foot::new(&grid, s))
        .collect();
    let candidates: Vec<usize> = reach
        .iter()
        .copied()
        .filter(|&i| {
            free[i] && (i % grid.nx).is_multiple_of(stride) && (i / grid.nx).is_multiple_of(stride)
        })
        .collect();
    let targets: Vec<usize> = reach
        .iter()
        .copied()
        .filter(|&i| (i % grid.nx).is_multiple_of(2) && (i / grid.nx).is_multiple_of(2))
        .collect();
    let target_m2 = (2.0 * grid.cell).powi(2);
    let sees: Vec<Vec<u32>> = candidates
        .par_iter()
        .map(|&c| {
            let pc = grid.centre(c);
            targets
                .iter()
                .enumerate()
                .filter(|(_, &t)| {
                    let pt = grid.centre(t);
                    (pt[0] - pc[0]).hypot(pt[1] - pc[1]) <= cfg.cover_radius_m && grid.sight(c, t)
                })
                .map(|(k, _)| k as u32)
                .collect()
        })
        .collect();
    let Some(first) = (0..candidates.len()).max_by_key(|&k| sees[k].len()) else {
        return Err(no_space("the free floor is too small for a single pose"));
    };
    // (A candidate within `max_step_m` of a chosen pose and in its sight can be registered.)
    let linked_to_chosen = |chosen: &[usize], k: usize| {
        let pk = grid.centre(candidates[k]);
        chosen.iter().any(|&c| {
            let pc = grid.centre(candidates[c]);
            (pc[0] - pk[0]).hypot(pc[1] - pk[1]) <= cfg.max_step_m
                && grid.sight(candidates[c], candidates[k])
        })
    };
    let mut seen = vec![false; targets.len()];
    let mut chosen: Vec<usize> = vec![first];
    for &t in &sees[first] {
        seen[t as usize] = true;
    }
    let rooms = floor_grid(b, &g, cfg.cell_m, true);
    let (room_of_cell, _) = rooms.regions(&rooms.clear_of(cfg.clearance_m));
    let swings = grid.door_swings(b, cfg.clearance_m);
    loop {
        loop {
            let mut best: Option<(usize, usize)> = None;
            for (k, sees_k) in sees.iter().enumerate() {
                let gain = sees_k.iter().filter(|&&t| !seen[t as usize]).count();
                if gain == 0 || best.is_some_and(|b| gain <= b.1) {
                    continue;
                }
                let overlap = (sees_k.len() - gain) as f64 / sees_k.len() as f64;
                if overlap < cfg.min_overlap {
                    continue;
                }
                if linked_to_chosen(&chosen, k) {
                    best = Some((k, gain));
                }
            }
            match best {
                Some((k, gain)) if gain as f64 * target_m2 >= cfg.min_gain_m2 => {
                    for &t in &sees[k] {
                        seen[t as usize] = true;
                    }
                    chosen.push(k);
                }
                _ => break,
            }
        }
        // 3b. At least one pose inside every room reached (a doorway's view of a room is not
        //     a survey of it; see `rooms`).
        let before = chosen.len();
        let unseen = seen.iter().filter(|&&s| !s).count();
        // Where the poses left most of the reachable floor unseen (the first one in a room
        // whose door, ajar, shows little of the corridor beyond: no pose a step away gains
        // enough), the survey is stuck, not done: the rooms' poses are new starts for step 3,
        // and a room no one stone reaches is walked to.
        let stuck = unseen as f64 > STUCK_UNSEEN * seen.len() as f64;
        rooms::enter_rooms(
            &mut chosen,
            candidates.len(),
            |k| room_of_cell[candidates[k]],
            linked_to_chosen,
            rooms::shared(&sees, &seen),
            |k| !swings[candidates[k]],
            stuck,
        );
        if !stuck || chosen.len() == before {
            break;
        }
        for &k in &chosen[before..] {
            for &t in &sees[k] {
                seen[t as usize] = true;
            }
        }
    }
    // 3c. Every staircase that starts on the floor seen from its foot (its risers face a pose
    //     in front of it; from the side or from above its steps hide each other): where no
    //     pose stands within `stairs_view_m` of the foot, within 60 degrees of the flight's
    //     axis and in sight of it, the candidate there sharing most with what was seen.
    //     (Where none is linked to a chosen pose, none is added: stepping stones towards the
    //     foot were tried, and made the office stairs worse; see the README.)
    let shared = rooms::shared(&sees, &seen);
    for f in &feet {
        let sees_foot = |k: usize| f.seen_from(&grid, candidates[k], cfg.stairs_view_m);
        if chosen.iter().any(|&c| sees_foot(c)) {
            continue;
        }
        let at_foot = (0..candidates.len())
            .filter(|&k| sees_foot(k) && linked_to_chosen(&chosen, k))
            .max_by_key(|&k| shared(k));
        if let Some(k) = at_foot {
            chosen.push(k);
        }
    }
    // 4. The walk: from the first pose, always on to the nearest pose not yet visited that
    //    stands within `max_step_m` of a visited one and in its sight (so it can be
    //    registered), keeping consecutive poses close (odometry drifts with distance); each
    //    yaw points the way walked.
    let at: Vec<usize> = chosen.iter().map(|&k| candidates[k]).collect();
    let dist = |a: usize, b: usize| {
        let (pa, pb) = (grid.centre(at[a]), grid.centre(at[b]));
        (pa[0] - pb[0]).hypot(pa[1] - pb[1])
    };
    let linked = |a: usize, b: usize| dist(a, b) <= cfg.max_step_m && grid.sight(at[a], at[b]);
    let mut visited = vec![false; at.len()];
    let mut walk = vec![0usize];
    visited[0] = true;
    while walk.len() < at.len() {
        let last = walk[walk.len() - 1];
        let next = (0..at.len())
            .filter(|&j| !visited[j] && walk.iter().any(|&i| linked(i, j)))
            .min_by(|&a, &b| dist(last, a).total_cmp(&dist(last, b)))
            // Every chosen pose was linked to an earlier one, so one is always eligible.
            .or_else(|| (0..at.len()).find(|&j| !visited[j]));
        let Some(j) = next else { break };
        visited[j] = true;
        walk.push(j);
    }
    let heading = |from: [f64; 2], to: [f64; 2]| {
        ((to[1] - from[1]).atan2(to[0] - from[0]).to_degrees() * 10.0).round() / 10.0
    };
    let mut order: Vec<ScanPose> = walk
        .windows(2)
        .map(|w| {
            (
                grid.centre(at[w[1]]),
                heading(grid.centre(at[w[0]]), grid.centre(at[w[1]])),
            )
        })
        .map(|(p, yaw_deg)| ScanPose {
            x_m: p[0],
            y_m: p[1],
            yaw_deg,
        })
        .collect();
    let p0 = grid.centre(at[0]);
    order.insert(
        0,
        ScanPose {
            x_m: p0[0],
            y_m: p0[1],
            yaw_deg: order.first().map_or(0.0, |q| heading(p0, [q.x_m, q.y_m])),
        },
    );
    Ok(order)
}

/// The rooms of `b`: regions of free floor with every door shut, each as the index of the
/// room a point lies in (`None`: not on free floor). For tests and reports: which rooms a
/// survey reaches.
pub fn room_of(
    b: &Building,
    cfg: &SurveyConfig,
    points: &[[f64; 2]],
) -> Result<Vec<Option<usize>>> {
    cfg.validate()?;
    let g = BuildingGeometry::new(b);
    let grid = floor_grid(b, &g, cfg.cell_m, true);
    // Rooms with a small clearance, so that a pose near furniture still counts as inside.
    let free = grid.clear_of(cfg.cell_m);
    let (of, _) = grid.regions(&free);
    Ok(points
        .iter()
        .map(|p| grid.index(*p).and_then(|i| of[i]))
        .collect())
}
