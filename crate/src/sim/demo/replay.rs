//! Replaying a demonstration in the simulator, and the demonstration's states `L0..LN` as the
//! scene graph sees them.

use super::data::{committed, fail, AnchorPose, DemoAction, DemoError, Demonstration};
use crate::sim::geometry::yaw_of;
use crate::sim::panda;
use crate::sim::world::World;
use crate::sim::Benchmark;
use crate::sim::MotionKind;
use crate::sim::SceneGraph;
use nalgebra::{Isometry3, Translation3};

/// Replays a demonstration in `world` (which should be the template scene): each action's
/// samples are mapped through its anchor frame — the anchor object's current pose for actions
/// that grasp or pull (by the world's declared motions), the recorded `anchor_pose` for
/// releases — and commanded step by
/// step with the recorded gripper events. `after_step` is called after every simulator step
/// (tests check invariants there).
pub fn replay(
    world: &mut World,
    demo: &Demonstration,
    mut after_step: impl FnMut(&World, &DemoAction, usize) -> Result<(), DemoError>,
) -> Result<(), DemoError> {
    for a in &demo.actions {
        let arm = world
            .arm_index(&a.arm)
            .ok_or_else(|| fail(&a.action, format!("unknown arm {}", a.arm)))?;
        let grasps = world
            .motions()
            .actions
            .get(&a.name)
            .is_some_and(|m| matches!(m.motion, MotionKind::Grasp | MotionKind::Pull));
        let anchor = match grasps {
            true => {
                let p = world
                    .body_pose(&a.anchor)
                    .ok_or_else(|| fail(&a.action, format!("unknown body {}", a.anchor)))?;
                AnchorPose::from_pose(&p).isometry()
            }
            false => a.anchor_pose.isometry(),
        };
        let ayaw = yaw_of(&anchor.rotation);
        let (_, mut grip) = world
            .arm_command(arm)
            .ok_or_else(|| fail(&a.action, "no arm"))?;
        let mut ev = a.gripper.iter().peekable();
        for (k, s) in a.samples.iter().enumerate() {
            while let Some(e) = ev.peek() {
                if e.step <= k {
                    grip = e.command;
                    ev.next();
                } else {
                    break;
                }
            }
            let p = anchor * nalgebra::Point3::new(s[0], s[1], s[2]);
            let cmd = Isometry3::from_parts(
                Translation3::from(p.coords),
                panda::down_orientation(ayaw + s[3]),
            );
            world
                .command_arm(arm, cmd, grip)
                .map_err(|e| fail(&a.action, e.to_string()))?;
            world.step();
            after_step(world, a, k)?;
        }
    }
    Ok(())
}

/// The demonstration's states `L0..LN` as the scene graph sees them: the facts of the template
/// world and after each action of the committed demo, replayed in the simulator. (They equal the
/// PDDL states derived by applying the actions, plus the static facts the scene graph reports —
/// the integration tests check this.)
pub fn demo_states(b: Benchmark) -> Result<Vec<std::collections::BTreeSet<String>>, DemoError> {
    let d = committed(b)?;
    let mut w = b.scene();
    let facts = |w: &World| -> std::collections::BTreeSet<String> {
        SceneGraph::from_world(w).to_strings().into_iter().collect()
    };
    let mut out = vec![facts(&w)];
    replay(&mut w, &d, |w, a, k| {
        if k + 1 == a.samples.len() {
            out.push(facts(w));
        }
        Ok(())
    })?;
    Ok(out)
}
