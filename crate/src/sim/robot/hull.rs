//! A link's collision shapes as parry shapes: URDF primitives as they are, meshes as the convex
//! hull of their vertices (one hull per mesh file and scale, computed once per process).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{ConvexPolyhedron, Cuboid, SharedShape};

use super::dae::parse_dae;
use super::files::RobotFiles;
use super::mesh::{parse_obj, parse_stl, MeshError, TriangleMesh};
use super::urdf::Geometry;

/// Reads a mesh file by its extension: `.stl`, `.obj` or `.dae` (any case).
pub fn read_mesh(path: &Path) -> Result<TriangleMesh, MeshError> {
    read_mesh_in(&RobotFiles::disk(), path)
}

/// [`read_mesh`] from `files`.
fn read_mesh_in(files: &RobotFiles, path: &Path) -> Result<TriangleMesh, MeshError> {
    let file = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if !matches!(ext.as_str(), "stl" | "obj" | "dae") {
        return Err(MeshError::new(
            &file,
            None,
            format!("mesh format `.{ext}` is not supported (STL, OBJ or DAE)"),
        ));
    }
    let bytes = files
        .read(path)
        .map_err(|e| MeshError::new(&file, None, e))?;
    if ext == "stl" {
        return parse_stl(&bytes, &file);
    }
    let text = String::from_utf8(bytes)
        .map_err(|e| MeshError::new(&file, None, format!("not UTF-8 text: {e}")))?;
    if ext == "obj" {
        parse_obj(&text, &file)
    } else {
        parse_dae(&text, &file)
    }
}

/// What a collision shape is, with its size: what `robot check` lists.
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeKind {
    /// A URDF `<box>`.
    Box {
        /// Full side lengths (m).
        size: [f64; 3],
    },
    /// A URDF `<cylinder>` (along the shape frame's z).
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Length (m).
        length: f64,
    },
    /// A URDF `<sphere>`.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// The convex hull of a URDF `<mesh>`'s vertices, scaled.
    Hull {
        /// The mesh file on disk.
        file: PathBuf,
        /// The hull's vertex count.
        vertices: usize,
        /// The hull's bounding box in the shape frame (m): lowest and highest corner.
        aabb: ([f64; 3], [f64; 3]),
    },
}

/// One collision shape of a link: the parry shape posed in the link's frame.
#[derive(Clone)]
pub struct LinkShape {
    /// Pose of the parry shape in the link's frame.
    pub pose: Isometry3<f64>,
    /// The parry shape (a cuboid, cylinder, ball or convex polyhedron).
    pub shape: SharedShape,
    /// What it is and its size.
    pub kind: ShapeKind,
    /// Centre (link frame) and radius of a sphere around the shape, for quick rejection.
    pub(super) sphere: (Point3<f64>, f64),
    /// The shape's bounding box, posed in the link frame: a tighter second rejection.
    pub(super) bound: (Isometry3<f64>, Cuboid),
}

impl std::fmt::Debug for LinkShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LinkShape")
            .field("pose", &self.pose)
            .field("kind", &self.kind)
            .finish()
    }
}

impl LinkShape {
    /// The shape of URDF `geometry` at `origin` (link frame); `mesh_file` is where a mesh is.
    pub(super) fn new(
        origin: &Isometry3<f64>,
        geometry: &Geometry,
        mesh_file: Option<&Path>,
        files: &RobotFiles,
    ) -> Result<LinkShape, MeshError> {
        let (shape, kind, turn) = match geometry {
            Geometry::Box { size } => (
                SharedShape::cuboid(size[0] / 2.0, size[1] / 2.0, size[2] / 2.0),
                ShapeKind::Box { size: *size },
                None,
            ),
            Geometry::Cylinder { radius, length } => (
                SharedShape::cylinder(length / 2.0, *radius),
                ShapeKind::Cylinder {
                    radius: *radius,
                    length: *length,
                },
                // parry's cylinders run along y, URDF's along z: +90° about x takes y to z.
                Some(UnitQuaternion::from_axis_angle(
                    &Vector3::x_axis(),
                    std::f64::consts::FRAC_PI_2,
                )),
            ),
            Geometry::Sphere { radius } => (
                SharedShape::ball(*radius),
                ShapeKind::Sphere { radius: *radius },
                None,
            ),
            Geometry::Mesh { filename, scale } => {
                let path = mesh_file.unwrap_or(Path::new(filename));
                let hull = hull_in(files, path, *scale)?;
                let aabb = hull.local_aabb();
                let kind = ShapeKind::Hull {
                    file: path.to_path_buf(),
                    vertices: hull.points().len(),
                    aabb: (aabb.mins.coords.into(), aabb.maxs.coords.into()),
                };
                (SharedShape(hull), kind, None)
            }
        };
        let pose = match turn {
            Some(r) => origin * r,
            None => *origin,
        };
        let s = shape.compute_local_bounding_sphere();
        let b = shape.compute_local_aabb();
        Ok(LinkShape {
            pose,
            sphere: (pose * s.center, s.radius),
            bound: (
                pose * Translation3::from(b.center().coords),
                Cuboid::new(b.half_extents()),
            ),
            shape,
            kind,
        })
    }
}

/// Identifies a hull: the file (canonical path, size, modification time or content hash) and the
/// scale's bits, so that a changed file is read again.
type HullKey = (PathBuf, u64, u128, [u64; 3]);

/// The hulls computed so far in this process.
fn hulls() -> &'static Mutex<HashMap<HullKey, Arc<ConvexPolyhedron>>> {
    static CELL: OnceLock<Mutex<HashMap<HullKey, Arc<ConvexPolyhedron>>>> = OnceLock::new();
    CELL.get_or_init(Default::default)
}

/// The convex hull of the mesh file at `path`, its vertices scaled by `scale`: from the
/// process-wide cache, or read and computed once.
pub fn hull_of(path: &Path, scale: [f64; 3]) -> Result<Arc<ConvexPolyhedron>, MeshError> {
    hull_in(&RobotFiles::disk(), path, scale)
}

/// [`hull_of`] from `files`.
fn hull_in(
    files: &RobotFiles,
    path: &Path,
    scale: [f64; 3],
) -> Result<Arc<ConvexPolyhedron>, MeshError> {
    let file = path.display().to_string();
    let (at, len, stamp) = files
        .stamp(path)
        .map_err(|e| MeshError::new(&file, None, e))?;
    let key = (at, len, stamp, scale.map(f64::to_bits));
    if let Some(h) = hulls().lock().ok().and_then(|m| m.get(&key).cloned()) {
        return Ok(h);
    }
    let mesh = read_mesh_in(files, path)?;
    if mesh.vertices.is_empty() {
        return Err(MeshError::new(&file, None, "the mesh has no vertices"));
    }
    let points: Vec<Point3<f64>> = mesh
        .vertices
        .iter()
        .map(|p| Point3::new(p.x * scale[0], p.y * scale[1], p.z * scale[2]))
        .collect();
    let hull = (!flat(&points))
        .then(|| ConvexPolyhedron::from_convex_hull(&points))
        .flatten()
        .ok_or_else(|| {
            MeshError::new(
                &file,
                None,
                format!(
                "no convex hull of its {} vertices (scaled by {scale:?}): they lie in one plane \
                 or on one line",
                points.len()
            ),
            )
        })?;
    let hull = Arc::new(hull);
    if let Ok(mut m) = hulls().lock() {
        m.insert(key, hull.clone());
    }
    Ok(hull)
}

/// Whether `points` lie on one plane (or line, or point), relative to their extent: they bound
/// no solid.
fn flat(points: &[Point3<f64>]) -> bool {
    let p0 = points[0];
    let farthest = |d: &dyn Fn(&Point3<f64>) -> f64| {
        points
            .iter()
            .map(|p| (d(p), *p))
            .fold((0.0, p0), |a, b| if b.0 > a.0 { b } else { a })
    };
    let (extent, p1) = farthest(&|p| (p - p0).norm());
    let tol = 1e-9 * extent;
    if extent == 0.0 {
        return true;
    }
    let u = (p1 - p0) / extent;
    let off_line = |p: &Point3<f64>| {
        let v = p - p0;
        (v - u * v.dot(&u)).norm()
    };
    let (off, p2) = farthest(&off_line);
    if off <= tol {
        return true;
    }
    let n = u.cross(&(p2 - p0)).normalize();
    farthest(&|p| (p - p0).dot(&n).abs()).0 <= tol
}
