//! Fixtures of the obstacles stage's tests (a grid, a car's top, a cluster, a scene), and the
//! stage's own regression.

use super::*;

/// The points of a test data file of the stage's regressions (`tests/data/*.txt`): one
/// `x y z` line per point (metres), `#` lines its description.
pub(crate) fn test_points(text: &str) -> Vec<Vec3> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let v: Vec<f32> = l
                .split_whitespace()
                .map(|t| t.parse().expect("a number"))
                .collect();
            Vec3::new(v[0], v[1], v[2])
        })
        .collect()
}

/// A 4 x 5 m grid of 5 cm cells over x -1..3, y -1..4, moved by `shift` steps of `step_m`
/// (5 along x, then y; the regressions mapped on 25 grids: where the cells fall decides what
/// a cell holds).
pub(crate) fn test_shifted_frame(shift: usize, step_m: f64) -> ImageFrame {
    ImageFrame {
        origin_m: [
            -1.0 + step_m * (shift % 5) as f64,
            4.0 + step_m * (shift / 5) as f64,
        ],
        resolution_m: 0.05,
        width_px: 80,
        height_px: 100,
    }
}

/// A 10 x 6 m grid of 10 cm cells (the frames' and necks' tests).
pub(crate) fn test_grid() -> ImageFrame {
    ImageFrame {
        origin_m: [0.0, 6.0],
        resolution_m: 0.1,
        width_px: 100,
        height_px: 60,
    }
}

/// The top of a boxy car 4.4 x 1.8 m at `p` (the levels' and junctions' tests): its body's at
/// 1.0 m, a cabin 2.2 m long over its middle at 1.44 m; `None` off the car.
pub(crate) fn test_car_top(p: DVec2) -> Option<f32> {
    if !(p.x > 1.0 && p.x < 5.4 && p.y > 2.0 && p.y < 3.8) {
        None
    } else if p.x > 2.1 && p.x < 4.3 {
        Some(1.44)
    } else {
        Some(1.0)
    }
}

/// A cluster with the box `size` around `center` along `dir` as its hull, z range `z` (the
/// merge steps' tests).
pub(crate) fn test_cluster(
    center: [f64; 2],
    dir: DVec2,
    size: [f64; 2],
    z: (f64, f64),
    overhead: bool,
) -> DetectedObstacle {
    let c = DVec2::from_array(center);
    DetectedObstacle {
        class: EntityClass::Obstacle,
        center: c,
        dir,
        size,
        z_range: z,
        hull: fit::rect_corners(c, dir, size).to_vec(),
        fill: 1.0,
        support: 100,
        overhead,
        beside_top: false,
        rules: Vec::new(),
    }
}

/// A scene of `points` (`explained` by other entities or not) over a floor at 0 m under a
/// ceiling at `ceiling_m`, in `image`, with `walls` and nothing kept out (the stage's tests).
pub(crate) fn test_scene<'a>(
    points: &'a [Vec3],
    explained: &'a [bool],
    ceiling_m: f64,
    image: &'a ImageFrame,
    walls: &'a [WallFit],
) -> ObstacleScene<'a> {
    ObstacleScene {
        points,
        explained,
        floor: 0.0,
        ceiling: ceiling_m,
        image,
        walls,
        keep_out: &[],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::classify::fit_cluster;

    /// Regression: a cluster whose points all lie at one height got a box of zero height, which
    /// the simulation refuses (`semsim run` on small_gicp's outdoor pair exited 2).
    #[test]
    fn a_cluster_at_one_height_gets_a_box_with_height() {
        let points: Vec<Vec3> = (0..40)
            .map(|i| Vec3::new(2.0 + 0.01 * i as f32, 3.0 + 0.005 * (i % 7) as f32, 1.2))
            .collect();
        let explained = vec![false; points.len()];
        let image = ImageFrame {
            origin_m: [0.0, 10.0],
            resolution_m: 0.05,
            width_px: 200,
            height_px: 200,
        };
        let scene = test_scene(&points, &explained, 3.0, &image, &[]);
        let members: Vec<u32> = (0..points.len() as u32).collect();
        let o = fit_cluster(
            &scene,
            &members,
            8,
            (1.2, 1.2),
            false,
            &image,
            &ObstacleConfig::default(),
        )
        .expect("a box");
        assert!(o.z_range.1 - o.z_range.0 >= 0.02, "{:?}", o.z_range);
        assert!(o.size.iter().all(|s| *s > 0.0), "{:?}", o.size);
    }
}
