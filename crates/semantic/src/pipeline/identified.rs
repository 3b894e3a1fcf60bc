//! Steps 4 to 6a of the pipeline: the semantic net, the map points' labels and the ramps. A
//! staircase whose treads lie on a ramp's footprint is the ramp's side face read as steps (a
//! sparsely sampled side face's top edge is itself stepped; no flight stands on a ramp, whose
//! profile climbs in one straight line): it is dropped, and the net, the labels and the ramps
//! are made again without it (its points then go to the ramp).

use super::output::Clock;
use super::SemanticConfig;
use crate::image_frame::ImageFrame;
use crate::labels::label_points;
use crate::map::{OrientedBox, SemanticMap};
use crate::net::{assemble, Detections, Ids};
use crate::points::XyIndex;
use crate::ramps::{find_ramps, DetectedRamp, RampScene};
use crate::stairs::DetectedStairs;
use cloud::{EntityClass, Label};
use glam::{DVec2, Vec3};

/// The share of a flight's treads on a ramp's footprint at which it is the ramp's side face.
const ON_RAMP_SHARE: f64 = 0.5;

/// What steps 4 to 6a made.
pub(super) struct Identified {
    pub map: SemanticMap,
    pub ids: Ids,
    /// Per map point: its entity (0: none yet).
    pub map_labels: Vec<Label>,
    /// Boxes no ramp or obstacle may take: door leaves' swings and staircases.
    pub keep_out: Vec<OrientedBox>,
    pub ramps: Vec<DetectedRamp>,
}

/// The net, the labels and the ramps of `det`, without the staircases on a ramp (dropped from
/// `det`, each said in the rules of the ramp it lay on).
pub(super) fn identify_net_and_ramps(
    det: &mut Detections,
    points: &[Vec3],
    index: &XyIndex,
    frame: &ImageFrame,
    config: &SemanticConfig,
    clock: &mut Clock,
) -> Identified {
    let mut dropped: Vec<DetectedStairs> = Vec::new();
    loop {
        // 4. The semantic net: entities with ids and boxes, and their relations.
        let (map, ids) = assemble(det, &config.net);
        clock.lap("net");
        // 5. Per-point labels of those entities (map points).
        let map_labels = label_points(points, index, det, &ids, &config.labels);
        clock.lap("labels");
        // 6a. Ramps: among the points no entity labelled, off door swings and staircases.
        let explained: Vec<bool> = map_labels.iter().map(|l| l.entity != 0).collect();
        let keep_out = keep_out_boxes(&map);
        let scene = RampScene {
            points,
            explained: &explained,
            floor: det.levels.floor_ref_m,
            image: frame,
            walls: &det.walls,
            keep_out: &keep_out,
        };
        let mut ramps = find_ramps(&scene, &config.ramps, config.projection.max_pixels);
        clock.lap("ramps");
        // A staircase on a ramp: dropped, and all of it made again without it.
        let (on_ramp, kept): (Vec<_>, Vec<_>) = std::mem::take(&mut det.stairs)
            .into_iter()
            .partition(|s| ramps.iter().any(|r| on_ramp_share(s, r) >= ON_RAMP_SHARE));
        det.stairs = kept;
        if on_ramp.is_empty() {
            note_dropped(&mut ramps, &dropped);
            return Identified {
                map,
                ids,
                map_labels,
                keep_out,
                ramps,
            };
        }
        dropped.extend(on_ramp);
    }
}

/// Door leaves' swings and staircases' boxes: no ramp or obstacle takes their points.
fn keep_out_boxes(map: &SemanticMap) -> Vec<OrientedBox> {
    map.entities
        .iter()
        .filter_map(|e| match (&e.class, &e.door) {
            (EntityClass::Door, Some(d)) => Some(d.swing_square(&e.geometry)),
            (EntityClass::Stairs, _) => Some(e.geometry),
            _ => None,
        })
        .collect()
}

/// The share of `s`'s treads (from its first step's front edge to its top step's back edge,
/// across its width) on `r`'s footprint, from a grid of 10 x 10 samples.
fn on_ramp_share(s: &DetectedStairs, r: &DetectedRamp) -> f64 {
    const N: usize = 10;
    let across = s.dir.perp();
    let length = s.steps as f64 * s.run;
    let (r_across, half) = (r.dir.perp(), DVec2::new(r.size[0], r.size[1]) / 2.0);
    let mut on = 0;
    for i in 0..N {
        for j in 0..N {
            let t = (i as f64 + 0.5) / N as f64;
            let u = (j as f64 + 0.5) / N as f64 - 0.5;
            let p = s.start + s.dir * (t * length) + across * (u * s.width) - r.center;
            if p.dot(r.dir).abs() <= half.x && p.dot(r_across).abs() <= half.y {
                on += 1;
            }
        }
    }
    on as f64 / (N * N) as f64
}

/// Says, in the rules of the ramp each dropped staircase lay on, that it was dropped.
fn note_dropped(ramps: &mut [DetectedRamp], dropped: &[DetectedStairs]) {
    for s in dropped {
        let best = ramps
            .iter_mut()
            .map(|r| (on_ramp_share(s, r), r))
            .filter(|(share, _)| *share > 0.0)
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((share, r)) = best {
            r.rules.push(format!(
                "a {}-step staircase read on it ({:.0}% of its treads on the ramp's footprint) \
                 dropped: its side face's top edge, sampled sparsely, reads as steps, and no \
                 flight stands on a ramp",
                s.steps,
                100.0 * share
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ramp climbing +Y over x 45.5-48.5, y 1-10 (garage-382 of the blind seeds 381-385).
    fn ramp() -> DetectedRamp {
        DetectedRamp {
            center: DVec2::new(47.0, 5.5),
            dir: DVec2::Y,
            size: [9.0, 3.0],
            z_range: (0.0, 1.0),
            fill: 0.9,
            points: Vec::new(),
            rules: Vec::new(),
        }
    }

    /// A 3-step flight climbing +Y from `(x, 2.75)`, 1 m wide.
    fn flight(x: f64) -> DetectedStairs {
        DetectedStairs {
            dir: DVec2::Y,
            start: DVec2::new(x, 2.75),
            ..DetectedStairs::straight(0.0, 3, 0.13, 0.41)
        }
    }

    #[test]
    fn a_flight_read_on_a_ramps_side_face_lies_on_its_footprint() {
        // garage-382: a "flight" of 3 steps of 0.13 x 0.41 m along the ramp's west edge.
        assert!(on_ramp_share(&flight(46.0), &ramp()) >= ON_RAMP_SHARE);
    }

    #[test]
    fn a_flight_beside_a_ramp_is_kept() {
        // A real flight beside the ramp: its treads end 0.2 m into the ramp's footprint at most.
        assert!(on_ramp_share(&flight(45.3), &ramp()) < ON_RAMP_SHARE);
        assert_eq!(on_ramp_share(&flight(44.0), &ramp()), 0.0);
        // ... and one climbing across the ramp's foot, before it.
        let across = DetectedStairs {
            dir: DVec2::X,
            start: DVec2::new(45.0, 0.5),
            ..DetectedStairs::straight(0.0, 8, 0.18, 0.3)
        };
        assert!(on_ramp_share(&across, &ramp()) < ON_RAMP_SHARE);
    }

    #[test]
    fn a_dropped_flight_is_said_in_its_ramps_rules() {
        let mut ramps = vec![ramp()];
        note_dropped(&mut ramps, &[flight(46.0)]);
        assert_eq!(ramps[0].rules.len(), 1);
        assert!(
            ramps[0].rules[0].contains("3-step staircase"),
            "{:?}",
            ramps[0].rules
        );
    }
}
