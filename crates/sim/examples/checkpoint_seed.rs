//! Writes the checkpoint of a small simulation (a 6 m x 4 m room with one wall ahead of a
//! Pioneer 3-AT driving at it, after 30 steps): the fuzz seed of the `checkpoint` target.
//!
//! `cargo run -p sim --example checkpoint_seed -- fuzz/formats/corpus/checkpoint/room.ckpt`

use sim::{RobotModel, Scenario, Simulation, WorldSpec};
use std::path::PathBuf;

const BUILDING: &str = r#"
[floor]
min_m = [0.0, -2.0]
max_m = [6.0, 2.0]
[ceiling]
height_m = 2.5
[[walls]]
start_m = [5.0, -2.0]
end_m = [5.0, 2.0]
thickness_m = 0.2
"#;

const SCENARIO: &str = r#"
robot = "pioneer3at"
time_limit_s = 4.0
start = { x_m = 2.0, y_m = 0.0, yaw_deg = 0.0 }
[[velocity]]
from_s = 0.1
to_s = 4.0
linear_mps = 0.6
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .ok_or("usage: checkpoint_seed OUT_FILE")?;
    let building = scanner::Building::from_toml_str(BUILDING, std::path::Path::new("room.toml"))?;
    let spec = WorldSpec::from_building(&building)?;
    let scenario = Scenario::from_toml_str(SCENARIO, "checkpoint_seed")?;
    let model = RobotModel::builtin(&scenario.robot)?;
    let mut simulation = Simulation::new(&spec, &scenario, &model)?;
    for _ in 0..30 {
        simulation.step();
    }
    simulation.save_checkpoint(&out)?;
    println!(
        "{}: checkpoint at t = {:.3} s",
        out.display(),
        simulation.time_s()
    );
    Ok(())
}
