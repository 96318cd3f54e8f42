//! World operations under fuzzing — drags and new blocks as the page sends them, with
//! hostile names, colours and coordinates — and the oracle: a refused operation changes nothing,
//! an accepted one keeps the world's invariants.

use nalgebra::Vector3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

use super::common::{ensure, Verdict};
use crate::sim::Benchmark;
use crate::sim::World;

/// A coordinate in a world-ops input: a number, or `"nan"`, `"inf"`, `"-inf"` (JSON has none).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Coord {
    /// A finite number.
    Num(f64),
    /// `"nan"`, `"inf"` or `"-inf"`.
    Special(SpecialFloat),
}

/// A non-finite coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpecialFloat {
    /// Not a number.
    Nan,
    /// +∞.
    Inf,
    /// −∞.
    #[serde(rename = "-inf")]
    NegInf,
}

impl Coord {
    /// The coordinate of `x`, non-finite values spelled as strings.
    pub(super) fn new(x: f64) -> Coord {
        if x.is_nan() {
            Coord::Special(SpecialFloat::Nan)
        } else if x == f64::INFINITY {
            Coord::Special(SpecialFloat::Inf)
        } else if x == f64::NEG_INFINITY {
            Coord::Special(SpecialFloat::NegInf)
        } else {
            Coord::Num(x)
        }
    }

    /// The value.
    pub fn value(self) -> f64 {
        match self {
            Coord::Num(x) => x,
            Coord::Special(SpecialFloat::Nan) => f64::NAN,
            Coord::Special(SpecialFloat::Inf) => f64::INFINITY,
            Coord::Special(SpecialFloat::NegInf) => f64::NEG_INFINITY,
        }
    }
}

/// One request from the page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case")]
pub enum WorldOp {
    /// A drag (`World::move_block`).
    Move {
        /// Body name.
        body: String,
        /// Requested centre.
        to: [Coord; 3],
    },
    /// A drag with a new yaw (`World::move_block_to`).
    MoveYaw {
        /// Body name.
        body: String,
        /// Requested centre.
        to: [Coord; 3],
        /// Yaw (rad).
        yaw: Coord,
    },
    /// A new block (`World::add_block`).
    Add {
        /// New name.
        body: String,
        /// Colour `#rrggbb`.
        color: String,
        /// Requested centre.
        at: [Coord; 3],
    },
}

/// A world-ops input: a benchmark's template world and the requests applied to it in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorldOps {
    /// `b1`, `b2` or `b3`.
    pub benchmark: String,
    /// The requests.
    pub ops: Vec<WorldOp>,
}

const OP_NAMES: [&str; 12] = [
    "a", "b", "c", "d", "hook", "table", "shelf", "panda", "e", "", "A", "<b>",
];
const OP_COLORS: [&str; 4] = ["#123456", "red", "#12345", "#GGGGGG"];

fn random_coord(rng: &mut Pcg64Mcg, lo: f64, hi: f64) -> f64 {
    if rng.random_range(0..9) == 0 {
        const S: [f64; 6] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e12, -1e12, 0.0];
        S[rng.random_range(0..S.len())]
    } else {
        rng.random_range(lo..hi)
    }
}

fn random_point(rng: &mut Pcg64Mcg) -> [Coord; 3] {
    let z = if rng.random_range(0..4) < 3 {
        rng.random_range(0.0..0.4)
    } else {
        random_coord(rng, -0.4, 1.2)
    };
    [
        Coord::new(random_coord(rng, -0.4, 1.2)),
        Coord::new(random_coord(rng, -0.4, 1.2)),
        Coord::new(z),
    ]
}

impl WorldOp {
    /// A random request (hostile names, colours and coordinates included).
    pub fn random(rng: &mut Pcg64Mcg) -> WorldOp {
        let body = OP_NAMES[rng.random_range(0..OP_NAMES.len())].to_string();
        match rng.random_range(0..6) {
            0..=3 => WorldOp::Move {
                body,
                to: random_point(rng),
            },
            4 => WorldOp::MoveYaw {
                body,
                to: random_point(rng),
                yaw: Coord::new(random_coord(rng, -0.4, 1.2)),
            },
            _ => WorldOp::Add {
                body,
                color: OP_COLORS[rng.random_range(0..OP_COLORS.len())].to_string(),
                at: random_point(rng),
            },
        }
    }

    /// Applies the request; `Err` is the world's refusal reason.
    pub fn apply(&self, w: &mut World) -> Result<(), String> {
        let v = |p: &[Coord; 3]| Vector3::new(p[0].value(), p[1].value(), p[2].value());
        let r = match self {
            WorldOp::Move { body, to } => w.move_block(body, v(to)).map(|_| ()),
            WorldOp::MoveYaw { body, to, yaw } => {
                w.move_block_to(body, v(to), yaw.value()).map(|_| ())
            }
            WorldOp::Add { body, color, at } => w.add_block(body, color, v(at), 0.3).map(|_| ()),
        };
        r.map_err(|e| e.reason)
    }
}

pub(super) fn check_world_ops(input: &str) -> Result<Verdict, String> {
    let ops: WorldOps = match serde_json::from_str(input) {
        Ok(o) => o,
        Err(e) => {
            ensure(e.line() >= 1, || format!("unlocated world-ops error: {e}"))?;
            return Ok(Verdict::Refused);
        }
    };
    let Some(b) = Benchmark::parse(&ops.benchmark) else {
        return Ok(Verdict::Refused);
    };
    let mut w = b.scene();
    let snap = |w: &World| serde_json::to_string(&w.snapshot()).unwrap_or_default();
    let mut accepted = false;
    for (i, op) in ops.ops.iter().enumerate() {
        let before = snap(&w);
        match op.apply(&mut w) {
            Err(reason) => {
                ensure(!reason.is_empty(), || format!("op {i}: empty refusal"))?;
                ensure(snap(&w) == before, || {
                    format!("op {i} {op:?}: refused ({reason}) but changed the world")
                })?;
            }
            Ok(()) => {
                accepted = true;
                if let Err(v) = w.check_invariants() {
                    return Err(format!(
                        "op {i} {op:?}: accepted but broke invariants: {v:?}"
                    ));
                }
            }
        }
    }
    Ok(if accepted {
        Verdict::Accepted
    } else {
        Verdict::Refused
    })
}
