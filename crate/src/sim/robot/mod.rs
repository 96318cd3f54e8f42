//! A robot from its URDF: the robot file (`robot.json`) beside a URDF, the kinematic chain from
//! the base link to the tip link, the tool centre point, the home posture and the gripper.
//!
//! ```json
//! { "name": "panda",
//!   "urdf": "example-robot-data/robots/panda_description/urdf/panda.urdf",
//!   "packages": { "example-robot-data": "example-robot-data" },
//!   "base_link": "panda_link0", "tip_link": "panda_link8",
//!   "tcp": { "xyz": [0, 0, 0.1034], "rpy": [0, 0, -0.7854] },
//!   "home": [0, -0.785, 0, -2.356, 0, 1.571, 0.785],
//!   "gripper": { "joints": ["panda_finger_joint1", "panda_finger_joint2"], "max_opening": 0.08 } }
//! ```
//!
//! Paths are relative to the robot file; `packages` maps the ROS package names of
//! `package://NAME/…` mesh paths to folders. The TCP frame is the tip link's frame moved by `tcp`:
//! its z axis points from the hand towards the object, its y axis along the fingers' closing
//! direction.
//!
//! The collision model ([`RobotCollision`], built apart from [`Robot::load`]) reads each link's
//! `<collision>` shapes, meshes (STL, OBJ, COLLADA) as convex hulls, for self-collision and
//! obstacle distances.

mod chain;
mod collision;
mod dae;
mod file;
mod files;
mod hull;
mod ik;
mod mesh;
mod model;
#[cfg(not(first_load))]
mod shipped;
mod urdf;

pub use chain::{Chain, ChainJoint};
pub use collision::{CollisionLink, PairExclusion, RobotCollision};
pub use dae::parse_dae;
pub use file::{GripperSpec, Robot, RobotError, TcpSpec};
pub use files::RobotFiles;
pub use hull::{hull_of, read_mesh, LinkShape, ShapeKind};
pub use ik::{IkFailure, IkOptions, IkResult};
pub use mesh::{parse_obj, parse_stl, MeshError, TriangleMesh};
#[cfg(not(first_load))]
pub(crate) use model::Model;
#[cfg(not(first_load))]
pub use shipped::{shipped_robot, SHIPPED_ROBOTS};
pub use urdf::{
    parse_urdf, Collision, Geometry, JointKind, JointLimits, Urdf, UrdfError, UrdfJoint, UrdfLink,
};
