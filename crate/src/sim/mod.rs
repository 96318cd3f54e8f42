//! A small deterministic kinematic world: tables, a shelf, 6 cm blocks, a hook and 7-DoF
//! Panda-like arms (paper §IV, benchmarks B1–B3), its scene graph of PDDL facts and the reach
//! queries that say whether an arm can work a block where it lies.
//!
//! # Model
//!
//! Bodies are unions of boxes (parry [`Cuboid`](parry3d_f64::shape::Cuboid)s) at nalgebra poses;
//! arms are chains from the Panda's modified DH parameters ([`panda`]), with capsule links and a
//! parallel gripper whose tool centre point (TCP) lies between the fingertips. Time advances in
//! fixed steps `dt` (default 10 ms) by [`World::step`]; every arm follows its commanded TCP pose
//! ([`World::command_arm`]) through damped-least-squares IK, each joint moving at most
//! `q̇_max · dt` per step.
//!
//! # Contact rules (kinematic, not dynamic)
//!
//! 1. **Grasp.** When a gripper's command switches to *close* while its fingers are open, the
//!    first free block or hook whose volume (grown by 5 mm) contains the TCP is grasped; from then
//!    on it moves rigidly with the TCP (its pose in the TCP frame is frozen at the grasp).
//! 2. **Release.** When the command switches to *open*, the held body is levelled (tilt removed,
//!    yaw kept) and dropped straight down (a parry shape cast) onto the first body under it. It
//!    comes to rest there if its centroid lies over a top face at that height (a block, a table, the
//!    shelf). Otherwise it would tip over or it falls past every support: it is then *lost*, lies on
//!    the floor and takes no further part in contacts or facts.
//! 3. **Hook.** When the held hook moves by `d` during a step, each free block that the hook's
//!    boxes hit while translating along `d` (parry shape cast, the swept volume) is pushed
//!    horizontally by the part of `d` left after the impact, together with the blocks standing on
//!    it. A block pushed off its support is lost.
//! 4. **User moves** ([`World::move_block`]): a block goes to the requested position and settles
//!    as in rule 2; blocks that stood on it settle onto what is below them. A move that would
//!    interpenetrate a body or an arm link, or leave a block without support, is refused with the
//!    reason and the world is left unchanged.
//! 5. Nothing else moves: carried blocks are not pushed by other carried blocks, there is no
//!    friction, no toppling of towers. [`World::check_invariants`] reports any interpenetration
//!    deeper than 2 mm, any free body more than 5 mm above its support, lost bodies, and joints
//!    outside their limits.
//!
//! Everything is deterministic: fixed steps, seeded randomness, `Vec`s in stable order.
//!
//! # Example
//!
//! ```
//! use logic_lfd::sim::{Benchmark, geometry, GripperCommand, SceneGraph};
//!
//! let mut world = Benchmark::B1.scene();
//! assert!(SceneGraph::from_world(&world).contains("(ontable c)"));
//! // Move the gripper onto block c (2 s at 10 ms steps), close it, lift.
//! let grasp = geometry::grasp_pose(&world, 0, "c").unwrap();
//! let start = world.tcp_pose(0).unwrap();
//! for k in 1..=200 {
//!     let s = k as f64 / 200.0;
//!     let p = start.translation.vector.lerp(&grasp.translation.vector, s);
//!     let r = start.rotation.slerp(&grasp.rotation, s);
//!     world.command_arm(0, nalgebra::Isometry3::from_parts(p.into(), r), GripperCommand::Open).unwrap();
//!     world.step();
//! }
//! for _ in 0..20 {
//!     world.command_arm(0, grasp, GripperCommand::Close).unwrap();
//!     world.step();
//! }
//! assert_eq!(world.held_by(0), Some("c"));
//! assert!(SceneGraph::from_world(&world).contains("(holding panda c)"));
//! world.check_invariants().unwrap();
//! ```

// Index loops mirror the maths (joint k, coordinate i) in this module.
#![allow(clippy::needless_range_loop)]

mod benchmark;
mod check;
pub mod collide;
pub mod demo;
mod fast_math;
mod folder;
mod generate;
pub mod geometry;
mod json_input;
mod kinematics;
mod motions;
pub mod panda;
mod reach;
mod robot;
mod scene_graph;
mod snapshot;
mod world;

pub use benchmark::{
    goal_facts, Benchmark, BenchmarkSources, FolderRecord, BLOCK_COLORS, BLOCK_SIZE,
};
pub use check::{check_names, check_scene_against_problem, check_sources, Finding, MIN_GAP_MM};
pub use folder::{
    content_hash, FileDifference, FolderError, TaskFolder, FOLDER_FILES, REQUIRED_FILES,
};
pub use generate::{
    block_names, block_range, block_ranges_text, tower_goal, tower_heights, tower_task, MAX_BLOCKS,
    MAX_BLOCKS_B3, MAX_TOWER_HEIGHT, MIN_BLOCKS_B1, MIN_BLOCKS_B3, SPOT_SPACING, TOWER_SPACING,
};
pub use json_input::{parse_json, world_from_json, JsonError};
pub(crate) use kinematics::{joint_line, ArmPart, ArmShape};
pub use kinematics::{ArmModel, IkParams, IkSolution, Joints, Unreachable};
pub use motions::{
    ActionMotion, FactSpec, MotionKind, Motions, MotionsError, ObjectKind, ObjectSpec, Onto,
    Relation, Slot,
};
pub use reach::{handleable, hook_can_pull};
pub use robot::{
    hull_of, parse_dae, parse_obj, parse_stl, parse_urdf, read_mesh, Chain, ChainJoint, Collision,
    CollisionLink, Geometry, GripperSpec, IkFailure, IkOptions, IkResult, JointKind, JointLimits,
    LinkShape, MeshError, PairExclusion, Robot, RobotCollision, RobotError, RobotFiles, ShapeKind,
    TcpSpec, TriangleMesh, Urdf, UrdfError, UrdfJoint, UrdfLink,
};
#[cfg(not(first_load))]
pub use robot::{shipped_robot, SHIPPED_ROBOTS};
pub use scene_graph::{Fact, SceneGraph};
pub use snapshot::{
    ArmSnapshot, BodyKind, BodySnapshot, CapsuleSnapshot, CuboidSnapshot, PartSnapshot,
    PoseSnapshot, ReachSnapshot, RegionSnapshot, ShapeSnapshot, WorldSnapshot, SNAPSHOT_VERSION,
};

pub(crate) use benchmark::block;
pub(crate) use geometry::yaw_of;
pub(crate) use scene_graph::normalise;
pub(crate) use world::LINK_TOLERANCE;
pub use world::{
    GripperCommand, MoveOutcome, Refused, SceneError, SimError, Violation, World, WorldEvent,
    WorldParams,
};
