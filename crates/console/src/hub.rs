//! The hub between the simulation thread and the connections: every message is serialised
//! once and broadcast; the hub keeps what a connection joining later needs (the latest state,
//! the rules, this session's events and verdict) and who drives.
//!
//! Publishing and joining take the same lock, so a new connection gets the backlog up to some
//! message and every message after it from its receiver: nothing twice, nothing missed.

use crate::protocol::{Role, ServerMessage};
use sim::LiveRule;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use tokio::sync::broadcast;

/// Messages a connection may fall behind by before it misses some.
const CHANNEL_CAPACITY: usize = 4096;
/// Events (and verdicts) of a session kept for connections that join later.
const BACKLOG: usize = 5000;

/// What the hub keeps of a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Keep {
    /// Nothing (sent to the current connections only).
    Nothing,
    /// As the latest state.
    State,
    /// In the session's backlog (events, verdicts).
    Backlog,
}

struct Inner {
    next_id: u64,
    /// Connections in the order they came; the first drives.
    connections: Vec<u64>,
    session: u32,
    rules: Vec<LiveRule>,
    state: Option<Arc<str>>,
    backlog: VecDeque<Arc<str>>,
}

/// What a joining connection gets.
pub(crate) struct Joined {
    pub id: u64,
    pub role: Role,
    pub session: u32,
    pub rules: Vec<LiveRule>,
    /// The latest state, then this session's events and verdicts.
    pub catch_up: Vec<Arc<str>>,
    pub receiver: broadcast::Receiver<Arc<str>>,
}

/// See the module docs.
pub(crate) struct Hub {
    inner: Mutex<Inner>,
    sender: broadcast::Sender<Arc<str>>,
    /// The driving connection's id (0: none).
    driver: AtomicU64,
}

impl Hub {
    pub(crate) fn new(session: u32, rules: Vec<LiveRule>) -> Hub {
        let (sender, _) = broadcast::channel(CHANNEL_CAPACITY);
        Hub {
            inner: Mutex::new(Inner {
                next_id: 1,
                connections: vec![],
                session,
                rules,
                state: None,
                backlog: VecDeque::new(),
            }),
            sender,
            driver: AtomicU64::new(0),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic while holding the lock leaves consistent data (every update is one
        // assignment), so a poisoned lock is used as is.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Sends `message` to every connection, keeping it as `keep` says.
    pub(crate) fn publish(&self, message: &ServerMessage, keep: Keep) {
        let text: Arc<str> = Arc::from(message.to_json());
        let mut inner = self.lock();
        match keep {
            Keep::Nothing => {}
            Keep::State => inner.state = Some(text.clone()),
            Keep::Backlog => {
                if inner.backlog.len() >= BACKLOG {
                    inner.backlog.pop_front();
                }
                inner.backlog.push_back(text.clone());
            }
        }
        if let ServerMessage::Rules { rules, .. } = message {
            inner.rules = rules.clone();
        }
        // No receivers is fine: nobody is watching.
        let _ = self.sender.send(text);
    }

    /// A new session: its number and rules; the backlog starts empty.
    pub(crate) fn new_session(&self, session: u32, rules: Vec<LiveRule>) {
        let mut inner = self.lock();
        inner.session = session;
        inner.rules = rules;
        inner.backlog.clear();
    }

    /// A connection joins: it drives if it is the only one.
    pub(crate) fn join(&self) -> Joined {
        let mut inner = self.lock();
        let id = inner.next_id;
        inner.next_id += 1;
        inner.connections.push(id);
        let role = if inner.connections.len() == 1 {
            self.driver.store(id, Ordering::SeqCst);
            Role::Driver
        } else {
            Role::Watcher
        };
        let catch_up = inner
            .state
            .iter()
            .chain(inner.backlog.iter())
            .cloned()
            .collect();
        Joined {
            id,
            role,
            session: inner.session,
            rules: inner.rules.clone(),
            catch_up,
            receiver: self.sender.subscribe(),
        }
    }

    /// A connection leaves; returns whether it was the driver (then the next connection in
    /// order drives).
    pub(crate) fn leave(&self, id: u64) -> bool {
        let mut inner = self.lock();
        inner.connections.retain(|c| *c != id);
        let was_driver = self.driver.load(Ordering::SeqCst) == id;
        if was_driver {
            let next = inner.connections.first().copied().unwrap_or(0);
            self.driver.store(next, Ordering::SeqCst);
        }
        was_driver
    }

    /// A connection's role now.
    pub(crate) fn role_of(&self, id: u64) -> Role {
        if self.driver.load(Ordering::SeqCst) == id {
            Role::Driver
        } else {
            Role::Watcher
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_drives_and_the_next_takes_over() {
        let hub = Hub::new(1, vec![]);
        let a = hub.join();
        let b = hub.join();
        let c = hub.join();
        assert_eq!(
            (a.role, b.role, c.role),
            (Role::Driver, Role::Watcher, Role::Watcher)
        );
        assert!(!hub.leave(b.id));
        assert_eq!(hub.role_of(c.id), Role::Watcher);
        assert!(hub.leave(a.id));
        assert_eq!(hub.role_of(c.id), Role::Driver);
    }

    #[test]
    fn late_joiners_get_the_state_and_the_backlog_once() {
        let hub = Hub::new(1, vec![]);
        hub.publish(&ServerMessage::error("e1"), Keep::Backlog);
        hub.publish(&ServerMessage::error("s1"), Keep::State);
        hub.publish(&ServerMessage::error("s2"), Keep::State);
        hub.publish(&ServerMessage::error("gone"), Keep::Nothing);
        let mut j = hub.join();
        assert_eq!(j.catch_up.len(), 2);
        assert!(j.catch_up[0].contains("s2") && j.catch_up[1].contains("e1"));
        hub.publish(&ServerMessage::error("after"), Keep::Backlog);
        let next = j.receiver.try_recv().expect("one message");
        assert!(next.contains("after"));
        assert!(j.receiver.try_recv().is_err());
        hub.new_session(2, vec![]);
        assert_eq!(hub.join().catch_up.len(), 1, "the state only");
    }
}
