//! One Logic-LfD query and its result, shared by `logicLfd` (which reads the domain, problem and
//! demonstration first) and the `LogicLfd` class (which read them once, when it was built).

use serde::Serialize;

use super::super::PerformanceClock;
use super::diagnostics::{input_error, location_message, options_diag, Diag};
use super::input::{Files, Options, Texts};
use crate::lfd::{LfdError, LfdPlan, LogicLfd, Observed, PlanSource};
use crate::plan::{Clock, SearchConfig, SearchOutcome, SearchStats};

/// The demonstration as the result shows it (`LogicLfdDemo`).
#[derive(Debug, Default, Serialize)]
pub(super) struct Demo {
    actions: Vec<String>,
    states: Vec<Vec<String>>,
    costs: Vec<u64>,
}

#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
struct Stats {
    expanded: u64,
    generated: u64,
    evaluated: u64,
    time_ms: f64,
}

impl Stats {
    fn of(s: &SearchStats) -> Self {
        Stats {
            expanded: s.expanded,
            generated: s.generated,
            evaluated: s.evaluated,
            time_ms: s.time_secs * 1e3,
        }
    }
}

#[derive(Debug, Serialize)]
struct Scratch {
    ok: bool,
    plan: Vec<String>,
    cost: Option<u64>,
    stats: Stats,
}

/// `LogicLfdResult`. The parts that do not depend on S_C are borrowed, so the class can keep
/// them across queries.
#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct LfdResult<'f> {
    ok: bool,
    kind: &'static str,
    message: String,
    diagnostics: Vec<Diag>,
    demo: Option<&'f Demo>,
    statics: &'f [String],
    fluents: &'f [String],
    state: Vec<String>,
    applicable: Vec<String>,
    logic_in: Option<usize>,
    k: Option<usize>,
    source: Option<&'static str>,
    prefix: Vec<String>,
    suffix: Vec<String>,
    plan: Vec<String>,
    cost: Option<u64>,
    /// `None` when not asked for (`validate: false`) or when there is no plan.
    valid: Option<bool>,
    stats: Stats,
    scratch: Option<Scratch>,
}

/// What a result says whatever S_C is: the demonstration, the static facts, the fluents.
#[derive(Debug)]
pub(super) struct Fixed {
    pub(super) demo: Demo,
    pub(super) statics: Vec<String>,
    pub(super) fluents: Vec<String>,
}

impl Fixed {
    pub(super) fn of(lfd: &LogicLfd) -> Self {
        Fixed {
            demo: Demo {
                actions: lfd.demo_actions().to_vec(),
                states: lfd
                    .demo_states()
                    .iter()
                    .map(|l| l.iter().cloned().collect())
                    .collect(),
                costs: lfd
                    .spec()
                    .goals
                    .iter()
                    .take(lfd.demo_states().len())
                    .map(|g| g.terminal_cost)
                    .collect(),
            },
            statics: lfd.static_facts().to_vec(),
            fluents: lfd.task().facts.clone(),
        }
    }
}

impl<'f> LfdResult<'f> {
    /// The result with `fixed`'s demonstration, static facts and fluents.
    pub(super) fn with(mut self, fixed: &'f Fixed) -> Self {
        self.demo = Some(&fixed.demo);
        self.statics = &fixed.statics;
        self.fluents = &fixed.fluents;
        self
    }

    /// `ok: false` for a bad option.
    pub(super) fn options_failure(message: String) -> Self {
        LfdResult {
            kind: "options",
            message: message.clone(),
            diagnostics: vec![options_diag(message)],
            ..LfdResult::default()
        }
    }

    /// `ok: false` for an input that could not be read, with its located diagnostic.
    pub(super) fn input_failure(kind: &'static str, d: Diag) -> Self {
        LfdResult {
            kind,
            message: location_message(&d),
            diagnostics: vec![d],
            ..LfdResult::default()
        }
    }
}

/// S_C as a query gives it.
pub(super) enum Current {
    /// PDDL atoms.
    Atoms(String),
    /// The state a plan prefix reaches from the problem's `:init`.
    After(String),
    /// The problem's initial state.
    Init,
}

impl Current {
    /// S_C read on `lfd`, or the result kind and diagnostic of a bad state.
    pub(super) fn read<'l>(
        self,
        lfd: &'l LogicLfd,
        files: &Files,
    ) -> Result<Observed<'l>, (&'static str, Diag)> {
        match self {
            Current::Atoms(text) => lfd.state_in(&files.state, &text),
            Current::After(text) => lfd
                .state_after(&files.state, &text)
                .map(|s| lfd.observed(s)),
            Current::Init => Ok(lfd.observed(lfd.task().init.clone())),
        }
        .map_err(|e| input_error(&e, files, "state"))
    }
}

/// Reads the domain, the problem and the demonstration, or says why not (a result to return).
pub(super) fn prepare(files: &Files, t: &Texts) -> Result<LogicLfd, (&'static str, Diag)> {
    LogicLfd::named(
        (&files.domain, &t.domain),
        (&files.problem, &t.problem),
        (&files.demo, &t.demo),
    )
    .map_err(|e| input_error(&e, files, "problem"))
}

/// One query on a prepared instance: S_C, LogicIn, the merged plan and (unless `validate` is off)
/// its replay on the lifted domain, and with `compare` planning from scratch. The result leaves out the demonstration,
/// the static facts and the fluents ([`LfdResult::with`] adds them).
pub(super) fn answer(
    lfd: &LogicLfd,
    files: &Files,
    current: Current,
    o: &Options,
) -> LfdResult<'static> {
    let s = match current.read(lfd, files) {
        Ok(s) => s,
        Err((kind, d)) => return LfdResult::input_failure(kind, d),
    };
    let mut out = LfdResult {
        state: s.names(),
        applicable: s.applicable().map(str::to_string).collect(),
        logic_in: s.logic_in(),
        ..LfdResult::default()
    };
    let clock = PerformanceClock;
    let t0 = clock.now_secs();
    match s.replan(o.mode, &o.config, &clock) {
        Ok(p) => found(&s, p, o.validate, &mut out),
        Err(e) => {
            out.kind = match e {
                LfdError::Budget(_) => "budget",
                _ => "unsolvable",
            };
            out.message = e.to_string();
            out.stats.time_ms = (clock.now_secs() - t0) * 1e3;
        }
    }
    if o.compare {
        out.scratch = Some(scratch(&s, &o.config, &clock));
    }
    out
}

fn found(s: &Observed, p: LfdPlan, validate: bool, out: &mut LfdResult) {
    // The lifted replay costs several times the search on small tasks (string-heavy): a caller
    // that replans in a loop may skip it.
    out.valid = validate.then(|| s.validate(&p.names).is_ok_and(|r| r.is_valid()));
    out.ok = true;
    out.kind = "plan";
    out.k = p.k;
    out.source = Some(match p.source {
        PlanSource::GoalHolds => "goal-holds",
        PlanSource::LogicIn => "logic-in",
        PlanSource::MultiGoal => "multi-goal",
    });
    out.prefix = p.prefix().to_vec();
    out.suffix = p.suffix().to_vec();
    out.cost = Some(p.cost);
    out.stats = Stats::of(&p.stats);
    out.plan = p.names;
}

fn scratch(s: &Observed, config: &SearchConfig, clock: &dyn Clock) -> Scratch {
    let r = s.plan_from_scratch(config, clock);
    let stats = Stats::of(&r.stats);
    match r.outcome {
        SearchOutcome::Plan(p) => Scratch {
            ok: true,
            plan: p
                .names(s.lfd().task())
                .into_iter()
                .map(str::to_string)
                .collect(),
            cost: Some(p.cost),
            stats,
        },
        _ => Scratch {
            ok: false,
            plan: vec![],
            cost: None,
            stats,
        },
    }
}
