//! The episode log: every external event with its tick, every replan and action, the result.

use serde::{Deserialize, Serialize};

use crate::lfd::{FailReason, Replan};
use crate::sim::WorldSnapshot;

use super::options::SessionOptions;

/// An external event of the episode, with the tick before which it happened.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case", try_from = "EventFields")]
pub enum EpisodeEvent {
    /// A user drag.
    Perturb {
        /// Tick.
        tick: u64,
        /// Body.
        body: String,
        /// Requested centre (m).
        position: [f64; 3],
    },
    /// An injected disturbance.
    Inject {
        /// Tick.
        tick: u64,
        /// `l1`..`l4`.
        level: String,
        /// What it did.
        description: String,
    },
    /// The plan was dropped.
    Cancel {
        /// Tick.
        tick: u64,
    },
}

/// The kind of an event: its `event` tag.
#[derive(Deserialize)]
#[serde(rename_all = "snake_case")]
enum EventKind {
    Perturb,
    Inject,
    Cancel,
}

/// An event as read: field by field, whatever its kind, so that a bad value inside an event is
/// named by its path and position (`events[3].position[1]: … at line L column C`) — an internally
/// tagged enum reads the event whole before its tag and loses both. A key has the same type in
/// every kind; a key of another kind is checked and ignored.
#[derive(Deserialize)]
struct EventFields {
    event: EventKind,
    #[serde(default)]
    tick: Given<u64>,
    #[serde(default)]
    body: Given<String>,
    #[serde(default)]
    position: Given<[f64; 3]>,
    #[serde(default)]
    level: Given<String>,
    #[serde(default)]
    description: Given<String>,
}

/// A key that may be absent (as `Option`, but `null` is not a value).
struct Given<T>(Option<T>);

impl<T> Default for Given<T> {
    fn default() -> Self {
        Given(None)
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Given<T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        T::deserialize(d).map(|v| Given(Some(v)))
    }
}

impl<T> Given<T> {
    fn need(self, key: &str) -> Result<T, String> {
        self.0.ok_or_else(|| format!("missing field `{key}`"))
    }
}

impl TryFrom<EventFields> for EpisodeEvent {
    type Error = String;

    fn try_from(f: EventFields) -> Result<Self, String> {
        let tick = f.tick.need("tick")?;
        Ok(match f.event {
            EventKind::Perturb => EpisodeEvent::Perturb {
                tick,
                body: f.body.need("body")?,
                position: f.position.need("position")?,
            },
            EventKind::Inject => EpisodeEvent::Inject {
                tick,
                level: f.level.need("level")?,
                description: f.description.need("description")?,
            },
            EventKind::Cancel => EpisodeEvent::Cancel { tick },
        })
    }
}

/// One executed (or interrupted) action.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ActionRecord {
    /// The action.
    pub action: String,
    /// Tick it started.
    pub start_tick: u64,
    /// Tick it ended.
    pub end_tick: Option<u64>,
    /// `done`, `interrupted: …`, `failed: …`, `no effect`.
    pub outcome: String,
}

/// The end of an episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeResult {
    /// The goal holds.
    pub success: bool,
    /// Why it failed.
    pub reason: Option<FailReason>,
    /// Simulated execution time (s).
    pub time_s: f64,
    /// Ticks.
    pub ticks: u64,
    /// Actions completed.
    pub actions_executed: usize,
    /// Replans (including the initial plan).
    pub replans: usize,
}

/// The full log of an episode; replays exactly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeLog {
    /// Format version (1).
    pub version: u32,
    /// The session options (benchmark, method, mode, seed, skill).
    pub options: SessionOptions,
    /// The initial world.
    pub scene: WorldSnapshot,
    /// The demonstration JSON if not the benchmark's own.
    pub demo_json: Option<String>,
    /// The task folder the episode ran on (absent for a benchmark's task).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub folder: Option<crate::sim::FolderRecord>,
    /// External events.
    pub events: Vec<EpisodeEvent>,
    /// Every replan.
    pub replans: Vec<Replan>,
    /// Every action started.
    pub actions: Vec<ActionRecord>,
    /// Ticks simulated so far.
    pub ticks: u64,
    /// The result, when the episode ended.
    pub result: Option<EpisodeResult>,
    /// The final facts.
    pub final_facts: Vec<String>,
    /// The final world.
    pub final_world: WorldSnapshot,
}

impl EpisodeLog {
    /// The log with wall-clock planning and binding times zeroed: equal for two runs of the same episode.
    pub fn canonical(&self) -> EpisodeLog {
        let mut c = self.clone();
        for r in &mut c.replans {
            r.time_ms = 0.0;
            r.bind_ms = 0.0;
        }
        c
    }
}
