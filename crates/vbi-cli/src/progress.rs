//! Progress of a long command on standard error: an `indicatif` bar on a terminal; otherwise
//! (a Slurm log, a pipe, a file) a plain line at a steady interval with the cases done, the rate
//! and the time left, so that a log shows how far a job got without a bar's control characters.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use std::io::IsTerminal;

/// Default interval between log lines when standard error is not a terminal [s].
pub const DEFAULT_INTERVAL_S: f64 = 30.0;

/// Progress over a known number of items.
pub struct Progress {
    what: String,
    total: u64,
    started: Instant,
    mode: Mode,
}

enum Mode {
    Bar(indicatif::ProgressBar),
    Log {
        interval: Duration,
        state: Mutex<LogState>,
    },
}

struct LogState {
    done: u64,
    last: Instant,
}

impl Progress {
    /// A bar on a terminal; otherwise log lines every `interval_s` seconds (0: after every item)
    /// naming `what` ("cases").
    pub fn new(what: &str, total: u64, interval_s: f64) -> Progress {
        let started = Instant::now();
        let mode = if std::io::stderr().is_terminal() {
            let bar = indicatif::ProgressBar::new(total);
            if let Ok(style) = indicatif::ProgressStyle::with_template(&format!(
                "{{bar:40}} {{pos}}/{{len}} {what}  {{per_sec}}  elapsed {{elapsed}}  ETA {{eta}}"
            )) {
                bar.set_style(style);
            }
            Mode::Bar(bar)
        } else {
            Mode::Log {
                interval: Duration::from_secs_f64(interval_s.max(0.0)),
                state: Mutex::new(LogState {
                    done: 0,
                    last: started,
                }),
            }
        };
        Progress {
            what: what.to_string(),
            total,
            started,
            mode,
        }
    }

    /// One more item done.
    pub fn inc(&self) {
        match &self.mode {
            Mode::Bar(bar) => bar.inc(1),
            Mode::Log { interval, state } => {
                let Ok(mut state) = state.lock() else { return };
                state.done += 1;
                let now = Instant::now();
                if now.duration_since(state.last) >= *interval || state.done == self.total {
                    state.last = now;
                    eprintln!("{}", self.line(state.done, now));
                }
            }
        }
    }

    /// `done` items done in all (a position that only grows).
    pub fn set(&self, done: u64) {
        match &self.mode {
            Mode::Bar(bar) => bar.set_position(done),
            Mode::Log { interval, state } => {
                let Ok(mut state) = state.lock() else { return };
                if done == state.done {
                    return;
                }
                state.done = done;
                let now = Instant::now();
                if now.duration_since(state.last) >= *interval || state.done == self.total {
                    state.last = now;
                    eprintln!("{}", self.line(state.done, now));
                }
            }
        }
    }

    /// Clears the bar (log lines stay).
    pub fn finish(&self) {
        if let Mode::Bar(bar) = &self.mode {
            bar.finish_and_clear();
        }
    }

    /// `progress: 120/1080 cases (11.1 %), 8.30 cases/s, elapsed 14 s, ETA 1 min 56 s`.
    fn line(&self, done: u64, now: Instant) -> String {
        let elapsed = now.duration_since(self.started).as_secs_f64();
        let rate = done as f64 / elapsed.max(1e-9);
        let left = self.total.saturating_sub(done) as f64 / rate.max(1e-12);
        format!(
            "progress: {done}/{} {} ({:.1} %), {rate:.2} {}/s, elapsed {}, ETA {}",
            self.total,
            self.what,
            100.0 * done as f64 / (self.total.max(1)) as f64,
            self.what,
            duration(elapsed),
            duration(left),
        )
    }
}

/// A duration for people: `14 s`, `1 min 56 s`, `2 h 03 min`.
fn duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    match s {
        0..=59 => format!("{s} s"),
        60..=3599 => format!("{} min {:02} s", s / 60, s % 60),
        _ => format!("{} h {:02} min", s / 3600, (s % 3600) / 60),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_in_seconds_minutes_and_hours() {
        assert_eq!(duration(14.2), "14 s");
        assert_eq!(duration(116.0), "1 min 56 s");
        assert_eq!(duration(7380.0), "2 h 03 min");
    }
}
