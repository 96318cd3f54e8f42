//! One Logic-LfD query and its result, shared by `logicLfd` (which reads the domain, problem and
//! demonstration first) and the `LogicLfd` class (which read them once, when it was built).

use crate::pddl::Source;
use serde::Serialize;
use tsify::Tsify;

use super::super::convert::PerformanceClock;
use super::diagnostics::{input_error, location_message, options_diag, LogicLfdDiagnostic};
use super::input::{Files, Options, Texts};
use crate::lfd::{LfdError, LfdPlan, LogicLfd, Observed, PlanSource};
use crate::plan::{Clock, SearchConfig, SearchOutcome, SearchStats};

/// The demonstration as Logic-LfD reads it.
#[derive(Debug, Default, Serialize, Tsify)]
#[tsify(missing_as_null)]
pub(super) struct LogicLfdDemo {
    /// a_1 … a_N.
    actions: Vec<String>,
    /// L_0 … L_N: the fluents before a_1, after a_1, …, after a_N (sorted names).
    states: Vec<Vec<String>>,
    /// c_0 … c_N: the cost of the demonstration left after L_k.
    costs: Vec<u64>,
}

/// Search statistics; `timeMs` is the search time (parsing and grounding excluded).
#[derive(Debug, Default, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
struct LogicLfdStats {
    /// States expanded.
    expanded: u64,
    /// States generated.
    generated: u64,
    /// Heuristic evaluations.
    evaluated: u64,
    /// Search time in milliseconds.
    time_ms: f64,
}

impl LogicLfdStats {
    fn of(s: &SearchStats) -> Self {
        LogicLfdStats {
            expanded: s.expanded,
            generated: s.generated,
            evaluated: s.evaluated,
            time_ms: s.time_secs * 1e3,
        }
    }
}

/// Classical planning from S_C to G with the same search (`compare: true`).
#[derive(Debug, Serialize, Tsify)]
#[tsify(missing_as_null)]
struct LogicLfdScratch {
    /// A plan was found.
    ok: bool,
    /// The plan (empty without one).
    plan: Vec<String>,
    /// Its cost.
    cost: Option<u64>,
    /// The search's statistics.
    stats: LogicLfdStats,
}

/// What `logicLfd` found. The parts that do not depend on S_C are borrowed, so the class can
/// keep them across queries.
#[derive(Debug, Default, Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
#[tsify(missing_as_null)]
pub(super) struct LogicLfdResult<'f> {
    /// `true` iff a plan was produced.
    ok: bool,
    /// `plan`, or what stopped it.
    #[tsify(type = "'plan' | 'parse' | 'demo' | 'state' | 'options' | 'unsolvable' | 'budget'")]
    kind: &'static str,
    /// One line for people (`''` when ok).
    message: String,
    /// Located errors (empty when ok).
    diagnostics: Vec<LogicLfdDiagnostic>,
    /// `null` when the inputs did not parse.
    demo: Option<&'f LogicLfdDemo>,
    /// The problem's static facts.
    statics: &'f [String],
    /// Every fluent atom of the grounded task.
    fluents: &'f [String],
    /// S_C's atoms without the problem's static facts, sorted.
    state: Vec<String>,
    /// The actions applicable in S_C.
    applicable: Vec<String>,
    /// LogicIn(S_C): the largest k with L_k ⊆ S_C.
    logic_in: Option<usize>,
    /// The demonstration state joined (`null`: G directly, or no plan).
    k: Option<usize>,
    /// How the plan was made.
    source: Option<PlanSource>,
    /// New actions to L_k.
    prefix: Vec<String>,
    /// The demonstration's actions after L_k.
    suffix: Vec<String>,
    /// `prefix` then `suffix`.
    plan: Vec<String>,
    /// The plan's cost.
    cost: Option<u64>,
    /// The lifted validator replayed `plan` from S_C to the goal; `null` without a plan or with
    /// `validate: false`.
    valid: Option<bool>,
    /// Search statistics.
    stats: LogicLfdStats,
    /// With `compare`: classical planning from S_C to G with the same search.
    scratch: Option<LogicLfdScratch>,
}

/// What a result says whatever S_C is: the demonstration, the static facts, the fluents.
#[derive(Debug)]
pub(super) struct Fixed {
    pub(super) demo: LogicLfdDemo,
    pub(super) statics: Vec<String>,
    pub(super) fluents: Vec<String>,
}

impl Fixed {
    pub(super) fn of(lfd: &LogicLfd) -> Self {
        Fixed {
            demo: LogicLfdDemo {
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

impl<'f> LogicLfdResult<'f> {
    /// The result with `fixed`'s demonstration, static facts and fluents.
    pub(super) fn with(mut self, fixed: &'f Fixed) -> Self {
        self.demo = Some(&fixed.demo);
        self.statics = &fixed.statics;
        self.fluents = &fixed.fluents;
        self
    }

    /// `ok: false` for a bad option.
    pub(super) fn options_failure(message: String) -> Self {
        LogicLfdResult {
            kind: "options",
            message: message.clone(),
            diagnostics: vec![options_diag(message)],
            ..LogicLfdResult::default()
        }
    }

    /// `ok: false` for an input that could not be read, with its located diagnostic.
    pub(super) fn input_failure(kind: &'static str, d: LogicLfdDiagnostic) -> Self {
        LogicLfdResult {
            kind,
            message: location_message(&d),
            diagnostics: vec![d],
            ..LogicLfdResult::default()
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
    ) -> Result<Observed<'l>, (&'static str, LogicLfdDiagnostic)> {
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
pub(super) fn prepare(
    files: &Files,
    t: &Texts,
) -> Result<LogicLfd, (&'static str, LogicLfdDiagnostic)> {
    LogicLfd::named(
        &Source::new(&files.domain, &t.domain),
        &Source::new(&files.problem, &t.problem),
        &Source::new(&files.demo, &t.demo),
    )
    .map_err(|e| input_error(&e, files, "problem"))
}

/// One query on a prepared instance: S_C, LogicIn, the merged plan and (unless `validate` is off)
/// its replay on the lifted domain, and with `compare` planning from scratch. The result leaves out the demonstration,
/// the static facts and the fluents ([`LogicLfdResult::with`] adds them).
pub(super) fn answer(
    lfd: &LogicLfd,
    files: &Files,
    current: Current,
    o: &Options,
) -> LogicLfdResult<'static> {
    let s = match current.read(lfd, files) {
        Ok(s) => s,
        Err((kind, d)) => return LogicLfdResult::input_failure(kind, d),
    };
    let mut out = LogicLfdResult {
        state: s.names(),
        applicable: s.applicable().map(str::to_string).collect(),
        logic_in: s.logic_in(),
        ..LogicLfdResult::default()
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

fn found(s: &Observed, p: LfdPlan, validate: bool, out: &mut LogicLfdResult) {
    // The lifted replay costs several times the search on small tasks (string-heavy): a caller
    // that replans in a loop may skip it.
    out.valid = validate.then(|| s.validate(&p.names).is_ok_and(|r| r.is_valid()));
    out.ok = true;
    out.kind = "plan";
    out.k = p.k;
    out.source = Some(p.source);
    out.prefix = p.prefix().to_vec();
    out.suffix = p.suffix().to_vec();
    out.cost = Some(p.cost);
    out.stats = LogicLfdStats::of(&p.stats);
    out.plan = p.names;
}

fn scratch(s: &Observed, config: &SearchConfig, clock: &dyn Clock) -> LogicLfdScratch {
    let r = s.plan_from_scratch(config, clock);
    let stats = LogicLfdStats::of(&r.stats);
    match r.outcome {
        SearchOutcome::Plan(p) => LogicLfdScratch {
            ok: true,
            plan: p
                .names(s.lfd().task())
                .into_iter()
                .map(str::to_string)
                .collect(),
            cost: Some(p.cost),
            stats,
        },
        _ => LogicLfdScratch {
            ok: false,
            plan: vec![],
            cost: None,
            stats,
        },
    }
}
