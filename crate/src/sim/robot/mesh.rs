//! Triangle meshes from the files URDFs name for their shapes: STL (binary and ASCII) and
//! Wavefront OBJ. COLLADA (`.dae`) is read by `dae.rs`.
//!
//! Coordinates are taken as written (URDF meshes are in metres); the URDF's `<mesh scale>` is
//! applied by the caller. Errors name the file and, for text formats, the line.

use std::collections::HashMap;
use std::fmt;

use nalgebra::Point3;

/// A triangle mesh: vertices and triangles indexing them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// The vertices (m); an STL's repeated corners are merged.
    pub vertices: Vec<Point3<f64>>,
    /// Triangles as indices into `vertices` (polygons fan-triangulated).
    pub triangles: Vec<[usize; 3]>,
}

impl TriangleMesh {
    /// The smallest axis-aligned box around the vertices (`None` for a mesh without vertices).
    pub fn bounding_box(&self) -> Option<(Point3<f64>, Point3<f64>)> {
        let first = *self.vertices.first()?;
        Some(
            self.vertices
                .iter()
                .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p))),
        )
    }

    /// Appends `p` unless a vertex with the very same coordinates is there; its index.
    fn merged(&mut self, seen: &mut HashMap<[u64; 3], usize>, p: [f64; 3]) -> usize {
        // `+ 0.0` turns −0 into +0, so both spellings of a corner merge.
        let key = p.map(|c| (c + 0.0).to_bits());
        *seen.entry(key).or_insert_with(|| {
            self.vertices.push(Point3::new(p[0], p[1], p[2]));
            self.vertices.len() - 1
        })
    }
}

/// A mesh file that cannot be read: the file, the line where one applies, and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshError {
    /// The file as given by the caller.
    pub file: String,
    /// 1-based line (text formats), if the fault has one.
    pub line: Option<u32>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{}:{l}: {}", self.file, self.message),
            None => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for MeshError {}

impl MeshError {
    pub(super) fn new(file: &str, line: Option<u32>, message: impl Into<String>) -> MeshError {
        MeshError {
            file: file.into(),
            line,
            message: message.into(),
        }
    }
}

/// Size of a binary STL's header: 80 bytes of text and the triangle count.
const STL_HEADER: usize = 84;
/// Size of one binary STL triangle: normal, three corners (12 `f32`s) and a 2-byte attribute.
const STL_TRIANGLE: usize = 50;

/// Reads an STL file's bytes, binary or ASCII; `file` names it in errors.
///
/// A file is ASCII when it starts with `solid`, is text and has a `facet` or `endsolid` (binary
/// headers may start with `solid` too, but their floats put NUL or non-UTF-8 bytes in the file).
/// Text that fails as ASCII but has exactly the size its binary header announces is read as
/// binary.
pub fn parse_stl(bytes: &[u8], file: &str) -> Result<TriangleMesh, MeshError> {
    let start = bytes.iter().position(|b| !b.is_ascii_whitespace());
    let solid = start.is_some_and(|s| bytes[s..].starts_with(b"solid"));
    if solid && !bytes.contains(&0) {
        if let Ok(text) = std::str::from_utf8(bytes) {
            if text.contains("facet") || text.contains("endsolid") {
                let ascii = parse_ascii_stl(text, file);
                let n = bytes
                    .get(80..84)
                    .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize);
                let binary_size = n.is_some_and(|n| {
                    n.checked_mul(STL_TRIANGLE)
                        .and_then(|b| b.checked_add(STL_HEADER))
                        == Some(bytes.len())
                });
                if ascii.is_ok() || !binary_size {
                    return ascii;
                }
            }
        }
    }
    parse_binary_stl(bytes, file)
}

fn parse_binary_stl(bytes: &[u8], file: &str) -> Result<TriangleMesh, MeshError> {
    let err = |m: String| MeshError::new(file, None, m);
    if bytes.len() < STL_HEADER {
        return Err(err(format!(
            "binary STL of {} bytes, shorter than its {STL_HEADER}-byte header",
            bytes.len()
        )));
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let need = n
        .checked_mul(STL_TRIANGLE)
        .and_then(|b| b.checked_add(STL_HEADER));
    if need.is_none_or(|need| bytes.len() < need) {
        return Err(err(format!(
            "binary STL truncated: its header announces {n} triangles ({STL_HEADER} + 50 × {n} \
             bytes), the file has {} bytes",
            bytes.len()
        )));
    }
    let mut mesh = TriangleMesh::default();
    let mut seen = HashMap::new();
    for t in 0..n {
        let rec = &bytes[STL_HEADER + t * STL_TRIANGLE..][..STL_TRIANGLE];
        let f = |k: usize| {
            let b = &rec[4 * k..4 * k + 4];
            f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        };
        let mut tri = [0; 3];
        for (c, slot) in tri.iter_mut().enumerate() {
            // Floats 0..3 are the normal; corner c is floats 3 + 3c ..
            let p = [f(3 + 3 * c), f(4 + 3 * c), f(5 + 3 * c)];
            if p.iter().any(|v| !v.is_finite()) {
                return Err(err(format!(
                    "triangle {}: corner {} is not a finite point ({p:?})",
                    t + 1,
                    c + 1
                )));
            }
            *slot = mesh.merged(&mut seen, p);
        }
        mesh.triangles.push(tri);
    }
    Ok(mesh)
}

/// A text line's number `tok`, or an error at `line` naming `what`.
fn number(tok: Option<&str>, file: &str, line: u32, what: &str) -> Result<f64, MeshError> {
    match tok.map(str::parse::<f64>) {
        Some(Ok(v)) if v.is_finite() => Ok(v),
        Some(_) => Err(MeshError::new(
            file,
            Some(line),
            format!("{what}: `{}` is not a finite number", tok.unwrap_or("")),
        )),
        None => Err(MeshError::new(
            file,
            Some(line),
            format!("{what}: expected 3 numbers"),
        )),
    }
}

/// `solid` … `facet normal` / `outer loop` / `vertex x y z` ×3 / `endloop` / `endfacet` …
/// `endsolid`, one or more solids.
fn parse_ascii_stl(text: &str, file: &str) -> Result<TriangleMesh, MeshError> {
    let mut mesh = TriangleMesh::default();
    let mut seen = HashMap::new();
    // Where the open `solid`, `facet` and `outer loop` started, and the loop's corners.
    let (mut solid, mut facet, mut lp) = (None::<u32>, None::<u32>, None::<u32>);
    let mut corners: Vec<usize> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let ln = i as u32 + 1;
        let mut toks = raw.split_whitespace();
        let Some(word) = toks.next() else { continue };
        let err = |m: String| MeshError::new(file, Some(ln), m);
        let expect = |ok: bool, m: &str| if ok { Ok(()) } else { Err(err(m.into())) };
        match word {
            "solid" => {
                expect(solid.is_none(), "`solid` inside a solid")?;
                solid = Some(ln);
            }
            "facet" => {
                expect(
                    solid.is_some() && facet.is_none(),
                    "`facet` outside a solid",
                )?;
                facet = Some(ln);
            }
            "outer" => {
                expect(
                    facet.is_some() && lp.is_none(),
                    "`outer loop` outside a facet",
                )?;
                lp = Some(ln);
                corners.clear();
            }
            "vertex" => {
                expect(lp.is_some(), "`vertex` outside an `outer loop`")?;
                let mut p = [0.0; 3];
                for v in &mut p {
                    *v = number(toks.next(), file, ln, "vertex")?;
                }
                corners.push(mesh.merged(&mut seen, p));
            }
            "endloop" => {
                expect(lp.is_some(), "`endloop` without `outer loop`")?;
                if corners.len() < 3 {
                    return Err(err(format!(
                        "a loop of {} vertices; a facet needs 3",
                        corners.len()
                    )));
                }
                for k in 1..corners.len() - 1 {
                    mesh.triangles
                        .push([corners[0], corners[k], corners[k + 1]]);
                }
                lp = None;
            }
            "endfacet" => {
                expect(
                    facet.is_some() && lp.is_none(),
                    "`endfacet` without a closed facet",
                )?;
                facet = None;
            }
            "endsolid" => {
                expect(
                    solid.is_some() && facet.is_none(),
                    "`endsolid` inside a facet",
                )?;
                solid = None;
            }
            other => return Err(err(format!("ASCII STL: unexpected `{other}`"))),
        }
    }
    if let Some(open) = lp.or(facet).or(solid) {
        return Err(MeshError::new(
            file,
            Some(open),
            "the file ends inside the facet or solid opened here (truncated?)",
        ));
    }
    Ok(mesh)
}

/// Reads a Wavefront OBJ text: `v x y z` vertices and `f a b c …` faces (1-based indices,
/// negative ones counting back from the last vertex; `a/t/n` forms use the vertex index), each
/// polygon fan-triangulated. Other statements (normals, texture coordinates, groups, materials)
/// are read past.
pub fn parse_obj(text: &str, file: &str) -> Result<TriangleMesh, MeshError> {
    let mut mesh = TriangleMesh::default();
    // Faces may name vertices defined further down: positive indices are checked at the end.
    let mut checks: Vec<(u32, usize)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let ln = i as u32 + 1;
        let line = raw.split('#').next().unwrap_or("");
        let mut toks = line.split_whitespace();
        match toks.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for v in &mut p {
                    *v = number(toks.next(), file, ln, "v")?;
                }
                mesh.vertices.push(Point3::new(p[0], p[1], p[2]));
            }
            Some("f") => {
                let mut face = Vec::new();
                for t in toks {
                    let idx = t.split('/').next().unwrap_or("");
                    let k: i64 = idx.parse().map_err(|_| {
                        MeshError::new(file, Some(ln), format!("f: `{t}` is not a vertex index"))
                    })?;
                    let n = mesh.vertices.len() as i64;
                    let at = match k {
                        0 => None,
                        k if k > 0 => Some(k - 1),
                        k => Some(n + k).filter(|a| *a >= 0),
                    };
                    let Some(at) = at else {
                        return Err(MeshError::new(
                            file,
                            Some(ln),
                            format!("f: vertex index {k} with {n} vertices defined so far"),
                        ));
                    };
                    checks.push((ln, at as usize));
                    face.push(at as usize);
                }
                if face.len() < 3 {
                    return Err(MeshError::new(
                        file,
                        Some(ln),
                        format!("f: a face of {} vertices; it needs 3", face.len()),
                    ));
                }
                for k in 1..face.len() - 1 {
                    mesh.triangles.push([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if let Some((ln, at)) = checks.iter().find(|(_, at)| *at >= mesh.vertices.len()) {
        return Err(MeshError::new(
            file,
            Some(*ln),
            format!(
                "f: vertex index {} but the file has {} vertices",
                at + 1,
                mesh.vertices.len()
            ),
        ));
    }
    Ok(mesh)
}
