//! One WebSocket connection: `hello`, then what the hub broadcasts, while the client's
//! messages are rate-limited, size-checked, parsed, checked against the connection's role and
//! handed to the simulation thread. A refused message gets an `error` reply and changes
//! nothing else; the connection and the session go on.

use crate::app::App;
use crate::hub::Joined;
use crate::protocol::{ClientMessage, Role, ServerMessage, PROTOCOL_VERSION};
use crate::rate::RateLimiter;
use crate::runner::Control;
use axum::extract::ws::{Message, WebSocket};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, oneshot};

/// How long a command may wait for the simulation thread.
const REPLY_TIMEOUT: Duration = Duration::from_secs(10);

async fn send(socket: &mut WebSocket, text: &str) -> bool {
    socket.send(Message::Text(text.into())).await.is_ok()
}

/// Serves one connection until it closes or the console stops.
pub(crate) async fn serve(mut socket: WebSocket, app: Arc<App>) {
    let Joined {
        id,
        mut role,
        session,
        rules,
        catch_up,
        mut receiver,
    } = app.hub.join();
    let mut scenario = app.scenario.clone();
    scenario.rules = rules;
    let hello = ServerMessage::Hello {
        protocol: PROTOCOL_VERSION,
        connection: id,
        role,
        session,
        world: app.world.clone(),
        scenario,
        limits: app.limits.clone(),
    };
    let mut open = send(&mut socket, &hello.to_json()).await;
    for text in &catch_up {
        open = open && send(&mut socket, text).await;
    }
    let mut limiter = RateLimiter::new(app.config.max_messages_per_s, Instant::now());
    let mut stop = app.stop.clone();
    while open && !*stop.borrow() {
        tokio::select! {
            incoming = socket.recv() => {
                let reply = match incoming {
                    Some(Ok(Message::Text(text))) => {
                        handle(&app, id, text.as_str(), &mut limiter).await
                    }
                    Some(Ok(Message::Binary(_))) => Some(if limiter.allow(Instant::now()) {
                        "binary messages are not accepted: send JSON text".to_string()
                    } else {
                        rate_message(&app)
                    }),
                    Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                    Some(Ok(_)) => None, // ping and pong: answered by the library
                };
                if let Some(message) = reply {
                    open = send(&mut socket, &ServerMessage::error(message).to_json()).await;
                }
            }
            outgoing = receiver.recv() => {
                match outgoing {
                    Ok(text) => {
                        let now = app.hub.role_of(id);
                        if now != role {
                            role = now;
                            open = send(&mut socket, &ServerMessage::Role { role }.to_json()).await;
                        }
                        open = open && send(&mut socket, &text).await;
                    }
                    Err(broadcast::error::RecvError::Lagged(n)) => {
                        let m = format!("this connection fell behind: {n} messages were dropped");
                        open = send(&mut socket, &ServerMessage::error(m).to_json()).await;
                    }
                    Err(broadcast::error::RecvError::Closed) => break,
                }
            }
            _ = stop.changed() => {}
        }
    }
    let _ = socket.send(Message::Close(None)).await;
    if app.hub.leave(id) {
        app.control(Control::DriverLeft);
    }
}

fn rate_message(app: &App) -> String {
    format!(
        "rate limit: at most {} messages per second; this one was dropped",
        app.config.max_messages_per_s
    )
}

/// Handles a text message; returns the error reply, if any.
async fn handle(app: &App, id: u64, text: &str, limiter: &mut RateLimiter) -> Option<String> {
    if !limiter.allow(Instant::now()) {
        return Some(rate_message(app));
    }
    let max = app.config.max_message_bytes;
    if text.len() > max {
        return Some(format!(
            "message of {} bytes refused: the limit is {max} bytes",
            text.len()
        ));
    }
    let command = match ClientMessage::parse(text) {
        Ok(c) => c,
        Err(e) => return Some(e),
    };
    if app.hub.role_of(id) != Role::Driver {
        return Some(
            "this connection watches: only the driving connection (the first one) sends commands"
                .into(),
        );
    }
    let (reply, answer) = oneshot::channel();
    if !app.control(Control::Command { command, reply }) {
        return Some("the simulation has stopped".into());
    }
    match tokio::time::timeout(REPLY_TIMEOUT, answer).await {
        Ok(Ok(Ok(()))) => None,
        Ok(Ok(Err(message))) => Some(message),
        Ok(Err(_)) | Err(_) => Some("the simulation did not answer".into()),
    }
}
