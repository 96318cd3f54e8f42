//! A session's log, and its replay: the loop re-run tick by tick reproduces the episode exactly.

use crate::plan::NoClock;

use super::log::{EpisodeEvent, EpisodeLog, EpisodeResult};
use super::{facts_of, Session, SessionError, SessionParams};
use crate::sim::ArmModel;
use crate::sim::{BenchmarkSources, TaskFolder};
use std::sync::Arc;

impl Session {
    /// Re-runs a logged episode tick by tick (see [`Session::replay_with_sources`]).
    pub fn replay(episode_json: &str) -> Result<Session, SessionError> {
        Session::replay_with_robots(episode_json, &[])
    }

    /// [`Session::replay`] of an episode that ran on robots read from their URDFs: each arm the
    /// log's scene names a robot for takes the model of that name from `robots`.
    pub fn replay_with_robots(
        episode_json: &str,
        robots: &[Arc<ArmModel>],
    ) -> Result<Session, SessionError> {
        let log: EpisodeLog = crate::sim::parse_json(episode_json)
            .map_err(|e| SessionError::Json(format!("episode: {e}")))?;
        let files = match &log.folder {
            None => super::sources_for(log.options.benchmark, log.options.blocks)?,
            Some(record) => match TaskFolder::from_record(record) {
                Some(folder) => folder.sources()?,
                None => {
                    return Err(SessionError::Json(format!(
                        "episode: it ran on the task folder {}, which the log does not carry: \
                         replay it with that folder",
                        record.dir
                    )))
                }
            },
        };
        Session::replay_on(&files, episode_json, robots)
    }

    /// Re-runs a logged episode on `folder`, after checking the folder's files are those the
    /// episode ran on (each file that differs is named), with the robots the log's scene names
    /// ([`Session::replay_on`]).
    pub fn replay_in_folder(
        folder: &TaskFolder,
        episode_json: &str,
        robots: &[Arc<ArmModel>],
    ) -> Result<Session, SessionError> {
        let log: EpisodeLog = crate::sim::parse_json(episode_json)
            .map_err(|e| SessionError::Json(format!("episode: {e}")))?;
        let Some(record) = &log.folder else {
            return Err(SessionError::Json(format!(
                "episode: it ran on benchmark {}'s task, not on a task folder: replay it without {}",
                log.options.benchmark.as_str(),
                folder.dir
            )));
        };
        folder.check_against(record)?;
        Session::replay_on(&folder.sources()?, episode_json, robots)
    }

    /// The full log of the episode so far.
    pub fn log(&self) -> EpisodeLog {
        let result = self.outcome.as_ref().map(|o| EpisodeResult {
            success: o.is_ok(),
            reason: o.as_ref().err().cloned(),
            time_s: self.world.time(),
            ticks: self.tick,
            actions_executed: self.actions_done,
            replans: self.controller.replans().len(),
        });
        EpisodeLog {
            version: 1,
            options: self.options.clone(),
            scene: self.initial.clone(),
            demo_json: self.demo_json.clone(),
            folder: self.sources.folder.clone(),
            events: self.events.clone(),
            replans: self.controller.replans().to_vec(),
            actions: self.actions.clone(),
            ticks: self.tick,
            result,
            final_facts: facts_of(&self.world),
            final_world: self.world.snapshot(),
        }
    }

    /// The full log as JSON; [`Session::replay`] reproduces the episode from it.
    pub fn episode_json(&self) -> String {
        serde_json::to_string(&self.log()).unwrap_or_default()
    }

    /// Re-runs a logged episode tick by tick, applying its events at their ticks.
    pub fn replay_with_sources(
        files: &BenchmarkSources,
        episode_json: &str,
    ) -> Result<Session, SessionError> {
        Session::replay_on(files, episode_json, &[])
    }

    /// [`Session::replay_with_sources`] with the robots the log's scene names
    /// ([`Session::replay_with_robots`]).
    pub fn replay_on(
        files: &BenchmarkSources,
        episode_json: &str,
        robots: &[Arc<ArmModel>],
    ) -> Result<Session, SessionError> {
        let log: EpisodeLog = crate::sim::parse_json(episode_json)
            .map_err(|e| SessionError::Json(format!("episode: {e}")))?;
        // Through JSON and back, as a scene file is read; then each named robot's model.
        let scene = serde_json::to_string(&log.scene)
            .map_err(|e| SessionError::Json(format!("episode: scene: {e}")))?;
        let mut scene: crate::sim::WorldSnapshot = crate::sim::parse_json(&scene)
            .map_err(|e| SessionError::Json(format!("episode: scene: {e}")))?;
        for arm in &mut scene.arms {
            arm.model = arm
                .robot
                .as_ref()
                .and_then(|name| robots.iter().find(|r| r.name() == name))
                .cloned();
        }
        let mut s = Session::starting(
            log.options.clone(),
            files,
            super::Start::Snapshot(&scene),
            log.demo_json.as_deref(),
            SessionParams::default(),
        )?;
        let mut events = log.events.iter().peekable();
        let clock = NoClock;
        loop {
            while let Some(e) = events.peek() {
                let t = match e {
                    EpisodeEvent::Perturb { tick, .. }
                    | EpisodeEvent::Inject { tick, .. }
                    | EpisodeEvent::Cancel { tick } => *tick,
                };
                if t > s.tick {
                    break;
                }
                match e {
                    EpisodeEvent::Perturb { body, position, .. } => {
                        let _ = s.perturb(body, *position);
                    }
                    EpisodeEvent::Inject { level, .. } => {
                        let _ = s.inject(level);
                    }
                    EpisodeEvent::Cancel { .. } => s.cancel(),
                }
                events.next();
            }
            if s.outcome.is_some() {
                break;
            }
            if s.tick >= log.ticks {
                // The final decision (done / failed) takes no tick.
                if log.result.is_some() {
                    s.tick_once(&clock);
                }
                break;
            }
            let before = s.tick;
            s.tick_once(&clock);
            if s.tick == before && s.outcome.is_none() && s.exec.is_none() {
                break;
            }
        }
        // The next `step` reports the facts that change after the replayed end, not since the start.
        s.prev_facts = facts_of(&s.world);
        Ok(s)
    }
}
