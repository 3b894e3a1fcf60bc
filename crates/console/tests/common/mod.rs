//! What the console's tests share: a small world with a wall ahead of the robot, a console on
//! a free loopback port, a WebSocket client, and a plain HTTP GET. Every wait has a timeout,
//! so a broken server fails the test instead of hanging it.
#![allow(dead_code)]

use console::{Console, ConsoleConfig, ConsoleWorld, SessionSetup};
use futures_util::{SinkExt, StreamExt};
use serde_json::{json, Value};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// How long any wait may take (generous: CI machines are slow and busy).
pub const TIMEOUT: Duration = Duration::from_secs(90);

/// A room 8 m x 4 m, a wall across it at x = 5 m; the robot starts at x = 2 m facing it.
pub const BUILDING: &str = r#"
    name = "test room"
    [floor]
    min_m = [0.0, -2.0]
    max_m = [8.0, 2.0]
    [ceiling]
    height_m = 2.5
    [[walls]]
    start_m = [5.0, -2.0]
    end_m = [5.0, 2.0]
    thickness_m = 0.2
"#;

/// The robot stands still unless driven; touching walls over 0.5 s fails the run.
pub fn scenario_toml(time_limit_s: f64) -> String {
    format!(
        r#"
        name = "drive to the wall"
        robot = "pioneer3at"
        time_limit_s = {time_limit_s}
        start = {{ x_m = 2.0, y_m = 0.0, yaw_deg = 0.0 }}
        [rules]
        max_wall_contact_s = 0.5
        no_tipping = true
        "#
    )
}

/// A session setup saving into `out`.
pub fn setup(out: PathBuf, time_limit_s: f64) -> SessionSetup {
    let building = scanner::Building::from_toml_str(BUILDING, std::path::Path::new("test.toml"))
        .expect("building");
    let text = scenario_toml(time_limit_s);
    let scenario = sim::Scenario::from_toml_str(&text, "test scenario").expect("scenario");
    let robot = sim::RobotModel::builtin("pioneer3at").expect("robot");
    SessionSetup {
        world: ConsoleWorld::from_building(&building).expect("world"),
        scenario,
        scenario_toml: text,
        robot,
        out_dir: out,
        cloud: None,
    }
}

/// A console serving in the background.
pub struct Running {
    pub addr: SocketAddr,
    pub url: String,
    stop: Option<oneshot::Sender<()>>,
    task: Option<JoinHandle<console::Result<Vec<PathBuf>>>>,
}

impl Running {
    /// Stops it (the session is saved); returns the run folders saved.
    pub async fn stop(mut self) -> Vec<PathBuf> {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        let task = self.task.take().expect("running");
        tokio::time::timeout(TIMEOUT, task)
            .await
            .expect("the console stops in time")
            .expect("the serving task did not panic")
            .expect("the console stopped cleanly")
    }
}

/// Starts a console on a free loopback port.
pub async fn start(config: ConsoleConfig, setup: SessionSetup) -> Running {
    let console = Console::bind(config, setup).await.expect("binds");
    let addr = console.local_addr();
    let url = console.url();
    let (stop, stopped) = oneshot::channel::<()>();
    let task = tokio::spawn(console.serve(async move {
        let _ = stopped.await;
    }));
    Running {
        addr,
        url,
        stop: Some(stop),
        task: Some(task),
    }
}

/// The default configuration on port 0.
pub fn any_port() -> ConsoleConfig {
    ConsoleConfig {
        listen: "127.0.0.1:0".parse().expect("addr"),
        ..ConsoleConfig::default()
    }
}

pub type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// Opens the WebSocket (no Origin header, as a non-browser client).
pub async fn connect(addr: SocketAddr) -> Ws {
    let (ws, _) = tokio::time::timeout(
        TIMEOUT,
        tokio_tungstenite::connect_async(format!("ws://{addr}/ws")),
    )
    .await
    .expect("connects in time")
    .expect("connects");
    ws
}

/// The next JSON message (pings and pongs skipped).
pub async fn next(ws: &mut Ws) -> Value {
    loop {
        let m = tokio::time::timeout(TIMEOUT, ws.next())
            .await
            .expect("a message in time")
            .expect("the connection is open")
            .expect("a message");
        if let Message::Text(t) = m {
            return serde_json::from_str(t.as_str()).expect("JSON");
        }
        assert!(!matches!(m, Message::Close(_)), "closed by the server");
    }
}

/// Reads messages until one satisfies `wanted`; returns it.
pub async fn wait_for(ws: &mut Ws, what: &str, wanted: impl Fn(&Value) -> bool) -> Value {
    let deadline = tokio::time::Instant::now() + TIMEOUT;
    loop {
        assert!(tokio::time::Instant::now() < deadline, "no {what} in time");
        let m = next(ws).await;
        if wanted(&m) {
            return m;
        }
    }
}

/// Sends a JSON message.
pub async fn send(ws: &mut Ws, message: Value) {
    send_text(ws, message.to_string()).await;
}

/// Sends a text message as is.
pub async fn send_text(ws: &mut Ws, text: String) {
    ws.send(Message::Text(text.into())).await.expect("sends");
}

/// Sends a command and makes the simulation run 10 times faster than real time.
pub async fn fast(ws: &mut Ws) {
    send(ws, json!({"type": "speed", "factor": 10.0})).await;
}

/// `GET path` over HTTP/1.1: (status, body).
pub async fn get(addr: SocketAddr, path: &str) -> (u16, Vec<u8>) {
    let fetch = async {
        let mut s = TcpStream::connect(addr).await.expect("connects");
        let req = format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
        s.write_all(req.as_bytes()).await.expect("writes");
        let mut raw = vec![];
        s.read_to_end(&mut raw).await.expect("reads");
        raw
    };
    let raw = tokio::time::timeout(TIMEOUT, fetch)
        .await
        .expect("answers in time");
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&raw[..end]).to_string();
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("a status");
    let mut body = raw[end + 4..].to_vec();
    if head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked")
    {
        body = dechunk(&body);
    }
    (status, body)
}

fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = vec![];
    loop {
        let Some(eol) = data.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let size = usize::from_str_radix(String::from_utf8_lossy(&data[..eol]).trim(), 16)
            .expect("a chunk size");
        if size == 0 {
            return out;
        }
        out.extend_from_slice(&data[eol + 2..eol + 2 + size]);
        data = &data[eol + 2 + size + 2..];
    }
}
