//! User moves (contact rule 4): a block or the hook dragged to a new place, or a new block
//! added, settling as a release does; refused with the reason, world unchanged, when it would
//! interpenetrate a body or an arm or be left without support.

use super::load::{check_color, check_name};
use super::settle::Settle;
use super::{Body, World};
use crate::sim::collide;
use crate::sim::geometry::yaw_of;
use crate::sim::BodyKind;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::Cuboid;
use serde::{Deserialize, Serialize};

/// A user move refused, with the reason (the world is unchanged).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[error("cannot move {body}: {reason}")]
pub struct Refused {
    /// The body the user tried to move.
    pub body: String,
    /// Why, in words (shown on the page).
    pub reason: String,
}

/// The result of an accepted [`World::move_block`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MoveOutcome {
    /// The moved body.
    pub body: String,
    /// Its previous centre (m).
    pub from: [f64; 3],
    /// Its new centre after settling (m).
    pub to: [f64; 3],
    /// What it rests on now.
    pub support: String,
    /// Bodies that were standing on it and settled down after it left, with their new centres.
    pub also_moved: Vec<(String, [f64; 3])>,
}

fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

impl World {
    /// Moves a block (or the hook) as a user drag does: its centre goes to `position` (yaw kept),
    /// then it settles straight down onto the highest support under it. Bodies that stood on it
    /// settle down in turn. Refused, with the world unchanged, if the body is unknown, fixed, held
    /// or lost, if it would interpenetrate another body or an arm, or if nothing would support it.
    pub fn move_block(
        &mut self,
        name: &str,
        position: Vector3<f64>,
    ) -> Result<MoveOutcome, Refused> {
        let yaw = self
            .body_pose(name)
            .map(|p| yaw_of(&p.rotation))
            .unwrap_or(0.0);
        self.move_block_to(name, position, yaw)
    }

    /// Like [`World::move_block`] with a new yaw (rad about world `z`).
    pub fn move_block_to(
        &mut self,
        name: &str,
        position: Vector3<f64>,
        yaw: f64,
    ) -> Result<MoveOutcome, Refused> {
        let refuse = |reason: String| Refused {
            body: name.to_string(),
            reason,
        };
        let Some(bi) = self.body_index(name) else {
            return Err(refuse("there is no such body".into()));
        };
        if let Some(why) = self.unmovable(bi) {
            return Err(refuse(why.into()));
        }
        if !(position.iter().all(|v| v.is_finite()) && yaw.is_finite()) {
            return Err(refuse("the position is not finite".into()));
        }
        let from = self.bodies[bi].pose.translation.vector;
        let mut trial = self.clone();
        let above = trial.stack_above(bi);
        let pose = Isometry3::from_parts(
            Translation3::from(position),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        );
        trial.bodies[bi].pose = pose;
        trial.overlap_at_place(bi, &above).map_err(refuse)?;
        let support = trial.settle_moved(bi, &pose, &above).map_err(refuse)?;
        trial.arm_hit(bi).map_err(refuse)?;
        let also = trial.settle_stack(&above).map_err(refuse)?;
        let to = trial.bodies[bi].pose.translation.vector;
        let support = trial.bodies[support].name.clone();
        *self = trial;
        Ok(MoveOutcome {
            body: name.to_string(),
            from: from.into(),
            to: to.into(),
            support,
            also_moved: also,
        })
    }

    /// Why a user may not move body `bi` at all, if so: it is fixed, lost or held.
    fn unmovable(&self, bi: usize) -> Option<&'static str> {
        if !self.bodies[bi].is_movable() {
            Some("it is fixed (only blocks and the hook move)")
        } else if self.bodies[bi].lost {
            Some("it is lost")
        } else if self.is_held(bi) {
            Some("it is held by a gripper")
        } else {
            None
        }
    }

    /// `Err(why)` if body `bi`, put at its requested place, interpenetrates another body beyond
    /// the tolerance (what stood on it, `above`, stays behind and does not count).
    fn overlap_at_place(&self, bi: usize, above: &[usize]) -> Result<(), String> {
        for (j, o) in self.bodies.iter().enumerate() {
            if j == bi || o.lost || above.contains(&j) {
                continue;
            }
            let depth = self.bodies[bi].penetration(o);
            if depth > self.params.penetration_tolerance {
                return Err(format!(
                    "it would interpenetrate {} by {:.1} mm",
                    o.name,
                    depth * 1000.0
                ));
            }
        }
        Ok(())
    }

    /// Settles the moved body `bi` from `pose` (bodies held by a gripper are obstacles, `above`
    /// is not): its support, or `Err(why)` if it would fall, end inside a body, or rest where a
    /// drag may not leave it.
    fn settle_moved(
        &mut self,
        bi: usize,
        pose: &Isometry3<f64>,
        above: &[usize],
    ) -> Result<usize, String> {
        match self.settle_probe_among(bi, pose, above, true) {
            Settle::On { support, drop } => {
                if let Some(why) = self.support_refusal(support) {
                    return Err(why);
                }
                self.bodies[bi].pose.translation.z -= drop;
                Ok(support)
            }
            Settle::Falls(reason) => Err(format!("it would fall: {reason}")),
            Settle::Blocked(j) => Err(format!("it would interpenetrate {}", self.bodies[j].name)),
        }
    }

    /// `Err(why)` if body `bi` (at its new place) touches a link of an arm.
    fn arm_hit(&self, bi: usize) -> Result<(), String> {
        for ai in 0..self.arms.len() {
            let (parts, _) = self.arm_parts(ai, &self.arms[ai].joints);
            for part in &parts {
                for (iso, c) in self.bodies[bi].world_parts() {
                    if collide::intersects(&part.iso, &part.shape, &iso, c) {
                        return Err(format!("it would hit the arm {}", self.arms[ai].name));
                    }
                }
            }
        }
        Ok(())
    }

    /// Settles the bodies `above` that stood on a moved one, bottom first: their names and new
    /// centres (rounded to µm), or `Err(why)` if one would rest badly, end inside a body or fall.
    fn settle_stack(&mut self, above: &[usize]) -> Result<Vec<(String, [f64; 3])>, String> {
        let mut also = Vec::new();
        let mut events = Vec::new();
        for &j in above {
            let p = self.bodies[j].pose;
            match self.settle_probe_among(j, &p, &[], true) {
                Settle::On { support, drop } => {
                    if let Some(why) = self.support_refusal(support) {
                        return Err(format!(
                            "{} standing on it would settle badly: {why}",
                            self.bodies[j].name
                        ));
                    }
                    self.bodies[j].pose.translation.z -= drop
                }
                Settle::Falls(reason) => self.make_lost(j, reason, &mut events),
                Settle::Blocked(k) => {
                    return Err(format!(
                        "{} standing on it would end inside {}",
                        self.bodies[j].name, self.bodies[k].name
                    ))
                }
            }
            if self.bodies[j].lost {
                return Err(format!(
                    "{} standing on it would fall off",
                    self.bodies[j].name
                ));
            }
            let t = self.bodies[j].pose.translation.vector;
            also.push((
                self.bodies[j].name.clone(),
                [round6(t.x), round6(t.y), round6(t.z)],
            ));
        }
        Ok(also)
    }

    /// Adds a new 6 cm block called `name` (colour `#rrggbb`) and drops it at `position` with yaw
    /// `yaw` as [`World::move_block`] does. Refused (world unchanged) for a bad or taken name, a
    /// bad colour, or a place where it cannot rest.
    pub fn add_block(
        &mut self,
        name: &str,
        color: &str,
        position: Vector3<f64>,
        yaw: f64,
    ) -> Result<MoveOutcome, Refused> {
        let refuse = |reason: String| Refused {
            body: name.to_string(),
            reason,
        };
        check_name(name, "block").map_err(|e| refuse(e.message))?;
        check_color(color, "block").map_err(|e| refuse(e.message))?;
        if self.body_index(name).is_some()
            || self.arm_index(name).is_some()
            || self.regions.iter().any(|r| r.name == name)
        {
            return Err(refuse("the name is taken".into()));
        }
        let h = 0.5 * crate::sim::BLOCK_SIZE;
        let mut trial = self.clone();
        trial.bodies.push(Body {
            name: name.to_string(),
            kind: BodyKind::Block,
            parts: vec![(Isometry3::identity(), Cuboid::new(Vector3::repeat(h)))],
            // Far above everything until it is moved into place.
            pose: Isometry3::translation(0.0, 0.0, 100.0),
            color: color.to_string(),
            lost: false,
        });
        let out = trial.move_block_to(name, position, yaw)?;
        *self = trial;
        Ok(out)
    }
}
