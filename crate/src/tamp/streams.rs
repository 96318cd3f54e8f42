//! Streams: samplers of an action's continuous parameters, each sample certified before use.
//!
//! For a skeleton a_1..a_n the binder rolls the geometric state forward (body poses, what each
//! arm holds) and, per action,
//!
//! ```text
//!   grasp x by r:        g = top grasp of x (yaw ∈ yaw_x + k·π/2, closest to the arm's heading)
//!                        certify IK(r, g) and IK(r, g + h·ẑ)               (reachable, approach)
//!   release x on y:      p = x centred on y's top;  certify IK and  x@p ∩ others = ∅  (parry)
//!   release x on a surface (table / shelf / region R):
//!                        sample (u, v) ~ U(top face ∩ R ∩ reach annulus of r), yaw ~ U{0, π/2}
//!                        certify x@p ∩ others = ∅, IK(r, tcp(p)), IK(r, tcp(p) + h·ẑ)
//!   pull x with hook:    certify the stroke's via-points are reachable; x moves towards r
//! ```
//!
//! A skeleton fails at the first action for which no sample (within the budget) is certified.
//! Actions from the demonstration's suffix (Logic-LfD) skip certification: their motion comes from
//! the demonstrated skills re-targeted to the objects, only their surface placements are sampled.

use std::collections::BTreeMap;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::Cuboid;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::lfd::control::Binder;
use crate::lfd::exec::{classify, fact_args, ActionKind, Placement};
use crate::plan::Task;
use crate::sim::snapshot::BodyKind;
use crate::sim::World;

/// Tunables of the streams.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamParams {
    /// Samples drawn per surface placement before the action is declared unbindable.
    pub placement_samples: usize,
    /// Height of the approach pose checked above grasps and placements (m).
    pub approach_height: f64,
    /// Shapes are shrunk by this before collision tests, so touching faces do not count (m).
    pub contact_slack: f64,
    /// Free space kept around a placed body (m).
    pub clearance: f64,
}

impl Default for StreamParams {
    fn default() -> Self {
        StreamParams {
            placement_samples: 48,
            approach_height: 0.10,
            contact_slack: 0.002,
            clearance: 0.008,
        }
    }
}

/// A fixed body: name, kind and its boxes in the world.
type FixedBody = (String, BodyKind, Vec<(Isometry3<f64>, Cuboid)>);

/// Binds skeletons against a world with certified samples; remembers the last bindings.
pub struct StreamBinder<'w> {
    world: &'w World,
    fixed: Vec<FixedBody>,
    regions: Vec<crate::sim::snapshot::RegionSnapshot>,
    reach: Vec<crate::sim::snapshot::ReachSnapshot>,
    hooks: Vec<String>,
    rng: Pcg64Mcg,
    params: StreamParams,
    /// Placement per action of the last successfully bound skeleton (`None`: nothing to bind).
    pub bindings: Vec<Option<Placement>>,
    /// Certifications (IK + collision tests) done so far.
    pub certifications: usize,
    /// Placements the demonstration used, by action: `(x, y, yaw)` of the resting pose.
    hints: BTreeMap<String, (f64, f64, f64)>,
}

#[derive(Clone, Debug)]
struct Geo {
    poses: BTreeMap<String, Isometry3<f64>>,
    held: BTreeMap<usize, String>,
}

impl<'w> StreamBinder<'w> {
    /// A binder over `world` drawing samples from `seed`.
    pub fn new(world: &'w World, seed: u64, params: StreamParams) -> Self {
        let snap = world.snapshot();
        let fixed = snap
            .bodies
            .iter()
            .filter(|b| matches!(b.kind, BodyKind::Table | BodyKind::Shelf))
            .map(|b| (b.name.clone(), b.kind, world.body_shapes(&b.name)))
            .collect();
        StreamBinder {
            world,
            fixed,
            regions: snap.regions.clone(),
            reach: snap.arms.iter().map(|a| a.reach.clone()).collect(),
            hooks: snap
                .bodies
                .iter()
                .filter(|b| b.kind == BodyKind::Hook)
                .map(|b| b.name.clone())
                .collect(),
            rng: Pcg64Mcg::seed_from_u64(seed),
            params,
            bindings: vec![],
            certifications: 0,
            hints: BTreeMap::new(),
        }
    }

    /// Placements to try first for these actions (the demonstration's), `(x, y, yaw)`.
    pub fn with_hints(mut self, hints: &BTreeMap<String, (f64, f64, f64)>) -> Self {
        self.hints = hints.clone();
        self
    }

    fn geo(&self) -> Geo {
        let snap_bodies = self.world.block_names();
        let mut poses = BTreeMap::new();
        for b in snap_bodies {
            if let Some(p) = self.world.body_pose(b) {
                poses.insert(b.to_string(), p);
            }
        }
        for name in &self.hooks {
            if let Some(p) = self.world.body_pose(name) {
                poses.insert(name.clone(), p);
            }
        }
        let mut held = BTreeMap::new();
        for (i, _) in self.world.arm_names().iter().enumerate() {
            if let Some(h) = self.world.held_by(i) {
                held.insert(i, h.to_string());
            }
        }
        Geo { poses, held }
    }

    fn half_extents(&self, body: &str) -> Vector3<f64> {
        match self.world.body_aabb(body) {
            Some((lo, hi)) if self.world.body_kind(body) == Some(BodyKind::Block) => {
                0.5 * (hi - lo)
            }
            _ => Vector3::repeat(0.03),
        }
    }

    /// Whether `body` at `pose` is free of every other body in `geo` and of the fixed bodies
    /// (touching faces allowed).
    fn collision_free(&mut self, geo: &Geo, body: &str, pose: &Isometry3<f64>) -> bool {
        self.certifications += 1;
        let slack = Vector3::repeat(self.params.contact_slack);
        let grow = Vector3::new(self.params.clearance, self.params.clearance, 0.0);
        // The moving body's boxes, relative to its frame, placed at `pose`.
        let cur = self.world.body_pose(body).unwrap_or(*pose);
        let mine: Vec<(Isometry3<f64>, Vector3<f64>)> = self
            .world
            .body_shapes(body)
            .into_iter()
            .map(|(iso, c)| (pose * cur.inverse() * iso, c.half_extents))
            .collect();
        for (my_iso, h) in &mine {
            let me = Cuboid::new((h - slack).sup(&(h * 0.5)));
            let grown = Cuboid::new((h + grow - slack).sup(&(h * 0.5)));
            if !self.part_free(geo, body, my_iso, &me, &grown) {
                return false;
            }
        }
        true
    }

    fn part_free(
        &self,
        geo: &Geo,
        body: &str,
        pose: &Isometry3<f64>,
        me: &Cuboid,
        grown: &Cuboid,
    ) -> bool {
        for (name, p) in &geo.poses {
            if name == body || geo.held.values().any(|v| v == name) {
                continue;
            }
            for (off, c) in self.world.body_shapes(name) {
                // body_shapes is at the body's current pose; move it to the rolled-forward pose.
                let cur = self.world.body_pose(name).unwrap_or(*p);
                let iso = p * cur.inverse() * off;
                let other = Cuboid::new(
                    c.half_extents
                        - Vector3::repeat(self.params.contact_slack).inf(&(c.half_extents * 0.5)),
                );
                let test_shape = if self.world.body_kind(name) == Some(BodyKind::Block) {
                    grown
                } else {
                    me
                };
                if query::intersection_test(pose, test_shape, &iso, &other).unwrap_or(true) {
                    return false;
                }
            }
        }
        for (_, _, parts) in &self.fixed {
            for (iso, c) in parts {
                if query::intersection_test(pose, me, iso, c).unwrap_or(true) {
                    return false;
                }
            }
        }
        true
    }

    fn reachable(&mut self, arm: usize, tcp: &Isometry3<f64>) -> bool {
        self.certifications += 1;
        let above = Isometry3::from_parts(
            Translation3::from(tcp.translation.vector + Vector3::z() * self.params.approach_height),
            tcp.rotation,
        );
        self.world.reachable(arm, tcp).is_ok() && self.world.reachable(arm, &above).is_ok()
    }

    fn top_grasp(&self, arm: usize, pose: &Isometry3<f64>) -> Isometry3<f64> {
        let p = pose.translation.vector;
        let base = self
            .world
            .arm_base(arm)
            .map(|b| b.translation.vector)
            .unwrap_or_default();
        let heading = libm::atan2(p.y - base.y, p.x - base.x);
        let (_, _, yaw) = pose.rotation.euler_angles();
        let step = std::f64::consts::FRAC_PI_2;
        let k = ((heading - yaw) / step).round();
        let g = yaw + k * step;
        Isometry3::from_parts(
            Translation3::from(p),
            crate::sim::panda::down_orientation(g),
        )
    }

    /// The support surfaces a release onto `facts` may use: (x-range, y-range, top z).
    fn surfaces(&self, adds: &[String], body: &str) -> Vec<([f64; 2], [f64; 2], f64)> {
        let mut out = vec![];
        for f in adds {
            let (p, a) = fact_args(f);
            if a.first() != Some(&body) {
                continue;
            }
            let kind = match p {
                "ontable" => Some(BodyKind::Table),
                "onshelf" => Some(BodyKind::Shelf),
                _ => None,
            };
            if let Some(kind) = kind {
                for (name, _, _) in self.fixed.iter().filter(|b| b.1 == kind) {
                    if let Some((lo, hi)) = self.world.body_aabb(name) {
                        out.push(([lo.x, hi.x], [lo.y, hi.y], hi.z));
                    }
                }
            }
            if p == "at" && a.len() == 2 {
                if let Some(r) = self.regions.iter().find(|r| r.name == a[1]) {
                    // The region lies on a table: its top is the highest table top under it.
                    let cx = 0.5 * (r.min[0] + r.max[0]);
                    let cy = 0.5 * (r.min[1] + r.max[1]);
                    let top = self
                        .fixed
                        .iter()
                        .filter(|b| b.1 == BodyKind::Table)
                        .filter_map(|b| self.world.body_aabb(&b.0))
                        .filter(|(lo, hi)| lo.x <= cx && cx <= hi.x && lo.y <= cy && cy <= hi.y)
                        .map(|(_, hi)| hi.z)
                        .fold(f64::NEG_INFINITY, f64::max);
                    if top.is_finite() {
                        out.push(([r.min[0], r.max[0]], [r.min[1], r.max[1]], top));
                    }
                }
            }
        }
        out
    }

    /// Whether `(x, y)` is within `margin` of a shelf's footprint.
    fn near_shelf(&self, x: f64, y: f64, margin: f64) -> bool {
        self.fixed
            .iter()
            .filter(|b| b.1 == BodyKind::Shelf)
            .filter_map(|b| self.world.body_aabb(&b.0))
            .any(|(lo, hi)| {
                x > lo.x - margin && x < hi.x + margin && y > lo.y - margin && y < hi.y + margin
            })
    }

    /// Whether arm `a`'s reach annulus contains `(x, y)`.
    fn in_annulus(&self, a: usize, x: f64, y: f64) -> bool {
        match (self.reach.get(a), self.world.arm_base(a)) {
            (Some(r), Some(b)) => {
                let d = libm::hypot(x - b.translation.x, y - b.translation.y);
                d >= r.min_radius && d <= r.max_radius
            }
            _ => false,
        }
    }

    /// A certified resting pose for `body` on one of `surfaces`: the demonstration's `hint`
    /// first, then uniform samples. Certified: inside the placing arm's reach annulus,
    /// collision-free, reachable (with approach) by the placing arm and by every other arm whose
    /// annulus contains it (hand-over spots must be graspable from the other side).
    fn sample_surface(
        &mut self,
        geo: &Geo,
        arm: usize,
        body: &str,
        surfaces: &[([f64; 2], [f64; 2], f64)],
        hint: Option<(f64, f64, f64)>,
    ) -> Option<(Placement, Isometry3<f64>)> {
        if surfaces.is_empty() {
            return None;
        }
        let h = self.half_extents(body);
        let margin = h.x.max(h.y) + 0.01;
        // Height of the body's frame above its lowest point (the hook's frame is not centred).
        let (lo, _) = self.world.body_aabb(body)?;
        let lift = self.world.body_pose(body)?.translation.z - lo.z;
        let is_block = self.world.body_kind(body) == Some(BodyKind::Block);
        for n in 0..=self.params.placement_samples {
            let (x, y, yaw, top) = if n == 0 {
                let Some((x, y, yaw)) = hint else { continue };
                let Some(&(_, _, top)) = surfaces
                    .iter()
                    .find(|(xr, yr, _)| xr[0] <= x && x <= xr[1] && yr[0] <= y && y <= yr[1])
                else {
                    continue;
                };
                (x, y, yaw, top)
            } else {
                let (xr, yr, top) = surfaces[self.rng.random_range(0..surfaces.len())];
                if xr[1] - xr[0] <= 2.0 * margin || yr[1] - yr[0] <= 2.0 * margin {
                    continue;
                }
                let x = self.rng.random_range(xr[0] + margin..xr[1] - margin);
                let y = self.rng.random_range(yr[0] + margin..yr[1] - margin);
                let yaw = if self.rng.random_bool(0.5) {
                    0.0
                } else {
                    std::f64::consts::FRAC_PI_2
                };
                (x, y, yaw, top)
            };
            if is_block && !self.in_annulus(arm, x, y) {
                continue;
            }
            let pose = Isometry3::from_parts(
                Translation3::new(x, y, top + lift),
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
            );
            if !self.collision_free(geo, body, &pose) {
                continue;
            }
            // The carried hook is not routed around obstacles: sampled hook spots keep clear of
            // shelves and stay where the arm carried it in the demonstration (near its hint).
            if !is_block && n > 0 {
                let near_hint = hint.is_some_and(|(hx, hy, _)| libm::hypot(x - hx, y - hy) < 0.15);
                if self.near_shelf(x, y, 0.12) || (hint.is_some() && !near_hint) {
                    continue;
                }
            }
            if is_block {
                let tcp = self.top_grasp(arm, &pose);
                if !self.reachable(arm, &tcp) {
                    continue;
                }
                let others: Vec<usize> = (0..self.reach.len())
                    .filter(|&a| a != arm && self.in_annulus(a, x, y))
                    .collect();
                if others.iter().any(|&a| {
                    let g = self.top_grasp(a, &pose);
                    !self.reachable(a, &g)
                }) {
                    continue;
                }
            }
            return Some((Placement::At { x, y, yaw }, pose));
        }
        None
    }
}

impl Binder for StreamBinder<'_> {
    fn bind(&mut self, task: &Task, ops: &[usize], demo_from: usize) -> Result<(), usize> {
        let mut geo = self.geo();
        let mut out = Vec::with_capacity(ops.len());
        for (i, &o) in ops.iter().enumerate() {
            let op = &task.operators[o];
            let certify = i < demo_from;
            let Some(kind) = classify(task, op, self.world) else {
                out.push(None);
                continue;
            };
            match kind {
                ActionKind::Grasp { arm, body } => {
                    let Some(pose) = geo.poses.get(&body).copied() else {
                        return Err(i);
                    };
                    if certify {
                        let g = self.top_grasp(arm, &pose);
                        if !self.reachable(arm, &g) {
                            return Err(i);
                        }
                    }
                    geo.held.insert(arm, body);
                    out.push(None);
                }
                ActionKind::Release {
                    arm,
                    body,
                    placement: Some(Placement::OnBlock(y)),
                } => {
                    let Some(py) = geo.poses.get(&y).copied() else {
                        return Err(i);
                    };
                    let hy = self.half_extents(&y);
                    let hb = self.half_extents(&body);
                    let pose = Isometry3::from_parts(
                        Translation3::from(py.translation.vector + Vector3::z() * (hy.z + hb.z)),
                        py.rotation,
                    );
                    if certify {
                        let tcp = self.top_grasp(arm, &pose);
                        if !self.reachable(arm, &tcp) {
                            return Err(i);
                        }
                    }
                    geo.held.remove(&arm);
                    geo.poses.insert(body, pose);
                    out.push(Some(Placement::OnBlock(y)));
                }
                ActionKind::Release { arm, body, .. } => {
                    let adds: Vec<String> = op
                        .add
                        .iter()
                        .map(|&f| task.facts[f as usize].clone())
                        .collect();
                    let surfaces = self.surfaces(&adds, &body);
                    geo.held.remove(&arm);
                    let hint = self.hints.get(&op.name).copied();
                    let Some((placement, pose)) =
                        self.sample_surface(&geo, arm, &body, &surfaces, hint)
                    else {
                        return Err(i);
                    };
                    geo.poses.insert(body, pose);
                    out.push(Some(placement));
                }
                ActionKind::Pull { arm, body, .. } => {
                    let Some(pose) = geo.poses.get(&body).copied() else {
                        return Err(i);
                    };
                    let base = self
                        .world
                        .arm_base(arm)
                        .map(|b| b.translation.vector)
                        .unwrap_or_default();
                    let p = pose.translation.vector;
                    let mut d = Vector3::new(p.x - base.x, p.y - base.y, 0.0);
                    let r = d.norm().max(1e-6);
                    d /= r;
                    let pulled = p - d * 0.25;
                    if certify {
                        let g = self.top_grasp(
                            arm,
                            &Isometry3::from_parts(
                                Translation3::from(pulled),
                                UnitQuaternion::identity(),
                            ),
                        );
                        if !self.reachable(arm, &g) {
                            return Err(i);
                        }
                    }
                    geo.poses.insert(
                        body,
                        Isometry3::from_parts(Translation3::from(pulled), pose.rotation),
                    );
                    out.push(None);
                }
            }
        }
        self.bindings = out;
        Ok(())
    }
}
