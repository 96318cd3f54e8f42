//! The world's invariants: no interpenetration beyond the tolerance, every free body resting on
//! a support, nothing lost, every joint within its limits; and the support a body rests on.

use super::state::LIMIT_SLACK;
use super::World;
use crate::sim::panda::DOF;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A broken invariant found by [`World::check_invariants`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "violation", rename_all = "snake_case")]
pub enum Violation {
    /// Two bodies overlap deeper than the tolerance.
    Interpenetration {
        /// First body.
        a: String,
        /// Second body.
        b: String,
        /// Penetration depth (m).
        depth: f64,
    },
    /// A free body does not rest on anything.
    Unsupported {
        /// The body.
        body: String,
        /// Height of its bottom above the nearest support under its centre (m; infinite if none).
        gap: f64,
    },
    /// A body fell off every support.
    Lost {
        /// The body.
        body: String,
    },
    /// A joint is outside its limits.
    JointLimit {
        /// The arm.
        arm: String,
        /// Joint index 0..7.
        joint: usize,
        /// Its value (rad).
        value: f64,
    },
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::Interpenetration { a, b, depth } => {
                write!(f, "{a} and {b} interpenetrate by {:.2} mm", depth * 1000.0)
            }
            Violation::Unsupported { body, gap } => {
                write!(
                    f,
                    "{body} is in the air ({:.1} mm above any support)",
                    gap * 1000.0
                )
            }
            Violation::Lost { body } => write!(f, "{body} is lost (fell off)"),
            Violation::JointLimit { arm, joint, value } => {
                write!(
                    f,
                    "{arm} joint {} = {value:.4} rad is outside its limits",
                    joint + 1
                )
            }
        }
    }
}

impl World {
    /// Checks the world's invariants: no two bodies interpenetrate deeper than
    /// [`WorldParams::penetration_tolerance`] (parry contact test on every pair of boxes), every
    /// free block and the hook rest on a support (bottom within
    /// [`WorldParams::support_tolerance`] of a top face under its centre), no body is lost, every
    /// joint is within its limits.
    ///
    /// [`WorldParams::penetration_tolerance`]: super::WorldParams::penetration_tolerance
    /// [`WorldParams::support_tolerance`]: super::WorldParams::support_tolerance
    pub fn check_invariants(&self) -> Result<(), Vec<Violation>> {
        let v = self.check_invariants_list();
        if v.is_empty() {
            Ok(())
        } else {
            Err(v)
        }
    }

    pub(super) fn check_invariants_list(&self) -> Vec<Violation> {
        let mut out = Vec::new();
        let tol = self.params.penetration_tolerance;
        for i in 0..self.bodies.len() {
            if self.bodies[i].lost {
                out.push(Violation::Lost {
                    body: self.bodies[i].name.clone(),
                });
                continue;
            }
            for j in i + 1..self.bodies.len() {
                if self.bodies[j].lost {
                    continue;
                }
                // Fixed bodies may touch each other as built (a shelf on a table).
                if !self.bodies[i].is_movable() && !self.bodies[j].is_movable() {
                    continue;
                }
                let depth = self.bodies[i].penetration(&self.bodies[j]);
                if depth > tol {
                    out.push(Violation::Interpenetration {
                        a: self.bodies[i].name.clone(),
                        b: self.bodies[j].name.clone(),
                        depth,
                    });
                }
            }
        }
        for (i, b) in self.bodies.iter().enumerate() {
            if !b.is_movable() || b.lost || self.is_held(i) {
                continue;
            }
            let gap = self.support_gap(i);
            if gap > self.params.support_tolerance {
                out.push(Violation::Unsupported {
                    body: b.name.clone(),
                    gap,
                });
            }
        }
        for a in &self.arms {
            for k in 0..DOF {
                let v = a.joints[k];
                if !(a.model.lower[k] - LIMIT_SLACK..=a.model.upper[k] + LIMIT_SLACK).contains(&v) {
                    out.push(Violation::JointLimit {
                        arm: a.name.clone(),
                        joint: k,
                        value: v,
                    });
                }
            }
        }
        out
    }

    /// Height of body `bi`'s bottom above the highest top face under its centroid (∞ if none).
    fn support_gap(&self, bi: usize) -> f64 {
        let b = &self.bodies[bi];
        let c = b.centroid_at(&b.pose);
        let (lo, _) = b.aabb();
        let mut best = f64::INFINITY;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || self.is_held(j) {
                continue;
            }
            if let Some(t) = o.top_under(c.x, c.y, 0.0) {
                let gap = lo.z - t;
                if gap >= -self.params.support_tolerance && gap.abs() < best.abs() {
                    best = gap;
                }
            }
        }
        best.abs()
    }

    /// The support body under `bi` (top within tolerance under its centroid), if any.
    pub(crate) fn support_of(&self, bi: usize) -> Option<usize> {
        let b = &self.bodies[bi];
        let c = b.centroid_at(&b.pose);
        let (lo, _) = b.aabb();
        let mut best: Option<(f64, usize)> = None;
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || self.is_held(j) {
                continue;
            }
            if let Some(t) = o.top_under(c.x, c.y, 0.0) {
                let gap = (lo.z - t).abs();
                if gap <= self.params.support_tolerance && best.is_none_or(|(g, _)| gap < g) {
                    best = Some((gap, j));
                }
            }
        }
        best.map(|(_, j)| j)
    }
}
