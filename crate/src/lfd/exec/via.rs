//! Via-point poses: where the TCP goes for each kind of via-point, computed from the world when
//! a segment starts (and again when its anchor moves), with the object frame of its skill.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};

use super::steps::{Anchor, Via};
use super::ActionExec;
use crate::lfd::stroke_frame;
use crate::sim::geometry::{raised, rest_pose, rest_pose_on, tcp_for_body_pose};
use crate::sim::World;
use crate::tamp::{grasp_pose, release_turns};
use crate::tamp::{ActionKind, Placement};

/// Centre + yaw of a pose (the demo's anchor-frame convention).
pub(super) fn anchor_frame(p: &Isometry3<f64>) -> Isometry3<f64> {
    let (_, _, yaw) = p.rotation.euler_angles();
    Isometry3::from_parts(
        p.translation,
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
    )
}

impl ActionExec {
    /// Where via-point `via` puts the TCP, now that it is at `start`.
    pub(super) fn via_pose(
        &self,
        world: &World,
        via: &Via,
        start: &Isometry3<f64>,
    ) -> Result<ViaPose, String> {
        match via {
            Via::Grasp { body, dz, .. } => {
                let bp = world.body_pose(body);
                let g = bp
                    .and_then(|at| grasp_pose(world, world, self.arm, body, &at, &self.motion))
                    .ok_or_else(|| format!("{body} cannot be grasped"))?;
                let at = bp.map(|q| q.translation.vector);
                Ok(ViaPose {
                    goal: raised(&g, *dz),
                    frame: bp.map(|q| anchor_frame(&q)),
                    anchor: at.map(|at| Anchor {
                        body: body.clone(),
                        at,
                    }),
                })
            }
            Via::Place { placement, dz, .. } => {
                let body = match &self.kind {
                    ActionKind::Release { body, .. } => body.clone(),
                    _ => return Err("not a release".into()),
                };
                let (pose, anchor) = placement_pose(world, &body, placement)?;
                // The hand turned as the streams certified it (nearest `hand_yaw`), else nearest
                // the heading from the base.
                let pose = match world.grasp_transform(self.arm) {
                    Some(g) => release_turns(world, self.arm, &body, &pose, &g, self.hand_yaw)[0],
                    None => pose,
                };
                let tcp = tcp_for_body_pose(world, self.arm, &pose);
                Ok(ViaPose {
                    goal: raised(&tcp, *dz),
                    frame: Some(anchor_frame(&pose)),
                    anchor,
                })
            }
            Via::Up { dz, .. } => {
                let mut g = *start;
                g.translation.vector.z += dz;
                Ok(ViaPose {
                    goal: g,
                    frame: self.event_frame,
                    anchor: None,
                })
            }
            Via::Rise { z } => {
                let mut g = *start;
                g.translation.vector.z = *z;
                Ok(ViaPose {
                    goal: g,
                    frame: None,
                    anchor: None,
                })
            }
            Via::Unwind => Ok(ViaPose {
                goal: *start,
                frame: None,
                anchor: None,
            }),
            Via::Over { inner, z } => {
                let ViaPose {
                    goal: mut g,
                    anchor,
                    ..
                } = self.via_pose(world, inner, start)?;
                g.translation.vector.z = *z;
                Ok(ViaPose {
                    goal: g,
                    frame: None,
                    anchor,
                })
            }
            Via::Stroke { body, turn } => {
                let stroke = pull_stroke(world, self.arm, body, *turn)?;
                let at = world.body_pose(body).map(|q| q.translation.vector);
                Ok(ViaPose {
                    goal: stroke.pulled,
                    frame: Some(stroke.frame()),
                    anchor: at.map(|at| Anchor {
                        body: body.clone(),
                        at,
                    }),
                })
            }
            Via::Pull { body, stage, turn } => {
                let g = pull_via(world, self.arm, body, *stage, *turn)?;
                let at = world.body_pose(body).map(|q| q.translation.vector);
                Ok(ViaPose {
                    goal: g,
                    frame: None,
                    anchor: if *stage == 0 {
                        at.map(|at| Anchor {
                            body: body.clone(),
                            at,
                        })
                    } else {
                        None
                    },
                })
            }
        }
    }
}

/// Where a via-point puts the TCP, the skill's object frame (centre + yaw) and the body the
/// segment follows for re-anchoring.
pub(super) struct ViaPose {
    pub(super) goal: Isometry3<f64>,
    pub(super) frame: Option<Isometry3<f64>>,
    pub(super) anchor: Option<Anchor>,
}

/// The resting pose of `body` at a placement, and the anchor it follows (the block below).
fn placement_pose(
    world: &World,
    body: &str,
    placement: &Placement,
) -> Result<(Isometry3<f64>, Option<Anchor>), String> {
    match placement {
        Placement::OnBlock(y) => {
            let pose = rest_pose_on(world, body, y, 0.0)
                .ok_or_else(|| format!("nothing to put {body} on at {y}"))?;
            let at = world.body_pose(y).map(|q| q.translation.vector);
            Ok((
                pose,
                at.map(|at| Anchor {
                    body: y.clone(),
                    at,
                }),
            ))
        }
        Placement::At { x, y, yaw } => {
            let pose = rest_pose(world, body, *x, *y, *yaw)
                .ok_or_else(|| format!("no support under ({x:.3}, {y:.3})"))?;
            Ok((pose, None))
        }
        Placement::Stroke(_) => Err(format!("a pull stroke is not a placement of {body}")),
    }
}

/// The TCP poses of a pull stroke: the hook behind the block and at the end of the drag.
pub(super) struct PullStroke {
    pub(super) contact: Isometry3<f64>,
    pub(super) pulled: Isometry3<f64>,
}

impl PullStroke {
    /// The stroke's skill frame (`lfd::stroke_frame`).
    pub(super) fn frame(&self) -> Isometry3<f64> {
        stroke_frame(
            &Point3::from(self.contact.translation.vector),
            &Point3::from(self.pulled.translation.vector),
        )
    }
}

/// The TCP poses of the stroke turned by `turn` that pulls `body` into reach of `arm` (the
/// simulator's hook geometry, `sim::demo::pull_hook_poses_turned`: the block ends
/// `PULL_TARGET_RADIUS` from the base).
pub(super) fn pull_stroke(
    world: &World,
    arm: usize,
    body: &str,
    turn: f64,
) -> Result<PullStroke, String> {
    let base = world.arm_base(arm).ok_or("no such arm")?;
    let bp = world
        .body_pose(body)
        .ok_or_else(|| format!("no body {body}"))?;
    let reach = crate::sim::demo::PULL_TARGET_RADIUS;
    let (contact, pulled) = crate::sim::demo::pull_hook_poses_turned(&base, &bp, reach, turn)
        .ok_or_else(|| format!("no stroke turned by {turn:.2} rad pulls {body} into reach"))?;
    Ok(PullStroke {
        contact: tcp_for_body_pose(world, arm, &contact),
        pulled: tcp_for_body_pose(world, arm, &pulled),
    })
}

/// Via-points of a pull stroke: 0 above the contact pose (blade behind the block), 1 the contact
/// pose, 2 the pulled pose, 3 lifted from there.
fn pull_via(
    world: &World,
    arm: usize,
    body: &str,
    stage: u8,
    turn: f64,
) -> Result<Isometry3<f64>, String> {
    let PullStroke { contact, pulled } = pull_stroke(world, arm, body, turn)?;
    let lift = |iso: Isometry3<f64>| raised(&iso, crate::sim::demo::PULL_LIFT);
    Ok(match stage {
        0 => lift(contact),
        1 => contact,
        2 => pulled,
        _ => lift(pulled),
    })
}
