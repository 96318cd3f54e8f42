//! The motion skills the executor calls for each segment of an action.
//!
//! A segment goes from the current TCP pose x_0 to a via-point x_T in the frame of the object
//! acted on. The position profile comes from the skill learned for that kind of segment (grasp,
//! place, retreat, pull); without a learned skill the profile is the minimum-jerk interpolation
//!
//! ```text
//!   x(s) = x_0 + (x_T − x_0)(10 s³ − 15 s⁴ + 6 s⁵),   s = t / T
//! ```
//!
//! which is what LQT-CP with a goal target and a smoothness cost converges to in one dimension.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};

/// One planned segment: TCP positions at every tick and the start orientation.
#[derive(Clone, Debug, PartialEq)]
pub struct SkillSegment {
    /// Positions, one per simulation tick (the last is the goal).
    pub positions: Vec<Vector3<f64>>,
    /// Orientation at the start (interpolated to the goal's by the executor).
    pub start_rotation: UnitQuaternion<f64>,
}

impl SkillSegment {
    /// Number of ticks.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the segment is empty.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The position at tick `i` (clamped to the last).
    pub fn position(&self, i: usize) -> Vector3<f64> {
        self.positions[i.min(self.positions.len() - 1)]
    }
}

/// The skills available to the executor, by segment kind.
#[derive(Clone, Debug, Default)]
pub struct SkillLibrary {}

impl SkillLibrary {
    /// Plans the segment `name` from `start` to `goal` over `steps` ticks of `dt` seconds.
    pub fn segment(
        &self,
        _name: &str,
        start: &Isometry3<f64>,
        goal: &Isometry3<f64>,
        _anchor: Option<Vector3<f64>>,
        steps: usize,
        _dt: f64,
    ) -> SkillSegment {
        let x0 = start.translation.vector;
        let xt = goal.translation.vector;
        let n = steps.max(2);
        let positions = (1..=n)
            .map(|i| {
                let s = i as f64 / n as f64;
                let b = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
                x0 + (xt - x0) * b
            })
            .collect();
        SkillSegment {
            positions,
            start_rotation: start.rotation,
        }
    }
}
