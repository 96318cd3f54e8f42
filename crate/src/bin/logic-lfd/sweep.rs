//! Sweeps on every core and across machines, for the commands whose work is a list of
//! independent items: `soak` (episodes), `bench table1` (tasks), `bench table2` (trials),
//! `bench scaling` (tasks) and `lfd --perturb` (drawn states).
//!
//! * `--threads N` runs the items on a local pool of N threads (default: every core; `1`: one
//!   after another on the calling thread). Every item is seeded from the sweep's seed and its own
//!   index alone, the records are collected in item order and the report is built from them
//!   afterwards, so the output is byte-identical for every N (wall-clock times aside).
//! * `--shard K/N` runs only shard K of N: item `i` (0-based, in the sweep's order) belongs to
//!   shard `(i mod N) + 1`, so the shards interleave and each gets its share of slow and fast
//!   items. Instead of the report the run prints its shard file ([`ShardFile`], JSON) on stdout;
//!   `logic-lfd merge` joins the N files into the report the whole sweep prints.

use std::fmt;
use std::process::ExitCode;
use std::str::FromStr;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::exit;

/// The `format` of every shard file.
pub const FORMAT: &str = "logic-lfd shard";

/// The version of the shard-file layout; `merge` reads this version only.
pub const FORMAT_VERSION: u32 = 1;

/// Stack of a pool thread: as deep as the main thread's, for the recursive parts of planning.
const THREAD_STACK: usize = 16 << 20;

/// Shard K of N: item `i` of a sweep belongs to shard `(i mod N) + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which shard, 1 … n.
    pub k: usize,
    /// How many shards.
    pub n: usize,
}

impl Shard {
    /// Whether item `index` belongs to this shard.
    pub fn holds(self, index: usize) -> bool {
        index % self.n == self.k - 1
    }

    /// The indices of this shard's items among `items`, in order.
    pub fn indices(self, items: usize) -> Vec<usize> {
        (self.k - 1..items).step_by(self.n).collect()
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let expected = "expected K/N with whole numbers 1 ≤ K ≤ N, e.g. 2/8";
        let (k, n) = s.split_once('/').ok_or_else(|| expected.to_string())?;
        let number = |t: &str| t.trim().parse::<usize>().ok();
        match (number(k), number(n)) {
            (Some(k), Some(n)) if n >= 1 && (1..=n).contains(&k) => Ok(Shard { k, n }),
            (Some(_), Some(0)) => Err(format!("N is 0; {expected}")),
            (Some(0), Some(_)) => Err(format!("shards count from 1; {expected}")),
            (Some(_), Some(_)) => Err(format!("K is larger than N; {expected}")),
            _ => Err(expected.to_string()),
        }
    }
}

/// A positive number of threads.
fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("expected a whole number of threads ≥ 1".into()),
    }
}

/// The sweep options of a command: `--threads N`, `--shard K/N`.
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct SweepArgs {
    /// Worker threads (default: every core; 1 runs the items one after another). The output
    /// is the same for every number (wall-clock times aside).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Run only shard K of N (item i belongs to shard (i mod N) + 1) and print its shard file
    /// (JSON) instead of the report; `logic-lfd merge` joins the N files into the report.
    #[arg(long, value_name = "K/N", value_parser = Shard::from_str)]
    pub shard: Option<Shard>,
}

impl SweepArgs {
    /// The items this run covers, out of `items`: all, or the shard's.
    pub fn indices(&self, items: usize) -> Vec<usize> {
        match self.shard {
            Some(s) => s.indices(items),
            None => (0..items).collect(),
        }
    }

    /// The threads this run works on: `--threads`, else every core.
    fn threads(&self) -> usize {
        self.threads.unwrap_or_else(|| {
            std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
        })
    }

    /// Runs `run_item` on every index of `indices` and returns the records in that order, or
    /// the error of the first failing index in that order (so the message does not depend on
    /// the number of threads). One thread runs them in turn and stops at the first error; more
    /// run on a pool of this command's own (or in turn, with a warning, if it cannot start).
    pub fn map<R: Send, E: Send>(
        &self,
        indices: &[usize],
        run_item: impl Fn(usize) -> Result<R, E> + Sync,
    ) -> Result<Vec<R>, E> {
        let threads = self.threads().min(indices.len().max(1));
        let pool = (threads > 1).then(|| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .stack_size(THREAD_STACK)
                .thread_name(|i| format!("sweep-{i}"))
                .build()
        });
        let pool = match pool {
            Some(Ok(pool)) => pool,
            Some(Err(e)) => {
                eprintln!("--threads: cannot start {threads} threads ({e}); running on one");
                return indices.iter().map(|&i| run_item(i)).collect();
            }
            None => return indices.iter().map(|&i| run_item(i)).collect(),
        };
        // One item per task: items differ in cost by orders of magnitude, so no batching.
        let results: Vec<Result<R, E>> = pool.install(|| {
            indices
                .par_iter()
                .with_max_len(1)
                .map(|&i| run_item(i))
                .collect()
        });
        results.into_iter().collect()
    }
}

/// One item's record in a shard file.
#[derive(Debug, Serialize, Deserialize)]
pub struct Indexed<R> {
    /// The item's index in the whole sweep.
    pub index: usize,
    /// What the item gave.
    pub record: R,
}

/// What `--shard K/N` prints and `logic-lfd merge` reads: the sweep it is part of and the
/// records of its items.
#[derive(Debug, Serialize, Deserialize)]
pub struct ShardFile<H, R> {
    /// Always [`FORMAT`].
    pub format: String,
    /// The layout's version ([`FORMAT_VERSION`]).
    pub version: u32,
    /// The program that wrote it (`logic-lfd 0.1.0`): the shards of a sweep come from one.
    pub program: String,
    /// The command (`soak`, `bench table1`, `bench table2`, `bench scaling`, `lfd --perturb`).
    pub command: String,
    /// The sweep's parameters: the shards of a sweep carry equal ones.
    pub sweep: H,
    /// Items in the whole sweep.
    pub items: usize,
    /// Which shard this is.
    pub shard: Shard,
    /// The records of the shard's items, in item order.
    pub records: Vec<Indexed<R>>,
}

/// This program's name and version, as shard files record it.
pub fn program() -> String {
    format!("logic-lfd {}", env!("CARGO_PKG_VERSION"))
}

/// Prints shard `shard` of a `command` sweep (`sweep`: its parameters, `items` in all) with the
/// records of `indices` on stdout.
pub fn print_shard<H: Serialize, R: Serialize>(
    command: &str,
    sweep: &H,
    items: usize,
    shard: Shard,
    indices: &[usize],
    records: Vec<R>,
) -> ExitCode {
    let file = ShardFile {
        format: FORMAT.into(),
        version: FORMAT_VERSION,
        program: program(),
        command: command.into(),
        sweep,
        items,
        shard,
        records: indices
            .iter()
            .zip(records)
            .map(|(&index, record)| Indexed { index, record })
            .collect(),
    };
    match serde_json::to_string(&file) {
        Ok(s) => {
            println!("{s}");
            ExitCode::from(exit::OK)
        }
        Err(e) => {
            eprintln!("{command}: cannot write the shard file: {e}");
            ExitCode::from(exit::BAD_INPUT)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_partition_the_items() {
        let s: Shard = "2/3".parse().unwrap();
        assert_eq!(s, Shard { k: 2, n: 3 });
        assert_eq!(s.indices(8), vec![1, 4, 7]);
        let mut all: Vec<usize> = (1..=3)
            .flat_map(|k| Shard { k, n: 3 }.indices(10))
            .collect();
        all.sort();
        assert_eq!(all, (0..10).collect::<Vec<_>>());
        for bad in ["0/3", "4/3", "a/b", "3", "1/0", "-1/3", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
