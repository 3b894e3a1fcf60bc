//! The console replaying a recorded run (`semsim console --run RUN_DIR`): the same page and
//! world routes as a live console, plus `/api/run.json` (the run's trajectory, events, verdict
//! and rules, [`RecordedRun`]), which tells the page to replay it with a time slider instead of
//! connecting to a simulation. Nothing is simulated and nothing can be driven: every message on
//! the WebSocket gets an `error` reply (its upgrade is refused from another page's origin, as
//! the live console's is). Nothing is written.

use crate::blocking::Serve;
use crate::cloud_layer::CloudLayer;
use crate::config::{own_origins, ConsoleConfig};
use crate::error::Result;
use crate::http::WorldFiles;
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
    /// The registered point cloud, shown as a layer (`--cloud`).
    pub cloud: Option<CloudLayer>,
}

struct RunApp {
    origins: Vec<String>,
    max_message_bytes: usize,
    run_json: String,
}

/// A console serving a recorded run, listening, not yet serving.
pub struct RunConsole {
    listener: tokio::net::TcpListener,
    addr: SocketAddr,
    app: Arc<RunApp>,
    files: WorldFiles,
}

impl RunConsole {
    /// Builds the world's GLB (the robot at `start`) and opens the listening socket.
    pub async fn bind(config: ConsoleConfig, setup: RunSetup) -> Result<RunConsole> {
        config.validate()?;
        let files = WorldFiles {
            glb: setup.world.glb(&setup.robot, setup.start)?,
            world_json: setup
                .world
                .entities_json(&setup.robot_name, &setup.robot.name),
            cloud: setup.cloud,
        };
        let (listener, addr) = crate::http::bind(config.listen).await?;
        let mut origins = own_origins(addr);
        origins.extend(config.allowed_origins.iter().cloned());
        let app = Arc::new(RunApp {
            origins,
            max_message_bytes: config.max_message_bytes,
            run_json: setup.run.to_json(),
        });
        Ok(RunConsole {
            listener,
            addr,
            app,
            files,
        })
    }

    /// The address it listens on.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL, `http://HOST:PORT/`.
    pub fn url(&self) -> String {
        crate::http::page_url(self.addr)
    }

    /// Serves until `shutdown` completes.
    pub async fn serve<F>(self, shutdown: F) -> Result<()>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let router = Router::new()
            .route("/api/run.json", get(run_json))
            .route("/ws", get(websocket))
            .with_state(self.app)
            .merge(crate::http::world_routes(self.files));
        crate::http::serve(self.listener, router, shutdown).await
    }
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

impl Serve for RunConsole {
    type Setup = RunSetup;
    type Output = ();

    fn bind(config: ConsoleConfig, setup: RunSetup) -> impl Future<Output = Result<Self>> {
        RunConsole::bind(config, setup)
    }

    fn url(&self) -> String {
        RunConsole::url(self)
    }

    fn serve<F>(self, shutdown: F) -> impl Future<Output = Result<()>>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        RunConsole::serve(self, shutdown)
    }
}
