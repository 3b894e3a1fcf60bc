//! The tour: from the start, repeatedly the nearest reachable goal next (a Dijkstra search
//! from where the robot stands), doors first, staircases and ramps last. A door is passed as a
//! straight leg from an approach point on one side of its free space to a point on the other
//! side where the robot has left it; a staircase as a leg from a point before its foot, facing
//! up the stairs, to the middle of its landing (or top step); a ramp likewise, to its upper
//! end. Paths between goals are simplified into waypoints. A tour with no door or staircase to
//! pass sweeps the start's free region instead (to its farthest point, then to the point
//! farthest from there: a corridor's two ends, a room's far corners; of the points where the
//! robot can turn in place, where there are any), so that the robot drives the space the map
//! holds rather than stand.

use super::footprint::Footprint;
use super::goals::{door_leg, stairs_leg, ClimbLeg, DoorLeg};
use super::grid::FreeGrid;
use super::ramp_leg::ramp_leg;
use super::search::{length_m, simplify, Reach};
use super::{Goal, PlanConfig, Unreachable};
use crate::controller::Waypoint;
use crate::ramps::ramps_of;
use crate::spec::WorldSpec;

/// Entering an opening from the side its leaf swings towards (pulling) counts as this much
/// longer a path (m): pushing a leaf open is what the robot can do, pulling it is not.
const PULL_PENALTY_M: f64 = 10.0;
/// Waypoint tolerance at a staircase's top (m): the middle of the landing, not its edge (and
/// at a ramp's upper end, not past it).
const TOP_TOLERANCE_M: f64 = 0.1;
/// A sweep leg shorter than this (m, weighted path length) is not driven: a free region no
/// longer than a robot or two is a place to stand, not a space to cover.
const MIN_SWEEP_M: f64 = 1.0;

/// A planned tour.
pub(crate) struct Tour {
    pub goals: Vec<Goal>,
    pub waypoints: Vec<Waypoint>,
    pub length_m: f64,
    pub drive_time_s: f64,
    pub unreachable: Vec<Unreachable>,
    /// The farthest point of the sweep of a tour without goals: the robot must reach it.
    pub sweep_end: Option<[f64; 2]>,
}

/// At most this many openings are crossed on the way between two goals (each costs a search).
const MAX_CROSSINGS: usize = 64;

struct Builder<'a> {
    grid: &'a FreeGrid,
    doors: &'a [DoorLeg],
    comfort_m: f64,
    cfg: &'a PlanConfig,
    max_speed_mps: f64,
    tour: Tour,
    pos: usize,
}

impl Builder<'_> {
    fn speed(&self, asked: f64) -> f64 {
        asked.min(self.max_speed_mps)
    }

    /// Drives the searched path to `goal`; false when unreachable. Where the path crosses a
    /// door opening, the robot crosses it straight, along the opening's normal, from its
    /// approach point to its exit point (a long robot turning inside an opening touches its
    /// jambs); the rest is simplified into waypoints.
    fn drive_to(&mut self, reach: &Reach, goal_m: [f64; 2]) -> bool {
        let Some(goal) = self.grid.cell_of(goal_m) else {
            return false;
        };
        let Some(cells) = reach.path(goal) else {
            return false;
        };
        let mut crossings = 0;
        let mut cells = cells;
        loop {
            let pts: Vec<[f64; 2]> = cells.iter().map(|&c| self.grid.centre(c)).collect();
            let leg = (crossings < MAX_CROSSINGS)
                .then(|| self.first_crossing(&pts))
                .flatten();
            let Some((a, e)) = leg else {
                self.follow(&pts, goal_m);
                return true;
            };
            crossings += 1;
            // Up to the approach point, straight through, then on from the exit point.
            let (Some(ca), Some(ce)) = (self.grid.cell_of(a), self.grid.cell_of(e)) else {
                self.follow(&pts, goal_m);
                return true;
            };
            let to_a = Reach::from(self.grid, self.pos, self.comfort_m).path(ca);
            let from_e = Reach::from(self.grid, ce, self.comfort_m).path(goal);
            let (Some(to_a), Some(from_e)) = (to_a, from_e) else {
                self.follow(&pts, goal_m);
                return true;
            };
            let to_a: Vec<[f64; 2]> = to_a.iter().map(|&c| self.grid.centre(c)).collect();
            self.follow(&to_a, a);
            self.leg(e, None);
            cells = from_e;
        }
    }

    /// The first opening the path crosses (in on one side, out on the other): its leg from
    /// the side the path comes from.
    fn first_crossing(&self, pts: &[[f64; 2]]) -> Option<([f64; 2], [f64; 2])> {
        for (k, p) in pts.iter().enumerate().skip(1) {
            for d in self
                .doors
                .iter()
                .filter(|d| d.inside(*p) && !d.inside(pts[k - 1]))
            {
                let before = d.local(pts[k - 1]).1;
                let after = pts[k..].iter().find(|q| !d.inside(**q));
                if after.is_some_and(|q| d.local(*q).1 * before < 0.0) {
                    return d.leg_from(pts[k - 1]);
                }
            }
        }
        None
    }

    /// Follows a path of cell centres (the first is where the robot stands), simplified,
    /// ending exactly at `end_m` (a point in the path's last cell).
    fn follow(&mut self, pts: &[[f64; 2]], end_m: [f64; 2]) {
        let mut pts = simplify(self.grid, pts, self.cfg.simplify_tolerance_m);
        if let Some(last) = pts.last_mut() {
            *last = end_m;
        }
        let v = self.speed(self.cfg.cruise_speed_mps);
        for p in pts.iter().skip(1) {
            self.push(*p, v, None);
        }
        if let Some(c) = pts.last().and_then(|p| self.grid.cell_of(*p)) {
            self.pos = c;
        }
    }

    /// A straight leg to `p` at the careful speed.
    fn leg(&mut self, p: [f64; 2], tolerance_m: Option<f64>) {
        let v = self.speed(self.cfg.careful_speed_mps);
        self.push(p, v, tolerance_m);
        if let Some(c) = self.grid.cell_of(p) {
            self.pos = c;
        }
    }

    fn push(&mut self, p: [f64; 2], speed_mps: f64, tolerance_m: Option<f64>) {
        let from = self
            .tour
            .waypoints
            .last()
            .map_or(self.grid.centre(self.pos), |w| [w.x_m, w.y_m]);
        let d = length_m(&[from, p]);
        self.tour.length_m += d;
        self.tour.drive_time_s += d / speed_mps;
        self.tour.waypoints.push(Waypoint {
            x_m: p[0],
            y_m: p[1],
            speed_mps: Some(speed_mps),
            tolerance_m,
        });
    }
}

/// Plans the tour from `start` (a free cell).
pub(crate) fn plan_tour(
    world: &WorldSpec,
    grid: &FreeGrid,
    fp: &Footprint,
    robot_name: &str,
    max_speed_mps: f64,
    start: usize,
    cfg: &PlanConfig,
) -> Tour {
    let mut unreachable = vec![];
    // 1. The goals the robot fits: door openings wide enough with room on a side, staircases
    //    with steps it climbs and treads wide enough, ramps not too steep, wide and long
    //    enough.
    let mut all_doors: Vec<DoorLeg> = vec![];
    for fs in &world.free_spaces {
        match door_leg(world, grid, fp, cfg, fs) {
            Ok(d) => all_doors.push(d),
            Err(u) => unreachable.push(u),
        }
    }
    let mut doors: Vec<usize> = (0..all_doors.len()).collect();
    let mut climbs: Vec<ClimbLeg> = vec![];
    for s in &world.stairs {
        match stairs_leg(grid, fp, robot_name, cfg, s) {
            Ok(l) => climbs.push(l),
            Err(u) => unreachable.push(u),
        }
    }
    for r in ramps_of(world) {
        match ramp_leg(world, grid, fp, cfg, &r) {
            Ok(l) => climbs.push(l),
            Err(u) => unreachable.push(u),
        }
    }
    let mut b = Builder {
        grid,
        doors: &all_doors,
        comfort_m: fp.turn_radius_m() + cfg.margin_m,
        cfg,
        max_speed_mps,
        tour: Tour {
            goals: vec![],
            waypoints: vec![],
            length_m: 0.0,
            drive_time_s: 0.0,
            unreachable: vec![],
            sweep_end: None,
        },
        pos: start,
    };
    // 2. Doors, nearest first, each entered from the side that pushes its leaf where possible.
    while !doors.is_empty() {
        let reach = Reach::from(grid, b.pos, b.comfort_m);
        let best = doors
            .iter()
            .enumerate()
            .flat_map(|(i, &d)| all_doors[d].sides.iter().map(move |s| (i, s)))
            .filter_map(|(i, &(a, e, push))| {
                let cost = reach.cost(grid.cell_of(a)?);
                let cost = cost + if push { 0.0 } else { PULL_PENALTY_M };
                cost.is_finite().then_some((cost, i, a, e))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0));
        let Some((_, i, a, e)) = best else { break };
        let d = doors.remove(i);
        if !b.drive_to(&reach, a) {
            doors.push(d);
            break;
        }
        b.leg(e, None);
        b.tour.goals.push(Goal::Door(all_doors[d].name.clone()));
    }
    for d in doors {
        let reason = match &all_doors[d].pull_refused {
            Some(why) => {
                format!("no free path from the start to the side that pushes the leaf; {why}")
            }
            None => "no free path from the start to either side of the opening".into(),
        };
        unreachable.push(Unreachable {
            goal: Goal::Door(all_doors[d].name.clone()),
            reason,
        });
    }
    // 3. Staircases and ramps, nearest first; between two, the robot drives back down to the
    //    foot of the one it climbed (the tour goes on from its run-up point).
    let mut from = b.pos;
    let mut climbed: Option<ClimbLeg> = None;
    loop {
        let reach = Reach::from(grid, from, b.comfort_m);
        let best = climbs
            .iter()
            .enumerate()
            .filter_map(|(i, s)| Some((reach.cost(grid.cell_of(s.run_up)?), i)))
            .filter(|(c, _)| c.is_finite())
            .min_by(|x, y| x.0.total_cmp(&y.0));
        let Some((_, i)) = best else { break };
        let Some(cell) = grid.cell_of(climbs[i].run_up) else {
            break;
        };
        if let Some(prev) = climbed.take() {
            b.leg(prev.foot, None);
            b.leg(prev.run_up, None);
        }
        let s = climbs.remove(i);
        if !b.drive_to(&reach, s.run_up) {
            climbs.push(s);
            break;
        }
        b.leg(s.foot, None);
        b.leg(s.top, Some(TOP_TOLERANCE_M));
        b.tour.goals.push(s.goal.clone());
        from = cell;
        climbed = Some(s);
    }
    for s in climbs {
        let what = match s.goal {
            Goal::Ramp(_) => "ramp",
            _ => "stairs",
        };
        unreachable.push(Unreachable {
            goal: s.goal,
            reason: format!("no free path from the start to the foot of the {what}"),
        });
    }
    // 4. Nothing to pass or climb: sweep the start's free region, to its farthest point, then
    //    to the point farthest from there.
    if b.tour.goals.is_empty() {
        for _ in 0..2 {
            let reach = Reach::from(grid, b.pos, b.comfort_m);
            let Some((cost, far)) = farthest(grid, &reach, b.comfort_m) else {
                break;
            };
            // Centimetres are enough for a goal a robot's length across (and read better).
            let end = grid.centre(far).map(|v| (v * 100.0).round() / 100.0);
            if cost < MIN_SWEEP_M || !b.drive_to(&reach, end) {
                break;
            }
            // The goal: the sweep's first end, the farthest from the start (the second may
            // lie back near the start, where a robot standing still would reach it).
            b.tour.sweep_end.get_or_insert(end);
        }
    }
    b.tour.unreachable = unreachable;
    b.tour
}

/// The reachable cell farthest (weighted path length) from the search's start, with its cost:
/// of those where the robot can turn in place (clearance `comfort_m`) if any. A sweep's end is
/// where the robot stops and turns for the next leg; the farthest free cell of all lies in a
/// tight spot (a doorway with nothing mapped beyond, a niche), where it turned into the jamb
/// (the 3DTK corridor, touching a wall for 0.7 s).
fn farthest(grid: &FreeGrid, reach: &Reach, comfort_m: f64) -> Option<(f64, usize)> {
    let best = |roomy: bool| {
        (0..grid.len())
            .filter(|&c| !roomy || grid.clearance_m(c) >= comfort_m)
            .map(|c| (reach.cost(c), c))
            .filter(|(d, _)| d.is_finite())
            .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)))
    };
    best(true).or_else(|| best(false))
}
