//! `semsim map`: a (registered) cloud -> the semantic map, its labelled cloud and the pictures
//! of every stage; and `semsim eval map`: a semantic map against a building's ground truth.

use crate::config::SemsimConfig;
use crate::exit::bad_input;
use anyhow::Context;
use clap::{Args, Subcommand};
use cloud::{PcdEncoding, PointCloud};
use semantic::{EntityClass, MapOutput, SemanticMap};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `semsim map`.
#[derive(Args)]
pub struct MapArgs {
    /// The cloud(s): one registered map, or scans placed with --poses.
    #[arg(required = true, value_name = "CLOUD")]
    clouds: Vec<PathBuf>,
    /// A pose file (`name` + row-major 4x4 `world_from_scan` per line, as `semsim register`
    /// writes): each scan is placed by the pose of its file stem (or by order).
    #[arg(long, value_name = "FILE")]
    poses: Option<PathBuf>,
    /// Drop points farther than this from their scan's sensor (e.g. 30 for 3DTK's no-echo
    /// readings at 32.7 m).
    #[arg(long, value_name = "M")]
    max_range_m: Option<f64>,
    /// Downsample the merged cloud to this voxel edge first (labels.pcd is then the
    /// downsampled cloud).
    #[arg(long, value_name = "M")]
    voxel_m: Option<f64>,
    /// Output folder.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// `semsim eval ...`.
#[derive(Subcommand)]
pub enum EvalCommand {
    /// Score a semantic map against the building it was scanned in: per-class precision,
    /// recall and F1, wall endpoint errors, stairs step counts and rise/run errors.
    Map(EvalMapArgs),
}

/// Arguments of `semsim eval map`.
#[derive(Args)]
pub struct EvalMapArgs {
    /// The semantic map (semantic_map.json).
    #[arg(value_name = "MAP")]
    map: PathBuf,
    /// The building description (TOML/JSON) it was scanned in; "default" for the built-in one.
    #[arg(long, value_name = "FILE")]
    building: PathBuf,
    /// The scans the map was made from, with their ground-truth labels (as `semsim scan` and
    /// `semsim demo` write them; not the map's labels.pcd, whose labels are the map's own):
    /// only what they saw is expected. Without them every element of the building is expected.
    #[arg(long, value_name = "FILE", num_args = 1..)]
    cloud: Vec<PathBuf>,
    /// World poses of the `--cloud` scans (as for `semsim map`); without it they are taken as
    /// given (already in the world frame).
    #[arg(long, value_name = "FILE", requires = "cloud")]
    poses: Option<PathBuf>,
    /// Print the full evaluation as JSON instead of the table.
    #[arg(long)]
    json: bool,
}

/// Runs `semsim map`.
pub fn run(a: MapArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    if let Some(v) = a.voxel_m {
        if !(v.is_finite() && v > 0.0 && v <= 10.0) {
            return Err(bad_input(format!(
                "--voxel-m {v}: must be a length within (0, 10] m"
            )));
        }
    }
    if let Some(r) = a.max_range_m {
        if !(r.is_finite() && r > 0.0) {
            return Err(bad_input(format!(
                "--max-range-m {r}: must be a positive length"
            )));
        }
    }
    let t0 = Instant::now();
    let mut cloud = merge_scans(&a.clouds, a.poses.as_deref(), a.max_range_m)?;
    if let Some(v) = a.voxel_m {
        cloud = cloud::voxel_downsample(&cloud, v)?;
    }
    println!(
        "semantic map of {} points from {} file(s) (read in {:.0} ms)",
        cloud.len(),
        a.clouds.len(),
        t0.elapsed().as_secs_f64() * 1e3
    );
    let map = map_and_write(&cloud, cfg, &a.out)?;
    println!("{}", summary(&map));
    Ok(())
}

/// Reads the scans, places each with its pose (by file stem, else by order), drops missing
/// returns (and points beyond `max_range_m` from their sensor) and merges them.
pub fn merge_scans(
    files: &[PathBuf],
    poses: Option<&Path>,
    max_range_m: Option<f64>,
) -> anyhow::Result<PointCloud> {
    let poses = poses.map(cloud::read_poses).transpose()?;
    let scans = read_scans(files, max_range_m)?;
    place_and_merge(files, scans, poses.as_deref())
}

/// Reads scans, dropping missing returns and points beyond `max_range_m` from their sensor.
pub fn read_scans(files: &[PathBuf], max_range_m: Option<f64>) -> anyhow::Result<Vec<PointCloud>> {
    files
        .iter()
        .map(|f| {
            let scan = cloud::read_cloud(f)?.without_invalid();
            Ok(match max_range_m {
                Some(r) => keep_within(&scan, scan.sensor_origin, r as f32),
                None => scan,
            })
        })
        .collect()
}

/// Places each scan with its pose (by file stem, else by order) and merges them; labels are
/// kept if every scan has them.
pub fn place_and_merge(
    files: &[PathBuf],
    scans: Vec<PointCloud>,
    poses: Option<&[cloud::NamedPose]>,
) -> anyhow::Result<PointCloud> {
    let stem = |f: &PathBuf| f.file_stem().map(|s| s.to_string_lossy().to_string());
    if let Some(p) = poses {
        let by_name = files
            .iter()
            .all(|f| p.iter().any(|q| Some(&q.name) == stem(f).as_ref()));
        if !by_name && p.len() != files.len() {
            return Err(bad_input(format!(
                "{} poses for {} clouds, and not every cloud's file stem names a pose",
                p.len(),
                files.len()
            )));
        }
    }
    let mut merged = PointCloud::default();
    let mut labels = Vec::new();
    let mut all_labelled = true;
    for (k, (f, mut scan)) in files.iter().zip(scans).enumerate() {
        if let Some(p) = poses {
            let pose = p
                .iter()
                .find(|q| Some(&q.name) == stem(f).as_ref())
                .or_else(|| p.get(k))
                .map(|q| q.world_from_scan)
                .with_context(|| format!("no pose for {}", f.display()))?;
            scan.transform(&pose);
        }
        all_labelled &= scan.labels.is_some();
        labels.extend(scan.labels.take().unwrap_or_default());
        merged.points.extend(scan.points);
    }
    merged.labels = all_labelled.then_some(labels);
    Ok(merged)
}

fn keep_within(scan: &PointCloud, sensor: glam::Vec3, r: f32) -> PointCloud {
    let keep: Vec<usize> = (0..scan.len())
        .filter(|&i| scan.points[i].distance(sensor) <= r)
        .collect();
    PointCloud {
        points: keep.iter().map(|&i| scan.points[i]).collect(),
        intensity: scan
            .intensity
            .as_ref()
            .map(|v| keep.iter().map(|&i| v[i]).collect()),
        labels: scan
            .labels
            .as_ref()
            .map(|v| keep.iter().map(|&i| v[i]).collect()),
        organized: None,
        sensor_origin: scan.sensor_origin,
        sensor_orientation: scan.sensor_orientation,
    }
}

/// Builds the semantic map of `cloud` and writes `semantic_map.json`, `labels.pcd`, the
/// pictures of every stage and `config.toml` into `out`; prints the stage times.
pub fn map_and_write(
    cloud: &PointCloud,
    cfg: &SemsimConfig,
    out: &Path,
) -> anyhow::Result<SemanticMap> {
    let output = semantic::build_semantic_map(cloud, &cfg.semantic)?;
    std::fs::create_dir_all(out).map_err(|e| cloud::CloudError::io(out, e))?;
    output.map.save(&out.join("semantic_map.json"))?;
    cloud::io::pcd::write_pcd(
        &out.join("labels.pcd"),
        &output.labelled_cloud(cloud),
        PcdEncoding::Binary,
    )?;
    write_pictures(&output, cloud, out)?;
    cfg.write_beside(out)?;
    let times: Vec<String> = output
        .timings
        .iter()
        .map(|t| format!("{} {:.0}", t.stage, t.ms))
        .collect();
    println!(
        "stages (ms): {} = {:.0} ms",
        times.join(", "),
        output.total_ms()
    );
    println!(
        "wrote {}/semantic_map.json, labels.pcd, projection.png, filtered.png, dilated.png, \
         skeleton.png, segments.png, merged_segments.png, top_view.png, labels.png, config.toml",
        out.display()
    );
    Ok(output.map)
}

fn write_pictures(o: &MapOutput, cloud: &PointCloud, out: &Path) -> anyhow::Result<()> {
    use semantic::{render_labels, render_segments, render_top_view, save_png};
    save_png(&out.join("projection.png"), o.projection.clone())?;
    save_png(&out.join("filtered.png"), o.filtered.clone())?;
    save_png(&out.join("dilated.png"), o.dilated.clone())?;
    save_png(&out.join("skeleton.png"), o.skeleton.clone())?;
    let red = [220, 30, 30];
    save_png(
        &out.join("segments.png"),
        render_segments(&o.skeleton, &o.frame, &o.hough_segments, red),
    )?;
    save_png(
        &out.join("merged_segments.png"),
        render_segments(&o.projection, &o.frame, &o.merged_segments, red),
    )?;
    save_png(&out.join("top_view.png"), render_top_view(&o.map, &o.frame))?;
    save_png(
        &out.join("labels.png"),
        render_labels(cloud, &o.labels, &o.map, &o.frame),
    )?;
    Ok(())
}

/// One line per class with its count, and the number of relations.
pub fn summary(map: &SemanticMap) -> String {
    let classes = [
        EntityClass::Floor,
        EntityClass::Ceiling,
        EntityClass::Wall,
        EntityClass::WallAboveDoor,
        EntityClass::Door,
        EntityClass::FreeSpaceForDoor,
        EntityClass::Stairs,
    ];
    let counts: Vec<String> = classes
        .iter()
        .map(|c| format!("{} {}", map.of_class(*c).count(), c.name()))
        .collect();
    format!(
        "entities: {}; {} relations",
        counts.join(", "),
        map.relations.len()
    )
}

/// Checks that `cloud`'s labels are `building`'s ground truth: a sample of the labelled points
/// must lie on the building's entities of those ids (a map's labels.pcd carries the map's own
/// ids, which name other entities elsewhere).
fn check_ground_truth(cloud: &PointCloud, building: &scanner::Building) -> anyhow::Result<()> {
    let Some(labels) = &cloud.labels else {
        return Err(bad_input(
            "--cloud: the scans carry no labels; give the scans with their ground-truth labels",
        ));
    };
    let geometry = scanner::BuildingGeometry::new(building);
    let labelled: Vec<usize> = (0..labels.len())
        .filter(|&i| labels[i].entity != 0 && cloud.points[i].is_finite())
        .collect();
    let sample: Vec<usize> = labelled
        .iter()
        .copied()
        .step_by((labelled.len() / 2000).max(1))
        .collect();
    let on = sample
        .iter()
        .filter(|&&i| geometry.distance_to_entity(cloud.points[i], labels[i].entity) <= 0.1)
        .count();
    if sample.is_empty() || (on as f64) < 0.9 * sample.len() as f64 {
        return Err(bad_input(format!(
            "--cloud: only {on} of {} sampled labelled points lie on the building's entity of \
             their label: these are not its ground-truth labels (a map's labels.pcd holds the \
             map's own ids), or the scans are not placed (give --poses); give the scans as \
             `semsim scan` or `semsim demo` wrote them",
            sample.len()
        )));
    }
    Ok(())
}

/// Runs `semsim eval ...`.
pub fn run_eval(c: EvalCommand) -> anyhow::Result<()> {
    let EvalCommand::Map(a) = c;
    let map = SemanticMap::load(&a.map)?;
    let building = if a.building.as_os_str() == "default" {
        scanner::Building::default_building()?
    } else {
        scanner::Building::load(&a.building)?
    };
    let observed = if a.cloud.is_empty() {
        None
    } else {
        let merged = merge_scans(&a.cloud, a.poses.as_deref(), None)?;
        check_ground_truth(&merged, &building)?;
        Some(merged)
    };
    let ev = semantic::evaluate(&map, &building, observed.as_ref());
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&ev).context("serialising the evaluation")?
        );
        return Ok(());
    }
    println!(
        "{:<16} {:>8} {:>8} {:>8} {:>6} {:>6} {:>6}",
        "class", "expected", "detected", "matched", "P", "R", "F1"
    );
    for (name, s) in [
        ("walls", &ev.walls),
        ("door openings", &ev.door_openings),
        ("door leaves", &ev.doors),
        ("floor", &ev.floor),
        ("ceiling", &ev.ceiling),
        ("stairs", &ev.stairs),
    ] {
        println!(
            "{name:<16} {:>8} {:>8} {:>8} {:>6.3} {:>6.3} {:>6.3}",
            s.expected, s.detected, s.matched, s.precision, s.recall, s.f1
        );
    }
    println!(
        "wall endpoint error: mean {:.3} m, max {:.3} m",
        ev.wall_endpoint_error_mean_m, ev.wall_endpoint_error_max_m
    );
    for s in &ev.stairs_matches {
        println!(
            "stairs {}: {} steps (truth {}), rise error {:+.3} m, run error {:+.3} m",
            s.truth, s.steps, s.steps_truth, s.rise_error_m, s.run_error_m
        );
    }
    if !ev.missed.is_empty() {
        println!("missed: {}", ev.missed.join(", "));
    }
    if !ev.spurious.is_empty() {
        println!("spurious entity ids: {:?}", ev.spurious);
    }
    Ok(())
}
