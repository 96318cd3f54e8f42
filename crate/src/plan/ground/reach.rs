//! Relaxed reachability: the semi-naive fixpoint that finds every grounding whose positive
//! preconditions are reachable in the delete relaxation. A fact is joined with the schemas'
//! positive atoms when it is first reached, against the facts processed before it, so every
//! grounding is found once, when its last precondition fact arrives.

use std::collections::VecDeque;

use crate::pddl::{Domain, Problem};

use super::condition::Schemas;
use super::hash::{HashMap, HashSet};
use super::join::{FactIndex, Grounder};
use super::objects::{arg, Objects};
use super::schema::{value, GAtom, GroundError, Obj, MAX_OPERATORS, UNBOUND};

/// What the fixpoint reached.
pub(super) struct Reached {
    /// Every grounding `(schema, binding)` found, in the order found.
    pub(super) found: Vec<(usize, Vec<Obj>)>,
    /// Id of every fluent fact reached (initial or added).
    pub(super) fact_ids: HashMap<GAtom, u32>,
    /// The fluent facts reached, by id.
    pub(super) fact_list: Vec<GAtom>,
    /// The initial facts of static predicates.
    pub(super) statics: HashSet<GAtom>,
    /// Ids of the initial fluent facts.
    pub(super) init_fluent: Vec<u32>,
}

/// The fluent facts reached so far, with the queue of those not yet joined.
struct Frontier {
    fact_ids: HashMap<GAtom, u32>,
    fact_list: Vec<GAtom>,
    queue: VecDeque<u32>,
}

impl Frontier {
    /// Reaches `g`: a new fact gets the next id and joins the queue (`Some(id)`); a known one
    /// changes nothing (`None`).
    fn reach(&mut self, g: GAtom) -> Option<u32> {
        if self.fact_ids.contains_key(&g) {
            return None;
        }
        let id = self.fact_list.len() as u32;
        self.fact_ids.insert(g.clone(), id);
        self.fact_list.push(g);
        self.queue.push_back(id);
        Some(id)
    }
}

/// The groundings found so far (deduplicated) and what their add effects reached.
struct Found<'a> {
    domain: &'a Domain,
    problem: &'a Problem,
    objs: &'a Objects,
    schemas: &'a Schemas,
    found: Vec<(usize, Vec<Obj>)>,
    seen: HashSet<(usize, Vec<Obj>)>,
}

impl Found<'_> {
    /// Records the new bindings of schema `s` and reaches their add effects.
    fn emit(
        &mut self,
        s: usize,
        bindings: Vec<Vec<Obj>>,
        frontier: &mut Frontier,
    ) -> Result<(), GroundError> {
        for b in bindings {
            if !self.seen.insert((s, b.clone())) {
                continue;
            }
            for at in &self.domain.actions[self.schemas.list[s].action].effect.add {
                let g: GAtom = (
                    at.predicate,
                    at.args
                        .iter()
                        .map(|t| value(arg(self.objs, t), &b))
                        .collect(),
                );
                frontier.reach(g);
            }
            self.found.push((s, b));
            if self.found.len() > MAX_OPERATORS {
                return Err(GroundError::TooLarge(
                    self.problem.file().to_string(),
                    format!("more than {MAX_OPERATORS} operators"),
                ));
            }
        }
        Ok(())
    }
}

/// Runs the fixpoint from the problem's initial facts (see the module header).
pub(super) fn reach(
    domain: &Domain,
    problem: &Problem,
    objs: &Objects,
    schemas: &Schemas,
    fluent_pred: &[bool],
) -> Result<Reached, GroundError> {
    let Initial {
        statics,
        mut index,
        mut frontier,
        init_fluent,
    } = load_init(domain, problem, objs, fluent_pred);
    let (triggers, untriggered) = trigger_lists(domain, schemas, fluent_pred);
    let mut found = Found {
        domain,
        problem,
        objs,
        schemas,
        found: Vec::new(),
        seen: HashSet::default(),
    };
    for &s in &untriggered {
        let g = Grounder {
            schemas: &schemas.list,
            params_ty: &schemas.params_ty,
            objs,
            index: &index,
            statics: &statics,
            fluent_pred,
        };
        let mut out = Vec::new();
        let mut b = vec![UNBOUND; schemas.params_ty[s].len()];
        let mut matched = vec![false; schemas.list[s].pos.len()];
        g.join(s, &mut matched, &mut b, &mut out);
        found.emit(s, out, &mut frontier)?;
    }
    while let Some(f) = frontier.queue.pop_front() {
        let (pred, args) = frontier.fact_list[f as usize].clone();
        index.insert(pred, &args);
        for &(s, i) in &triggers[pred] {
            let g = Grounder {
                schemas: &schemas.list,
                params_ty: &schemas.params_ty,
                objs,
                index: &index,
                statics: &statics,
                fluent_pred,
            };
            let mut out = Vec::new();
            let mut b = vec![UNBOUND; schemas.params_ty[s].len()];
            let mut matched = vec![false; schemas.list[s].pos.len()];
            let mut newly = Vec::new();
            if g.unify(s, &schemas.list[s].pos[i], &args, &mut b, &mut newly) {
                matched[i] = true;
                g.join(s, &mut matched, &mut b, &mut out);
            }
            found.emit(s, out, &mut frontier)?;
        }
    }
    Ok(Reached {
        found: found.found,
        fact_ids: frontier.fact_ids,
        fact_list: frontier.fact_list,
        statics,
        init_fluent,
    })
}

/// The initial facts, split: static ones preloaded into the index, fluent ones queued.
struct Initial {
    statics: HashSet<GAtom>,
    index: FactIndex,
    frontier: Frontier,
    init_fluent: Vec<u32>,
}

/// Loads the problem's initial facts (see [`Initial`]).
fn load_init(domain: &Domain, problem: &Problem, objs: &Objects, fluent_pred: &[bool]) -> Initial {
    let nobj = objs.names.len();
    let mut statics: HashSet<GAtom> = HashSet::default();
    let mut index = FactIndex::new(domain, nobj);
    let mut frontier = Frontier {
        fact_ids: HashMap::default(),
        fact_list: Vec::new(),
        queue: VecDeque::new(),
    };
    let mut init_fluent: Vec<u32> = Vec::new();
    for a in &problem.init {
        let g: GAtom = (
            a.predicate,
            a.args.iter().map(|t| value(arg(objs, t), &[])).collect(),
        );
        if fluent_pred[a.predicate] {
            if let Some(id) = frontier.reach(g) {
                init_fluent.push(id);
            }
        } else if statics.insert(g.clone()) {
            index.insert(g.0, &g.1);
        }
    }
    Initial {
        statics,
        index,
        frontier,
        init_fluent,
    }
}

/// Per fluent predicate, the `(schema, positive atom)` pairs a new fact of it triggers; and the
/// schemas without a fluent positive atom (joined once, up front).
fn trigger_lists(
    domain: &Domain,
    schemas: &Schemas,
    fluent_pred: &[bool],
) -> (Vec<Vec<(usize, usize)>>, Vec<usize>) {
    let mut triggers: Vec<Vec<(usize, usize)>> = vec![Vec::new(); domain.predicates.len()];
    let mut untriggered = Vec::new();
    for (s, sch) in schemas.list.iter().enumerate() {
        let mut any = false;
        for (i, l) in sch.pos.iter().enumerate() {
            if fluent_pred[l.pred] {
                triggers[l.pred].push((s, i));
                any = true;
            }
        }
        if !any {
            untriggered.push(s);
        }
    }
    (triggers, untriggered)
}
