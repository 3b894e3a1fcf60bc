//! The console replaying a recorded run (`semsim console --run RUN_DIR`): the same page and
//! world routes as a live console, plus `/api/run.json` (the run's trajectory, events, verdict
//! and rules, [`RecordedRun`]), which tells the page to replay it with a time slider instead of
//! connecting to a simulation. Nothing is simulated and nothing can be driven: every message on
//! the WebSocket gets an `error` reply (its upgrade is refused from another page's origin, as
//! the live console's is). Nothing is written.

use crate::assets::ASSETS;
use crate::config::{own_origins, ConsoleConfig};
use crate::error::{ConsoleError, Result};
use crate::protocol::ServerMessage;
use crate::run::RecordedRun;
use crate::world::ConsoleWorld;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::State;
use axum::http::HeaderMap;
use axum::response::Response;
use axum::routing::get;
use axum::Router;
use sim::{RobotModel, StartPose};
use std::future::Future;
use std::net::SocketAddr;
use std::sync::Arc;

/// The reply to anything a page sends to a replaying console.
pub const REPLAY_REFUSAL: &str =
    "this console replays a recorded run (--run): there is nothing to drive or control";

/// What a replaying console shows.
pub struct RunSetup {
    /// The world the run was simulated in.
    pub world: ConsoleWorld,
    /// The robot model.
    pub robot: RobotModel,
    /// The robot's name in the scenario.
    pub robot_name: String,
    /// The robot's start (where the GLB draws it).
    pub start: StartPose,
    /// The run.
    pub run: RecordedRun,
}

struct RunApp {
    origins: Vec<String>,
    max_message_bytes: usize,
    glb: Vec<u8>,
    world_json: String,
    run_json: String,
}

/// A console serving a recorded run, listening, not yet serving.
pub struct RunConsole {
    listener: tokio::net::TcpListener,
    addr: SocketAddr,
    app: Arc<RunApp>,
}

impl RunConsole {
    /// Builds the world's GLB (the robot at `start`) and opens the listening socket.
    pub async fn bind(config: ConsoleConfig, setup: &RunSetup) -> Result<RunConsole> {
        config.validate()?;
        let glb = setup.world.glb(&setup.robot, setup.start)?;
        let world_json = setup
            .world
            .entities_json(&setup.robot_name, &setup.robot.name);
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
        let mut origins = own_origins(addr);
        origins.extend(config.allowed_origins.iter().cloned());
        let app = Arc::new(RunApp {
            origins,
            max_message_bytes: config.max_message_bytes,
            glb,
            world_json,
            run_json: setup.run.to_json(),
        });
        Ok(RunConsole {
            listener,
            addr,
            app,
        })
    }

    /// The address it listens on.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL, `http://HOST:PORT/`.
    pub fn url(&self) -> String {
        let mut addr = self.addr;
        if addr.ip().is_unspecified() {
            addr.set_ip(std::net::Ipv4Addr::LOCALHOST.into());
        }
        format!("http://{addr}/")
    }

    /// Serves until `shutdown` completes.
    pub async fn serve<F>(self, shutdown: F) -> Result<()>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let mut r = Router::new()
            .route("/world.glb", get(glb))
            .route("/api/world.json", get(world_json))
            .route("/api/run.json", get(run_json))
            .route("/ws", get(websocket));
        for asset in ASSETS {
            r = r.route(
                asset.path,
                get(move || async move { crate::http::file(asset.content_type, asset.bytes) }),
            );
        }
        axum::serve(self.listener, r.with_state(self.app))
            .with_graceful_shutdown(shutdown)
            .await
            .map_err(ConsoleError::Serve)
    }
}

async fn glb(State(app): State<Arc<RunApp>>) -> Response {
    crate::http::file("model/gltf-binary", app.glb.clone())
}

async fn world_json(State(app): State<Arc<RunApp>>) -> Response {
    crate::http::file("application/json", app.world_json.clone())
}

async fn run_json(State(app): State<Arc<RunApp>>) -> Response {
    crate::http::file("application/json", app.run_json.clone())
}

async fn websocket(
    State(app): State<Arc<RunApp>>,
    headers: HeaderMap,
    upgrade: WebSocketUpgrade,
) -> Response {
    if let Some(refusal) = crate::http::refuse_foreign_origin(&headers, &app.origins) {
        return refusal;
    }
    upgrade
        .max_message_size(app.max_message_bytes)
        .max_frame_size(app.max_message_bytes)
        .on_upgrade(refuse_everything)
}

/// Answers every message with an error until the page goes.
async fn refuse_everything(mut socket: WebSocket) {
    let reply = ServerMessage::error(REPLAY_REFUSAL.to_string()).to_json();
    while let Some(Ok(message)) = socket.recv().await {
        match message {
            Message::Text(_) | Message::Binary(_) => {
                if socket
                    .send(Message::Text(reply.clone().into()))
                    .await
                    .is_err()
                {
                    break;
                }
            }
            Message::Close(_) => break,
            Message::Ping(_) | Message::Pong(_) => {}
        }
    }
}

/// Serves a recorded run on a runtime of its own until `stop()` answers true (polled every
/// 100 ms), calling `listening` once the socket is open.
pub fn serve_run_blocking(
    config: ConsoleConfig,
    setup: &RunSetup,
    listening: impl FnOnce(&RunConsole),
    stop: impl Fn() -> bool + Send + 'static,
) -> Result<()> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(ConsoleError::Serve)?;
    runtime.block_on(async move {
        let console = RunConsole::bind(config, setup).await?;
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
