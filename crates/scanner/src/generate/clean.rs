//! The `clean` style (the original generator): a corridor with rooms on both sides, doors in
//! every state (closed, half-open, open, no leaf), a staircase with a landing in the largest
//! room, and clutter boxes. Its buildings must never change for a given seed (the README's
//! figures are measured on them; `tests/generate_styles.rs` pins a few).

use super::GeneratorConfig;
use crate::building::{
    Building, Ceiling, Door, Floor, Furniture, Hinge, Leaf, Staircase, Swing, Wall,
};
use cloud::Rng;

/// A room beside the corridor: its span along x, its y range, and which side it is on.
struct Room {
    x0: f64,
    x1: f64,
    y_near: f64,
    y_far: f64,
    north: bool,
    door: Option<(f64, f64)>,
}

/// Generates a clean-style building from `seed` (not yet validated).
pub(super) fn generate(seed: u64, config: &GeneratorConfig) -> Building {
    let mut r = Rng::new(seed);
    let c = config;
    let len = r
        .range(c.corridor_length_m[0], c.corridor_length_m[1])
        .max(6.0);
    let half_w = r.range(c.corridor_width_m[0], c.corridor_width_m[1]) / 2.0;
    let height = r.range(c.ceiling_height_m[0], c.ceiling_height_m[1]);
    let t = r.range(0.12, 0.25);
    let depth_n = r.range(c.room_depth_m[0], c.room_depth_m[1]);
    let depth_s = r.range(c.room_depth_m[0], c.room_depth_m[1]);
    let (yn, ys) = (half_w + t / 2.0, -half_w - t / 2.0);
    let (yn_out, ys_out) = (yn + depth_n, ys - depth_s);
    let mut walls = vec![
        wall(
            "south outer",
            [-t / 2.0, ys_out],
            [len + t / 2.0, ys_out],
            t,
        ),
        wall(
            "north outer",
            [-t / 2.0, yn_out],
            [len + t / 2.0, yn_out],
            t,
        ),
        wall("west outer", [0.0, ys_out], [0.0, yn_out], t),
        wall("east outer", [len, ys_out], [len, yn_out], t),
    ];
    let mut rooms = Vec::new();
    for north in [true, false] {
        let (y_near, y_far) = if north { (yn, yn_out) } else { (ys, ys_out) };
        let mut x0 = 0.0;
        while len - x0 > c.room_width_m[0] {
            let w = r.range(c.room_width_m[0], c.room_width_m[1]);
            let x1 = if len - (x0 + w) < c.room_width_m[0] {
                len
            } else {
                x0 + w
            };
            if x1 < len {
                let (a, b) = if north {
                    (y_near + t / 2.0, y_far - t / 2.0)
                } else {
                    (y_far + t / 2.0, y_near - t / 2.0)
                };
                walls.push(wall("partition", [x1, a], [x1, b], t * 0.8));
            }
            rooms.push(Room {
                x0,
                x1,
                y_near,
                y_far,
                north,
                door: None,
            });
            x0 = x1;
        }
    }
    let mut states: Vec<u32> = (0..rooms.len() as u32).map(|i| i % 4).collect();
    for i in (1..states.len()).rev() {
        states.swap(i, r.int(0, i as i64) as usize);
    }
    let mut corridor = [Vec::new(), Vec::new()];
    for (room, state) in rooms.iter_mut().zip(&states) {
        let width = r.range(0.8, 1.2);
        let offset = r.range(room.x0 + 0.35, room.x1 - 0.35 - width) - t / 2.0;
        let swing = if room.north {
            Swing::Left
        } else {
            Swing::Right
        };
        let hinge = if r.chance(0.5) {
            Hinge::Start
        } else {
            Hinge::End
        };
        let open_deg = match state {
            0 => Some(0.0),
            1 => Some(r.range(30.0, 60.0)),
            2 => Some(r.range(80.0, 100.0)),
            _ => None,
        };
        let leaf = open_deg.map(|open_deg| Leaf {
            hinge,
            swing,
            open_deg,
            thickness_m: 0.04,
            material: Default::default(),
        });
        room.door = Some((offset + t / 2.0, offset + t / 2.0 + width));
        corridor[usize::from(!room.north)].push(Door {
            offset_m: offset,
            width_m: width,
            height_m: r.range(1.95, 2.2).min(height - 0.2),
            leaf,
        });
    }
    for (k, (name, y)) in [("corridor north", yn), ("corridor south", ys)]
        .into_iter()
        .enumerate()
    {
        let mut w = wall(name, [t / 2.0, y], [len - t / 2.0, y], t);
        w.doors = std::mem::take(&mut corridor[k]);
        walls.push(w);
    }
    let (stairs, stair_zone) = place_stairs(&mut r, &rooms, t, height);
    let mut boxes = Vec::new();
    for room in &rooms {
        let n = r.int(0, c.max_boxes_per_room as i64);
        for _ in 0..n {
            if let Some(b) = place_box(&mut r, room, t, &stair_zone) {
                boxes.push(b);
            }
        }
    }
    Building {
        name: format!("generated, seed {seed}"),
        floor: Floor {
            min_m: [-t - 0.1, ys_out - t - 0.1],
            max_m: [len + t + 0.1, yn_out + t + 0.1],
            thickness_m: 0.2,
        },
        ceiling: Ceiling {
            height_m: height,
            thickness_m: 0.2,
        },
        walls,
        stairs: stairs.into_iter().collect(),
        boxes,
        ramps: Vec::new(),
    }
}

fn wall(name: &str, start_m: [f64; 2], end_m: [f64; 2], thickness_m: f64) -> Wall {
    Wall {
        name: name.into(),
        start_m,
        end_m,
        thickness_m,
        height_m: None,
        doors: Vec::new(),
        material: Default::default(),
    }
}

/// An axis-aligned keep-out rectangle [x0, y0, x1, y1].
type Zone = [f64; 4];

fn place_stairs(
    r: &mut Rng,
    rooms: &[Room],
    t: f64,
    height: f64,
) -> (Option<Staircase>, Option<Zone>) {
    let Some(room) = rooms
        .iter()
        .max_by(|a, b| (a.x1 - a.x0).total_cmp(&(b.x1 - b.x0)))
    else {
        return (None, None);
    };
    let inner = room.x1 - room.x0 - t - 0.6;
    let max_steps = ((height - 1.2) / 0.14).floor().clamp(3.0, 10.0) as i64;
    let mut steps = r.int(4, max_steps) as u32;
    let run = r.range(0.25, 0.32);
    let landing = r.range(0.8, 1.2);
    while steps > 3 && steps as f64 * run + landing > inner {
        steps -= 1;
    }
    let rise = r.range(0.14, 0.19).min((height - 1.2) / steps as f64);
    let width = r.range(0.9, 1.3);
    let sign = if room.north { 1.0 } else { -1.0 };
    let y = room.y_far - sign * (t / 2.0 + 0.2 + width / 2.0);
    let ascend_east = r.chance(0.5);
    let total = steps as f64 * run + landing;
    let (x_start, dir) = if ascend_east {
        (room.x0 + t / 2.0 + 0.3, 0.0)
    } else {
        (room.x1 - t / 2.0 - 0.3, 180.0)
    };
    let x_end = if ascend_east {
        x_start + total
    } else {
        x_start - total
    };
    let zone = [
        x_start.min(x_end) - 0.3,
        y - width / 2.0 - 0.3,
        x_start.max(x_end) + 0.3,
        y + width / 2.0 + 0.3,
    ];
    let s = Staircase {
        name: "generated stairs".into(),
        start_m: [x_start, y],
        direction_deg: dir,
        steps,
        rise_m: rise,
        run_m: run,
        width_m: width,
        landing_m: landing,
        base_m: 0.0,
    };
    (Some(s), Some(zone))
}

fn place_box(r: &mut Rng, room: &Room, t: f64, stairs: &Option<Zone>) -> Option<Furniture> {
    let (ylo, yhi) = if room.north {
        (room.y_near, room.y_far)
    } else {
        (room.y_far, room.y_near)
    };
    for _ in 0..20 {
        let size = [r.range(0.3, 1.4), r.range(0.3, 1.0), r.range(0.4, 1.6)];
        let half = size[0].max(size[1]) * 0.75;
        let x = r.range(room.x0 + t + half, room.x1 - t - half);
        let y = r.range(ylo + t + half, yhi - t - half);
        let zone = [x - half, y - half, x + half, y + half];
        let door_swing = room.door.map(|(a, b)| {
            let (y0, y1) = if room.north {
                (room.y_near, room.y_near + 1.4)
            } else {
                (room.y_near - 1.4, room.y_near)
            };
            [a - 0.3, y0, b + 0.3, y1]
        });
        let overlaps = |z: &Option<Zone>| {
            z.is_some_and(|z| zone[0] < z[2] && z[0] < zone[2] && zone[1] < z[3] && z[1] < zone[3])
        };
        if x.is_finite() && y.is_finite() && !overlaps(stairs) && !overlaps(&door_swing) {
            return Some(Furniture {
                name: "clutter".into(),
                class: cloud::EntityClass::Furniture,
                material: Default::default(),
                center_m: [x, y, size[2] / 2.0],
                size_m: size,
                yaw_deg: r.range(-45.0, 45.0),
            });
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::generate_building;

    #[test]
    fn same_seed_same_building_and_every_seed_is_valid_and_varied() {
        let cfg = GeneratorConfig::default();
        assert_eq!(
            generate_building(5, &cfg).expect("valid"),
            generate_building(5, &cfg).expect("valid")
        );
        let mut lengths = Vec::new();
        for seed in 0..40 {
            let b = generate_building(seed, &cfg).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            assert!(!b.stairs.is_empty(), "seed {seed}: no staircase");
            let doors: Vec<&Door> = b.walls.iter().flat_map(|w| &w.doors).collect();
            assert!(doors.len() >= 4, "seed {seed}: {} doors", doors.len());
            let open = |lo: f64, hi: f64| {
                doors.iter().any(|d| {
                    d.leaf
                        .as_ref()
                        .is_some_and(|l| l.open_deg >= lo && l.open_deg <= hi)
                })
            };
            assert!(
                open(0.0, 0.0) && open(30.0, 60.0) && open(80.0, 100.0),
                "seed {seed}: door states missing"
            );
            lengths.push(b.floor.max_m[0].to_bits());
        }
        lengths.sort_unstable();
        lengths.dedup();
        assert!(lengths.len() > 30, "buildings do not vary");
    }
}
