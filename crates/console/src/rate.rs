//! A token bucket: a connection may send `per_s` messages a second, in bursts of as many.

use std::time::Instant;

/// See the module docs.
#[derive(Debug, Clone)]
pub(crate) struct RateLimiter {
    per_s: f64,
    tokens: f64,
    last: Instant,
}

impl RateLimiter {
    pub(crate) fn new(per_s: u32, now: Instant) -> RateLimiter {
        RateLimiter {
            per_s: per_s as f64,
            tokens: per_s as f64,
            last: now,
        }
    }

    /// Whether a message arriving at `now` is allowed (it takes a token if so).
    pub(crate) fn allow(&mut self, now: Instant) -> bool {
        let elapsed_s = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = self.last.max(now);
        self.tokens = (self.tokens + elapsed_s * self.per_s).min(self.per_s);
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn a_burst_then_the_rate() {
        let t0 = Instant::now();
        let mut r = RateLimiter::new(100, t0);
        assert_eq!((0..150).filter(|_| r.allow(t0)).count(), 100);
        // 0.1 s later: 10 more.
        let t1 = t0 + Duration::from_millis(100);
        assert_eq!((0..50).filter(|_| r.allow(t1)).count(), 10);
        // Long idle refills to the burst, not beyond.
        let t2 = t1 + Duration::from_secs(60);
        assert_eq!((0..500).filter(|_| r.allow(t2)).count(), 100);
    }
}
