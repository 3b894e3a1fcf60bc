//! The HTTP server (axum on tokio): the page and its files, `/world.glb`, `/api/world.json`
//! and the WebSocket `/ws`, whose upgrade is refused (403) unless the request comes from the
//! console's own page (no `Origin` header, or one of the console's origins).

use crate::app::App;
use crate::assets::ASSETS;
use crate::config::{own_origins, ConsoleConfig};
use crate::error::{ConsoleError, Result};
use crate::hub::Hub;
use crate::protocol::{
    Limits, RobotSummary, ScenarioSummary, WorldSummary, MAX_ANGULAR_RAD_S, MAX_LINEAR_M_S,
    MAX_SPEED_FACTOR, MIN_SPEED_FACTOR,
};
use crate::runner::{self, Control, Runner};
use crate::session::{first_free_session, SessionSetup};
use axum::extract::ws::WebSocketUpgrade;
use axum::extract::State;
use axum::http::header::{CACHE_CONTROL, CONTENT_TYPE, X_CONTENT_TYPE_OPTIONS};
use axum::http::HeaderMap;
use axum::response::Response;
use axum::routing::get;
use axum::Router;
use std::future::Future;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::{mpsc, Arc, Mutex};
use tokio::sync::{oneshot, watch};

/// A console listening on its socket, not yet serving.
pub struct Console {
    listener: tokio::net::TcpListener,
    addr: SocketAddr,
    app: Arc<App>,
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
        let listener = tokio::net::TcpListener::bind(config.listen)
            .await
            .map_err(|source| ConsoleError::Bind {
                addr: config.listen,
                source,
            })?;
        let addr = listener.local_addr().map_err(|source| ConsoleError::Bind {
            addr: config.listen,
            source,
        })?;
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
            glb,
            world_json,
            stop: stop_rx,
        });
        Ok(Console {
            listener,
            addr,
            app,
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
        let mut addr = self.addr;
        if addr.ip().is_unspecified() {
            addr.set_ip(IpAddr::V4(Ipv4Addr::LOCALHOST));
        }
        format!("http://{addr}/")
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
        let served = axum::serve(listener, router(app))
            .with_graceful_shutdown(graceful)
            .await;
        let _ = thread.join();
        served.map_err(ConsoleError::Serve)?;
        let result = saved
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .unwrap_or(Err(ConsoleError::SimulationThread));
        result
    }
}

fn router(app: Arc<App>) -> Router {
    let mut r = Router::new()
        .route("/world.glb", get(glb))
        .route("/api/world.json", get(world_json))
        .route("/api/run.json", get(no_run))
        .route("/ws", get(websocket));
    for asset in ASSETS {
        r = r.route(
            asset.path,
            get(move || async move {
                (
                    [
                        (CONTENT_TYPE, asset.content_type),
                        (CACHE_CONTROL, "no-cache"),
                        (X_CONTENT_TYPE_OPTIONS, "nosniff"),
                    ],
                    asset.bytes,
                )
            }),
        );
    }
    r.with_state(app)
}

async fn glb(State(app): State<Arc<App>>) -> Response {
    crate::http::file("model/gltf-binary", app.glb.clone())
}

async fn world_json(State(app): State<Arc<App>>) -> Response {
    crate::http::file("application/json", app.world_json.clone())
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

/// Runs a console on a runtime of its own until `stop()` answers true (polled every 100
/// ms; e.g. a Ctrl-C flag), calling `listening` once the socket is open; returns the run
/// folders saved. For programs without a tokio runtime (the `semsim` binary).
pub fn serve_blocking(
    config: ConsoleConfig,
    setup: SessionSetup,
    listening: impl FnOnce(&Console),
    stop: impl Fn() -> bool + Send + 'static,
) -> Result<Vec<PathBuf>> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(ConsoleError::Serve)?;
    runtime.block_on(async move {
        let console = Console::bind(config, setup).await?;
        listening(&console);
        console
            .serve(async move {
                while !stop() {
                    tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                }
            })
            .await
    })
}
