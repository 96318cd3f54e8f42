//! Task generator for the paper's Table I: random initial states of a benchmark, same goal, the
//! template world varied by one disturbance of a given level (B2 and B3 keep their two blocks, as
//! the paper does; L4 adds one).
//!
//! Task `i` of a batch with seed `s` uses the injector seed `s · 1000 + i` (then `+ 100 000 · k` for
//! the k-th retry if an injector finds no arrangement), so any task can be regenerated alone.

use super::benchmark::Benchmark;
use super::demo::{demo_states, DemoError};
use super::disturb::{inject, DisturbError, Level};
use super::scene_graph::SceneGraph;
use super::snapshot::WorldSnapshot;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// One generated task.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TaskInstance {
    /// Benchmark directory name.
    pub benchmark: String,
    /// Disturbance level of the initial state.
    pub level: Level,
    /// Index in the batch.
    pub index: usize,
    /// Injector seed that produced it.
    pub seed: u64,
    /// What the injector did, in words.
    pub description: String,
    /// The initial world.
    pub scene: WorldSnapshot,
    /// Its scene-graph facts.
    pub facts: Vec<String>,
    /// The PDDL problem (objects and init from the scene, the benchmark's goal).
    pub problem_pddl: String,
}

/// Why tasks could not be generated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TaskError {
    /// The committed demo could not be replayed.
    #[error(transparent)]
    Demo(#[from] DemoError),
    /// An injector failed on every retry.
    #[error("task {index}: {source}")]
    Disturb {
        /// Task index.
        index: usize,
        /// Last injector error.
        source: DisturbError,
    },
}

/// Generates `count` tasks of benchmark `b` whose initial states are the template varied at
/// `level`.
pub fn generate(
    b: Benchmark,
    level: Level,
    count: usize,
    seed: u64,
) -> Result<Vec<TaskInstance>, TaskError> {
    let states = demo_states(b)?;
    (0..count)
        .map(|i| generate_one(b, level, i, seed, &states))
        .collect()
}

/// The paper's Table I batch: `count` tasks of `b`, spread evenly over L1..L4 (task `i` has
/// level `L(1 + i mod 4)`).
pub fn generate_table1(
    b: Benchmark,
    count: usize,
    seed: u64,
) -> Result<Vec<TaskInstance>, TaskError> {
    let states = demo_states(b)?;
    (0..count)
        .map(|i| generate_one(b, Level::ALL[i % 4], i, seed, &states))
        .collect()
}

fn generate_one(
    b: Benchmark,
    level: Level,
    index: usize,
    seed: u64,
    states: &[BTreeSet<String>],
) -> Result<TaskInstance, TaskError> {
    let mut last = DisturbError::Failed("no attempt".into());
    for retry in 0..5u64 {
        let s = seed
            .wrapping_mul(1000)
            .wrapping_add(index as u64)
            .wrapping_add(100_000 * retry);
        let mut w = b.scene();
        match inject(&mut w, b, level, states, s) {
            Ok(d) => {
                let name = format!("{}-{}-{index}", b.dir_name(), level.id());
                return Ok(TaskInstance {
                    benchmark: b.dir_name().to_string(),
                    level,
                    index,
                    seed: s,
                    description: d.description,
                    scene: w.snapshot(),
                    facts: SceneGraph::from_world(&w).to_strings(),
                    problem_pddl: b.problem_for(&w, &name),
                });
            }
            Err(e) => last = e,
        }
    }
    Err(TaskError::Disturb {
        index,
        source: last,
    })
}
