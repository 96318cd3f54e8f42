//! A chain folded for inverse kinematics: per moving joint the fixed transform before it and its
//! axis, and the fixed transform from the last one to the TCP; forward kinematics, the joint
//! frames and the geometric Jacobian on fixed-size arrays (no allocation per iteration).

use nalgebra::{Isometry3, Quaternion, SMatrix, UnitQuaternion, Vector3};

use super::chain::Chain;
use super::urdf::JointKind;

/// Most moving joints the solver handles.
pub(crate) const MAX_DOF: usize = crate::sim::panda::DOF;

/// A joint vector padded to [`MAX_DOF`] (unused entries stay 0).
pub(crate) type Joints = [f64; MAX_DOF];

/// Geometric Jacobian, linear rows first; columns past the chain's joints are 0.
pub(crate) type Jacobian = SMatrix<f64, 6, MAX_DOF>;

/// The chain with its fixed joints folded into the moving joints' frames.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Model {
    /// Number of moving joints.
    pub(crate) n: usize,
    /// Pose of moving joint `i`'s frame (at `q_i = 0`) in the frame moved by joint `i − 1`.
    pre: [Isometry3<f64>; MAX_DOF],
    /// Unit axis of moving joint `i` in its own frame.
    axis: [Vector3<f64>; MAX_DOF],
    /// Whether moving joint `i` slides rather than turns.
    pub(super) prismatic: [bool; MAX_DOF],
    /// The TCP in the frame moved by the last joint.
    tail: Isometry3<f64>,
    /// Lower limits (`-∞` for continuous joints).
    pub(super) lower: Joints,
    /// Upper limits (`∞` for continuous joints).
    pub(super) upper: Joints,
}

/// The TCP and every moving joint's axis and origin in the base's frame, for one joint vector.
#[derive(Clone, Debug)]
pub(crate) struct Frames {
    /// The TCP's pose.
    pub(crate) tcp: Isometry3<f64>,
    /// The frame each moving joint moves (its child link's), after its motion.
    #[cfg_attr(first_load, allow(dead_code))]
    pub(crate) links: [Isometry3<f64>; MAX_DOF],
    axes: [Vector3<f64>; MAX_DOF],
    origins: [Vector3<f64>; MAX_DOF],
}

impl Model {
    /// The model of `chain` with `tcp` on its tip; `Err(dof)` when the chain has no moving joint
    /// or more than [`MAX_DOF`].
    pub(crate) fn new(chain: &Chain, tcp: &Isometry3<f64>) -> Result<Model, usize> {
        let n = chain.dof();
        if n == 0 || n > MAX_DOF {
            return Err(n);
        }
        let mut m = Model {
            n,
            pre: [Isometry3::identity(); MAX_DOF],
            axis: [Vector3::z(); MAX_DOF],
            prismatic: [false; MAX_DOF],
            tail: Isometry3::identity(),
            lower: [0.0; MAX_DOF],
            upper: [0.0; MAX_DOF],
        };
        let mut acc = Isometry3::identity();
        let mut i = 0;
        for j in &chain.joints {
            acc *= j.origin;
            if j.moves() {
                m.pre[i] = acc;
                m.axis[i] = j.axis.into_inner();
                m.prismatic[i] = j.kind == JointKind::Prismatic;
                m.lower[i] = j.lower;
                m.upper[i] = j.upper;
                acc = Isometry3::identity();
                i += 1;
            }
        }
        m.tail = acc * tcp;
        Ok(m)
    }

    /// Forward kinematics with the joint frames the Jacobian needs.
    pub(crate) fn frames(&self, q: &Joints) -> Frames {
        let mut t = Isometry3::identity();
        let mut axes = [Vector3::zeros(); MAX_DOF];
        let mut origins = [Vector3::zeros(); MAX_DOF];
        let mut links = [Isometry3::identity(); MAX_DOF];
        for i in 0..self.n {
            t *= self.pre[i];
            axes[i] = t.rotation * self.axis[i];
            origins[i] = t.translation.vector;
            if self.prismatic[i] {
                t.translation.vector += axes[i] * q[i];
            } else {
                // Rot(axis, q) as a quaternion, its half-angle sine and cosine from libm.
                let (s, c) = libm::sincos(0.5 * q[i]);
                let a = self.axis[i] * s;
                let r = UnitQuaternion::new_unchecked(Quaternion::new(c, a.x, a.y, a.z));
                t.rotation *= r;
            }
            links[i] = t;
        }
        Frames {
            tcp: t * self.tail,
            links,
            axes,
            origins,
        }
    }

    /// The geometric Jacobian at `f`: column `i` maps joint `i`'s rate to the TCP's linear and
    /// angular velocity in the base's frame (`a × (p_tcp − p_i); a` turning, `a; 0` sliding).
    pub(crate) fn jacobian(&self, f: &Frames) -> Jacobian {
        let mut j = Jacobian::zeros();
        let p = f.tcp.translation.vector;
        for i in 0..self.n {
            let a = f.axes[i];
            if self.prismatic[i] {
                j.fixed_view_mut::<3, 1>(0, i).copy_from(&a);
            } else {
                j.fixed_view_mut::<3, 1>(0, i)
                    .copy_from(&a.cross(&(p - f.origins[i])));
                j.fixed_view_mut::<3, 1>(3, i).copy_from(&a);
            }
        }
        j
    }
}

/// The rotation vector (axis · angle, base frame) that turns `current` into `target`: the
/// orientation error whose rate is the Jacobian's angular rows.
pub(super) fn rotation_error(
    target: &UnitQuaternion<f64>,
    current: &UnitQuaternion<f64>,
) -> Vector3<f64> {
    let d = target * current.inverse();
    // Take the short way round: q and −q are the same rotation.
    let (w, v) = if d.w < 0.0 {
        (-d.w, -d.imag())
    } else {
        (d.w, d.imag())
    };
    let s = v.norm();
    if s < 1e-12 {
        return v * 2.0;
    }
    v * (2.0 * libm::atan2(s, w) / s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::robot::urdf::parse_urdf;
    use nalgebra::Translation3;

    /// A pure translation.
    fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
    }

    const TOY: &str = r#"<robot name="toy">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/></joint>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="0" upper="0.5" velocity="1"/></joint>
  <joint name="j3" type="continuous"><parent link="c"/><child link="d"/><axis xyz="1 0 0"/></joint>
</robot>"#;

    #[test]
    fn folded_forward_kinematics_equals_the_chains() {
        let u = parse_urdf(TOY, "toy.urdf").unwrap();
        let chain = Chain::new(&u, "base", "d").unwrap();
        let tcp = at(0.0, 0.05, 0.1);
        let m = Model::new(&chain, &tcp).unwrap();
        assert_eq!(m.n, 3);
        for q in [[0.3, 0.2, -1.0], [-2.0, 0.45, 4.0], [0.0; 3]] {
            let mut padded = [0.0; MAX_DOF];
            padded[..3].copy_from_slice(&q);
            let want = chain.tip_frame(&q) * tcp;
            let got = m.frames(&padded).tcp;
            assert!((want.translation.vector - got.translation.vector).norm() < 1e-12);
            assert!(want.rotation.angle_to(&got.rotation) < 1e-9);
        }
    }

    #[test]
    fn jacobian_columns_match_finite_differences() {
        let u = parse_urdf(TOY, "toy.urdf").unwrap();
        let chain = Chain::new(&u, "base", "d").unwrap();
        let m = Model::new(&chain, &at(0.0, 0.05, 0.1)).unwrap();
        let q = [0.4, 0.1, 0.7, 0.0, 0.0, 0.0, 0.0];
        let f = m.frames(&q);
        let j = m.jacobian(&f);
        let h = 1e-6;
        for i in 0..3 {
            let mut qp = q;
            qp[i] += h;
            let fp = m.frames(&qp).tcp;
            let dp = (fp.translation.vector - f.tcp.translation.vector) / h;
            let dr = rotation_error(&fp.rotation, &f.tcp.rotation) / h;
            for r in 0..3 {
                assert!((j[(r, i)] - dp[r]).abs() < 1e-5, "column {i} row {r}");
                assert!(
                    (j[(r + 3, i)] - dr[r]).abs() < 1e-5,
                    "column {i} row {}",
                    r + 3
                );
            }
        }
        assert!(j.column(3).norm() == 0.0, "unused columns stay zero");
    }

    #[test]
    fn a_half_turn_error_is_pi_about_its_axis() {
        let t = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI);
        let e = rotation_error(&t, &UnitQuaternion::identity());
        assert!((e.norm() - std::f64::consts::PI).abs() < 1e-12);
        assert!(e.x.abs() < 1e-12 && e.z.abs() < 1e-12);
    }
}
