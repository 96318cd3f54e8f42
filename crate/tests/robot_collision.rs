//! A URDF robot's collision shapes: STL, OBJ and COLLADA meshes read to the expected vertices,
//! the Panda's convex hulls, self-collision pairs and distances to an obstacle.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use logic_lfd::sim::{
    hull_of, parse_dae, parse_obj, parse_stl, read_mesh, PairExclusion, Robot, RobotCollision,
    ShapeKind, TriangleMesh,
};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::Cuboid;

use crate::support::cli::run_cli;

fn robots() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

fn panda() -> Robot {
    Robot::load(&robots().join("panda.json")).unwrap()
}

/// A fresh temporary folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("logic-lfd-collision-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn bbox(m: &TriangleMesh) -> ([f64; 3], [f64; 3]) {
    let (lo, hi) = m.bounding_box().unwrap();
    (lo.coords.into(), hi.coords.into())
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// The 12 triangles of the unit cube [0, 1]³, as corner triples.
fn cube_triangles() -> Vec<[[f64; 3]; 3]> {
    let c = |i: usize| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64];
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    quads
        .iter()
        .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
        .collect()
}

#[test]
fn an_ascii_stl_unit_cube_reads_as_eight_shared_corners() {
    let mut text = String::from("solid cube\n");
    for t in cube_triangles() {
        text += "  facet normal 0 0 0\n    outer loop\n";
        for p in t {
            text += &format!("      vertex {} {} {}\n", p[0], p[1], p[2]);
        }
        text += "    endloop\n  endfacet\n";
    }
    text += "endsolid cube\n";
    let m = parse_stl(text.as_bytes(), "cube.stl").unwrap();
    assert_eq!(m.triangles.len(), 12);
    assert_eq!(m.vertices.len(), 8);
    assert_eq!(bbox(&m), ([0.0; 3], [1.0; 3]));
    let e = parse_stl(
        text.replace("vertex 1 1 1", "vertex 1 x 1").as_bytes(),
        "cube.stl",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("cube.stl:") && e.contains("`x` is not a finite number"),
        "{e}"
    );
    let cut = &text[..text.len() / 2];
    let e = parse_stl(cut.as_bytes(), "half.stl")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("half.stl:") && e.contains("ends inside"),
        "{e}"
    );
}

/// A binary STL of `triangles`, its header starting with `solid` as some exporters write it.
fn binary_stl(triangles: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut b = b"solid exported".to_vec();
    b.resize(80, b' ');
    b.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        b.extend([0u8; 12]);
        for p in t {
            for v in p {
                b.extend((*v as f32).to_le_bytes());
            }
        }
        b.extend([0u8; 2]);
    }
    b
}

#[test]
fn a_binary_stl_reads_and_a_truncated_one_is_an_error_naming_the_file() {
    let dir = scratch("binary-stl");
    let tris: Vec<[[f64; 3]; 3]> = cube_triangles()
        .iter()
        .map(|t| t.map(|p| [p[0] * 0.5 - 0.1, p[1] * 0.25, p[2] * 2.0]))
        .collect();
    let bytes = binary_stl(&tris);
    assert_eq!(bytes.len(), 84 + 50 * 12);
    let path = dir.join("box.STL");
    std::fs::write(&path, &bytes).unwrap();
    let m = read_mesh(&path).unwrap();
    assert_eq!((m.vertices.len(), m.triangles.len()), (8, 12));
    // Binary STL stores f32: the corners are the nearest f32s.
    let (lo, hi) = bbox(&m);
    assert!(
        close(lo, [-0.1, 0.0, 0.0], 1e-7) && close(hi, [0.4, 0.25, 2.0], 1e-7),
        "{lo:?} {hi:?}"
    );
    let cut = dir.join("cut.stl");
    std::fs::write(&cut, &bytes[..bytes.len() - 7]).unwrap();
    let e = read_mesh(&cut).unwrap_err().to_string();
    assert!(e.contains("cut.stl") && e.contains("truncated"), "{e}");
    std::fs::write(&cut, &bytes[..40]).unwrap();
    let e = read_mesh(&cut).unwrap_err().to_string();
    assert!(e.contains("cut.stl") && e.contains("84-byte header"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_obj_quad_is_split_into_two_triangles_and_negative_indices_count_back() {
    let text = "# a quad and a triangle\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0.5\nvn 0 0 1\n\
                f 1/1/1 2/2/1 3//1 4\nv 1 1 3\nf -1 -2 -3\n";
    let m = parse_obj(text, "quad.obj").unwrap();
    assert_eq!(m.vertices.len(), 5);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [4, 3, 2]]);
    assert_eq!(bbox(&m), ([0.0, 0.0, 0.0], [2.0, 1.0, 3.0]));
    let e = parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 7\n", "bad.obj")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("bad.obj:3:") && e.contains("vertex index 7"),
        "{e}"
    );
    let e = parse_obj("v 0 0\n", "short.obj").unwrap_err().to_string();
    assert!(e.starts_with("short.obj:1:"), "{e}");
}

/// A COLLADA file: a unit cube's 8 corners (in centimetres, y up), placed by a node `<matrix>`
/// that moves it 100 cm along x and doubles it along y.
const DAE: &str = r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="cube" name="cube">
      <mesh>
        <source id="cube-pos">
          <float_array id="cube-pos-array" count="24">0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1</float_array>
          <technique_common><accessor source="#cube-pos-array" count="8" stride="3">
            <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
          </accessor></technique_common>
        </source>
        <source id="cube-n"><float_array id="cube-n-array" count="3">0 0 1</float_array></source>
        <vertices id="cube-verts"><input semantic="POSITION" source="#cube-pos"/></vertices>
        <triangles count="2">
          <input semantic="VERTEX" source="#cube-verts" offset="0"/>
          <input semantic="NORMAL" source="#cube-n" offset="1"/>
          <p>0 0 1 0 3 0 0 0 3 0 2 0</p>
        </triangles>
        <polylist count="2">
          <input semantic="VERTEX" source="#cube-verts" offset="0"/>
          <vcount>4 4</vcount>
          <p>4 5 7 6 0 1 5 4</p>
        </polylist>
        <polygons count="1">
          <input semantic="VERTEX" source="#cube-verts" offset="0"/>
          <p>2 3 7 6</p>
        </polygons>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
      <node id="placed">
        <matrix>1 0 0 100  0 2 0 0  0 0 1 0  0 0 0 1</matrix>
        <instance_geometry url="#cube"/>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"##;

#[test]
fn a_dae_applies_its_node_matrix_unit_and_up_axis() {
    let m = parse_dae(DAE, "cube.dae").unwrap();
    assert_eq!(m.vertices.len(), 8);
    // 2 triangles, 2 quads and 1 quad: 8 triangles.
    assert_eq!(m.triangles.len(), 8);
    // Node: x + 100, y · 2 (cm); then metres; then y up → z up: (x, y, z) ↦ (x, −z, y).
    let (lo, hi) = bbox(&m);
    assert!(close(lo, [1.0, -0.01, 0.0], 1e-12), "{lo:?}");
    assert!(close(hi, [1.01, 0.0, 0.02], 1e-12), "{hi:?}");
    let moved = DAE.replace(
        "<matrix>1 0 0 100  0 2 0 0  0 0 1 0  0 0 0 1</matrix>",
        "<translate>0 0 5</translate><rotate>0 0 1 90</rotate><scale>3 1 1</scale>",
    );
    let m = parse_dae(&moved.replace("Y_UP", "Z_UP"), "cube.dae").unwrap();
    // Scaled along x to 3 cm, turned 90° about z (x ↦ y), raised 5 cm.
    let (lo, hi) = bbox(&m);
    assert!(close(lo, [-0.01, 0.0, 0.05], 1e-12), "{lo:?}");
    assert!(close(hi, [0.0, 0.03, 0.06], 1e-12), "{hi:?}");
    let e = parse_dae(&DAE.replace("0 2 0 0", "0 2 0"), "cube.dae")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("cube.dae:") && e.contains("<matrix> needs 16"),
        "{e}"
    );
    let e = parse_dae(
        &DAE.replace("4 5 7 6 0 1 5 4", "4 5 7 6 0 1 5 9"),
        "cube.dae",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("vertex index 9"), "{e}");
    let line = DAE.lines().position(|l| l.contains("<p>4 5 7 6")).unwrap() + 1;
    assert!(e.starts_with(&format!("cube.dae:{line}:")), "{e}");
    let e = parse_dae(&DAE.replace("</mesh>", "</mseh>"), "cube.dae").unwrap_err();
    assert!(e.line.is_some() && e.to_string().contains("XML"), "{e}");
}

#[test]
fn the_pandas_collision_meshes_become_hulls_the_size_of_its_links() {
    let r = panda();
    let m = RobotCollision::new(&r).unwrap();
    let names: Vec<&str> = m.links().iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names[..9],
        [
            "panda_link0",
            "panda_link1",
            "panda_link2",
            "panda_link3",
            "panda_link4",
            "panda_link5",
            "panda_link6",
            "panda_link7",
            "panda_link8"
        ]
    );
    for extra in [
        "panda_hand",
        "panda_hand_tcp",
        "panda_leftfinger",
        "panda_rightfinger",
    ] {
        assert!(names.contains(&extra), "{extra} in {names:?}");
    }
    for l in m.links() {
        let n = l.name.as_str();
        if n.contains("finger") {
            assert_eq!(l.shapes.len(), 4, "{n}");
            assert!(l
                .shapes
                .iter()
                .all(|s| matches!(s.kind, ShapeKind::Box { .. })));
            continue;
        }
        if matches!(n, "panda_link8" | "panda_hand_tcp") {
            assert!(l.shapes.is_empty());
            continue;
        }
        let [s] = &l.shapes[..] else {
            panic!("{n}: {:?}", l.shapes)
        };
        let ShapeKind::Hull { vertices, aabb, .. } = &s.kind else {
            panic!("{n}: {:?}", s.kind)
        };
        assert!(
            (50..=400).contains(vertices),
            "{n}: {vertices} hull vertices"
        );
        let size: Vec<f64> = (0..3).map(|i| aabb.1[i] - aabb.0[i]).collect();
        // The Panda's links are 5–13 cm thick and at most 35 cm long; the hand 20 cm wide.
        assert!(
            size.iter().all(|s| (0.05..0.35).contains(s)),
            "{n}: {size:?}"
        );
    }
    // The hand's hull spans its 20 cm across the fingers' direction (y).
    let hand = &m.links()[names.iter().position(|n| *n == "panda_hand").unwrap()];
    let ShapeKind::Hull { aabb, .. } = &hand.shapes[0].kind else {
        unreachable!()
    };
    assert!((aabb.1[1] - aabb.0[1] - 0.2044).abs() < 0.005, "{aabb:?}");
}

#[test]
fn a_mesh_hull_is_computed_once_per_file() {
    let file =
        robots().join("example-robot-data/robots/panda_description/meshes/collision/link3.stl");
    let a = hull_of(&file, [1.0; 3]).unwrap();
    let b = hull_of(&file, [1.0; 3]).unwrap();
    assert!(Arc::ptr_eq(&a, &b));
    let scaled = hull_of(&file, [2.0, 1.0, 1.0]).unwrap();
    assert!(!Arc::ptr_eq(&a, &scaled));
    let (wa, ws) = (a.local_aabb(), scaled.local_aabb());
    assert!(((ws.maxs.x - ws.mins.x) - 2.0 * (wa.maxs.x - wa.mins.x)).abs() < 1e-12);
}

#[test]
fn the_panda_is_free_of_self_collision_at_home_and_reports_a_folded_arm() {
    let r = panda();
    let m = RobotCollision::new(&r).unwrap();
    for opening in [0.0, 0.04, 0.08] {
        assert_eq!(m.self_collisions(&r.home, opening).unwrap(), vec![]);
    }
    let excluded = m.excluded_pairs();
    for (a, b) in [
        ("panda_link0", "panda_link1"),
        ("panda_link7", "panda_hand"),
        ("panda_link7", "panda_leftfinger"),
    ] {
        assert!(
            excluded.contains(&(a, b, PairExclusion::Adjacent)),
            "{a}–{b}: {excluded:?}"
        );
    }
    // No two arm links overlap at home: the only pair left out as touching there is the closed
    // fingers.
    let touching: Vec<_> = excluded
        .iter()
        .filter(|p| p.2 == PairExclusion::TouchAtHome)
        .collect();
    assert_eq!(
        touching,
        [&(
            "panda_leftfinger",
            "panda_rightfinger",
            PairExclusion::TouchAtHome
        )]
    );
    let checked = m.checked_pairs();
    assert!(
        checked.contains(&("panda_link0", "panda_hand"))
            && checked.contains(&("panda_link1", "panda_link7"))
    );
    // Elbow (joint 4) at its limit, shoulder forward, wrist bent back: the hand comes down into
    // the base link.
    let folded = [0.0, 0.705, 0.0, -3.0718, 0.0, 2.99, 0.785];
    let hits = m.self_collisions(&folded, 0.04).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    let (a, b, depth) = &hits[0];
    assert_eq!((a.as_str(), b.as_str()), ("panda_link0", "panda_hand"));
    assert!(*depth > 0.005, "{depth}");
    // Wrist bent the other way: the hand and fingers fold onto link 1.
    let onto_link1 = [0.0, 0.0, 0.0, -3.0718, 0.0, 1.3, 0.785];
    let hits = m.self_collisions(&onto_link1, 0.04).unwrap();
    let pairs: Vec<(&str, &str)> = hits
        .iter()
        .map(|(a, b, _)| (a.as_str(), b.as_str()))
        .collect();
    assert!(pairs.contains(&("panda_link1", "panda_hand")), "{pairs:?}");
    assert!(pairs.iter().all(|(a, _)| *a == "panda_link1"), "{pairs:?}");
    // The closest checked pair at home is apart, and refusals name the joint.
    let (_, _, d) = m.closest_pair(&r.home, 0.04).unwrap().unwrap();
    assert!(d > 0.005, "{d}");
    assert!(m
        .self_collisions(&[0.0; 7], 0.0)
        .unwrap_err()
        .contains("panda_joint4"));
    assert!(m
        .self_collisions(&r.home, 0.1)
        .unwrap_err()
        .contains("opening"));
}

/// A six-joint robot whose joints all turn about z at the base: its `tool` link is a box
/// 0.2 × 0.1 × 0.05 m centred 0.5 m up, link `l3` a cylinder (r 0.1 m, 1 m long) centred 2 m
/// up, link `l2` a ball (r 0.05 m) at (0, 1, 0).
fn toy_robot(dir: &Path, tool_geometry: &str) -> Robot {
    let mut urdf = String::from("<robot name=\"toy\">\n<link name=\"base\"/>\n");
    let shapes = [
        ("l1", String::new()),
        (
            "l2",
            "<origin xyz=\"0 1 0\"/><geometry><sphere radius=\"0.05\"/></geometry>".into(),
        ),
        (
            "l3",
            "<origin xyz=\"0 0 2\"/><geometry><cylinder radius=\"0.1\" length=\"1\"/></geometry>"
                .into(),
        ),
        ("l4", String::new()),
        ("l5", String::new()),
        (
            "tool",
            format!("<origin xyz=\"0 0 0.5\"/><geometry>{tool_geometry}</geometry>"),
        ),
    ];
    let mut parent = "base";
    for (i, (name, c)) in shapes.iter().enumerate() {
        let coll = if c.is_empty() {
            String::new()
        } else {
            format!("<collision>{c}</collision>")
        };
        urdf += &format!(
            "<link name=\"{name}\">{coll}</link>\n<joint name=\"j{}\" type=\"revolute\">\
             <parent link=\"{parent}\"/><child link=\"{name}\"/><axis xyz=\"0 0 1\"/>\
             <limit lower=\"-3\" upper=\"3\" velocity=\"1\"/></joint>\n",
            i + 1
        );
        parent = name;
    }
    urdf += "</robot>\n";
    std::fs::write(dir.join("toy.urdf"), urdf).unwrap();
    std::fs::write(
        dir.join("toy.json"),
        r#"{ "name": "toy", "urdf": "toy.urdf", "base_link": "base", "tip_link": "tool",
             "home": [0, 0, 0, 0, 0, 0],
             "gripper": { "max_opening": 0.08, "finger_length": 0.05 } }"#,
    )
    .unwrap();
    Robot::load(&dir.join("toy.json")).unwrap()
}

#[test]
fn the_distance_to_a_block_matches_the_analytic_value_for_primitive_links() {
    let dir = scratch("toy");
    let r = toy_robot(&dir, "<box size=\"0.2 0.1 0.05\"/>");
    let m = RobotCollision::new(&r).unwrap();
    let block = Cuboid::new(Vector3::new(0.1, 0.1, 0.1));
    let at = |x: f64, y: f64, z: f64| {
        Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
    };
    let q0 = [0.0; 6];
    // Beside the tool, 2 m out along x: the box's face is at x = 0.1, the block's at 1.9.
    let (link, d) = m
        .distance_to(&block, &at(2.0, 0.0, 0.5), &q0, 0.0)
        .unwrap()
        .unwrap();
    assert_eq!(link, "tool");
    assert!((d - 1.8).abs() < 1e-6, "{d}");
    // Joints 1 and 6 turn the tool by 90° in all: its 5 cm half-width now faces the block.
    let turned = [0.5, 0.0, 0.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2 - 0.5];
    let (_, d) = m
        .distance_to(&block, &at(2.0, 0.0, 0.5), &turned, 0.0)
        .unwrap()
        .unwrap();
    assert!((d - 1.85).abs() < 1e-6, "{d}");
    // Above the cylinder: its top is at z = 2.5 (URDF cylinders run along z), the block's
    // bottom at 2.9.
    let (link, d) = m
        .distance_to(&block, &at(0.0, 0.0, 3.0), &q0, 0.0)
        .unwrap()
        .unwrap();
    assert_eq!(link, "l3");
    assert!((d - 0.4).abs() < 1e-6, "{d}");
    // Beside the ball at (0, 1, 0): the block's face at y = 1.4, the ball's at 1.05.
    let (link, d) = m
        .distance_to(&block, &at(0.0, 1.5, 0.0), &q0, 0.0)
        .unwrap()
        .unwrap();
    assert_eq!(link, "l2");
    assert!((d - 0.35).abs() < 1e-6, "{d}");
    // Sunk 3 cm into the tool's face: the distance is minus the depth.
    let (_, d) = m
        .distance_to(&block, &at(0.17, 0.0, 0.5), &q0, 0.0)
        .unwrap()
        .unwrap();
    assert!((d + 0.03).abs() < 1e-6, "{d}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_malformed_collision_mesh_is_an_error_naming_the_file() {
    let dir = scratch("bad-mesh");
    std::fs::write(dir.join("flat.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("cut.stl"), &binary_stl(&cube_triangles())[..300]).unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 zero\n").unwrap();
    std::fs::write(dir.join("shape.ply"), "ply\n").unwrap();
    for (file, says) in [
        ("flat.obj", "one plane"),
        ("cut.stl", "truncated"),
        ("bad.obj", "bad.obj:2:"),
        ("shape.ply", "not supported"),
    ] {
        let r = toy_robot(&dir, &format!("<mesh filename=\"{file}\"/>"));
        let e = RobotCollision::new(&r).unwrap_err().to_string();
        assert!(
            e.contains("toy.urdf:") && e.contains(file) && e.contains(says),
            "{e}"
        );
    }
    // A scaled mesh hull: a unit cube OBJ scaled to the toy's box gives its distances.
    let mut obj = String::new();
    for i in 0..8 {
        obj += &format!(
            "v {} {} {}\n",
            (i & 1) as f64 - 0.5,
            ((i >> 1) & 1) as f64 - 0.5,
            ((i >> 2) & 1) as f64 - 0.5
        );
    }
    std::fs::write(dir.join("cube.obj"), obj + "f 1 2 4 3\n").unwrap();
    let r = toy_robot(&dir, "<mesh filename=\"cube.obj\" scale=\"0.2 0.1 0.05\"/>");
    let m = RobotCollision::new(&r).unwrap();
    let block = Cuboid::new(Vector3::new(0.1, 0.1, 0.1));
    let pose = Isometry3::translation(2.0, 0.0, 0.5);
    let (_, d) = m
        .distance_to(&block, &pose, &[0.0; 6], 0.0)
        .unwrap()
        .unwrap();
    assert!((d - 1.8).abs() < 1e-6, "{d}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn robot_check_lists_hulls_and_reports_no_self_collision_at_home() {
    let file = robots().join("panda.json");
    let (code, out, err) = run_cli(&["robot", "check", file.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let link3 = v["links"]
        .as_array()
        .unwrap()
        .iter()
        .find(|l| l["name"] == "panda_link3")
        .unwrap();
    let hull = &link3["shapes"][0];
    assert_eq!(hull["kind"], "hull");
    assert!(hull["vertices"].as_u64().unwrap() > 50);
    assert_eq!(hull["aabb_min"].as_array().unwrap().len(), 3);
    assert!(v["links"]
        .as_array()
        .unwrap()
        .iter()
        .any(|l| l["name"] == "panda_leftfinger"));
    assert_eq!(v["self_collision"]["at_home"], serde_json::json!([]));
    assert!(v["self_collision"]["checked_pairs"].as_u64().unwrap() > 30);
    let (code, out, _) = run_cli(&["robot", "check", file.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(
        out.contains("hull") && out.contains("no self-collision at home"),
        "{out}"
    );
}
