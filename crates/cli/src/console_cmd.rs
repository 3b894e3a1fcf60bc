//! `semsim console`: the operator console, a local web server showing the world in 3D where a
//! person drives the robot live; each session is saved as a run folder. The CLI only parses
//! the arguments, prints the URL and the folders saved (the console crate does the rest).

use crate::exit::bad_input;
use clap::Args;
use console::{
    CloudLayer, Console, ConsoleConfig, ConsoleWorld, RecordedRun, RunConsole, RunSetup,
    SessionSetup, MAX_CLOUD_POINTS,
};
use pipeline::ScenarioSource;
use scanner::Building;
use sim::RobotModel;
use std::io::Write as _;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::{Path, PathBuf};

/// Arguments of `semsim console`.
#[derive(Args)]
pub struct ConsoleArgs {
    /// A semantic map (semantic_map.json): the world is built from its entities. A folder
    /// (`semsim demo`'s or `semsim run`'s output) means its `map/semantic_map.json`.
    #[arg(long, value_name = "FILE|DIR", conflicts_with = "building")]
    map: Option<PathBuf>,
    /// A building description (TOML/JSON), or "default" for the built-in building; default:
    /// the scenario's building.
    #[arg(long, value_name = "FILE")]
    building: Option<PathBuf>,
    /// The scenario (TOML): robot, start, time limit and the rules the session is judged by;
    /// default: the built-in default scenario. Its scripted commands drive until the operator
    /// does.
    #[arg(long, value_name = "FILE")]
    scenario: Option<PathBuf>,
    /// The robot instead of the scenario's: a built-in name (pioneer3at, inspection), a robot
    /// TOML or a URDF file.
    #[arg(long, value_name = "NAME|FILE")]
    robot: Option<String>,
    /// Replay a recorded run folder (from `semsim simulate` or a console session) with a time
    /// slider instead of a live simulation; its world is --map or --building (default: its
    /// scenario's building). Nothing can be driven.
    #[arg(long, value_name = "RUN_DIR", conflicts_with_all = ["scenario", "robot"])]
    run: Option<PathBuf>,
    /// A registered point cloud (PCD or any cloud file semsim reads) shown as a layer,
    /// downsampled to at most 200,000 points, coloured by class (its `class` field) or by
    /// height. Default: the cloud beside --map (`labels.pcd`, else `../registration/map.pcd`)
    /// or beside --run's folder (`../map/labels.pcd`, `../registration/map.pcd`), if there is
    /// one.
    #[arg(long, value_name = "FILE")]
    cloud: Option<PathBuf>,
    /// The port (0: any free port).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// The address to listen on; anything but loopback lets others on the network reach the
    /// console (a warning says so).
    #[arg(long, value_name = "ADDR", default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    listen: IpAddr,
    /// Another page origin allowed to open the WebSocket (http://HOST:PORT), e.g. the
    /// machine's address when listening on 0.0.0.0; may be repeated.
    #[arg(long, value_name = "URL")]
    allow_origin: Vec<String>,
    /// The folder the sessions are saved in (session-001/, session-002/, ...).
    #[arg(long, value_name = "DIR", default_value = "semsim-console")]
    out: PathBuf,
}

/// Runs `semsim console` until Ctrl-C (which saves the session and exits 0).
pub fn run(a: ConsoleArgs) -> anyhow::Result<()> {
    if let Some(dir) = &a.run {
        return replay_run(&a, dir);
    }
    pipeline::check_output_dir(&a.out)?;
    let mut source = ScenarioSource::load(a.scenario.as_deref())?;
    if let Some(robot) = &a.robot {
        use_robot(&mut source, robot)?;
    }
    let world = world(&a, &source)?;
    let config = config(&a)?;
    let setup = SessionSetup {
        world,
        scenario: source.scenario,
        scenario_toml: source.text,
        robot: source.robot,
        out_dir: a.out.clone(),
        cloud: cloud_layer(&a, MAX_CLOUD_POINTS)?,
    };
    crate::interrupt::install();
    let saved = console::serve_blocking::<Console>(
        config,
        setup,
        |c| {
            println!("console: {}", c.url());
            eprintln!(
                "drive with WASD or the arrow keys (space stops); sessions are saved in {}; \
                 Ctrl-C saves the session and quits",
                a.out.display()
            );
            let _ = std::io::stdout().flush();
        },
        crate::interrupt::requested,
    )?;
    for dir in &saved {
        println!("saved {}", dir.display());
    }
    if saved.is_empty() {
        println!("no session to save (the simulation took no step)");
    }
    Ok(())
}

/// The world: --map, --building, or the scenario's building.
fn world(a: &ConsoleArgs, source: &ScenarioSource) -> anyhow::Result<ConsoleWorld> {
    let map = map_file(a);
    if let (None, Some(m)) = (&a.map, &map) {
        eprintln!(
            "world: {} (the map beside the run; --map or --building to choose another)",
            m.display()
        );
    }
    world_from(map.as_deref(), a.building.as_deref(), source)
}

/// --map as a file: a folder means its `map/semantic_map.json` (a demo's or run's output), or
/// its `semantic_map.json`. Without --map and --building, a --run folder that `semsim run` or
/// `semsim demo` wrote (`OUT/simulation`) is replayed in the map beside it (`OUT/map`), the
/// world it ran in.
fn map_file(a: &ConsoleArgs) -> Option<PathBuf> {
    let Some(m) = a.map.as_ref() else {
        let beside = a
            .run
            .as_ref()
            .filter(|_| a.building.is_none())
            .map(|run| run.join("../map/semantic_map.json"))
            .filter(|m| m.is_file())?;
        return Some(beside);
    };
    if !m.is_dir() {
        return Some(m.clone());
    }
    let nested = m.join("map/semantic_map.json");
    Some(if nested.is_file() {
        nested
    } else {
        m.join("semantic_map.json")
    })
}

/// The cloud layer: --cloud, else the registered cloud found beside --map or --run (see
/// [`found_cloud`]), downsampled to `max_points`.
pub(crate) fn cloud_layer(
    a: &ConsoleArgs,
    max_points: usize,
) -> anyhow::Result<Option<CloudLayer>> {
    let path = match &a.cloud {
        Some(c) => c.clone(),
        None => {
            let beside = map_file(a)
                .and_then(|m| found_cloud(m.parent()?, &["labels.pcd", "../registration/map.pcd"]))
                .or_else(|| {
                    let run = a.run.as_ref()?;
                    found_cloud(run, &["../map/labels.pcd", "../registration/map.pcd"])
                });
            match beside {
                Some(p) => {
                    eprintln!("cloud layer: {} (found beside the map or run; --cloud FILE to choose another)", p.display());
                    p
                }
                None => return Ok(None),
            }
        }
    };
    Ok(Some(CloudLayer::from_file(&path, max_points)?))
}

/// The first of `names` (relative to `dir`) that is a file: where `semsim demo` and
/// `semsim run` leave the registered cloud (`map/labels.pcd`, labelled by the map, and
/// `registration/map.pcd`).
fn found_cloud(dir: &Path, names: &[&str]) -> Option<PathBuf> {
    names.iter().map(|n| dir.join(n)).find(|p| p.is_file())
}

/// The world of `--map M | --building B|default`, else the building `source` names (shared by
/// `console` and `report`).
pub(crate) fn world_from(
    map: Option<&Path>,
    building: Option<&Path>,
    source: &ScenarioSource,
) -> anyhow::Result<ConsoleWorld> {
    Ok(match (map, building) {
        (Some(m), _) => ConsoleWorld::from_semantic_map_file(m)?,
        (None, Some(b)) if b.as_os_str() == "default" => {
            ConsoleWorld::from_building(&Building::default_building()?)?
        }
        (None, b) => ConsoleWorld::from_building(&source.building(b)?)?,
    })
}

/// The server's configuration, checked; warns when it listens beyond this machine.
fn config(a: &ConsoleArgs) -> anyhow::Result<ConsoleConfig> {
    let config = ConsoleConfig {
        listen: SocketAddr::new(a.listen, a.port),
        allowed_origins: a.allow_origin.clone(),
        ..ConsoleConfig::default()
    };
    config.validate().map_err(|e| bad_input(e.to_string()))?;
    if !config.is_loopback() {
        eprintln!(
            "warning: listening on {}: anyone who can reach this address can watch and drive \
             (the console has no login); use the default 127.0.0.1 to keep it to this machine",
            a.listen
        );
    }
    Ok(config)
}

/// `semsim console --run RUN_DIR`: serves the recorded run until Ctrl-C (then exits 0).
fn replay_run(a: &ConsoleArgs, dir: &Path) -> anyhow::Result<()> {
    let run = RecordedRun::load(dir)?;
    let source = ScenarioSource::load(Some(&dir.join("scenario.toml")))?;
    let about = format!(
        "replaying {} ({} events, verdict: {}); Ctrl-C quits",
        dir.display(),
        run.events.len(),
        run.verdict
    );
    let setup = RunSetup {
        world: world(a, &source)?,
        robot_name: source.scenario.robot_name.clone(),
        start: source.scenario.start,
        robot: source.robot,
        run,
        cloud: cloud_layer(a, MAX_CLOUD_POINTS)?,
    };
    let config = config(a)?;
    crate::interrupt::install();
    console::serve_blocking::<RunConsole>(
        config,
        setup,
        |c| {
            println!("console: {}", c.url());
            eprintln!("{about}");
            let _ = std::io::stdout().flush();
        },
        crate::interrupt::requested,
    )?;
    Ok(())
}

/// Makes the scenario drive `robot` (a built-in name or a file), and its saved `scenario.toml`
/// name it (a file by its absolute path), so a replay uses the same robot.
fn use_robot(source: &mut ScenarioSource, robot: &str) -> anyhow::Result<()> {
    let model = RobotModel::resolve(robot, Path::new("."))?;
    let name = if Path::new(robot).is_file() {
        std::fs::canonicalize(robot)
            .map_err(|e| cloud::CloudError::io(robot, e))?
            .display()
            .to_string()
    } else {
        robot.to_string()
    };
    let mut table: toml::Table =
        toml::from_str(&source.text).map_err(|e| bad_input(format!("the scenario: {e}")))?;
    table.insert("robot".into(), toml::Value::String(name.clone()));
    source.text = format!(
        "# semsim console --robot {robot}: the scenario with this robot\n{}",
        toml::to_string(&table).map_err(|e| bad_input(format!("the scenario: {e}")))?
    );
    source.scenario.robot = name;
    source.robot = model;
    Ok(())
}
