//! Planning a pull's stroke with the library's stroke skill, through the demonstrated
//! via-points carried into the new stroke frame (see `stroke.rs`).

use nalgebra::{Isometry3, Point3};

use super::kind::SkillKind;
use super::library::{LearnedSkill, SkillLibrary, SkillSegment};
use super::stroke::{params, stroke_frame, StrokePlan, StrokeViaPoint, SLOWDOWN_TOLERANCE};
use crate::lqt::ViaPoint;

impl SkillLibrary {
    /// Plans the stroke skill `key` from TCP position `start` for a stroke from TCP position
    /// `contact` to `pulled`, through its via-points there. `None` without such a skill.
    pub fn stroke_plan(
        &self,
        key: &str,
        start: &Point3<f64>,
        contact: &Point3<f64>,
        pulled: &Point3<f64>,
    ) -> Option<StrokePlan> {
        let entry = self.skills.get(key)?;
        let demo = entry.stroke.as_ref()?;
        let frame = stroke_frame(contact, pulled);
        let along = frame.rotation;
        // A longer drag than the demonstrated one runs slower: the same skill, learned from the
        // demonstration played slower.
        let slow = demo.slowdown((contact - pulled).norm());
        let slowed;
        let skill = if slow > 1.0 + SLOWDOWN_TOLERANCE {
            let kind = match &entry.skill {
                LearnedSkill::Lqt(_) => SkillKind::Lqt,
                LearnedSkill::Dmp(_) => SkillKind::Dmp,
            };
            slowed = LearnedSkill::learn(kind, &demo.slowed(slow), demo.dt, params())?;
            &slowed
        } else {
            &entry.skill
        };
        let n = match skill {
            LearnedSkill::Lqt(s) => s.demo().len(),
            LearnedSkill::Dmp(d) => d.n_steps(),
        };
        let via_points: Vec<StrokeViaPoint> = demo
            .vias
            .iter()
            .map(|v| StrokeViaPoint {
                label: v.label.clone(),
                step: libm::round(v.phase * (n - 1) as f64) as usize,
                position: contact + along * v.offset,
            })
            .collect();
        let in_frame: Vec<ViaPoint> = demo
            .vias
            .iter()
            .zip(&via_points)
            .map(|(v, w)| ViaPoint {
                phase: v.phase,
                position: frame.inverse_transform_point(&w.position).coords,
                weight: None,
                velocity: Some(v.velocity / slow),
            })
            .collect();
        let trajectory = skill.plan(start, &frame, &in_frame)?;
        Some(StrokePlan {
            trajectory,
            frame,
            via_points,
        })
    }

    /// The stroke skill `key` as an executor segment from TCP pose `start` (see
    /// [`stroke_plan`](Self::stroke_plan)), with its frame and the step after which the hook
    /// is behind the block (the last via-point's).
    pub fn stroke_segment(
        &self,
        key: &str,
        start: &Isometry3<f64>,
        contact: &Point3<f64>,
        pulled: &Point3<f64>,
    ) -> Option<(SkillSegment, Isometry3<f64>, usize)> {
        let from = Point3::from(start.translation.vector);
        let plan = self.stroke_plan(key, &from, contact, pulled)?;
        let behind = plan.via_points.iter().map(|v| v.step).max().unwrap_or(0);
        let seg = SkillSegment::closed(&plan.trajectory, start.rotation)?;
        Some((seg, plan.frame, behind))
    }
}
