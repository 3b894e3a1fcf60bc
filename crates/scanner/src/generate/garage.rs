//! The `garage` style: an underground car park. Parking bays 5.5 m deep along both long walls
//! with a 6-6.5 m aisle between them; rows of pillars (0.4-0.6 m) on the bays' front lines
//! every 7.5-8.2 m (three 2.5-2.7 m parking slots between two pillars); downstand beams
//! (0.3-0.45 m deep) over every row of pillars, a duct and a pipe running under the beams;
//! parked cars; a straight staircase in a stair core at the west end (no beam above it), a
//! ramp (5-9 degrees) along the east wall, and a lobby behind a door.

use super::furniture::{car, overhead, pillar, Place, CAR_M};
use super::layout::{wall, Layout};
use super::stairs::flight;
use crate::building::{Building, Door, Hinge, Leaf, Material, Ramp, Swing};
use cloud::Rng;

/// Depth of a parking bay from the wall to the pillar line (m).
const BAY_M: f64 = 5.5;
/// Width of the stair core at the west end and of the ramp zone at the east end (m).
const CORE_M: f64 = 4.0;
const RAMP_ZONE_M: f64 = 4.5;
/// Depth of the lobby behind the door (m).
const LOBBY_M: f64 = 2.5;

/// Generates a car park from `seed`.
pub(super) fn generate(seed: u64) -> Building {
    let mut r = Rng::stream(seed, 0x6a7a6e);
    let spans = r.int(3, 5) as usize;
    let span = r.range(7.5, 8.2);
    let aisle = r.range(6.0, 6.5);
    let height = r.range(2.7, 3.0);
    let t = 0.25;
    let len = CORE_M + spans as f64 * span + RAMP_ZONE_M;
    let depth = 2.0 * BAY_M + aisle;
    let mut l = Layout::new(
        format!("generated garage, seed {seed}"),
        [-t - 0.1, -t - 0.1],
        [len + t + 0.1, depth + LOBBY_M + t + 0.1],
        height,
    );
    // 1. Outer walls (inner faces at x = 0, len and y = 0, depth), a door to the lobby.
    let h = t / 2.0;
    let door_w = r.range(0.9, 1.1);
    let leaf = r.chance(0.7).then(|| Leaf {
        hinge: Hinge::Start,
        swing: Swing::Left,
        open_deg: r.range(85.0, 100.0),
        thickness_m: 0.05,
        material: Material::Matte,
    });
    let mut north = wall("north outer", [-t, depth + h], [len + t, depth + h], t);
    north.doors.push(Door {
        offset_m: t + CORE_M - 0.5 - door_w,
        width_m: door_w,
        height_m: 2.1_f64.min(height - 0.2),
        leaf,
    });
    for w in [
        wall("south outer", [-t, -h], [len + t, -h], t),
        wall("west outer", [-h, -h], [-h, depth + LOBBY_M + t], t),
        wall("east outer", [len + h, -h], [len + h, depth + h], t),
        wall(
            "lobby north",
            [-h, depth + LOBBY_M + h],
            [CORE_M + h, depth + LOBBY_M + h],
            t,
        ),
        wall(
            "lobby east",
            [CORE_M + h, depth + t],
            [CORE_M + h, depth + LOBBY_M + h],
            t,
        ),
    ] {
        l.wall(w, 0.0);
    }
    l.wall(north, 1.2);
    // 2. Rows of pillars on the bays' front lines, beams over them, a duct and a pipe under
    //    the beams (a surveyor's laser at 0.5 m sees them all from below).
    let side = r.range(0.4, 0.6);
    let beam_depth = r.range(0.3, 0.45);
    let lines: Vec<f64> = (0..=spans).map(|k| CORE_M + k as f64 * span).collect();
    for (k, &x) in lines.iter().enumerate() {
        for (j, y) in [BAY_M, depth - BAY_M].into_iter().enumerate() {
            let (boxes, fp) = pillar(x, y, side, height, &format!("pillar {k}.{j}"));
            l.thing(fp, boxes);
        }
        let (boxes, fp) = overhead(
            [x, 0.0],
            [x, depth],
            side,
            beam_depth,
            height,
            0.0,
            &format!("beam {k}"),
        );
        l.overhead(fp, boxes);
    }
    let (x0, x1) = (CORE_M - 0.5, len - RAMP_ZONE_M + 0.5);
    let below_beams = beam_depth + 0.05;
    for (y, w, d, name) in [(depth - 1.0, 0.5, 0.25, "duct"), (0.6, 0.12, 0.12, "pipe")] {
        let (boxes, fp) = overhead([x0, y], [x1, y], w, d, height, below_beams, name);
        l.overhead(fp, boxes);
    }
    // 3. Parked cars nose to the wall, three slots per span on each side (at least two cars).
    let mut cars = 0;
    for (k, &line) in lines[..spans].iter().enumerate() {
        for slot in 0..3 {
            for south in [true, false] {
                let x = line + span * (slot as f64 + 0.5) / 3.0;
                let y = if south {
                    0.3 + CAR_M[0] / 2.0
                } else {
                    depth - 0.3 - CAR_M[0] / 2.0
                };
                let must = cars < 2 && k == spans - 1 && slot == 2;
                if !(must || r.chance(0.6)) {
                    continue;
                }
                let yaw_deg = if south { 90.0 } else { -90.0 } + r.range(-3.0, 3.0);
                let p = Place { x, y, yaw_deg };
                let (boxes, fp) = car(&mut r, &p, &format!("car {cars}"));
                if l.thing(fp, boxes) {
                    cars += 1;
                }
            }
        }
    }
    // 4. A staircase along the west wall in the stair core, rising north.
    if let Some(mut s) = flight(&mut r, [0.0, 1.0], 90.0, depth - 2.5, height, "stairs") {
        s.start_m[0] = 0.35 + s.width_m / 2.0;
        l.stairs(s);
    }
    // 5. A ramp along the east wall, 5-9 degrees, leaving 1.2 m under the ceiling at its head.
    let length = r.range(6.0, 9.0);
    let pitch = r.range(5.0, 9.0).to_radians();
    let width = r.range(2.8, 3.2);
    let ramp = Ramp {
        name: "ramp".into(),
        start_m: [len - 0.35 - width / 2.0, 1.0],
        direction_deg: 90.0,
        length_m: length,
        width_m: width,
        rise_m: (length * pitch.tan()).min(height - 1.2),
        thickness_m: 0.2,
    };
    l.ramp(ramp);
    l.b
}
