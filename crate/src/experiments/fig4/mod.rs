//! The paper's Fig. 4 (§IV-D): LQT-CP against the classic DMP on two B2 sub-tasks, with skills
//! learned from B2's demonstration as the executor learns them (`lfd::skill`).
//!
//! * (a) *Pick the hook* at three positions: the learned approach of the demo's hook grasp
//!   (`pick/approach@hook`) from the template's start pose to the hook moved by
//!   [`HOOK_OFFSETS`], run in the simulator through its feedback controller; the goal error is
//!   the TCP's distance from the grasp pose at the end.
//! * (b) *Pull cube A* (the block the demo pulls, named by `motions.json` and the demo) to three
//!   goals: strokes turned by [`PULL_GOAL_TURNS`] from the line through the arm's base, each
//!   ending with the block [`PULL_TARGET_RADIUS`] from the base. The hand holds the hook (the
//!   demo's pick, executed) above the contact pose of the radial stroke, the same start for all
//!   three goals, turned along the stroke to come; the learned stroke (`pull/stroke`) is planned there with its two via-points
//!   (the TCP where the blade passes the block's far top edge and where it is down behind its
//!   far face, `lfd/skill/stroke.rs`). Reported: the distance of the planned trajectory from each
//!   via-point at its step and from the goal (LQT-CP passes the via-points, the DMP cannot encode
//!   them), the same distances for the TCP the simulator moved, and whether the simulated
//!   stroke left the block within [`GOAL_TOLERANCE`] of its goal.

pub mod plot;

use nalgebra::{Isometry3, Point3, Translation3, Vector3};
use serde::Serialize;

use crate::lfd::SkillKind;
use crate::lfd::{skill_key, SegmentKind, SkillLibrary, SkillSegment};
use crate::lfd::{ActionExec, ExecParams, ExecStatus};
use crate::sim::demo::{
    self, pull_hook_poses_turned, pulled_block_position, AnchorPose, DemoAction, PULL_LIFT,
    PULL_TARGET_RADIUS,
};
use crate::sim::geometry::{grasp_pose, raised, tcp_for_body_pose};
use crate::sim::Benchmark;
use crate::sim::MotionKind;
use crate::sim::World;
use crate::tamp::ActionKind;

/// A simulated pull reached its goal when the block's centre ends this close to it,
/// horizontally (m).
pub const GOAL_TOLERANCE: f64 = 0.01;

/// The three goals of the pull: turns of the stroke from the line through the arm's base (rad).
pub const PULL_GOAL_TURNS: [f64; 3] = [-0.26, 0.26, -0.45];

/// The three hook positions of the pick: offsets from the template's hook position (m, x and y).
pub const HOOK_OFFSETS: [[f64; 2]; 3] = [[0.0, 0.0], [0.06, 0.08], [-0.05, -0.07]];

/// Ticks the simulator runs on after a trajectory's end (the controller holds its goal).
const SETTLE_TICKS: usize = 50;

/// Most ticks the demo's hook grasp may take when the figure sets up the pull.
const PICK_TICKS: usize = 6000;

/// Duration of the move to the pull's start pose (s).
const START_MOVE_TIME: f64 = 1.5;

/// The hand must settle this close to the pull's start pose (m) ...
const START_TOLERANCE: f64 = 0.004;

/// ... and turned this close to it (rad).
const START_TURN_TOLERANCE: f64 = 0.05;

/// The methods compared, in the order they are reported.
const METHODS: [(SkillKind, &str); 2] = [(SkillKind::Lqt, "lqt-cp"), (SkillKind::Dmp, "dmp")];

/// One pick of the hook by one method.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PickRow {
    /// `lqt-cp` or `dmp`.
    pub method: String,
    /// Index of the hook position (0..3).
    pub position: usize,
    /// The hook's centre (world, m).
    pub hook: [f64; 3],
    /// The simulated TCP's distance from the grasp pose at the end (mm).
    pub goal_error_mm: f64,
    /// The planned TCP path (world, m).
    pub path: Vec<[f64; 3]>,
}

/// One pull of the block to one goal by one method.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PullRow {
    /// `lqt-cp` or `dmp`.
    pub method: String,
    /// Index of the goal (0..3).
    pub goal: usize,
    /// Where the block should end (world, m).
    pub block_goal: [f64; 3],
    /// Where the simulated stroke left it (world, m).
    pub block_end: [f64; 3],
    /// The planned trajectory's distance from its goal at the end (mm).
    pub goal_error_mm: f64,
    /// The planned trajectory's distance from each via-point at its step (mm).
    pub via_errors_mm: Vec<f64>,
    /// The simulated TCP's distance from each via-point at its step (mm).
    pub executed_via_errors_mm: Vec<f64>,
    /// The block's horizontal distance from its goal after the simulated stroke (mm).
    pub block_error_mm: f64,
    /// Whether that is within [`GOAL_TOLERANCE`].
    pub reached: bool,
    /// The via-points (world, m).
    pub via_points: Vec<[f64; 3]>,
    /// The planned TCP path (world, m).
    pub path: Vec<[f64; 3]>,
    /// The simulated TCP path (world, m).
    pub executed: Vec<[f64; 3]>,
}

/// The figure's numbers.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fig4 {
    /// The hook picked in (a).
    pub hook: String,
    /// The block pulled in (b) (the paper's cube A).
    pub block: String,
    /// Where the block starts (world, m).
    pub block_start: [f64; 3],
    /// The via-points' labels, in the order of `via_errors_mm`.
    pub via_labels: Vec<String>,
    /// [`GOAL_TOLERANCE`] in mm.
    pub goal_tolerance_mm: f64,
    /// (a), method by method within each position.
    pub pick: Vec<PickRow>,
    /// (b), method by method within each goal.
    pub pull: Vec<PullRow>,
}

/// B2's scene, demo and the skills of both methods.
struct Setup {
    world: World,
    arm: usize,
    pick: DemoAction,
    pull: DemoAction,
    libraries: Vec<(SkillLibrary, &'static str)>,
}

fn setup() -> Result<Setup, String> {
    let b = Benchmark::B2;
    let world = b.scene();
    let demo = demo::committed(b).map_err(|e| e.to_string())?;
    let motions = b.motions();
    let hooks = world.hook_names();
    let motion_of = |a: &DemoAction| motions.actions.get(&a.name).map(|d| d.motion);
    let pull = demo
        .actions
        .iter()
        .find(|a| motion_of(a) == Some(MotionKind::Pull))
        .ok_or("the B2 demo has no pull")?
        .clone();
    let pick = demo
        .actions
        .iter()
        .find(|a| motion_of(a) == Some(MotionKind::Grasp) && hooks.contains(&a.anchor))
        .ok_or("the B2 demo grasps no hook")?
        .clone();
    let arm = world
        .arm_names()
        .iter()
        .position(|n| *n == pull.arm)
        .ok_or_else(|| format!("no arm {}", pull.arm))?;
    let libraries = METHODS
        .iter()
        .map(|&(kind, label)| {
            (
                SkillLibrary::learn(b.demo_json(), kind, &hooks, &motions),
                label,
            )
        })
        .collect();
    Ok(Setup {
        world,
        arm,
        pick,
        pull,
        libraries,
    })
}

/// Runs segment `seg` of arm `arm` in `world` through its controller (holding the gripper as it
/// is), turning the hand from the segment's start rotation to `goal`'s by step `turn_by`, then
/// [`SETTLE_TICKS`] more. The TCP before each tick.
fn run_segment(
    world: &mut World,
    arm: usize,
    mut seg: SkillSegment,
    goal: &Isometry3<f64>,
    turn_by: usize,
) -> Vec<Vector3<f64>> {
    let grip = world
        .arm_command(arm)
        .map(|c| c.1)
        .unwrap_or(crate::sim::GripperCommand::Open);
    let start = seg.start_rotation();
    let mut out = Vec::with_capacity(seg.len() + SETTLE_TICKS);
    for t in 0..seg.len() + SETTLE_TICKS {
        let Some(tcp) = world.tcp_pose(arm) else {
            break;
        };
        out.push(tcp.translation.vector);
        let pos = seg.command(t, &tcp.translation.vector);
        let s = (t as f64 / turn_by.max(1) as f64).min(1.0);
        let cmd = Isometry3::from_parts(Translation3::from(pos), start.slerp(&goal.rotation, s));
        // A command the arm cannot reach leaves it where the tracker gets: measured as is.
        let _ = world.command_arm(arm, cmd, grip);
        world.step();
    }
    out
}

fn arr(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn mm(d: f64) -> f64 {
    libm::round(d * 1e4) / 10.0
}

/// (a): every method picks the hook at every position of [`HOOK_OFFSETS`].
fn picks(s: &Setup) -> Result<Vec<PickRow>, String> {
    let hook = &s.pick.anchor;
    let start = s.world.tcp_pose(s.arm).ok_or("no arm")?;
    let at = s.world.body_pose(hook).ok_or("no hook")?.translation.vector;
    let key = skill_key(&s.pick.name, SegmentKind::Approach, true);
    let mut rows = Vec::new();
    for (i, off) in HOOK_OFFSETS.iter().enumerate() {
        let mut w = s.world.clone();
        w.move_block(hook, at + Vector3::new(off[0], off[1], 0.0))
            .map_err(|e| e.to_string())?;
        let pose = w.body_pose(hook).ok_or("no hook")?;
        let grasp = grasp_pose(&w, s.arm, hook).ok_or("the hook cannot be grasped")?;
        let anchor = AnchorPose::from_pose(&pose).isometry();
        for (lib, method) in &s.libraries {
            if !lib.has(&key) {
                return Err(format!("no learned skill {key}"));
            }
            let seg = lib.segment(&key, &start, &grasp, Some(&anchor), 2);
            let path = (0..seg.len()).map(|t| arr(&seg.planned(t))).collect();
            let turn_by = seg.len();
            let mut sim = w.clone();
            let done = run_segment(&mut sim, s.arm, seg, &grasp, turn_by);
            let end = done.last().copied().unwrap_or_default();
            rows.push(PickRow {
                method: method.to_string(),
                position: i,
                hook: arr(&pose.translation.vector),
                goal_error_mm: mm((end - grasp.translation.vector).norm()),
                path,
            });
        }
    }
    Ok(rows)
}

/// The world of (b): the demo's hook grasp executed.
fn holding_hook(s: &Setup) -> Result<World, String> {
    let mut w = s.world.clone();
    let (lib, _) = &s.libraries[0];
    let params = ExecParams::default();
    let kind = ActionKind::Grasp {
        arm: s.arm,
        body: s.pick.anchor.clone(),
    };
    let mut exec = ActionExec::new(&s.pick.action, kind, &w, lib, &params);
    let mut status = ExecStatus::Running;
    for _ in 0..PICK_TICKS {
        status = exec.tick(&mut w, lib, &params);
        if status != ExecStatus::Running {
            break;
        }
    }
    if status != ExecStatus::Done {
        return Err(format!("{}: {status:?}", s.pick.action));
    }
    Ok(w)
}

/// `w` with the hand moved to `above` turned as `turned` (the hook along the stroke to come)
/// and settled there.
fn moved_to(
    w: &World,
    s: &Setup,
    above: &Isometry3<f64>,
    turned: &Isometry3<f64>,
) -> Result<World, String> {
    let mut w = w.clone();
    let (lib, _) = &s.libraries[0];
    let target = Isometry3::from_parts(above.translation, turned.rotation);
    let from = w.tcp_pose(s.arm).ok_or("no arm")?;
    let steps = libm::round(START_MOVE_TIME / w.dt()) as usize;
    let seg = lib.segment("", &from, &target, None, steps);
    run_segment(&mut w, s.arm, seg, &target, steps);
    let tcp = w.tcp_pose(s.arm).ok_or("no arm")?;
    let off = (tcp.translation.vector - target.translation.vector).norm();
    let turn = (tcp.rotation * target.rotation.inverse()).angle();
    if off > START_TOLERANCE || turn > START_TURN_TOLERANCE {
        return Err(format!(
            "the hand stops {:.1} mm and {:.1}° from the pull's start",
            off * 1e3,
            turn.to_degrees()
        ));
    }
    Ok(w)
}

/// (b): every method pulls the block to every goal of [`PULL_GOAL_TURNS`].
fn pulls(s: &Setup) -> Result<(Vec<PullRow>, Vec<String>), String> {
    let held = holding_hook(s)?;
    let block = &s.pull.anchor;
    let key = skill_key(&s.pull.name, SegmentKind::Stroke, false);
    let bp = held.body_pose(block).ok_or("no block")?;
    let base = held.arm_base(s.arm).ok_or("no arm")?;
    // Every pull starts above the contact pose of the radial stroke.
    let (radial, _) =
        pull_hook_poses_turned(&base, &bp, PULL_TARGET_RADIUS, 0.0).ok_or("no radial stroke")?;
    let above = raised(&tcp_for_body_pose(&held, s.arm, &radial), PULL_LIFT);
    let mut rows = Vec::new();
    let mut labels = Vec::new();
    for (i, &turn) in PULL_GOAL_TURNS.iter().enumerate() {
        let (c, p) = pull_hook_poses_turned(&base, &bp, PULL_TARGET_RADIUS, turn)
            .ok_or_else(|| format!("no stroke turned by {turn} rad"))?;
        let goal = pulled_block_position(&bp, &c, &p);
        let (ct, pt) = (
            tcp_for_body_pose(&held, s.arm, &c),
            tcp_for_body_pose(&held, s.arm, &p),
        );
        let w0 = moved_to(&held, s, &above, &ct)?;
        let start = w0.tcp_pose(s.arm).ok_or("no arm")?;
        let from = Point3::from(start.translation.vector);
        let point = |q: &Isometry3<f64>| Point3::from(q.translation.vector);
        for (lib, method) in &s.libraries {
            let plan = lib
                .stroke_plan(&key, &from, &point(&ct), &point(&pt))
                .ok_or_else(|| format!("no learned skill {key}"))?;
            let traj = &plan.trajectory;
            let at = |t: usize| traj.positions[t.min(traj.len() - 1)];
            labels = plan.via_points.iter().map(|v| v.label.clone()).collect();
            let turn_by = plan.via_points.iter().map(|v| v.step).min().unwrap_or(1);
            let seg = SkillSegment::closed(traj, start.rotation).ok_or("empty stroke")?;
            let mut sim = w0.clone();
            let done = run_segment(&mut sim, s.arm, seg, &pt, turn_by);
            let end = sim.body_pose(block).ok_or("no block")?.translation.vector;
            let off = end - goal;
            let block_error = libm::hypot(off.x, off.y);
            let executed_at = |t: usize| done[t.min(done.len() - 1)];
            rows.push(PullRow {
                method: method.to_string(),
                goal: i,
                block_goal: arr(&goal),
                block_end: arr(&end),
                goal_error_mm: mm((at(usize::MAX) - point(&pt)).norm()),
                via_errors_mm: plan
                    .via_points
                    .iter()
                    .map(|v| mm((at(v.step) - v.position).norm()))
                    .collect(),
                executed_via_errors_mm: plan
                    .via_points
                    .iter()
                    .map(|v| mm((executed_at(v.step) - v.position.coords).norm()))
                    .collect(),
                block_error_mm: mm(block_error),
                reached: block_error <= GOAL_TOLERANCE,
                via_points: plan
                    .via_points
                    .iter()
                    .map(|v| arr(&v.position.coords))
                    .collect(),
                path: traj.positions.iter().map(|q| arr(&q.coords)).collect(),
                executed: done.iter().map(arr).collect(),
            });
        }
    }
    Ok((rows, labels))
}

/// Runs the figure's experiments (deterministic: no seed).
pub fn fig4() -> Result<Fig4, String> {
    let s = setup()?;
    let pick = picks(&s)?;
    let (pull, via_labels) = pulls(&s)?;
    let start = s
        .world
        .body_pose(&s.pull.anchor)
        .ok_or("no block")?
        .translation
        .vector;
    Ok(Fig4 {
        hook: s.pick.anchor.clone(),
        block: s.pull.anchor.clone(),
        block_start: arr(&start),
        via_labels,
        goal_tolerance_mm: GOAL_TOLERANCE * 1e3,
        pick,
        pull,
    })
}

/// The figure's numbers as markdown tables.
pub fn markdown(f: &Fig4) -> String {
    let mut s = format!(
        "Fig. 4 (a) — pick the hook `{}` at three positions (simulated TCP's distance from the \
         grasp pose at the end).\n\n| position | hook at (m) | method | goal error (mm) |\n\
         |---|---|---|---:|\n",
        f.hook
    );
    for r in &f.pick {
        s += &format!(
            "| {} | ({:.3}, {:.3}) | {} | {:.1} |\n",
            r.position + 1,
            r.hook[0],
            r.hook[1],
            r.method,
            r.goal_error_mm
        );
    }
    let vias = f.via_labels.join(", ");
    s += &format!(
        "\nFig. 4 (b) — pull `{}` from ({:.3}, {:.3}) to three goals with the learned stroke \
         (via-points: {vias}). Planned: the trajectory's distance from each via-point at its step \
         and from its goal; simulated: the TCP the simulator moved, and the block's distance from \
         its goal (reached within {:.0} mm).\n\n\
         | goal | block goal (m) | method | via-point error, planned (mm) | via-point error, \
         simulated (mm) | goal error (mm) | block error (mm) | reached |\n\
         |---|---|---|---|---|---:|---:|---|\n",
        f.block, f.block_start[0], f.block_start[1], f.goal_tolerance_mm
    );
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.1}"))
            .collect::<Vec<_>>()
            .join(" / ")
    };
    for r in &f.pull {
        s += &format!(
            "| {} | ({:.3}, {:.3}) | {} | {} | {} | {:.1} | {:.1} | {} |\n",
            r.goal + 1,
            r.block_goal[0],
            r.block_goal[1],
            r.method,
            list(&r.via_errors_mm),
            list(&r.executed_via_errors_mm),
            r.goal_error_mm,
            r.block_error_mm,
            if r.reached { "yes" } else { "no" }
        );
    }
    s
}
