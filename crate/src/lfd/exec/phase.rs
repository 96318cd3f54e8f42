//! The phase/via model of an action's motion: each action kind is a list of phases (moves to
//! via-points and gripper events), begun, when the arm needs it, by a rise out from among
//! bodies or an unwinding of a joint at its limit; a transit is inserted as two more moves.

use super::params::ExecParams;
use super::steps::{Phase, Via};
use super::ActionExec;
use crate::sim::{GripperCommand, World};
use crate::tamp::rise_before_action;
use crate::tamp::{ActionKind, Placement};

use crate::lfd::{skill_key, SegmentKind, SkillLibrary};

/// Below this [`ArmModel::limit_margin`] (of a joint's range) an action starts by unwinding the
/// arm ([`Via::Unwind`]).
///
/// [`ArmModel::limit_margin`]: crate::sim::ArmModel::limit_margin
const UNWIND_MARGIN: f64 = 0.01;

impl ActionExec {
    /// Inserts a transit (rise, over at height `z`) before phase `at` (whose move is `via`); that
    /// phase then descends straight (the learned approach's shape would swing the load back into
    /// what the transit avoids).
    pub(super) fn insert_transit(&mut self, at: usize, via: &Via, z: f64) {
        self.transit_at = Some(at);
        if let Some(Phase::Move(Via::Grasp { skill, .. } | Via::Place { skill, .. })) =
            self.phases.get_mut(at)
        {
            *skill = false;
        }
        self.phases.splice(
            at..at,
            [
                Phase::Move(Via::Rise { z }),
                Phase::Move(Via::Over {
                    inner: Box::new(via.clone()),
                    z,
                }),
            ],
        );
        self.segment = None;
    }

    /// The key of the learned skill a move to `via` runs (`profile` when none).
    pub(super) fn skill_name(&self, via: &Via) -> String {
        let segment = match via {
            Via::Grasp { skill: true, .. } | Via::Place { skill: true, .. } => {
                SegmentKind::Approach
            }
            Via::Up { skill: true, .. } => SegmentKind::Retreat,
            Via::Stroke { .. } => SegmentKind::Stroke,
            _ => return "profile".into(),
        };
        skill_key(
            schema_of(&self.action),
            segment,
            self.hook && !matches!(via, Via::Stroke { .. }),
        )
    }
}

/// The schema name of a grounded action `(name arg …)`.
pub(super) fn schema_of(action: &str) -> &str {
    action
        .trim_start_matches('(')
        .split([' ', ')'])
        .next()
        .unwrap_or_default()
}

/// The arm that executes `kind` and its phases: the learned skills' segments where the library
/// has them (`hook`: the `hook-…` ones), straight moves otherwise.
pub(super) fn action_phases(
    action: &str,
    kind: &ActionKind,
    skills: &SkillLibrary,
    p: &ExecParams,
    hook: bool,
) -> (usize, Vec<Phase>) {
    let key = |segment| skill_key(schema_of(action), segment, hook);
    match kind {
        ActionKind::Grasp { arm, body } => (*arm, grasp_phases(body, skills, p, &key)),
        ActionKind::Release { arm, placement, .. } => {
            let placement = placement.clone().unwrap_or(Placement::At {
                x: 0.0,
                y: 0.0,
                yaw: 0.0,
            });
            (*arm, release_phases(placement, skills, p, &key))
        }
        ActionKind::Pull {
            arm, body, turn, ..
        } => {
            let stage = |stage| {
                Phase::Move(Via::Pull {
                    body: body.clone(),
                    stage,
                    turn: *turn,
                })
            };
            // The learned stroke replaces the descent and the drag; without one, straight moves.
            let phases = if skills.has(&skill_key(schema_of(action), SegmentKind::Stroke, false)) {
                vec![
                    stage(0),
                    Phase::Move(Via::Stroke {
                        body: body.clone(),
                        turn: *turn,
                    }),
                    stage(3),
                ]
            } else {
                (0..4).map(stage).collect()
            };
            (*arm, phases)
        }
    }
}

/// A grasp of `body`: open, approach (the learned one, or above and down), close, lift.
fn grasp_phases(
    body: &str,
    skills: &SkillLibrary,
    p: &ExecParams,
    key: &dyn Fn(SegmentKind) -> String,
) -> Vec<Phase> {
    if skills.has(&key(SegmentKind::Approach)) {
        return vec![
            Phase::Gripper(GripperCommand::Open),
            Phase::Move(Via::Grasp {
                body: body.to_string(),
                dz: 0.0,
                skill: true,
            }),
            Phase::Gripper(GripperCommand::Close),
            Phase::Move(Via::Up {
                dz: p.motion.lift_height,
                skill: skills.has(&key(SegmentKind::Retreat)),
            }),
        ];
    }
    vec![
        Phase::Gripper(GripperCommand::Open),
        Phase::Move(Via::Grasp {
            body: body.to_string(),
            dz: p.motion.approach_height,
            skill: false,
        }),
        Phase::Move(Via::Grasp {
            body: body.to_string(),
            dz: 0.0,
            skill: false,
        }),
        Phase::Gripper(GripperCommand::Close),
        Phase::Move(Via::Up {
            dz: p.motion.lift_height,
            skill: false,
        }),
    ]
}

/// A release at `placement`: approach (the learned one, or above and down) to the release
/// height, open, retreat up.
fn release_phases(
    placement: Placement,
    skills: &SkillLibrary,
    p: &ExecParams,
    key: &dyn Fn(SegmentKind) -> String,
) -> Vec<Phase> {
    if skills.has(&key(SegmentKind::Approach)) && skills.has(&key(SegmentKind::Retreat)) {
        return vec![
            Phase::Move(Via::Place {
                placement,
                dz: p.motion.release_clearance,
                skill: true,
            }),
            Phase::Gripper(GripperCommand::Open),
            Phase::Move(Via::Up {
                dz: p.motion.approach_height,
                skill: true,
            }),
        ];
    }
    vec![
        Phase::Move(Via::Place {
            placement: placement.clone(),
            dz: p.motion.approach_height,
            skill: false,
        }),
        Phase::Move(Via::Place {
            placement,
            dz: p.motion.release_clearance,
            skill: false,
        }),
        Phase::Gripper(GripperCommand::Open),
        Phase::Move(Via::Up {
            dz: p.motion.approach_height,
            skill: false,
        }),
    ]
}

/// Puts in front of `phases` what arm `arm` must do first where the last action left it.
pub(super) fn prepare_arm(world: &World, arm: usize, p: &ExecParams, phases: &mut Vec<Phase>) {
    // An empty hand left down among bodies (the last action was interrupted at its
    // gripper event) first rises straight up, clear of them.
    if let Some(up) = rise_before_action(world, arm, &p.motion) {
        phases.insert(
            0,
            Phase::Move(Via::Rise {
                z: up.translation.z,
            }),
        );
    }
    // An arm the last action left with a joint at its limit (a recovery that failed, a
    // tracker wound up against a shelf) unwinds first, up there: from such a posture the
    // tracker comes down the same way and fails the same way again.
    if world
        .arm_model(arm)
        .zip(world.joints(arm))
        .is_some_and(|(m, q)| m.limit_margin(&q) < UNWIND_MARGIN)
    {
        let at = usize::from(matches!(
            phases.first(),
            Some(Phase::Move(Via::Rise { .. }))
        ));
        phases.insert(at, Phase::Move(Via::Unwind));
    }
}
