//! Path checks for planners and the executor: what a hand moved along TCP poses, or an arm
//! moved along a straight joint-space line, would sweep through (without moving anything).

use super::state::DEPTH_EPSILON;
use super::{Body, World, LINK_TOLERANCE};
use crate::sim::collide;
use crate::sim::joint_line;
use crate::sim::panda::DOF;
use crate::sim::BodyKind;
use nalgebra::Isometry3;
use parry3d_f64::shape::Cuboid;

/// Bodies' boxes are shrunk by this before a path check (m), so that touching faces and resting
/// contacts do not count as overlaps.
const TOUCH_SLACK: f64 = 0.002;

impl World {
    /// The world boxes of the bodies (not lost) that `keep` accepts (index, body), each with its
    /// body's index, shrunk by 2 mm so that touching faces and resting contacts do not count.
    fn parts_shrunk(
        &self,
        keep: impl Fn(usize, &Body) -> bool,
    ) -> Vec<(usize, Isometry3<f64>, Cuboid)> {
        self.bodies
            .iter()
            .enumerate()
            .filter(|(j, b)| !b.lost && keep(*j, b))
            .flat_map(|(j, b)| {
                b.world_parts()
                    .map(move |(iso, c)| (j, iso, crate::sim::geometry::shrunk(c, TOUCH_SLACK)))
            })
            .collect()
    }

    /// The first block or hook (`except` and held bodies excepted) that the hand's capsule
    /// ([`crate::sim::panda::hand_capsule`]) overlaps, by more than 2 mm, at one of the TCP poses
    /// `path` and did not already overlap at the first; `None` if none. The simulator stops the
    /// links only at tables and shelves, so the executor asks this of a learned approach's
    /// planned path before it follows it (a hand swept through a block would knock it over).
    pub(crate) fn hand_path_hits(
        &self,
        path: &[Isometry3<f64>],
        except: &[&str],
    ) -> Option<String> {
        let others = self.parts_shrunk(|j, b| {
            matches!(b.kind, BodyKind::Block | BodyKind::Hook)
                && !self.is_held(j)
                && !except.contains(&b.name.as_str())
        });
        let touching = |tcp: &Isometry3<f64>| -> Vec<usize> {
            let cap = crate::sim::geometry::hand_shape(tcp, 0.0);
            others
                .iter()
                .filter(|(_, iso, c)| collide::intersects(&Isometry3::identity(), &cap, iso, c))
                .map(|(j, _, _)| *j)
                .collect()
        };
        let at_start = path.first().map(touching).unwrap_or_default();
        path.iter().skip(1).find_map(|tcp| {
            touching(tcp)
                .into_iter()
                .find(|j| !at_start.contains(j))
                .map(|j| self.bodies[j].name.clone())
        })
    }

    /// What arm `arm` would sweep through on a straight joint-space move from `from` to `to`
    /// (sampled at most 0.05 rad apart in every joint, as the streams sample it), carrying what
    /// it holds: the name of the first body (`except` excepted) its links (the base link
    /// excepted) or its load overlap, by more than 2 mm, that they did not already overlap at
    /// `from`, or the table or shelf its links would stop at (pressing deeper than the simulator
    /// lets them); `None` if nothing. The executor's joint-space recovery asks this before it
    /// moves (a link passing through a block would knock it over).
    pub fn joint_move_hits(
        &self,
        arm: usize,
        from: &[f64; DOF],
        to: &[f64; DOF],
        except: &[&str],
    ) -> Option<String> {
        let a = self.arms.get(arm)?;
        let held = a.holding;
        // The load's boxes in the TCP frame.
        let load: Vec<(Isometry3<f64>, Cuboid)> = held
            .map(|(bi, g)| {
                self.bodies[bi]
                    .parts
                    .iter()
                    .map(|(p, c)| (g * p, *c))
                    .collect()
            })
            .unwrap_or_default();
        let others = self.parts_shrunk(|j, b| {
            held.is_none_or(|(bi, _)| bi != j) && !except.contains(&b.name.as_str())
        });
        // (part, other) pairs overlapping at q; parts: the arm's solids, then load boxes.
        let overlapping = |q: &[f64; DOF]| -> Vec<(usize, usize)> {
            let mut out = vec![];
            let (parts, base) = self.arm_parts(arm, q);
            for (pi, part) in parts.iter().enumerate().skip(base) {
                for (oi, (_, iso, c)) in others.iter().enumerate() {
                    if collide::intersects(&part.iso, &part.shape, iso, c) {
                        out.push((pi, oi));
                    }
                }
            }
            let tcp = a.model.forward_kinematics(&a.base, q);
            for (li, (off, lc)) in load.iter().enumerate() {
                let liso = tcp * off;
                for (oi, (_, iso, c)) in others.iter().enumerate() {
                    if collide::intersects(&liso, lc, iso, c) {
                        out.push((parts.len() + li, oi));
                    }
                }
            }
            out
        };
        let at_start = overlapping(from);
        // The links' stop at furniture, as in `step_arm`: deeper than LINK_TOLERANCE and deeper
        // than the step before.
        let mut furniture_depth = self.link_penetration(arm, from).0;
        joint_line(from, to).find_map(|q| {
            let (depth, with) = self.link_penetration(arm, &q);
            if depth > LINK_TOLERANCE && depth > furniture_depth + DEPTH_EPSILON {
                if let Some(j) = with {
                    return Some(self.bodies[j].name.clone());
                }
            }
            furniture_depth = depth;
            overlapping(&q)
                .into_iter()
                .find(|pair| !at_start.contains(pair))
                .map(|(_, oi)| self.bodies[others[oi].0].name.clone())
        })
    }
}
