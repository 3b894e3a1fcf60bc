//! The HTTP server (axum on tokio): the page and its files, `/world.glb`, `/api/world.json`
//! and the WebSocket `/ws`, whose upgrade is refused (403) unless the request comes from the
//! console's own page (no `Origin` header, or one of the console's origins).

use crate::app::App;
use crate::blocking::Serve;
use crate::config::{own_origins, ConsoleConfig};
use crate::error::{ConsoleError, Result};
use crate::http::WorldFiles;
use crate::hub::Hub;
use crate::protocol::{
    Limits, RobotSummary, ScenarioSummary, WorldSummary, MAX_ANGULAR_RAD_S, MAX_LINEAR_M_S,
    MAX_SPEED_FACTOR, MIN_SPEED_FACTOR,
};
use crate::runner::{self, Control, Runner};
use crate::session::{first_free_session, SessionSetup};
use axum::extract::ws::WebSocketUpgrade;
use axum::extract::State;
use axum::http::HeaderMap;
use axum::response::Response;
use axum::routing::get;
use axum::Router;
use std::future::Future;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{mpsc, Arc, Mutex};
use tokio::sync::{oneshot, watch};

/// A console listening on its socket, not yet serving.
pub struct Console {
    listener: tokio::net::TcpListener,
    addr: SocketAddr,
    app: Arc<App>,
    files: WorldFiles,
    stop: watch::Sender<bool>,
    thread: std::thread::JoinHandle<()>,
}

impl Console {
    /// Checks the setup (the scenario must fit the world), starts the first session's
    /// simulation thread (it runs from now on) and opens the listening socket.
    pub async fn bind(config: ConsoleConfig, setup: SessionSetup) -> Result<Console> {
        config.validate()?;
        let setup = Arc::new(setup);
        let robot_entity = setup.world.robot_entity();
        let glb = setup.world.glb(&setup.robot, setup.scenario.start)?;
        let world_json = setup
            .world
            .entities_json(&setup.scenario.robot_name, &setup.robot.name);
        let number = first_free_session(&setup.out_dir);
        let hub = Arc::new(Hub::new(number, vec![]));
        let runner = Runner::new(setup.clone(), hub.clone(), number, config.state_rate_hz)?;
        let rules = runner.rules();
        hub.new_session(number, rules.clone());
        let (listener, addr) = crate::http::bind(config.listen).await?;
        let (controls, received) = mpsc::channel();
        let thread = runner::spawn(runner, received)?;
        let spec = &setup.world.spec;
        let d = &setup.robot.drive;
        let world = WorldSummary {
            name: spec.name.clone(),
            entities: spec.entities().len(),
            fixed_boxes: spec.fixed.len(),
            doors: spec.doors.len(),
            free_spaces: spec.free_spaces.len(),
            stairs: spec.stairs.len(),
            robot: RobotSummary {
                entity: robot_entity,
                name: setup.scenario.robot_name.clone(),
                model: setup.robot.name.clone(),
                max_speed_mps: d.max_speed_mps,
                max_yaw_rate_radps: d.max_yaw_rate_radps,
            },
        };
        let s = &setup.scenario;
        let scenario = ScenarioSummary {
            name: s.name.clone(),
            description: s.description.clone(),
            time_limit_s: s.time_limit_s,
            dt_secs: s.world.dt_secs,
            rules,
        };
        let limits = Limits {
            max_message_bytes: config.max_message_bytes,
            max_messages_per_s: config.max_messages_per_s,
            max_linear_m_s: MAX_LINEAR_M_S,
            max_angular_rad_s: MAX_ANGULAR_RAD_S,
            min_speed_factor: MIN_SPEED_FACTOR,
            max_speed_factor: MAX_SPEED_FACTOR,
        };
        let mut origins = own_origins(addr);
        origins.extend(config.allowed_origins.iter().cloned());
        let (stop, stop_rx) = watch::channel(false);
        let app = Arc::new(App {
            config,
            origins,
            hub,
            controls,
            world,
            scenario,
            limits,
            stop: stop_rx,
        });
        let files = WorldFiles {
            glb,
            world_json,
            cloud: setup.cloud.clone(),
        };
        Ok(Console {
            listener,
            addr,
            app,
            files,
            stop,
            thread,
        })
    }

    /// The address it listens on (with the port chosen when 0 was asked for).
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL, `http://HOST:PORT/` (an unspecified listen address shows as
    /// 127.0.0.1).
    pub fn url(&self) -> String {
        crate::http::page_url(self.addr)
    }

    /// Serves until `shutdown` completes; then the session is saved (if it stepped since its
    /// last save), the connections are closed, and every run folder saved is returned.
    pub async fn serve<F>(self, shutdown: F) -> Result<Vec<PathBuf>>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let Console {
            listener,
            app,
            files,
            stop,
            thread,
            ..
        } = self;
        let saved: Arc<Mutex<Option<Result<Vec<PathBuf>>>>> = Arc::new(Mutex::new(None));
        let graceful = {
            let app = app.clone();
            let saved = saved.clone();
            async move {
                shutdown.await;
                let (reply, answer) = oneshot::channel();
                let result = if app.control(Control::Shutdown { reply }) {
                    answer.await.unwrap_or(Err(ConsoleError::SimulationThread))
                } else {
                    Err(ConsoleError::SimulationThread)
                };
                *saved.lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
                // The sockets close after the verdict went out.
                let _ = stop.send(true);
            }
        };
        let served = crate::http::serve(listener, router(app, files), graceful).await;
        let _ = thread.join();
        served?;
        let result = saved
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .unwrap_or(Err(ConsoleError::SimulationThread));
        result
    }
}

fn router(app: Arc<App>, files: WorldFiles) -> Router {
    Router::new()
        .route("/api/run.json", get(no_run))
        .route("/ws", get(websocket))
        .with_state(app)
        .merge(crate::http::world_routes(files))
}

/// A live console has no recorded run: `null` (a replaying one serves the run here).
async fn no_run() -> Response {
    crate::http::file("application/json", "null")
}

async fn websocket(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    upgrade: WebSocketUpgrade,
) -> Response {
    if let Some(refusal) = crate::http::refuse_foreign_origin(&headers, &app.origins) {
        return refusal;
    }
    let max = app.config.max_message_bytes.saturating_mul(16);
    upgrade
        .max_message_size(max)
        .max_frame_size(max)
        .on_upgrade(move |socket| crate::socket::serve(socket, app))
}

impl Serve for Console {
    type Setup = SessionSetup;
    type Output = Vec<PathBuf>;

    fn bind(config: ConsoleConfig, setup: SessionSetup) -> impl Future<Output = Result<Self>> {
        Console::bind(config, setup)
    }

    fn url(&self) -> String {
        Console::url(self)
    }

    fn serve<F>(self, shutdown: F) -> impl Future<Output = Result<Vec<PathBuf>>>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        Console::serve(self, shutdown)
    }
}
