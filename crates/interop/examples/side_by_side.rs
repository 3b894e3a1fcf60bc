//! semsim's half of `bench/mujoco_side_by_side.sh`: exports the default building's world with
//! a robot to MJCF, then runs the same world, robot and commands in semsim's own simulation
//! (`sim::Simulation`, event detectors and judge included) and prints, as JSON, how fast it
//! ran and where the robot and the doors ended.
//!
//! ```text
//! cargo run --release -p interop --example side_by_side -- OUT_DIR [--robot NAME]
//!     [--start X,Y,YAW_DEG] [--speed MPS] [--drive-s S] [--seconds S] [--runs N]
//! ```
//! The robot drives straight at `--speed` from 0 to `--drive-s` simulated seconds, then
//! brakes until `--seconds`. The MJCF is `OUT_DIR/world.xml`.

use interop::{write_export, ExportFormat, ExportOptions};
use serde_json::json;
use sim::{RobotModel, Scenario, Simulation, StartPose, WorldSpec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

struct Args {
    out_dir: PathBuf,
    robot: String,
    start: StartPose,
    speed_mps: f64,
    drive_s: f64,
    seconds: f64,
    runs: usize,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let [out_dir, rest @ ..] = args else {
        return Err(
            "usage: side_by_side OUT_DIR [--robot NAME] [--start X,Y,YAW_DEG] \
                    [--speed MPS] [--drive-s S] [--seconds S] [--runs N]"
                .into(),
        );
    };
    let mut a = Args {
        out_dir: PathBuf::from(out_dir),
        robot: "pioneer3at".into(),
        start: StartPose {
            x_m: 2.55,
            y_m: -0.6,
            yaw_deg: 90.0,
            z_m: 0.0,
        },
        speed_mps: 0.4,
        drive_s: 10.0,
        seconds: 20.0,
        runs: 5,
    };
    let mut it = rest.iter();
    while let Some(flag) = it.next() {
        let value = it.next().ok_or_else(|| format!("{flag} needs a value"))?;
        let number = || {
            value
                .parse::<f64>()
                .map_err(|_| format!("{flag} {value:?}: not a number"))
        };
        match flag.as_str() {
            "--robot" => a.robot = value.clone(),
            "--speed" => a.speed_mps = number()?,
            "--drive-s" => a.drive_s = number()?,
            "--seconds" => a.seconds = number()?,
            "--runs" => a.runs = number()?.max(1.0) as usize,
            "--start" => {
                let v: Vec<f64> = value
                    .split(',')
                    .map(|s| s.trim().parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| format!("--start {value:?}: expected X,Y,YAW_DEG"))?;
                let [x_m, y_m, yaw_deg] = v[..] else {
                    return Err(format!("--start {value:?}: expected X,Y,YAW_DEG"));
                };
                a.start = StartPose {
                    x_m,
                    y_m,
                    yaw_deg,
                    z_m: 0.0,
                };
            }
            _ => return Err(format!("unknown option {flag}")),
        }
    }
    Ok(a)
}

fn run(args: &[String]) -> Result<serde_json::Value, String> {
    let a = parse(args)?;
    let building = scanner::Building::default_building().map_err(|e| e.to_string())?;
    let spec = WorldSpec::from_building(&building).map_err(|e| e.to_string())?;
    let model = RobotModel::resolve(&a.robot, Path::new(".")).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&a.out_dir).map_err(|e| format!("{}: {e}", a.out_dir.display()))?;
    let mjcf = a.out_dir.join("world.xml");
    let options = ExportOptions {
        robot: Some((&model, a.start)),
        ..Default::default()
    };
    write_export(&mjcf, &spec, ExportFormat::Mjcf, &options).map_err(|e| e.to_string())?;
    let scenario = Scenario::from_toml_str(
        &format!(
            "robot = {:?}\ntime_limit_s = {}\ntrajectory_rate_hz = 10.0\n\
             start = {{ x_m = {}, y_m = {}, yaw_deg = {} }}\n\
             [[velocity]]\nfrom_s = 0.0\nto_s = {}\nlinear_mps = {}\n",
            model.name,
            a.seconds,
            a.start.x_m,
            a.start.y_m,
            a.start.yaw_deg,
            a.drive_s,
            a.speed_mps
        ),
        "side by side",
    )
    .map_err(|e| e.to_string())?;
    let mut wall = vec![];
    let mut last = None;
    for _ in 0..a.runs {
        let mut sim = Simulation::new(&spec, &scenario, &model).map_err(|e| e.to_string())?;
        let t0 = Instant::now();
        sim.run();
        wall.push(t0.elapsed().as_secs_f64());
        last = Some(sim);
    }
    let sim = last.ok_or("no run")?;
    wall.sort_by(f64::total_cmp);
    let median = wall[wall.len() / 2];
    let pose = sim.robot_pose();
    let doors: serde_json::Map<String, serde_json::Value> = spec
        .doors
        .iter()
        .map(|d| {
            (
                format!("door_{}", d.entity),
                json!(sim.world().door_angle_deg(d.entity)),
            )
        })
        .collect();
    Ok(json!({
        "mjcf": mjcf,
        "robot": model.name,
        "wheel_radius_m": model.wheels[0].radius_m,
        "start": { "x_m": a.start.x_m, "y_m": a.start.y_m, "yaw_deg": a.start.yaw_deg },
        "command": { "linear_mps": a.speed_mps, "from_s": 0.0, "to_s": a.drive_s },
        "seconds": a.seconds,
        "dt_s": scenario.world.dt_secs,
        "semsim": {
            "steps": sim.steps(),
            "sim_s": sim.time_s(),
            "wall_s": wall,
            "wall_s_median": median,
            "sim_s_per_wall_s": sim.time_s() / median,
            "final": { "x_m": pose.x_m, "y_m": pose.y_m, "z_m": pose.z_m, "yaw_deg": pose.yaw_deg },
            "doors_deg": doors,
            "events": sim.events().iter().filter(|e| e.kind.is_significant()).count(),
        },
    }))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(report) => {
            println!("{report:#}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("side_by_side: {e}");
            ExitCode::FAILURE
        }
    }
}
