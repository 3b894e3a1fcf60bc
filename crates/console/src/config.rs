//! The console's configuration: where it listens, which page origins may open its WebSocket,
//! and the limits on what a client may send.

use crate::error::{ConsoleError, Result};
use serde::{Deserialize, Serialize};
use std::net::{IpAddr, Ipv4Addr, SocketAddr};

/// How the console serves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ConsoleConfig {
    /// The address and port to listen on (port 0: any free port). Default `127.0.0.1:8080`:
    /// loopback only, so nobody else on the network can reach it.
    pub listen: SocketAddr,
    /// Page origins besides the console's own (`http://HOST:PORT` of the listen address, and
    /// `http://localhost:PORT` on loopback) allowed to open the WebSocket, e.g.
    /// `http://192.168.1.5:8080` when listening on `0.0.0.0`.
    pub allowed_origins: Vec<String>,
    /// The largest client message answered (bytes); larger ones get an error reply. Messages
    /// over 16 times this close the connection.
    pub max_message_bytes: usize,
    /// Messages a connection may send per second (a burst of as many is allowed); the excess
    /// gets error replies.
    pub max_messages_per_s: u32,
    /// State messages per second.
    pub state_rate_hz: f64,
}

impl Default for ConsoleConfig {
    fn default() -> Self {
        ConsoleConfig {
            listen: SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), 8080),
            allowed_origins: vec![],
            max_message_bytes: 64 * 1024,
            max_messages_per_s: 100,
            state_rate_hz: 30.0,
        }
    }
}

impl ConsoleConfig {
    /// Checks the limits.
    pub fn validate(&self) -> Result<()> {
        if !(256..=16 * 1024 * 1024).contains(&self.max_message_bytes) {
            return Err(ConsoleError::Config(format!(
                "max_message_bytes = {} (expected 256 to 16 MiB)",
                self.max_message_bytes
            )));
        }
        if !(1..=10_000).contains(&self.max_messages_per_s) {
            return Err(ConsoleError::Config(format!(
                "max_messages_per_s = {} (expected 1 to 10000)",
                self.max_messages_per_s
            )));
        }
        if !(self.state_rate_hz >= 1.0 && self.state_rate_hz <= 240.0) {
            return Err(ConsoleError::Config(format!(
                "state_rate_hz = {} (expected 1 to 240)",
                self.state_rate_hz
            )));
        }
        for o in &self.allowed_origins {
            if !(o.starts_with("http://") || o.starts_with("https://")) || o.ends_with('/') {
                return Err(ConsoleError::Config(format!(
                    "allowed origin {o:?}: expected http://HOST:PORT (no path, no trailing /)"
                )));
            }
        }
        Ok(())
    }

    /// Whether the listen address is loopback (reachable from this machine only).
    pub fn is_loopback(&self) -> bool {
        self.listen.ip().is_loopback()
    }
}

/// The origins a page served from `addr` has: `http://ADDR:PORT`, and on loopback also
/// `http://localhost:PORT`.
pub(crate) fn own_origins(addr: SocketAddr) -> Vec<String> {
    let port = addr.port();
    let mut out = vec![format!("http://{addr}")];
    if addr.ip().is_loopback() {
        out.push(format!("http://localhost:{port}"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_loopback_and_valid() {
        let c = ConsoleConfig::default();
        assert!(c.is_loopback());
        assert_eq!(c.listen.port(), 8080);
        c.validate().expect("valid");
    }

    #[test]
    fn origins_of_a_loopback_address() {
        let o = own_origins("127.0.0.1:9000".parse().expect("addr"));
        assert!(o.contains(&"http://127.0.0.1:9000".to_string()));
        assert!(o.contains(&"http://localhost:9000".to_string()));
        let o = own_origins("10.1.2.3:80".parse().expect("addr"));
        assert_eq!(o, vec!["http://10.1.2.3:80".to_string()]);
    }

    #[test]
    fn bad_limits_are_refused() {
        let c = ConsoleConfig {
            max_messages_per_s: 0,
            ..ConsoleConfig::default()
        };
        assert!(c.validate().is_err());
        let c = ConsoleConfig {
            allowed_origins: vec!["evil.example".into()],
            ..ConsoleConfig::default()
        };
        assert!(c.validate().is_err());
    }
}
