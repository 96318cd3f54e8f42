//! The grasp stream: the executor's grasp of a body where the rolled-forward state has it, the
//! approach, close and lift certified, and the body's lift checked for overhangs.

use crate::sim::collide;
use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;

use super::boxes::box_aabb;
use super::obstacles::shrunk_by;
use super::{Geo, Held, Predicted, StreamBinder, Transit};
use crate::sim::geometry::raised;
use crate::tamp::grasp_pose;

impl StreamBinder<'_> {
    /// Certifies `arm` grasping `body` (approach from above, close, lift) and rolls `geo` on:
    /// `None` if it cannot, else the height of the transit its approach needs, if any.
    pub(super) fn grasp(
        &mut self,
        geo: &mut Geo,
        arm: usize,
        body: &str,
        certify: bool,
    ) -> Option<Transit> {
        let pose = geo.poses.get(body).copied()?;
        // Certified or not, the body must rise free: a block dragged or nudged over its edge
        // stops the lift (the simulator's contact stop), and no motion of the hand helps.
        if let Some(over) = self.overhang(geo, body, &pose) {
            let why = format!("{over} overhangs {body}");
            self.collision(why, &over);
            return None;
        }
        let motion = self.params.motion;
        let tcp = grasp_pose(
            &Predicted { binder: self, geo },
            self.world,
            arm,
            body,
            &pose,
            &motion,
        )?;
        let lifted = raised(&tcp, motion.lift_height);
        let mut transit = None;
        if certify {
            let via = [raised(&tcp, self.params.motion.approach_height), tcp];
            let (q, z) = self.certify_approach(geo, arm, &via, &[body], 0.0).ok()?;
            transit = z;
            let mut after = geo.clone();
            after.tcp[arm] = tcp;
            after.q[arm] = q;
            after.held.insert(
                arm,
                Held {
                    body: body.to_string(),
                    grasp: tcp.inverse() * pose,
                },
            );
            let q = self.certify_path(&after, arm, &[lifted], &[], 0.0).ok()?;
            geo.q[arm] = q;
        } else if let Ok(sol) = self.world.reachable(arm, &lifted) {
            geo.q[arm] = sol.joints;
        }
        geo.tcp[arm] = lifted;
        geo.held.insert(
            arm,
            Held {
                body: body.to_string(),
                grasp: tcp.inverse() * pose,
            },
        );
        geo.poses.insert(
            body.to_string(),
            raised(&pose, self.params.motion.lift_height),
        );
        Some(transit)
    }

    /// A body of `geo` (not held) above the middle of `body` at `pose` that overlaps, by more
    /// than the simulator's contact stop lets a lifted body press into another, the box `body`
    /// sweeps rising straight up by the lift height: what would stop its lift.
    fn overhang(&self, geo: &Geo, body: &str, pose: &Isometry3<f64>) -> Option<String> {
        let slack = self.overhang_slack();
        let rise = self.params.motion.lift_height;
        let swept: Vec<(Isometry3<f64>, Cuboid)> = self
            .parts_at(body, pose)
            .into_iter()
            .map(|(iso, c)| {
                let tall = Cuboid::new(c.half_extents + Vector3::new(0.0, 0.0, 0.5 * rise));
                (raised(&iso, 0.5 * rise), shrunk_by(&tall, slack))
            })
            .collect();
        let middle = pose.translation.z;
        geo.poses
            .iter()
            .filter(|(name, _)| name.as_str() != body && !geo.is_held(name))
            .find_map(|(name, p)| {
                let parts = self.parts_at(name, p);
                let hit = parts.iter().any(|(oiso, oc)| {
                    let (lo, _) = box_aabb(oiso, oc);
                    let other = shrunk_by(oc, slack);
                    lo.z > middle
                        && swept
                            .iter()
                            .any(|(iso, c)| collide::intersects(iso, c, oiso, &other))
                });
                hit.then(|| name.clone())
            })
    }

    /// How much [`StreamBinder::overhang`] shrinks each box (m): a little less than half of the
    /// overlap the simulator's contact stop allows ([`OVERHANG_SLACK_OF_TOLERANCE`] of the
    /// world's penetration tolerance).
    fn overhang_slack(&self) -> f64 {
        OVERHANG_SLACK_OF_TOLERANCE * self.world.params().penetration_tolerance
    }
}

/// The fraction of the world's penetration tolerance by which [`StreamBinder::overhang`]
/// shrinks each box: a little less than half of the overlap the contact stop allows.
const OVERHANG_SLACK_OF_TOLERANCE: f64 = 0.4;
