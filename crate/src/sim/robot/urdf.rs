//! URDF robot descriptions: links with their collision shapes, joints with their origins, axes and
//! limits, read from the XML every robotics tool writes, with each error at its line and column.
//!
//! Supported: joints `revolute`, `continuous`, `prismatic` and `fixed`; collision geometry `box`,
//! `cylinder`, `sphere` and `mesh` (its file resolved by the caller). `floating` and `planar`
//! joints are refused by name. Visual elements, inertia and transmissions are read past.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// A parsed URDF: the robot's links and joints in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct Urdf {
    /// The `<robot name>`.
    pub name: String,
    /// Every `<link>`.
    pub links: Vec<UrdfLink>,
    /// Every `<joint>`.
    pub joints: Vec<UrdfJoint>,
}

/// One `<link>` and its collision shapes.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfLink {
    /// The link's name.
    pub name: String,
    /// Its `<collision>` elements, each posed in the link's frame.
    pub collisions: Vec<Collision>,
    /// 1-based line of the element, for messages.
    pub line: u32,
}

/// One `<collision>` element: a shape and its pose in the link's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// Pose of the shape's frame in the link's frame (`<origin>`).
    pub origin: Isometry3<f64>,
    /// The shape.
    pub geometry: Geometry,
    /// 1-based line of the element.
    pub line: u32,
}

/// A collision shape, in metres.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A box centred on its frame, with full side lengths.
    Box {
        /// Side lengths along x, y, z.
        size: [f64; 3],
    },
    /// A cylinder along its frame's z axis, centred on it.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Length along z.
        length: f64,
    },
    /// A sphere centred on its frame.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// A mesh file (`package://…`, `file://…` or a path relative to the URDF), scaled.
    Mesh {
        /// The `filename` attribute as written.
        filename: String,
        /// Scale along x, y, z (default 1).
        scale: [f64; 3],
    },
}

/// How a joint moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the axis, within limits.
    Revolute,
    /// Rotation about the axis, without limits.
    Continuous,
    /// Translation along the axis, within limits.
    Prismatic,
    /// No motion.
    Fixed,
}

impl JointKind {
    /// The URDF `type` attribute.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
        }
    }
}

/// A joint's `<limit>` (radians or metres, and per second).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower position limit.
    pub lower: f64,
    /// Upper position limit.
    pub upper: f64,
    /// Velocity limit.
    pub velocity: f64,
}

/// One `<joint>`.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfJoint {
    /// The joint's name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// The parent link.
    pub parent: String,
    /// The child link.
    pub child: String,
    /// Pose of the child's frame in the parent's at position 0 (`<origin>`).
    pub origin: Isometry3<f64>,
    /// The unit axis in the joint's frame (`<axis>`, default x).
    pub axis: Unit<Vector3<f64>>,
    /// Position and velocity limits (required for revolute and prismatic joints).
    pub limits: Option<JointLimits>,
    /// 1-based line of the element.
    pub line: u32,
}

/// A URDF that cannot be read: where and what.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{col}: {message}")]
pub struct UrdfError {
    /// The file as given by the caller.
    pub file: String,
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub col: u32,
    /// What is wrong.
    pub message: String,
}

/// Parses a URDF text; `file` names it in errors.
pub fn parse_urdf(text: &str, file: &str) -> Result<Urdf, UrdfError> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        UrdfError {
            file: file.into(),
            line: p.row,
            col: p.col,
            message: e.to_string(),
        }
    })?;
    let r = Reader { doc: &doc, file };
    let root = doc.root_element();
    if !root.has_tag_name("robot") {
        return Err(r.err(
            root,
            format!("expected <robot>, found <{}>", root.tag_name().name()),
        ));
    }
    let mut urdf = Urdf {
        name: root.attribute("name").unwrap_or("").to_string(),
        links: Vec::new(),
        joints: Vec::new(),
    };
    for node in root.children().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "link" => urdf.links.push(r.link(node)?),
            "joint" => urdf.joints.push(r.joint(node)?),
            _ => {}
        }
    }
    r.check_names(&urdf, root)?;
    Ok(urdf)
}

/// Reads elements of one document, locating errors in it.
struct Reader<'a, 'input> {
    doc: &'a roxmltree::Document<'input>,
    file: &'a str,
}

type Node<'a, 'input> = roxmltree::Node<'a, 'input>;

impl<'a, 'input> Reader<'a, 'input> {
    fn line(&self, node: Node) -> u32 {
        self.doc.text_pos_at(node.range().start).row
    }

    fn err(&self, node: Node, message: String) -> UrdfError {
        let p = self.doc.text_pos_at(node.range().start);
        UrdfError {
            file: self.file.into(),
            line: p.row,
            col: p.col,
            message,
        }
    }

    fn attr<'n>(&self, node: Node<'n, 'input>, name: &str) -> Result<&'n str, UrdfError> {
        node.attribute(name).ok_or_else(|| {
            self.err(
                node,
                format!("<{}> needs the attribute `{name}`", node.tag_name().name()),
            )
        })
    }

    fn number(&self, node: Node, name: &str, text: &str) -> Result<f64, UrdfError> {
        match text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.err(
                node,
                format!("`{name}` is `{text}`, expected a finite number"),
            )),
        }
    }

    fn numbers<const N: usize>(
        &self,
        node: Node,
        name: &str,
        text: &str,
    ) -> Result<[f64; N], UrdfError> {
        let parts: Vec<&str> = text.split_whitespace().collect();
        if parts.len() != N {
            return Err(self.err(node, format!("`{name}` is `{text}`, expected {N} numbers")));
        }
        let mut out = [0.0; N];
        for (o, p) in out.iter_mut().zip(parts) {
            *o = self.number(node, name, p)?;
        }
        Ok(out)
    }

    fn child<'n>(&self, node: Node<'n, 'input>, tag: &str) -> Option<Node<'n, 'input>> {
        node.children().find(|c| c.has_tag_name(tag))
    }

    /// An `<origin xyz rpy>` (identity when absent); rpy are fixed-axis roll, pitch, yaw.
    fn origin(&self, parent: Node) -> Result<Isometry3<f64>, UrdfError> {
        let Some(o) = self.child(parent, "origin") else {
            return Ok(Isometry3::identity());
        };
        let xyz = match o.attribute("xyz") {
            Some(t) => self.numbers::<3>(o, "xyz", t)?,
            None => [0.0; 3],
        };
        let rpy = match o.attribute("rpy") {
            Some(t) => self.numbers::<3>(o, "rpy", t)?,
            None => [0.0; 3],
        };
        Ok(Isometry3::from_parts(
            Translation3::new(xyz[0], xyz[1], xyz[2]),
            UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
        ))
    }

    fn positive(&self, node: Node, name: &str) -> Result<f64, UrdfError> {
        let v = self.number(node, name, self.attr(node, name)?)?;
        if v <= 0.0 {
            return Err(self.err(node, format!("`{name}` is {v}, expected a positive length")));
        }
        Ok(v)
    }

    fn geometry(&self, collision: Node) -> Result<Geometry, UrdfError> {
        let g = self
            .child(collision, "geometry")
            .ok_or_else(|| self.err(collision, "<collision> needs a <geometry>".into()))?;
        let Some(shape) = g.children().find(|c| c.is_element()) else {
            return Err(self.err(g, "<geometry> needs a box, cylinder, sphere or mesh".into()));
        };
        Ok(match shape.tag_name().name() {
            "box" => {
                let size = self.numbers::<3>(shape, "size", self.attr(shape, "size")?)?;
                if size.iter().any(|s| *s <= 0.0) {
                    return Err(self.err(shape, "a box's sizes must be positive".into()));
                }
                Geometry::Box { size }
            }
            "cylinder" => Geometry::Cylinder {
                radius: self.positive(shape, "radius")?,
                length: self.positive(shape, "length")?,
            },
            "sphere" => Geometry::Sphere {
                radius: self.positive(shape, "radius")?,
            },
            "mesh" => Geometry::Mesh {
                filename: self.attr(shape, "filename")?.to_string(),
                scale: match shape.attribute("scale") {
                    Some(t) => self.numbers::<3>(shape, "scale", t)?,
                    None => [1.0; 3],
                },
            },
            other => {
                return Err(self.err(
                    shape,
                    format!("geometry <{other}>: expected box, cylinder, sphere or mesh"),
                ))
            }
        })
    }

    fn link(&self, node: Node) -> Result<UrdfLink, UrdfError> {
        let mut collisions = Vec::new();
        for c in node.children().filter(|c| c.has_tag_name("collision")) {
            collisions.push(Collision {
                origin: self.origin(c)?,
                geometry: self.geometry(c)?,
                line: self.line(c),
            });
        }
        Ok(UrdfLink {
            name: self.attr(node, "name")?.to_string(),
            collisions,
            line: self.line(node),
        })
    }

    fn joint(&self, node: Node) -> Result<UrdfJoint, UrdfError> {
        let name = self.attr(node, "name")?.to_string();
        let kind = match self.attr(node, "type")? {
            "revolute" => JointKind::Revolute,
            "continuous" => JointKind::Continuous,
            "prismatic" => JointKind::Prismatic,
            "fixed" => JointKind::Fixed,
            other => {
                return Err(self.err(
                    node,
                    format!(
                        "joint `{name}`: type `{other}` is not supported (revolute, continuous, \
                         prismatic or fixed)"
                    ),
                ))
            }
        };
        let link_of = |tag: &str| -> Result<String, UrdfError> {
            let n = self
                .child(node, tag)
                .ok_or_else(|| self.err(node, format!("joint `{name}` needs a <{tag} link=…>")))?;
            Ok(self.attr(n, "link")?.to_string())
        };
        let axis = match self.child(node, "axis") {
            Some(a) => {
                let v = self.numbers::<3>(a, "xyz", self.attr(a, "xyz")?)?;
                let v = Vector3::new(v[0], v[1], v[2]);
                Unit::try_new(v, 1e-9).ok_or_else(|| {
                    self.err(a, format!("joint `{name}`: the axis is the zero vector"))
                })?
            }
            None => Vector3::x_axis(),
        };
        let limits = match self.child(node, "limit") {
            Some(l) => {
                let get = |attr: &str, default: f64| -> Result<f64, UrdfError> {
                    l.attribute(attr)
                        .map_or(Ok(default), |t| self.number(l, attr, t))
                };
                let lim = JointLimits {
                    lower: get("lower", 0.0)?,
                    upper: get("upper", 0.0)?,
                    velocity: get("velocity", f64::INFINITY)?,
                };
                if lim.lower > lim.upper {
                    return Err(self.err(
                        l,
                        format!(
                            "joint `{name}`: lower limit {} above upper {}",
                            lim.lower, lim.upper
                        ),
                    ));
                }
                Some(lim)
            }
            None if matches!(kind, JointKind::Revolute | JointKind::Prismatic) => {
                return Err(self.err(
                    node,
                    format!("joint `{name}`: a {} joint needs a <limit>", kind.as_str()),
                ))
            }
            None => None,
        };
        Ok(UrdfJoint {
            kind,
            parent: link_of("parent")?,
            child: link_of("child")?,
            origin: self.origin(node)?,
            axis,
            limits,
            line: self.line(node),
            name,
        })
    }

    /// Unique link and joint names; every joint names links that exist.
    fn check_names(&self, urdf: &Urdf, root: Node) -> Result<(), UrdfError> {
        let at = |line: u32, message: String| UrdfError {
            file: self.file.into(),
            line,
            col: 1,
            message,
        };
        let mut seen = std::collections::BTreeSet::new();
        for l in &urdf.links {
            if !seen.insert(l.name.as_str()) {
                return Err(at(l.line, format!("a second link named `{}`", l.name)));
            }
        }
        for j in &urdf.joints {
            for link in [&j.parent, &j.child] {
                if !seen.contains(link.as_str()) {
                    return Err(at(
                        j.line,
                        format!(
                            "joint `{}` names the link `{link}`, which the file does not define",
                            j.name
                        ),
                    ));
                }
            }
        }
        let mut joints = std::collections::BTreeSet::new();
        for j in &urdf.joints {
            if !joints.insert(j.name.as_str()) {
                return Err(at(j.line, format!("a second joint named `{}`", j.name)));
            }
        }
        if urdf.links.is_empty() {
            return Err(self.err(root, "the robot has no <link>".into()));
        }
        Ok(())
    }
}
