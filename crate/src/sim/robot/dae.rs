//! Triangle meshes from COLLADA (`.dae`) files, the other format URDFs name.
//!
//! Read: every `<geometry><mesh>` that a node of the scene's `<visual_scene>` instances
//! (`<instance_geometry>`, also through `<instance_node>`), its positions from
//! `<vertices><input semantic="POSITION">` → `<source><float_array>` with its `<accessor>`, its
//! faces from `<triangles>`, `<polylist>`, `<polygons>`, `<trifans>` and `<tristrips>` (`<p>`
//! indices read with the primitive's input offsets), each placed by the node transforms above it
//! (`<matrix>`, `<translate>`, `<rotate>`, `<scale>`, in document order). Then `<unit meter>`
//! scales the whole and `<up_axis>` (`Y_UP` by default, as the COLLADA specification says)
//! turns it so that z is up, as URDF tools expect. A file without a visual scene gives every
//! geometry once, untransformed. Lines, materials, normals and texture coordinates are read past.

use std::collections::hash_map::Entry;
use std::collections::HashMap;

use nalgebra::{Matrix4, Point3, Rotation3, Unit, Vector3};
use roxmltree::{Document, Node};

use super::mesh::{MeshError, TriangleMesh};

/// Deepest node nesting followed (`<instance_node>` may loop).
const MAX_DEPTH: usize = 64;

/// One geometry's positions and triangles, in its own frame.
type Part = (Vec<Point3<f64>>, Vec<[usize; 3]>);

/// Reads a COLLADA text; `file` names it in errors (with the XML line where one applies).
pub fn parse_dae(text: &str, file: &str) -> Result<TriangleMesh, MeshError> {
    let doc = Document::parse(text)
        .map_err(|e| MeshError::new(file, Some(e.pos().row), format!("XML: {e}")))?;
    let ids = doc
        .descendants()
        .filter_map(|n| n.attribute("id").map(|id| (id, n)))
        .collect();
    let r = Reader {
        doc: &doc,
        file,
        ids,
    };
    let root = doc.root_element();
    if !root.has_tag_name("COLLADA") {
        return Err(r.err(
            root,
            format!("expected <COLLADA>, found <{}>", root.tag_name().name()),
        ));
    }
    let global = r.asset(root)?;
    let mut out = TriangleMesh::default();
    let mut parts = HashMap::new();
    let chosen = match child(root, "scene").and_then(|s| child(s, "instance_visual_scene")) {
        Some(inst) => Some(r.target(inst)?),
        None => root.descendants().find(|n| n.has_tag_name("visual_scene")),
    };
    match chosen {
        Some(scene) => {
            for n in scene.children().filter(|c| c.has_tag_name("node")) {
                r.node(n, &global, &mut parts, &mut out, 0)?;
            }
        }
        None => {
            for g in root.descendants().filter(|n| n.has_tag_name("geometry")) {
                let part = r.geometry(g)?;
                append(&mut out, &part, &global);
            }
        }
    }
    Ok(out)
}

fn child<'a, 'i>(n: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.has_tag_name(tag))
}

/// Appends `part` placed by `t`.
fn append(out: &mut TriangleMesh, part: &Part, t: &Matrix4<f64>) {
    let base = out.vertices.len();
    out.vertices
        .extend(part.0.iter().map(|p| t.transform_point(p)));
    out.triangles
        .extend(part.1.iter().map(|t| t.map(|i| i + base)));
}

/// Reads the elements of one document, locating errors in it.
struct Reader<'a, 'i> {
    doc: &'a Document<'i>,
    file: &'a str,
    ids: HashMap<&'a str, Node<'a, 'i>>,
}

impl<'a, 'i> Reader<'a, 'i> {
    fn err(&self, node: Node, message: String) -> MeshError {
        let line = self.doc.text_pos_at(node.range().start).row;
        MeshError::new(self.file, Some(line), message)
    }

    /// The element a `url="#id"` (or `source="#id"`) attribute of `node` points at.
    fn target(&self, node: Node<'a, 'i>) -> Result<Node<'a, 'i>, MeshError> {
        let attr = if node.has_attribute("url") {
            "url"
        } else {
            "source"
        };
        let url = node.attribute(attr).unwrap_or("");
        url.strip_prefix('#')
            .and_then(|id| self.ids.get(id).copied())
            .ok_or_else(|| {
                self.err(
                    node,
                    format!(
                        "<{}> {attr}=\"{url}\" names no element of the file",
                        node.tag_name().name()
                    ),
                )
            })
    }

    /// The numbers of an element's text.
    fn numbers<T: std::str::FromStr>(&self, node: Node) -> Result<Vec<T>, MeshError> {
        let text = node.text().unwrap_or("");
        text.split_whitespace()
            .map(|t| {
                t.parse::<T>().map_err(|_| {
                    self.err(
                        node,
                        format!("<{}>: `{t}` is not a number", node.tag_name().name()),
                    )
                })
            })
            .collect()
    }

    /// Exactly `n` finite numbers.
    fn fixed(&self, node: Node, n: usize) -> Result<Vec<f64>, MeshError> {
        let v: Vec<f64> = self.numbers(node)?;
        if v.len() != n || v.iter().any(|x| !x.is_finite()) {
            return Err(self.err(
                node,
                format!(
                    "<{}> needs {n} finite numbers, found {}",
                    node.tag_name().name(),
                    v.len()
                ),
            ));
        }
        Ok(v)
    }

    /// `<asset>`: the unit and the up axis, as one transform into z-up metres.
    fn asset(&self, root: Node) -> Result<Matrix4<f64>, MeshError> {
        let asset = child(root, "asset");
        let mut meter = 1.0;
        if let Some(u) = asset.and_then(|a| child(a, "unit")) {
            if let Some(m) = u.attribute("meter") {
                meter = match m.trim().parse::<f64>() {
                    Ok(v) if v > 0.0 && v.is_finite() => v,
                    _ => {
                        return Err(self.err(
                            u,
                            format!("<unit meter=\"{m}\">: expected a positive number"),
                        ))
                    }
                };
            }
        }
        let up = asset.and_then(|a| child(a, "up_axis"));
        let up_text = up.and_then(|u| u.text()).map_or("Y_UP", str::trim);
        let turn = match up_text {
            "Z_UP" => Matrix4::identity(),
            // +90° about x: y up becomes z up.
            "Y_UP" => Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
                .to_homogeneous(),
            // −90° about y: x up becomes z up.
            "X_UP" => Rotation3::from_axis_angle(&Vector3::y_axis(), -std::f64::consts::FRAC_PI_2)
                .to_homogeneous(),
            other => {
                return Err(self.err(
                    up.unwrap_or(root),
                    format!("<up_axis> is `{other}`, expected X_UP, Y_UP or Z_UP"),
                ))
            }
        };
        Ok(turn * Matrix4::new_scaling(meter))
    }

    /// A `<node>`: its transforms, then its geometry instances and child nodes.
    fn node(
        &self,
        n: Node<'a, 'i>,
        parent: &Matrix4<f64>,
        parts: &mut HashMap<usize, Part>,
        out: &mut TriangleMesh,
        depth: usize,
    ) -> Result<(), MeshError> {
        if depth > MAX_DEPTH {
            return Err(self.err(
                n,
                format!("nodes nested deeper than {MAX_DEPTH} (an <instance_node> loop?)"),
            ));
        }
        let mut t = *parent;
        for c in n.children().filter(|c| c.is_element()) {
            t *= match c.tag_name().name() {
                "matrix" => Matrix4::from_row_slice(&self.fixed(c, 16)?),
                "translate" => {
                    let v = self.fixed(c, 3)?;
                    Matrix4::new_translation(&Vector3::new(v[0], v[1], v[2]))
                }
                "rotate" => {
                    let v = self.fixed(c, 4)?;
                    match Unit::try_new(Vector3::new(v[0], v[1], v[2]), 1e-12) {
                        Some(axis) => {
                            Rotation3::from_axis_angle(&axis, v[3].to_radians()).to_homogeneous()
                        }
                        None if v[3] == 0.0 => Matrix4::identity(),
                        None => {
                            return Err(self.err(c, "<rotate> about the zero axis".into()));
                        }
                    }
                }
                "scale" => {
                    let v = self.fixed(c, 3)?;
                    Matrix4::new_nonuniform_scaling(&Vector3::new(v[0], v[1], v[2]))
                }
                tag @ ("lookat" | "skew") => {
                    return Err(self.err(c, format!("node transform <{tag}> is not supported")));
                }
                _ => Matrix4::identity(),
            };
        }
        for c in n.children().filter(|c| c.is_element()) {
            match c.tag_name().name() {
                "instance_geometry" => {
                    let g = self.target(c)?;
                    let part = match parts.entry(g.id().get_usize()) {
                        Entry::Occupied(e) => e.into_mut(),
                        Entry::Vacant(e) => e.insert(self.geometry(g)?),
                    };
                    append(out, part, &t);
                }
                "node" => self.node(c, &t, parts, out, depth + 1)?,
                "instance_node" => {
                    let target = self.target(c)?;
                    self.node(target, &t, parts, out, depth + 1)?;
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// A `<geometry>`'s positions and triangles (none for a geometry without `<mesh>`).
    fn geometry(&self, g: Node<'a, 'i>) -> Result<Part, MeshError> {
        if !g.has_tag_name("geometry") {
            return Err(self.err(
                g,
                format!(
                    "<instance_geometry> points at a <{}>, not a <geometry>",
                    g.tag_name().name()
                ),
            ));
        }
        let Some(m) = child(g, "mesh") else {
            return Ok((vec![], vec![]));
        };
        let verts =
            child(m, "vertices").ok_or_else(|| self.err(m, "<mesh> has no <vertices>".into()))?;
        let input = verts
            .children()
            .find(|c| c.has_tag_name("input") && c.attribute("semantic") == Some("POSITION"))
            .ok_or_else(|| {
                self.err(
                    verts,
                    "<vertices> has no <input semantic=\"POSITION\">".into(),
                )
            })?;
        let positions = self.positions(self.target(input)?)?;
        let mut tris = Vec::new();
        for prim in m.children().filter(|c| c.is_element()) {
            let name = prim.tag_name().name();
            if matches!(
                name,
                "triangles" | "polylist" | "polygons" | "trifans" | "tristrips"
            ) {
                self.primitive(prim, positions.len(), &mut tris)?;
            }
        }
        Ok((positions, tris))
    }

    /// A `<source>`'s points: the first three values of each `<accessor>` stride.
    fn positions(&self, src: Node) -> Result<Vec<Point3<f64>>, MeshError> {
        let arr = child(src, "float_array")
            .ok_or_else(|| self.err(src, "the position <source> has no <float_array>".into()))?;
        let values: Vec<f64> = self.numbers(arr)?;
        let acc = child(src, "technique_common").and_then(|t| child(t, "accessor"));
        let attr = |name: &str, default: usize| -> Result<usize, MeshError> {
            match acc.and_then(|a| a.attribute(name)) {
                None => Ok(default),
                Some(t) => t.trim().parse().map_err(|_| {
                    self.err(
                        acc.unwrap_or(src),
                        format!("<accessor {name}=\"{t}\">: expected a count"),
                    )
                }),
            }
        };
        let stride = attr("stride", 3)?;
        let offset = attr("offset", 0)?;
        let count = attr("count", values.len() / stride.max(1))?;
        if stride < 3 {
            return Err(self.err(
                acc.unwrap_or(src),
                format!("positions need 3 values each; the accessor's stride is {stride}"),
            ));
        }
        if count > 0 && offset + (count - 1) * stride + 3 > values.len() {
            return Err(self.err(
                arr,
                format!(
                    "{} values; the accessor reads {count} points of stride {stride} from \
                     offset {offset}",
                    values.len()
                ),
            ));
        }
        if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
            return Err(self.err(arr, format!("<float_array> holds {bad}")));
        }
        Ok((0..count)
            .map(|i| {
                let k = offset + i * stride;
                Point3::new(values[k], values[k + 1], values[k + 2])
            })
            .collect())
    }

    /// Appends the triangles of one primitive element, checking its indices.
    fn primitive(
        &self,
        prim: Node,
        n_positions: usize,
        tris: &mut Vec<[usize; 3]>,
    ) -> Result<(), MeshError> {
        let name = prim.tag_name().name();
        let mut stride = 1;
        let mut vertex_offset = None;
        for input in prim.children().filter(|c| c.has_tag_name("input")) {
            let off: usize = match input.attribute("offset").map(|t| t.trim().parse()) {
                Some(Ok(o)) => o,
                _ => {
                    return Err(
                        self.err(input, format!("<{name}>'s <input> needs an `offset` index"))
                    )
                }
            };
            stride = stride.max(off + 1);
            if input.attribute("semantic") == Some("VERTEX") {
                vertex_offset = Some(off);
            }
        }
        let Some(voff) = vertex_offset else {
            return Err(self.err(prim, format!("<{name}> has no <input semantic=\"VERTEX\">")));
        };
        // Each polygon, fan or strip as the list of its corners' position indices.
        let corners = |p: Node| -> Result<Vec<usize>, MeshError> {
            let idx: Vec<usize> = self.numbers(p)?;
            if idx.len() % stride != 0 {
                return Err(self.err(
                    p,
                    format!(
                        "{} indices, not a multiple of the {stride} inputs per corner",
                        idx.len()
                    ),
                ));
            }
            let c: Vec<usize> = idx.chunks(stride).map(|ch| ch[voff]).collect();
            if let Some(bad) = c.iter().find(|&&i| i >= n_positions) {
                return Err(self.err(
                    p,
                    format!("vertex index {bad}, but the positions have {n_positions} points"),
                ));
            }
            Ok(c)
        };
        let ps = || prim.children().filter(|c| c.has_tag_name("p"));
        let fan = |c: &[usize], tris: &mut Vec<[usize; 3]>| {
            for k in 1..c.len().saturating_sub(1) {
                tris.push([c[0], c[k], c[k + 1]]);
            }
        };
        match name {
            "triangles" => {
                for p in ps() {
                    let c = corners(p)?;
                    if c.len() % 3 != 0 {
                        return Err(
                            self.err(p, format!("{} corners, not whole triangles", c.len()))
                        );
                    }
                    tris.extend(c.chunks(3).map(|t| [t[0], t[1], t[2]]));
                }
            }
            "polylist" => {
                let vc = child(prim, "vcount")
                    .ok_or_else(|| self.err(prim, "<polylist> has no <vcount>".into()))?;
                let counts: Vec<usize> = self.numbers(vc)?;
                let p = child(prim, "p")
                    .ok_or_else(|| self.err(prim, "<polylist> has no <p>".into()))?;
                let c = corners(p)?;
                if counts.iter().sum::<usize>() != c.len() {
                    return Err(self.err(
                        p,
                        format!(
                            "{} corners, but <vcount> adds up to {}",
                            c.len(),
                            counts.iter().sum::<usize>()
                        ),
                    ));
                }
                let mut at = 0;
                for n in counts {
                    fan(&c[at..at + n], tris);
                    at += n;
                }
            }
            "polygons" => {
                // `<ph>` (a polygon with holes): its outer `<p>`, holes ignored (a hull fills them).
                let outer = prim
                    .children()
                    .filter(|c| c.has_tag_name("ph"))
                    .filter_map(|ph| child(ph, "p"));
                for p in ps().chain(outer) {
                    fan(&corners(p)?, tris);
                }
            }
            "trifans" => {
                for p in ps() {
                    fan(&corners(p)?, tris);
                }
            }
            _ => {
                for p in ps() {
                    let c = corners(p)?;
                    for k in 0..c.len().saturating_sub(2) {
                        // Every other triangle of a strip turns the other way.
                        tris.push(if k % 2 == 0 {
                            [c[k], c[k + 1], c[k + 2]]
                        } else {
                            [c[k + 1], c[k], c[k + 2]]
                        });
                    }
                }
            }
        }
        Ok(())
    }
}
