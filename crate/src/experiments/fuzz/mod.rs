//! Mutation fuzzing of every input the library takes from users, shared by the
//! CI property tests (`crate/tests/fuzz`) and the `logic-lfd fuzz` command, so both run the same
//! mutators against the same guarantees.
//!
//! A [`FuzzTarget`] names an input format. Each has *base inputs* (the benchmarks' own files, built
//! into the library), a *mutator* (seeded edits: structural ones on the parsed form, then
//! byte-level ones on the text) and an *oracle* ([`check`]) that states the guarantees:
//!
//! | target      | parser under test                                  | guarantee besides "no panic"                                  |
//! |-------------|----------------------------------------------------|---------------------------------------------------------------|
//! | `pddl`      | `parse_domain`, `parse_problem`, `ground`          | an error names its file and a `line:col` inside the text      |
//! | `plan`      | `parse_plan`, `validate`                           | errors located; a failing step exists; counts agree           |
//! | `scene`     | `World::from_json`                                 | refusal names a key path or `line L column C`; an accepted scene is a valid world that round-trips |
//! | `case`      | `CaseInput::from_json_str`, `run_case`             | refusal names the key; an accepted case solves or fails numerically |
//! | `episode`   | `EpisodeLog` parse, `Session::replay`              | parse errors located; an accepted log replays                 |
//! | `world-ops` | `World::move_block(_to)`, `World::add_block`       | a refused operation changes nothing; an accepted one keeps the invariants |
//!
//! Every input is text, so a failing one can be saved to a corpus directory and replayed alone
//! (`logic-lfd fuzz --target T --replay FILE`). PDDL and plan inputs start with a comment line
//! `; fuzz <benchmark-dir> [domain|problem]` naming the files they stand for; world-ops inputs
//! are JSON (`{"benchmark":"b1","ops":[…]}`; coordinates may be strings `"nan"`, `"inf"`).
//!
//! Case `i` of a run with seed `S` draws everything from `Pcg64Mcg(mix_seed(S, i))`.
//!
//! This file holds what every format shares: the targets, the base inputs, the seeded driver
//! and its report. Each format's mutator and oracle live in a file of their own: PDDL text
//! (`pddl.rs`), plan files (`plan.rs`), JSON documents — scenes, LQT-CP cases, episodes
//! (`json.rs`) — and world operations (`world_ops.rs`).

mod common;
mod json;
mod pddl;
mod plan;
mod world_ops;

pub use common::Verdict;
use common::BENCH_DIRS;
pub use json::{hostile_value, is_line_col_within, mutate_json, JsonEdit, MAX_REPLAY_TICKS};
pub use pddl::{mutate_pddl, pddl_error_in_bounds, PddlEdit};
pub use plan::{check_plan_against, mutate_plan, PlanEdit};
pub use world_ops::{Coord, SpecialFloat, WorldOp, WorldOps};

use std::panic::{catch_unwind, AssertUnwindSafe};

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};
use serde_json::json;

use crate::lfd::{demo_actions, mix_seed};

/// An input format under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FuzzTarget {
    /// PDDL domain and problem files.
    Pddl,
    /// Plan files for `validate`.
    Plan,
    /// Scene JSON.
    Scene,
    /// LQT-CP case JSON.
    Case,
    /// Episode JSON (replay).
    Episode,
    /// World operations (drags, new blocks), as the page sends them.
    WorldOps,
}

impl FuzzTarget {
    /// Every target.
    pub const ALL: [FuzzTarget; 6] = [
        FuzzTarget::Pddl,
        FuzzTarget::Plan,
        FuzzTarget::Scene,
        FuzzTarget::Case,
        FuzzTarget::Episode,
        FuzzTarget::WorldOps,
    ];

    /// `pddl`, `plan`, `scene`, `case`, `episode`, `world-ops`.
    pub fn as_str(self) -> &'static str {
        match self {
            FuzzTarget::Pddl => "pddl",
            FuzzTarget::Plan => "plan",
            FuzzTarget::Scene => "scene",
            FuzzTarget::Case => "case",
            FuzzTarget::Episode => "episode",
            FuzzTarget::WorldOps => "world-ops",
        }
    }

    /// Parses a target name.
    pub fn parse(s: &str) -> Option<FuzzTarget> {
        FuzzTarget::ALL.into_iter().find(|t| t.as_str() == s)
    }

    /// File extension of a saved input.
    pub fn extension(self) -> &'static str {
        match self {
            FuzzTarget::Pddl => "pddl",
            FuzzTarget::Plan => "plan",
            _ => "json",
        }
    }
}

// ------------------------------------------------------------------------------ base inputs

/// The base inputs of a target (mutations start from one of them).
pub fn base_inputs(target: FuzzTarget) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    for (dir, b) in BENCH_DIRS {
        let files = b.sources().map_err(|e| e.to_string())?;
        match target {
            FuzzTarget::Pddl => {
                out.push(format!("; fuzz {dir} domain\n{}", files.domain));
                out.push(format!("; fuzz {dir} problem\n{}", files.problem));
            }
            FuzzTarget::Plan => {
                let demo = demo_actions(&files.demo).map_err(|e| e.to_string())?;
                out.push(format!("; fuzz {dir}\n{}\n", demo.join("\n")));
            }
            FuzzTarget::Scene => out.push(files.scene),
            FuzzTarget::Case | FuzzTarget::Episode | FuzzTarget::WorldOps => {}
        }
    }
    match target {
        FuzzTarget::Case => out.push(json::base_case()),
        FuzzTarget::Episode => out.push(json::base_episode()?),
        FuzzTarget::WorldOps => {
            for b in ["b1", "b2", "b3"] {
                out.push(json!({"benchmark": b, "ops": []}).to_string());
            }
        }
        _ => {}
    }
    Ok(out)
}

// ------------------------------------------------------------------------------ mutate

/// Mutates `base` for `target` with `1..=max_edits` random edits.
pub fn mutate(target: FuzzTarget, base: &str, max_edits: usize, rng: &mut Pcg64Mcg) -> String {
    let k = rng.random_range(1..=max_edits.max(1));
    let header_split = |t: &str| -> (String, String) {
        match t.split_once('\n') {
            Some((h, rest)) if h.starts_with("; fuzz ") => (format!("{h}\n"), rest.to_string()),
            _ => (String::new(), t.to_string()),
        }
    };
    match target {
        FuzzTarget::Pddl => {
            let (h, body) = header_split(base);
            let edits: Vec<PddlEdit> = (0..k).map(|_| PddlEdit::random(rng)).collect();
            h + &mutate_pddl(&body, &edits)
        }
        FuzzTarget::Plan => {
            let (h, body) = header_split(base);
            let edits: Vec<PlanEdit> = (0..k).map(|_| PlanEdit::random(rng)).collect();
            h + &mutate_plan(&body, &edits)
        }
        FuzzTarget::Scene | FuzzTarget::Case | FuzzTarget::Episode => {
            let edits: Vec<JsonEdit> = (0..k).map(|_| JsonEdit::random(rng)).collect();
            String::from_utf8_lossy(&mutate_json(base, &edits)).into_owned()
        }
        FuzzTarget::WorldOps => {
            let mut ops: WorldOps = serde_json::from_str(base).unwrap_or(WorldOps {
                benchmark: "b1".into(),
                ops: vec![],
            });
            let n = rng.random_range(1..=3 * max_edits.max(1));
            ops.ops.extend((0..n).map(|_| WorldOp::random(rng)));
            serde_json::to_string(&ops).unwrap_or_default()
        }
    }
}

/// Case `index` of a run with `seed`: a base input picked and mutated from
/// `Pcg64Mcg(mix_seed(seed, index))`.
pub fn generate(
    target: FuzzTarget,
    bases: &[String],
    seed: u64,
    index: u64,
    max_edits: usize,
) -> String {
    let mut rng = Pcg64Mcg::seed_from_u64(mix_seed(seed, index));
    let base = if bases.is_empty() {
        ""
    } else {
        &bases[rng.random_range(0..bases.len())]
    };
    mutate(target, base, max_edits, &mut rng)
}

// ------------------------------------------------------------------------------ oracles

/// The oracle: runs `input` through the parser(s) of `target` and checks the guarantees of the
/// module table. `Err` names a broken guarantee. It may panic (that is what fuzzing looks for):
/// [`run`] catches panics.
pub fn check(target: FuzzTarget, input: &str) -> Result<Verdict, String> {
    match target {
        FuzzTarget::Pddl => pddl::check_pddl(input),
        FuzzTarget::Plan => plan::check_plan(input),
        FuzzTarget::Scene => json::check_scene(input),
        FuzzTarget::Case => json::check_case(input),
        FuzzTarget::Episode => json::check_episode(input),
        FuzzTarget::WorldOps => world_ops::check_world_ops(input),
    }
}

// ------------------------------------------------------------------------------ runner

/// Tunables of a fuzz run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzParams {
    /// The target.
    pub target: FuzzTarget,
    /// Inputs to try.
    pub iterations: u64,
    /// Seed (case `i` draws from `mix_seed(seed, i)`).
    pub seed: u64,
    /// Most edits per input.
    pub max_edits: usize,
}

/// An input that broke a guarantee or panicked.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzFinding {
    /// Case index (regenerate with the same seed).
    pub index: u64,
    /// `panic` or `guarantee`.
    pub kind: String,
    /// The panic message or the broken guarantee.
    pub message: String,
    /// The input.
    pub input: String,
}

/// The figures of a fuzz run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FuzzReport {
    /// The parameters.
    pub params: FuzzParams,
    /// Inputs tried.
    pub inputs: u64,
    /// Inputs accepted (and checked).
    pub accepted: u64,
    /// Inputs refused with a located error.
    pub refused: u64,
    /// Every finding (inputs included).
    pub findings: Vec<FuzzFinding>,
}

impl FuzzReport {
    /// No panic and no broken guarantee.
    pub fn is_clean(&self) -> bool {
        self.findings.is_empty()
    }
}

/// Runs `input` through [`check`], turning a panic into `Err("panicked: …")`.
pub fn check_catching(target: FuzzTarget, input: &str) -> Result<Verdict, (String, String)> {
    match catch_unwind(AssertUnwindSafe(|| check(target, input))) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(m)) => Err(("guarantee".into(), m)),
        Err(p) => Err((
            "panic".into(),
            crate::experiments::panic_message(p.as_ref()),
        )),
    }
}

/// Runs a fuzz campaign; `before_each(index, input)` is called before each input runs (the CLI
/// saves it, so an input that aborts the process — a stack overflow — is not lost).
pub fn run(
    params: &FuzzParams,
    mut before_each: impl FnMut(u64, &str),
) -> Result<FuzzReport, String> {
    let bases = base_inputs(params.target)?;
    let mut report = FuzzReport {
        params: *params,
        inputs: 0,
        accepted: 0,
        refused: 0,
        findings: vec![],
    };
    for i in 0..params.iterations {
        let input = generate(params.target, &bases, params.seed, i, params.max_edits);
        before_each(i, &input);
        report.inputs += 1;
        match check_catching(params.target, &input) {
            Ok(Verdict::Accepted) => report.accepted += 1,
            Ok(Verdict::Refused) => report.refused += 1,
            Err((kind, message)) => report.findings.push(FuzzFinding {
                index: i,
                kind,
                message,
                input,
            }),
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pddl::{parse_domain, PddlError};

    #[test]
    fn targets_parse_their_names() {
        for t in FuzzTarget::ALL {
            assert_eq!(FuzzTarget::parse(t.as_str()), Some(t));
        }
        assert_eq!(FuzzTarget::parse("nope"), None);
    }

    #[test]
    fn generation_is_a_function_of_seed_and_index() {
        let bases = base_inputs(FuzzTarget::Pddl).unwrap();
        let a = generate(FuzzTarget::Pddl, &bases, 7, 3, 4);
        assert_eq!(a, generate(FuzzTarget::Pddl, &bases, 7, 3, 4));
        assert!(a.starts_with("; fuzz "), "the header is kept: {a:.40}");
        assert!((0..20).any(|i| generate(FuzzTarget::Pddl, &bases, 7, i, 4) != a));
    }

    #[test]
    fn unmutated_bases_are_accepted() {
        for t in [
            FuzzTarget::Pddl,
            FuzzTarget::Plan,
            FuzzTarget::Scene,
            FuzzTarget::Case,
            FuzzTarget::WorldOps,
        ] {
            for b in base_inputs(t).unwrap() {
                let v = check(t, &b);
                let want = if t == FuzzTarget::WorldOps {
                    Verdict::Refused // no op: nothing accepted
                } else {
                    Verdict::Accepted
                };
                assert_eq!(v, Ok(want), "{t:?}: {b:.60}");
            }
        }
    }

    #[test]
    fn oracles_catch_what_they_promise() {
        // An unlocated PDDL error would be caught: feed the oracle a located one and check it
        // passes, then a fake out-of-bounds location fails the bound check.
        let text = "(define (domain d)\n  (:predicates (p))";
        let e = parse_domain(text, "domain.pddl").unwrap_err();
        assert!(pddl_error_in_bounds(text, &e), "{e}");
        let far = PddlError {
            line: 9,
            ..e.clone()
        };
        assert!(!pddl_error_in_bounds(text, &far));
        assert!(is_line_col_within("line 1 column 3", "abcd"));
        assert!(!is_line_col_within("line 2 column 3", "abcd"));
        // A world-ops input whose op is accepted is checked against the invariants.
        let ops = WorldOps {
            benchmark: "b1".into(),
            ops: vec![WorldOp::Move {
                body: "a".into(),
                to: [Coord::Num(0.40), Coord::Num(-0.20), Coord::Num(0.1)],
            }],
        };
        let s = serde_json::to_string(&ops).unwrap();
        assert_eq!(check(FuzzTarget::WorldOps, &s), Ok(Verdict::Accepted));
        // Non-finite coordinates survive the JSON encoding.
        let nan = WorldOp::Move {
            body: "a".into(),
            to: [
                Coord::new(f64::NAN),
                Coord::new(f64::INFINITY),
                Coord::Num(0.1),
            ],
        };
        let back: WorldOp = serde_json::from_str(&serde_json::to_string(&nan).unwrap()).unwrap();
        match back {
            WorldOp::Move { to, .. } => {
                assert!(to[0].value().is_nan() && to[1].value() == f64::INFINITY)
            }
            _ => panic!("wrong op"),
        }
    }

    #[test]
    fn a_short_campaign_per_target_is_clean() {
        for t in [
            FuzzTarget::Pddl,
            FuzzTarget::Plan,
            FuzzTarget::Scene,
            FuzzTarget::Case,
            FuzzTarget::WorldOps,
        ] {
            let r = run(
                &FuzzParams {
                    target: t,
                    iterations: 40,
                    seed: 1,
                    max_edits: 3,
                },
                |_, _| {},
            )
            .unwrap();
            assert_eq!(r.inputs, 40);
            assert!(r.is_clean(), "{t:?}: {:#?}", r.findings);
            assert!(r.refused > 0, "{t:?}: every mutant accepted");
        }
    }
}
