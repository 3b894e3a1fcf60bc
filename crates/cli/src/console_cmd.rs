//! `semsim console`: the operator console, a local web server showing the world in 3D where a
//! person drives the robot live; each session is saved as a run folder. The CLI only parses
//! the arguments, prints the URL and the folders saved (the console crate does the rest).

use crate::exit::bad_input;
use clap::Args;
use console::{
    CloudLayer, Console, ConsoleConfig, ConsoleInputs, ConsoleWorld, RecordedRun, RunConsole,
    RunSetup, SessionSetup, WorldFile, MAX_CLOUD_POINTS,
};
use pipeline::ScenarioSource;
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
        source = source.with_robot(robot)?;
    }
    let world = world(&a, &source)?;
    let config = config(&a)?;
    let setup = SessionSetup {
        world,
        scenario: source.scenario,
        scenario_toml: source.text,
        robot: source.robot,
        out_dir: a.out.clone(),
        cloud: cloud_layer(&a)?,
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

/// What the command line names, for the console crate to find the world and cloud from.
fn inputs(a: &ConsoleArgs) -> ConsoleInputs {
    ConsoleInputs {
        map: a.map.clone(),
        building: a.building.clone(),
        run: a.run.clone(),
        cloud: a.cloud.clone(),
    }
}

/// The world (see [`ConsoleInputs::world_source`]); says which map it is when it was found
/// beside the run rather than named.
fn world(a: &ConsoleArgs, source: &ScenarioSource) -> anyhow::Result<ConsoleWorld> {
    let file = inputs(a).world_source(&source.scenario, &source.base_dir);
    if let WorldFile::Map(m) = &file {
        if m.was_found() {
            eprintln!(
                "world: {} (the map beside the run; --map or --building to choose another)",
                m.path().display()
            );
        }
    }
    Ok(file.load()?)
}

/// The cloud layer (see [`ConsoleInputs::cloud_file`]), downsampled to at most
/// [`MAX_CLOUD_POINTS`]; says which file it is when it was found rather than named.
fn cloud_layer(a: &ConsoleArgs) -> anyhow::Result<Option<CloudLayer>> {
    let Some(file) = inputs(a).cloud_file() else {
        return Ok(None);
    };
    if file.was_found() {
        eprintln!(
            "cloud layer: {} (found beside the map or run; --cloud FILE to choose another)",
            file.path().display()
        );
    }
    Ok(Some(CloudLayer::from_file(file.path(), MAX_CLOUD_POINTS)?))
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
        cloud: cloud_layer(a)?,
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
