//! The built-in Franka-Panda arm: forward kinematics and geometric Jacobian from its DH parameters.
//!
//! **Forward kinematics** uses the published modified (Craig) Denavit–Hartenberg parameters of the
//! Panda, one homogeneous transform per joint
//!
//! ```text
//! ⁱ⁻¹Tᵢ = Rot_x(αᵢ₋₁) · Trans_x(aᵢ₋₁) · Rot_z(qᵢ) · Trans_z(dᵢ)
//! ⁰T_tcp = ⁰T₁ ⋯ ⁶T₇ · T_flange(d = 0.107) · Rot_z(−π/4) · Trans_z(0.1034)
//! ```
//!
//! with the tool centre point (TCP) between the fingertips, its `z` axis pointing out of the hand
//! and its `y` axis joining the fingers.
//!
//! **Jacobian** (geometric, world frame) from the FK frames: for revolute joint i with axis zᵢ
//! through oᵢ, `Jᵢ = [zᵢ × (p_tcp − oᵢ); zᵢ]`.
//!
//!
//! The damped-least-squares IK on this and on URDF arms is [`ArmModel`](super::kinematics::ArmModel)'s.

use nalgebra::{Isometry3, Matrix3, Point3, SMatrix, Translation3, UnitQuaternion, Vector3};
use std::sync::OnceLock;

use super::fast_math::{quaternion_of, sincos_table};

/// Number of joints, and the width of every arm's joint vector (see `ArmModel`).
pub const DOF: usize = 7;

/// Modified DH `(a_{i-1}, d_i, alpha_{i-1})` of joints 1..7 (Franka documentation), metres / radians.
const DH: [(f64, f64, f64); DOF] = [
    (0.0, 0.333, 0.0),
    (0.0, 0.0, -std::f64::consts::FRAC_PI_2),
    (0.0, 0.316, std::f64::consts::FRAC_PI_2),
    (0.0825, 0.0, std::f64::consts::FRAC_PI_2),
    (-0.0825, 0.384, -std::f64::consts::FRAC_PI_2),
    (0.0, 0.0, std::f64::consts::FRAC_PI_2),
    (0.088, 0.0, std::f64::consts::FRAC_PI_2),
];
/// Distance from joint 7's frame to the flange (m).
const FLANGE_D: f64 = 0.107;
/// Distance from the flange to the tool centre point between the fingertips (m).
pub const TCP_OFFSET: f64 = 0.1034;

/// Lower joint limits (rad), Franka documentation.
pub const JOINT_LOWER: [f64; DOF] = [
    -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973,
];
/// Upper joint limits (rad), Franka documentation.
pub const JOINT_UPPER: [f64; DOF] = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973];
/// Joint velocity limits (rad/s), Franka documentation.
pub const JOINT_VELOCITY: [f64; DOF] = [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61];
/// The "ready" configuration: gripper pointing down in front of the base.
pub const READY: [f64; DOF] = [
    0.0,
    -std::f64::consts::FRAC_PI_4,
    0.0,
    -3.0 * std::f64::consts::FRAC_PI_4,
    0.0,
    std::f64::consts::FRAC_PI_2,
    std::f64::consts::FRAC_PI_4,
];
/// Largest finger opening (m).
pub const GRIPPER_MAX_OPENING: f64 = 0.08;

/// A rigid frame as rotation matrix + translation (cheaper to chain than quaternions).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub r: Matrix3<f64>,
    pub p: Vector3<f64>,
}

impl Frame {
    fn identity() -> Self {
        Frame {
            r: Matrix3::identity(),
            p: Vector3::zeros(),
        }
    }
    pub(crate) fn from_iso(iso: &Isometry3<f64>) -> Self {
        Frame {
            r: *iso.rotation.to_rotation_matrix().matrix(),
            p: iso.translation.vector,
        }
    }
    fn mul(&self, o: &Frame) -> Frame {
        Frame {
            r: self.r * o.r,
            p: self.r * o.p + self.p,
        }
    }
    pub(crate) fn to_iso(self) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::from(self.p), quaternion_of(&self.r))
    }
}

/// Modified DH transform `Rot_x(α) Trans_x(a) Rot_z(θ) Trans_z(d)` from `(sin α, cos α)` and
/// `(sin θ, cos θ)`.
fn dh((a, d): (f64, f64), (sa, ca): (f64, f64), (st, ct): (f64, f64)) -> Frame {
    Frame {
        r: Matrix3::new(ct, -st, 0.0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca),
        p: Vector3::new(a, -sa * d, ca * d),
    }
}

/// `libm::sincos` of the constant angles of the chain: the twists α of joints 1..7, then 0 (the
/// flange and TCP offsets) and −π/4 (the hand).
fn chain_trig() -> &'static [(f64, f64); DOF + 2] {
    static CELL: OnceLock<[(f64, f64); DOF + 2]> = OnceLock::new();
    let mut angles = [0.0; DOF + 2];
    for i in 0..DOF {
        angles[i] = DH[i].2;
    }
    angles[DOF + 1] = -std::f64::consts::FRAC_PI_4;
    sincos_table(&CELL, &angles)
}

/// All frames of one arm configuration, world coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ArmFrames {
    /// Base, joint frames 1..7, flange (index 8), hand (index 9: rotated −π/4, at the flange).
    pub frames: [Frame; 10],
    /// Tool centre point.
    pub tcp: Frame,
}

/// Forward kinematics of every frame.
pub(crate) fn forward_frames(base: &Isometry3<f64>, q: &[f64; DOF]) -> ArmFrames {
    let trig = chain_trig();
    let zero = trig[DOF];
    let mut frames = [Frame::identity(); 10];
    frames[0] = Frame::from_iso(base);
    for i in 0..DOF {
        let (a, d, _) = DH[i];
        frames[i + 1] = frames[i].mul(&dh((a, d), trig[i], libm::sincos(q[i])));
    }
    frames[8] = frames[7].mul(&dh((0.0, FLANGE_D), zero, zero));
    frames[9] = frames[8].mul(&dh((0.0, 0.0), zero, trig[DOF + 1]));
    let tcp = frames[9].mul(&dh((0.0, TCP_OFFSET), zero, zero));
    ArmFrames { frames, tcp }
}

/// Forward kinematics: the TCP pose in the world for joint angles `q` of an arm based at `base`.
pub fn forward_kinematics(base: &Isometry3<f64>, q: &[f64; DOF]) -> Isometry3<f64> {
    forward_frames(base, q).tcp.to_iso()
}

/// The geometric Jacobian (6×7, rows = linear then angular velocity, world frame) at `f`.
pub(crate) fn jacobian(f: &ArmFrames) -> SMatrix<f64, 6, DOF> {
    let mut j = SMatrix::<f64, 6, DOF>::zeros();
    for i in 0..DOF {
        let fr = &f.frames[i + 1];
        let z = fr.r.column(2).into_owned();
        let lin = z.cross(&(f.tcp.p - fr.p));
        j.fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
        j.fixed_view_mut::<3, 1>(3, i).copy_from(&z);
    }
    j
}

/// The built-in Panda's link capsules (base to hand) from its frames, world frame.
pub(crate) fn panda_links(f: &ArmFrames) -> Vec<(Vector3<f64>, Vector3<f64>, f64)> {
    let o = |i: usize| f.frames[i].p;
    let hand = &f.frames[9];
    let hp = |y: f64, z: f64| hand.p + hand.r * Vector3::new(0.0, y, z);
    vec![
        (o(0), o(1), 0.075),
        (o(2), o(3), 0.065),
        (o(3), o(4), 0.06),
        (o(4), o(5), 0.06),
        (o(5), o(7), 0.055),
        (o(7), o(8), 0.05),
        (
            hp(-HAND_HALF_SPAN, HAND_HEIGHT),
            hp(HAND_HALF_SPAN, HAND_HEIGHT),
            HAND_RADIUS,
        ),
    ]
}

/// The hand's capsule: half its span along the finger axis, its axis height above the hand
/// frame, its radius (m).
pub(crate) const HAND_HALF_SPAN: f64 = 0.08;
const HAND_HEIGHT: f64 = 0.05;
pub(crate) const HAND_RADIUS: f64 = 0.035;

/// The hand's capsule `(a, b, radius)` (world frame) when the TCP is at `tcp`: the last of an
/// arm's link capsules, without the rest of the arm. Every arm's gripper is checked as the
/// Panda's hand.
pub fn hand_capsule(tcp: &Isometry3<f64>) -> (Vector3<f64>, Vector3<f64>, f64) {
    let p = |y: f64| (tcp * Point3::new(0.0, y, HAND_HEIGHT - TCP_OFFSET)).coords;
    (p(-HAND_HALF_SPAN), p(HAND_HALF_SPAN), HAND_RADIUS)
}

/// A gripper orientation pointing straight down (`z` to −z world) with the fingers joined along the
/// world direction at angle `yaw` from +y.
pub fn down_orientation(yaw: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ready_pose_points_down_in_front() {
        let tcp = forward_kinematics(&Isometry3::identity(), &READY);
        let p = tcp.translation.vector;
        assert!((p.x - 0.307).abs() < 0.002, "{p}");
        assert!(p.y.abs() < 1e-9);
        assert!((p.z - (0.5903 - TCP_OFFSET)).abs() < 0.003, "{p}");
        let z = tcp.rotation * Vector3::z();
        assert!((z + Vector3::z()).norm() < 1e-9, "{z}");
    }
}
