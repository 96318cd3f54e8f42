//! The candidates of one Logic-LfD replan: for every L_k (and G) what the planner's own search
//! found — the cost of the prefix from S_C to L_k, the cost c_k of the demonstration left after
//! it, and their total — so a user can see why the mode joined the L_k it did.
//!
//! The numbers are the multi-goal search's (see
//! [`MultiGoalResult::reached`](crate::plan::MultiGoalResult::reached)): the cheapest path to a
//! state satisfying L_k among the states it registered. Goals it stopped before meeting are
//! `unreached`; goals it was never given (LogicIn matched without a search, L_k before an
//! action that could not be bound, an L_k the task cannot express) are `not-searched`; goals
//! prioritised mode's optimal search proved no cheaper than the joined one, without a path to
//! them below that bound, are `not-cheaper`.

use serde::{Deserialize, Serialize};

use super::demo::MultiGoalSpec;
use crate::plan::Goal;

/// What became of one candidate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "kebab-case")]
pub enum AlternativeStatus {
    /// The plan joins this one.
    Joined,
    /// The search found a path to it but the mode chose another.
    Reached,
    /// The search stopped before it met a state satisfying it.
    Unreached,
    /// No search looked for it.
    NotSearched,
    /// Prioritised mode's optimal search, bounded by the joined plan's cost, proved that no plan
    /// through it is cheaper (it found no path below that bound, so no numbers).
    NotCheaper,
}

/// One candidate L_k of a replan.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct Alternative {
    /// The demonstration state index (`None`: the task goal G itself).
    pub k: Option<usize>,
    /// What became of it.
    pub status: AlternativeStatus,
    /// Cost of the prefix from S_C to L_k the search found (`None` unless joined or reached).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prefix: Option<u64>,
    /// c_k, the cost of the demonstration actions after L_k (0 for G).
    pub suffix: u64,
    /// `prefix + suffix` (`None` unless joined or reached).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total: Option<u64>,
}

impl Alternative {
    fn new(k: Option<usize>, status: AlternativeStatus, prefix: Option<u64>, suffix: u64) -> Self {
        Alternative {
            k,
            status,
            prefix,
            suffix,
            total: prefix.map(|p| p.saturating_add(suffix)),
        }
    }
}

/// The goal index's L_k (`None` for G, index N + 1).
fn k_of(spec: &MultiGoalSpec, i: usize) -> Option<usize> {
    (i < spec.goal_index()).then_some(i)
}

/// The candidates after a multi-goal search over `goals` (the spec's goals, some possibly
/// emptied) that joined goal `joined` with a prefix of cost `joined_prefix`; `reached` is the
/// search's per-goal cheapest path cost.
pub(crate) fn after_search(
    spec: &MultiGoalSpec,
    goals: &[Goal],
    reached: &[Option<u64>],
    joined: usize,
    joined_prefix: u64,
) -> Vec<Alternative> {
    goals
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let k = k_of(spec, i);
            if i == joined {
                Alternative::new(
                    k,
                    AlternativeStatus::Joined,
                    Some(joined_prefix),
                    g.terminal_cost,
                )
            } else if g.alternatives.is_empty() {
                Alternative::new(k, AlternativeStatus::NotSearched, None, g.terminal_cost)
            } else {
                match reached.get(i).copied().flatten() {
                    Some(p) => {
                        Alternative::new(k, AlternativeStatus::Reached, Some(p), g.terminal_cost)
                    }
                    None => {
                        Alternative::new(k, AlternativeStatus::Unreached, None, g.terminal_cost)
                    }
                }
            }
        })
        .collect()
}

/// After an optimal search bounded by the joined plan's cost found nothing cheaper: every
/// candidate it did not reach is proved no cheaper.
pub(crate) fn proved_not_cheaper(alts: &mut [Alternative]) {
    for a in alts
        .iter_mut()
        .filter(|a| a.status == AlternativeStatus::Unreached)
    {
        a.status = AlternativeStatus::NotCheaper;
    }
}

/// Marks L_`k` (`None`: G) joined with a prefix of cost `prefix` in candidates another plan
/// joined: that plan's candidate becomes one reached at its own prefix.
pub(crate) fn rejoin(alts: &mut [Alternative], k: Option<usize>, prefix: u64) {
    for a in alts.iter_mut() {
        if a.status == AlternativeStatus::Joined {
            *a = Alternative::new(a.k, AlternativeStatus::Reached, a.prefix, a.suffix);
        }
    }
    if let Some(a) = alts.iter_mut().find(|a| a.k == k) {
        *a = Alternative::new(k, AlternativeStatus::Joined, Some(prefix), a.suffix);
    }
}

/// The candidates when LogicIn matched L_`k` and no search ran: the suffix from L_k, the rest
/// not searched.
pub(crate) fn after_logic_in(spec: &MultiGoalSpec, k: usize) -> Vec<Alternative> {
    spec.goals
        .iter()
        .enumerate()
        .map(|(i, g)| {
            if i == k {
                Alternative::new(
                    k_of(spec, i),
                    AlternativeStatus::Joined,
                    Some(0),
                    g.terminal_cost,
                )
            } else {
                Alternative::new(
                    k_of(spec, i),
                    AlternativeStatus::NotSearched,
                    None,
                    g.terminal_cost,
                )
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lfd::ControlParams;
    use crate::lfd::PlanSource;
    use crate::lfd::{LogicLfd, Method, Mode};
    use crate::lfd::{Session, SessionOptions};
    use crate::plan::{self, replay, MultiGoalMode, NoClock, State};
    use crate::sim::Benchmark;

    fn lfd_of(benchmark: Benchmark) -> LogicLfd {
        let session = Session::new(SessionOptions {
            benchmark,
            method: Method::LogicLfd,
            mode: Mode::Paper,
            seed: 0,
            skill: Default::default(),
            blocks: None,
        })
        .unwrap();
        let c = session.controller();
        LogicLfd::from_task(c.task().clone(), c.trace().clone())
    }

    /// The optimal cost from `s` to a state satisfying goal `i`, by a search of its own.
    fn optimum(lfd: &LogicLfd, s: &State, i: usize) -> Option<u64> {
        let mut goal = lfd.spec().goals[i].clone();
        goal.terminal_cost = 0;
        let cfg = ControlParams::default().search;
        plan::search_multi_goal(
            lfd.task(),
            s,
            &[goal],
            MultiGoalMode::FirstReached,
            &cfg,
            &NoClock,
        )
        .plan()
        .map(|p| p.cost)
    }

    /// Checks one replan's candidates against independent searches; true when it searched.
    fn check(lfd: &LogicLfd, s: &State, mode: Mode) -> Option<u64> {
        let cfg = ControlParams::default().search;
        let p = lfd.replan(s, mode, &cfg, &NoClock).ok()?;
        let spec = lfd.spec();
        let task = lfd.task();
        if p.source != PlanSource::MultiGoal {
            return None;
        }
        let goal_of = |a: &Alternative| a.k.unwrap_or(spec.goal_index());
        assert_eq!(p.alternatives.len(), spec.goals.len());
        let joined: Vec<&Alternative> = p
            .alternatives
            .iter()
            .filter(|a| a.status == AlternativeStatus::Joined)
            .collect();
        assert_eq!(joined.len(), 1, "{mode:?}");
        let j = joined[0];
        assert_eq!(j.k, p.k, "{mode:?}: the joined candidate is the plan's L_k");
        assert_eq!(j.prefix, Some(task.cost_of(&p.ops[..p.prefix_len])));
        assert_eq!(
            j.total,
            Some(p.cost),
            "{mode:?}: prefix + c_k is the merged plan's cost"
        );
        let optima: Vec<Option<u64>> = (0..spec.goals.len()).map(|i| optimum(lfd, s, i)).collect();
        for a in &p.alternatives {
            let i = goal_of(a);
            let suffix = spec.suffix(i).map(|ops| task.cost_of(&ops));
            if a.status != AlternativeStatus::NotSearched {
                assert_eq!(Some(a.suffix), suffix, "c_k of L{i}");
            }
            if let Some(prefix) = a.prefix {
                assert_eq!(a.total, Some(prefix + a.suffix));
                // A path the search really found: never cheaper than the optimum.
                let opt = optima[i].expect("a reached goal is reachable");
                assert!(
                    opt <= prefix,
                    "{mode:?}: L{i} reported {prefix} < optimum {opt}"
                );
            } else {
                assert_eq!(a.total, None);
            }
            if a.status == AlternativeStatus::NotCheaper {
                // Proved: no plan through it beats the joined one.
                assert_eq!(mode, Mode::Prioritised);
                if let (Some(opt), Some(total)) = (optima[i], j.total) {
                    assert!(
                        opt + a.suffix >= total,
                        "L{i}: {opt} + {} < {total}",
                        a.suffix
                    );
                }
            }
        }
        let best_total = optima
            .iter()
            .zip(&spec.goals)
            .filter(|(_, g)| !g.alternatives.is_empty())
            .filter_map(|(o, g)| o.map(|o| o + g.terminal_cost))
            .min();
        match mode {
            Mode::Prioritised => {
                let reported_min = p.alternatives.iter().filter_map(|a| a.total).min();
                assert_eq!(j.total, reported_min, "minimum among the reported totals");
                assert_eq!(j.total, best_total, "minimum over every L_k");
            }
            Mode::Paper => {
                // The first goal state A* takes off its list: the cheapest prefix to any L_k, and
                // among the goals holding there the one with the least demo left (then lowest k).
                let cheapest = optima.iter().flatten().min().copied();
                assert_eq!(j.prefix, cheapest, "first reached = cheapest prefix");
                let reported_min = p.alternatives.iter().filter_map(|a| a.prefix).min();
                assert_eq!(j.prefix, reported_min);
                let end = replay(task, s, &p.ops[..p.prefix_len]).unwrap();
                let holding = spec
                    .goals
                    .iter()
                    .enumerate()
                    .filter(|(_, g)| g.alternatives.iter().any(|c| c.holds(&end)));
                let rule = holding
                    .min_by_key(|(i, g)| (g.terminal_cost, *i))
                    .map(|(i, _)| i);
                assert_eq!(
                    Some(goal_of(j)),
                    rule,
                    "smallest (c_k, k) among the goals reached"
                );
            }
        }
        j.total
    }

    #[test]
    fn replan_candidates_carry_the_search_costs_and_each_mode_picks_by_its_rule() {
        let mut paper_longer = 0;
        for benchmark in [Benchmark::B1, Benchmark::B2] {
            let lfd = lfd_of(benchmark);
            let mut searched = 0;
            for (n, d) in lfd.perturb(40, 7, 6).into_iter().enumerate() {
                let paper = check(&lfd, &d.state, Mode::Paper);
                let prio = check(&lfd, &d.state, Mode::Prioritised);
                if let (Some(a), Some(b)) = (paper, prio) {
                    searched += 1;
                    assert!(b <= a, "{benchmark:?} state {n}");
                    paper_longer += usize::from(b < a);
                }
            }
            assert!(
                searched >= 5,
                "{benchmark:?}: only {searched} states needed a search"
            );
        }
        // Seeded states where the paper's first-reached L_k leaves a longer plan are among them.
        assert!(paper_longer >= 1);
    }

    #[test]
    fn a_logic_in_match_reports_the_suffix_alone() {
        let lfd = lfd_of(Benchmark::B1);
        let s = lfd.demo_state(2).unwrap().clone();
        let cfg = ControlParams::default().search;
        let p = lfd.replan(&s, Mode::Prioritised, &cfg, &NoClock).unwrap();
        assert_eq!(p.source, PlanSource::LogicIn);
        let j: Vec<&Alternative> = p
            .alternatives
            .iter()
            .filter(|a| a.status != AlternativeStatus::NotSearched)
            .collect();
        assert_eq!(j.len(), 1);
        assert_eq!(
            (j[0].k, j[0].prefix, j[0].total),
            (Some(2), Some(0), Some(p.cost))
        );
    }
}
