//! The semantic map of 3DTK's 2009 corridor (three registered scans), with its images.
//!
//! `cargo run --release -p semantic --example corridor -- [--out DIR] [--config CONFIG.json]
//! [--histogram] [--profile] [--segments]` (the last three print diagnostics: the z histogram of
//! the corridor, the south wall's position along the corridor, the merged segments).

use semantic::{build_semantic_map, render_segments, render_top_view, EntityClass, SemanticConfig};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out_dir = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map(PathBuf::from);
    let Some(cloud) = fixtures::threedtk_corridor() else {
        eprintln!(
            "3DTK corridor data not found beside the checkout (../shared/data/real/3dtk-corridor)"
        );
        return Ok(());
    };
    let config: SemanticConfig = match args
        .iter()
        .position(|a| a == "--config")
        .and_then(|i| args.get(i + 1))
    {
        Some(path) => serde_json::from_str(&std::fs::read_to_string(path)?)?,
        None => SemanticConfig::default(),
    };
    let out = build_semantic_map(&cloud, &config)?;
    eprintln!(
        "{} points, tilt {:.2} deg, floor {:?} ceiling {:?}, {:.0} ms",
        cloud.len(),
        out.tilt_deg,
        out.floor_z_m,
        out.ceiling_z_m,
        out.total_ms()
    );
    if args.iter().any(|a| a == "--histogram") {
        let t = out.map.input_from_map().inverse();
        let mut h = std::collections::BTreeMap::<i32, usize>::new();
        for p in &cloud.points {
            let q = t.transform_point3(p.as_dvec3());
            // corridor part only: y within the corridor walls
            if q.y > -1.0 && q.y < 1.6 {
                *h.entry((q.z / 0.05).floor() as i32).or_default() += 1;
            }
        }
        for (k, n) in h {
            eprintln!("z {:+.2}: {n}", k as f64 * 0.05);
        }
        let f = out.floor_z_m.unwrap_or(0.0);
        for tol in [0.01, 0.02, 0.04] {
            let n = cloud
                .points
                .iter()
                .filter(|p| (t.transform_point3(p.as_dvec3()).z - f).abs() <= tol)
                .count();
            eprintln!("floor points within {tol} m: {n}");
        }
    }
    if args.iter().any(|a| a == "--profile") {
        let t = out.map.input_from_map().inverse();
        let mut cols = std::collections::BTreeMap::<i32, Vec<f64>>::new();
        for p in &cloud.points {
            let q = t.transform_point3(p.as_dvec3());
            if q.z > 1.0 && q.z < 1.9 && q.y > -1.3 && q.y < -0.3 {
                cols.entry((q.x * 2.0).floor() as i32)
                    .or_default()
                    .push(q.y);
            }
        }
        for (k, mut v) in cols {
            v.sort_by(f64::total_cmp);
            let hist: Vec<usize> = (0..20)
                .map(|b| {
                    v.iter()
                        .filter(|y| ((**y + 1.3) / 0.05) as usize == b)
                        .count()
                })
                .collect();
            eprintln!(
                "x {:5.1}: n {:5} y-hist(5cm from -1.3) {hist:?}",
                k as f64 / 2.0,
                v.len()
            );
        }
    }
    if args.iter().any(|a| a == "--segments") {
        for s in &out.merged_segments {
            eprintln!(
                "merged {:?} -> {:?} ({:.2} m)",
                s.a_m.map(|v| (v * 100.0).round() / 100.0),
                s.b_m.map(|v| (v * 100.0).round() / 100.0),
                s.length_m()
            );
        }
    }
    for e in &out.map.entities {
        let extra = match (&e.wall, &e.opening) {
            (Some(w), _) => format!(
                "segment {:?} thickness {:.2} ({}) z {:?}",
                w.segment_m.map(|p| p.map(|v| (v * 100.0).round() / 100.0)),
                w.thickness_m,
                if w.thickness_measured {
                    "measured"
                } else {
                    "assumed"
                },
                w.z_range_m.map(|v| (v * 100.0).round() / 100.0)
            ),
            (_, Some(o)) => format!(
                "offset {:.2} width {:.2} height {:.2}",
                o.offset_m, o.width_m, o.height_m
            ),
            _ => format!(
                "centre {:?}",
                e.geometry.center_m.map(|v| (v * 100.0).round() / 100.0)
            ),
        };
        println!(
            "{:3} {:20} {:7} pts  {extra}",
            e.id,
            e.class.name(),
            e.support_points
        );
    }
    println!(
        "walls {}, openings {}, doors {}",
        out.map.of_class(EntityClass::Wall).count(),
        out.map.of_class(EntityClass::FreeSpaceForDoor).count(),
        out.map.of_class(EntityClass::Door).count()
    );
    if let Some(dir) = out_dir {
        std::fs::create_dir_all(&dir)?;
        out.projection.save(dir.join("projection.png"))?;
        out.skeleton.save(dir.join("skeleton.png"))?;
        render_segments(
            &out.projection,
            &out.frame,
            &out.merged_segments,
            [255, 0, 0],
        )
        .save(dir.join("segments.png"))?;
        render_top_view(&out.map, &out.frame).save(dir.join("top_view.png"))?;
        semantic::render_labels(&cloud, &out.labels, &out.map, &out.frame)
            .save(dir.join("labels.png"))?;
        out.map.save(&dir.join("map.json"))?;
    }
    Ok(())
}
