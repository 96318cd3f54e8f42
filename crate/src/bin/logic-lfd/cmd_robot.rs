//! `logic-lfd robot …`: a robot from its URDF (the robot file `robot.json` beside it, or a
//! shipped robot by name: `panda`, `ur5`).
//!
//! * `robot check ROBOT.json [--json]` — load and check the robot file and its URDF; print the
//!   chain's joints and limits, the links with their collision shapes (a mesh as its convex hull),
//!   self-collision at home, the TCP at home and the reach (sampled);
//! * `robot fk ROBOT.json --q q1,q2,… [--json]` — the TCP's pose in the base link's frame
//!   (metres; `--json`: `{"position": [x, y, z], "rotation": [[…], […], […]]}`);
//! * `robot ik ROBOT.json --position x,y,z [--rpy r,p,y] [--seed-q q1,…] [--json]` — joints
//!   within the limits that put the TCP at the pose (orientation default: the TCP's at home;
//!   seed default: home), with the residual errors.
//!
//! Exit codes: 0 success, 1 no joints reach the pose (`robot ik`), 2 bad input (the message names
//! the file and the JSON path or URDF line, or the flag).

use std::path::PathBuf;
use std::process::ExitCode;

use logic_lfd::sim::{Geometry, IkFailure, IkOptions, Robot};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::Serialize;

use crate::cmd_robot_collision::{
    collision_summary, print_self_collision, SelfCollisionRow, ShapeRow,
};
use crate::exit;

/// Arguments of `logic-lfd robot`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(clap::Subcommand)]
enum Action {
    /// Load and check a robot file and its URDF; print its joints, links, TCP and reach.
    Check {
        /// The robot file (robot.json), or a shipped robot: `panda`, `ur5`.
        robot: PathBuf,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// The TCP's pose in the base link's frame for a joint vector.
    Fk {
        /// The robot file (robot.json), or a shipped robot: `panda`, `ur5`.
        robot: PathBuf,
        /// Joint values (rad or m), comma-separated, one per moving joint of the chain.
        #[arg(long, allow_hyphen_values = true)]
        q: String,
        /// Print `{"position": [x, y, z], "rotation": [[…], […], […]]}`.
        #[arg(long)]
        json: bool,
    },
    /// Joints within the limits that put the TCP at a pose (inverse kinematics).
    Ik {
        /// The robot file (robot.json), or a shipped robot: `panda`, `ur5`.
        robot: PathBuf,
        /// Target TCP position in the base link's frame (m): x,y,z.
        #[arg(long, allow_hyphen_values = true)]
        position: String,
        /// Target TCP orientation as fixed-axis roll,pitch,yaw (rad) [default: the TCP's at home].
        #[arg(long, allow_hyphen_values = true)]
        rpy: Option<String>,
        /// Joint vector to start from, one value per moving joint [default: home].
        #[arg(long = "seed-q", allow_hyphen_values = true)]
        seed_q: Option<String>,
        /// Print `{"joints": […], "names": […], "position_error": …, …}`.
        #[arg(long)]
        json: bool,
    },
}

/// Postures sampled for the reach.
const REACH_SAMPLES: usize = 4000;

#[derive(Serialize)]
struct Pose {
    position: [f64; 3],
    rotation: [[f64; 3]; 3],
}

impl Pose {
    fn of(t: &Isometry3<f64>) -> Pose {
        let m = t.rotation.to_rotation_matrix();
        let m = m.matrix();
        Pose {
            position: [t.translation.x, t.translation.y, t.translation.z],
            rotation: std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)])),
        }
    }
}

#[derive(Serialize)]
struct JointRow {
    name: String,
    kind: &'static str,
    lower: f64,
    upper: f64,
    velocity: f64,
}

#[derive(Serialize)]
struct LinkRow {
    name: String,
    collision: Vec<String>,
    shapes: Vec<ShapeRow>,
}

#[derive(Serialize)]
struct Reach {
    samples: usize,
    /// Largest horizontal distance of the TCP from the base's z axis (m).
    max_radius: f64,
    /// Lowest and highest TCP height (m).
    min_z: f64,
    max_z: f64,
}

#[derive(Serialize)]
struct Summary {
    name: String,
    urdf: String,
    base_link: String,
    tip_link: String,
    dof: usize,
    joints: Vec<JointRow>,
    links: Vec<LinkRow>,
    self_collision: SelfCollisionRow,
    gripper_joints: Vec<String>,
    max_opening: f64,
    home_tcp: Pose,
    reach: Reach,
}

fn bad(msg: String) -> ExitCode {
    eprintln!("{msg}");
    ExitCode::from(exit::BAD_INPUT)
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    match args.action {
        Action::Check { robot, json } => check(&robot, json),
        Action::Fk { robot, q, json } => fk(&robot, &q, json),
        Action::Ik {
            robot,
            position,
            rpy,
            seed_q,
            json,
        } => ik(&robot, &position, rpy.as_deref(), seed_q.as_deref(), json),
    }
}

fn shape(g: &Geometry) -> String {
    match g {
        Geometry::Box { size } => format!("box {} × {} × {} m", size[0], size[1], size[2]),
        Geometry::Cylinder { radius, length } => {
            format!("cylinder r {radius} m, length {length} m")
        }
        Geometry::Sphere { radius } => format!("sphere r {radius} m"),
        Geometry::Mesh { filename, .. } => {
            format!("mesh {}", filename.rsplit('/').next().unwrap_or(filename))
        }
    }
}

/// The TCP's reach over seeded random postures within the joint limits (continuous joints: ±π).
fn reach(r: &Robot) -> Reach {
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    let bounds: Vec<(f64, f64)> = r
        .chain
        .moving()
        .map(|j| {
            (
                j.lower.max(-std::f64::consts::PI),
                j.upper.min(std::f64::consts::PI),
            )
        })
        .collect();
    let mut out = Reach {
        samples: REACH_SAMPLES,
        max_radius: 0.0,
        min_z: f64::INFINITY,
        max_z: f64::NEG_INFINITY,
    };
    for _ in 0..REACH_SAMPLES {
        let q: Vec<f64> = bounds
            .iter()
            .map(|&(lo, hi)| {
                if hi > lo {
                    rng.random_range(lo..hi)
                } else {
                    lo
                }
            })
            .collect();
        let p = (r.chain.tip_frame(&q) * r.tcp).translation.vector;
        out.max_radius = out.max_radius.max(libm::hypot(p.x, p.y));
        out.min_z = out.min_z.min(p.z);
        out.max_z = out.max_z.max(p.z);
    }
    out
}

fn check(path: &std::path::Path, json: bool) -> ExitCode {
    let r = match crate::robot_arg::robot(path) {
        Ok(r) => r,
        Err(e) => return bad(e.to_string()),
    };
    let (model_links, self_collision) = match collision_summary(&r) {
        Ok(c) => c,
        Err(e) => return bad(e),
    };
    let summary = Summary {
        name: r.name.clone(),
        urdf: r.urdf_file.display().to_string(),
        base_link: r.chain.base.clone(),
        tip_link: r.chain.tip.clone(),
        dof: r.chain.dof(),
        joints: r
            .chain
            .moving()
            .map(|j| JointRow {
                name: j.name.clone(),
                kind: j.kind.as_str(),
                lower: j.lower,
                upper: j.upper,
                velocity: j.velocity,
            })
            .collect(),
        links: model_links
            .into_iter()
            .map(|l| LinkRow {
                collision: r
                    .urdf
                    .links
                    .iter()
                    .filter(|u| u.name == l.name)
                    .flat_map(|u| u.collisions.iter().map(|c| shape(&c.geometry)))
                    .collect(),
                name: l.name,
                shapes: l.shapes,
            })
            .collect(),
        self_collision,
        gripper_joints: r.gripper.joints.clone(),
        max_opening: r.gripper.max_opening,
        home_tcp: Pose::of(&(r.chain.tip_frame(&r.home) * r.tcp)),
        reach: reach(&r),
    };
    if json {
        return match serde_json::to_string_pretty(&summary) {
            Ok(s) => {
                println!("{s}");
                ExitCode::from(exit::OK)
            }
            Err(e) => bad(format!("cannot write JSON: {e}")),
        };
    }
    let s = &summary;
    println!(
        "{}: {} joints from {} to {} ({})",
        s.name, s.dof, s.base_link, s.tip_link, s.urdf
    );
    for j in &s.joints {
        println!(
            "  {:<16} {:<10} [{:>8.4}, {:>8.4}]  ≤ {:.3}/s",
            j.name, j.kind, j.lower, j.upper, j.velocity
        );
    }
    for l in &s.links {
        let shapes = if l.shapes.is_empty() {
            "no collision shape".to_string()
        } else {
            l.shapes
                .iter()
                .map(ShapeRow::text)
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!("  link {:<14} {shapes}", l.name);
    }
    print_self_collision(&s.self_collision);
    let p = s.home_tcp.position;
    println!("  TCP at home: ({:.4}, {:.4}, {:.4}) m", p[0], p[1], p[2]);
    println!(
        "  gripper: {} (opens to {} m)",
        if s.gripper_joints.is_empty() {
            "kinematic fingers".to_string()
        } else {
            s.gripper_joints.join(", ")
        },
        s.max_opening
    );
    println!(
        "  reach ({} sampled postures): radius ≤ {:.3} m, height {:.3} to {:.3} m",
        s.reach.samples, s.reach.max_radius, s.reach.min_z, s.reach.max_z
    );
    ExitCode::from(exit::OK)
}

fn fk(path: &std::path::Path, q: &str, json: bool) -> ExitCode {
    let r = match crate::robot_arg::robot(path) {
        Ok(r) => r,
        Err(e) => return bad(e.to_string()),
    };
    let values = match numbers("--q", q) {
        Ok(v) => v,
        Err(m) => return bad(m),
    };
    let t = match r.tcp_pose(&values) {
        Ok(t) => t,
        Err(m) => return bad(format!("--q: {m}")),
    };
    let pose = Pose::of(&t);
    if json {
        match serde_json::to_string(&pose) {
            Ok(s) => println!("{s}"),
            Err(e) => return bad(format!("cannot write JSON: {e}")),
        }
    } else {
        let p = pose.position;
        println!("position: {:.6} {:.6} {:.6}", p[0], p[1], p[2]);
        for row in pose.rotation {
            println!("rotation: {:.6} {:.6} {:.6}", row[0], row[1], row[2]);
        }
    }
    ExitCode::from(exit::OK)
}

/// The comma-separated numbers of flag `flag`; the message names the flag and the value.
fn numbers(flag: &str, text: &str) -> Result<Vec<f64>, String> {
    text.split(',')
        .enumerate()
        .map(|(i, v)| match v.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(format!(
                "{flag}: value {} is `{v}`, expected a number",
                i + 1
            )),
        })
        .collect()
}

/// Exactly three numbers of flag `flag`, named `names` (`x,y,z`) in the message.
fn triple(flag: &str, names: &str, text: &str) -> Result<[f64; 3], String> {
    let v = numbers(flag, text)?;
    <[f64; 3]>::try_from(v.as_slice())
        .map_err(|_| format!("{flag}: {} values, expected 3 ({names})", v.len()))
}

#[derive(Serialize)]
struct IkRow {
    names: Vec<String>,
    joints: Vec<f64>,
    position_error: f64,
    orientation_error: f64,
    iterations: usize,
    attempts: usize,
}

fn ik(
    path: &std::path::Path,
    position: &str,
    rpy: Option<&str>,
    seed_q: Option<&str>,
    json: bool,
) -> ExitCode {
    let r = match crate::robot_arg::robot(path) {
        Ok(r) => r,
        Err(e) => return bad(e.to_string()),
    };
    let p = match triple("--position", "x,y,z", position) {
        Ok(p) => p,
        Err(m) => return bad(m),
    };
    let rotation = match rpy.map(|t| triple("--rpy", "roll,pitch,yaw", t)) {
        None => (r.chain.tip_frame(&r.home) * r.tcp).rotation,
        Some(Ok([a, b, c])) => UnitQuaternion::from_euler_angles(a, b, c),
        Some(Err(m)) => return bad(m),
    };
    let seed = match seed_q.map(|t| numbers("--seed-q", t)) {
        None => r.home.clone(),
        Some(Ok(q)) if q.len() != r.chain.dof() => {
            return bad(format!(
                "--seed-q: {} joint values for {} joints",
                q.len(),
                r.chain.dof()
            ))
        }
        Some(Ok(q)) => q,
        Some(Err(m)) => return bad(m),
    };
    let target = Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), rotation);
    let s = match r.ik(&target, &seed, &IkOptions::default()) {
        Ok(s) => s,
        Err(e @ IkFailure::Unreachable { .. }) => {
            eprintln!(
                "{}: no joints within the limits put the TCP at ({}, {}, {}): {e}",
                r.name, p[0], p[1], p[2]
            );
            return ExitCode::from(exit::UNREACHABLE);
        }
        Err(e) => return bad(e.to_string()),
    };
    let row = IkRow {
        names: r.chain.moving().map(|j| j.name.clone()).collect(),
        joints: s.joints,
        position_error: s.position_error,
        orientation_error: s.orientation_error,
        iterations: s.iterations,
        attempts: s.attempts,
    };
    if json {
        match serde_json::to_string(&row) {
            Ok(t) => println!("{t}"),
            Err(e) => return bad(format!("cannot write JSON: {e}")),
        }
        return ExitCode::from(exit::OK);
    }
    for (n, q) in row.names.iter().zip(&row.joints) {
        println!("{n:<20} {q:>10.6}");
    }
    println!(
        "error: {:.2e} m, {:.2e} rad ({} iterations, {} attempts)",
        row.position_error, row.orientation_error, row.iterations, row.attempts
    );
    ExitCode::from(exit::OK)
}
