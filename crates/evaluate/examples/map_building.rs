//! Builds the semantic map of a generated building (or the default one) scanned by the virtual
//! laser, evaluates it and optionally writes the images and the map.
//!
//! `cargo run --release -p evaluate --example map_building -- SEED|default [--full] [--voxel M]
//! [--config CONFIG.json] [--out DIR]` (`--full`: the laser's full 541 x 301 resolution instead
//! of the tests' 271 x 151; `--voxel`: downsampling, default 0.03 m). `--out` writes the stage
//! images, the map, a top view, the labelled points and a side view of the first staircase.

use evaluate::{evaluate, evaluate_labels};
use scanner::{Building, BuildingGeometry, LaserConfig};
use semantic::{build_semantic_map, render_segments, render_top_view, SemanticConfig};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let which = args.first().map(String::as_str).unwrap_or("default");
    let full = args.iter().any(|a| a == "--full");
    let out_dir = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map(PathBuf::from);
    let voxel = args
        .iter()
        .position(|a| a == "--voxel")
        .and_then(|i| args.get(i + 1))
        .map(|v| v.parse())
        .transpose()?
        .unwrap_or(0.03);
    let b: Building = if which == "default" {
        Building::default_building()?
    } else {
        scanner::generate_building(which.parse()?, &scanner::GeneratorConfig::default())?
    };
    let g = BuildingGeometry::new(&b);
    let poses = fixtures::survey_poses(&b, &g);
    let laser = if full {
        LaserConfig::default()
    } else {
        fixtures::test_laser()
    };
    for s in &b.stairs {
        eprintln!("truth stairs: start {:?} dir {} steps {} rise {:.3} run {:.3} width {:.2} landing {:.2}", s.start_m, s.direction_deg, s.steps, s.rise_m, s.run_m, s.width_m, s.landing_m);
    }
    eprintln!(
        "poses: {:?}",
        poses.iter().map(|p| (p.x_m, p.y_m)).collect::<Vec<_>>()
    );
    let t = std::time::Instant::now();
    let cloud = fixtures::scan_building(&b, &poses, &laser, voxel);
    eprintln!(
        "{} poses, {} points after {voxel} m voxels, scanned in {:.2} s",
        poses.len(),
        cloud.len(),
        t.elapsed().as_secs_f64()
    );
    let config: SemanticConfig = match args
        .iter()
        .position(|a| a == "--config")
        .and_then(|i| args.get(i + 1))
    {
        Some(path) => serde_json::from_str(&std::fs::read_to_string(path)?)?,
        None => SemanticConfig::default(),
    };
    let out = build_semantic_map(&cloud, &config)?;
    let timings: Vec<String> = out
        .timings
        .iter()
        .map(|t| format!("{} {:.1}", t.stage, t.ms))
        .collect();
    eprintln!("map in {:.1} ms: {}", out.total_ms(), timings.join(", "));
    let ev = evaluate(&out.map, &b, Some(&cloud));
    let labels = evaluate_labels(&out.labels, cloud.labels.as_deref().unwrap_or_default());
    println!("{}", serde_json::to_string_pretty(&ev)?);
    eprintln!(
        "walls F1 {:.3} ({}/{}/{}), openings F1 {:.3} ({}/{}/{}), leaves F1 {:.3}, floor {} ceiling {}, stairs {:?}, endpoint error {:.3} m, label accuracy {:.3}",
        ev.walls.f1, ev.walls.matched, ev.walls.detected, ev.walls.expected,
        ev.door_openings.f1, ev.door_openings.matched, ev.door_openings.detected, ev.door_openings.expected,
        ev.doors.f1, ev.floor.matched, ev.ceiling.matched,
        ev.stairs_matches.iter().map(|s| (s.steps_truth, s.steps, (s.rise_error_m * 1000.0).round(), (s.run_error_m * 1000.0).round())).collect::<Vec<_>>(),
        ev.wall_endpoint_error_mean_m, labels.accuracy
    );
    eprintln!("missed {:?} spurious {:?}", ev.missed, ev.spurious);
    if let (Some(dir), Some(st)) = (&out_dir, b.stairs.first()) {
        // Side view of the points around the true staircase: along its ascent (x) against z.
        let d = glam::DVec2::from_angle(st.direction_deg.to_radians());
        let o = glam::DVec2::from_array(st.start_m);
        let len = st.steps as f64 * st.run_m + st.landing_m;
        let (sx, sz) = (200.0, 200.0); // pixels per metre
        let mut img = image::RgbImage::from_pixel(
            ((len + 1.0) * sx) as u32,
            (1.6 * sz) as u32,
            image::Rgb([255, 255, 255]),
        );
        for (p, l) in cloud
            .points
            .iter()
            .zip(cloud.labels.as_deref().unwrap_or_default())
        {
            let q = glam::DVec2::new(p.x as f64, p.y as f64) - o;
            let (a, t) = (q.dot(d), d.perp_dot(q));
            if t.abs() > st.width_m / 2.0 + 0.3 || a < -0.5 || a > len + 0.5 || p.z < 0.02 {
                continue;
            }
            let (x, y) = (((a + 0.5) * sx) as i64, ((1.6 - p.z as f64) * sz) as i64);
            if x >= 0 && y >= 0 && (x as u32) < img.width() && (y as u32) < img.height() {
                let c = if l.class == cloud::EntityClass::Stairs {
                    [200, 100, 0]
                } else {
                    [0, 0, 200]
                };
                img.put_pixel(x as u32, y as u32, image::Rgb(c));
            }
        }
        for k in 0..=st.steps {
            let (x, y) = (
                ((k as f64 * st.run_m + 0.5) * sx) as u32,
                ((1.6 - k as f64 * st.rise_m) * sz) as u32,
            );
            for dx in 0..(st.run_m * sx) as u32 {
                if x + dx < img.width() && y < img.height() {
                    img.put_pixel(x + dx, y, image::Rgb([0, 180, 0]));
                }
            }
        }
        img.save(dir.join("stairs_side.png"))?;
    }
    if let Some(dir) = out_dir {
        std::fs::create_dir_all(&dir)?;
        semantic::save_png(&dir.join("projection.png"), out.projection.clone())?;
        semantic::save_png(&dir.join("filtered.png"), out.filtered.clone())?;
        semantic::save_png(&dir.join("dilated.png"), out.dilated.clone())?;
        semantic::save_png(&dir.join("skeleton.png"), out.skeleton.clone())?;
        render_segments(&out.skeleton, &out.frame, &out.merged_segments, [255, 0, 0])
            .save(dir.join("segments.png"))?;
        render_top_view(&out.map, &out.frame).save(dir.join("top_view.png"))?;
        semantic::render_labels(&cloud, &out.labels, &out.map, &out.frame)
            .save(dir.join("labels.png"))?;
        out.map.save(&dir.join("map.json"))?;
    }
    Ok(())
}
