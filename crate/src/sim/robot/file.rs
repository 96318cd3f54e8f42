//! The robot file (`robot.json`): which URDF, which chain, the TCP, home and gripper; loaded and
//! checked with every error at its JSON path or URDF line.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use serde::Deserialize;

use super::chain::Chain;
use super::files::RobotFiles;
use super::urdf::{parse_urdf, Geometry, Urdf};

/// The tool centre point relative to the tip link: a translation and fixed-axis roll, pitch, yaw.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TcpSpec {
    /// Translation (m).
    #[serde(default)]
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw (rad).
    #[serde(default)]
    pub rpy: [f64; 3],
}

/// The gripper: its finger joints in the URDF, or a kinematic two-finger gripper.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GripperSpec {
    /// The URDF's finger joints (empty: the arm has no hand; a kinematic one is added).
    #[serde(default)]
    pub joints: Vec<String>,
    /// Largest distance between the finger pads (m).
    pub max_opening: f64,
    /// Length of the kinematic fingers (m), for an arm without a hand.
    #[serde(default)]
    pub finger_length: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRobot {
    name: String,
    urdf: String,
    #[serde(default)]
    packages: BTreeMap<String, String>,
    base_link: String,
    tip_link: String,
    #[serde(default)]
    tcp: Option<TcpSpec>,
    home: Vec<f64>,
    gripper: GripperSpec,
    #[serde(default)]
    limits: BTreeMap<String, [f64; 2]>,
}

/// A robot file that cannot be loaded: the file with its JSON path or line, and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{at}: {message}")]
pub struct RobotError {
    /// `robot.json: home`, `panda.urdf:41:5`, …
    pub at: String,
    /// What is wrong.
    pub message: String,
}

/// A robot: its URDF, the chain from base to tip, the TCP, home posture and gripper.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// The robot's name.
    pub name: String,
    /// The robot file.
    pub file: PathBuf,
    /// The URDF file.
    pub urdf_file: PathBuf,
    /// The parsed URDF.
    pub urdf: Urdf,
    /// The chain from `base_link` to `tip_link`.
    pub chain: Chain,
    /// The TCP in the tip link's frame.
    pub tcp: Isometry3<f64>,
    /// The home posture, one entry per moving joint.
    pub home: Vec<f64>,
    /// The gripper.
    pub gripper: GripperSpec,
    /// ROS package name → folder, resolved against the robot file's folder.
    pub packages: BTreeMap<String, PathBuf>,
    /// Where the robot's files (URDF, meshes) are read.
    pub files: RobotFiles,
}

impl Robot {
    /// Loads and checks a robot file and its URDF from the disk.
    pub fn load(path: &Path) -> Result<Robot, RobotError> {
        Robot::load_from(path, RobotFiles::disk())
    }

    /// Loads and checks the robot file at `path` and its URDF, reading every file from `files`.
    pub fn load_from(path: &Path, files: RobotFiles) -> Result<Robot, RobotError> {
        let file = path.display().to_string();
        let text = files.read_text(path).map_err(|message| RobotError {
            at: file.clone(),
            message,
        })?;
        let mut de = serde_json::Deserializer::from_str(&text);
        let raw: RawRobot = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            let inner = e.inner();
            RobotError {
                at: format!("{file}:{}:{}: {}", inner.line(), inner.column(), e.path()),
                message: inner.to_string(),
            }
        })?;
        let at = |field: &str| format!("{file}: {field}");
        let dir = path.parent().unwrap_or(Path::new("."));
        let urdf_file = dir.join(&raw.urdf);
        let urdf_text = files.read_text(&urdf_file).map_err(|e| RobotError {
            at: at("urdf"),
            message: format!("{}: {e}", urdf_file.display()),
        })?;
        let urdf_name = urdf_file.display().to_string();
        let urdf = parse_urdf(&urdf_text, &urdf_name).map_err(|e| RobotError {
            at: format!("{}:{}:{}", e.file, e.line, e.col),
            message: e.message,
        })?;
        let mut chain =
            Chain::new(&urdf, &raw.base_link, &raw.tip_link).map_err(|m| RobotError {
                at: at(
                    if m.contains(&format!("`{}`", raw.base_link)) && !m.contains("not below") {
                        "base_link"
                    } else {
                        "tip_link"
                    },
                ),
                message: m,
            })?;
        if !(6..=7).contains(&chain.dof()) {
            return Err(RobotError {
                at: at("tip_link"),
                message: format!(
                    "the chain from `{}` to `{}` has {} moving joints; an arm needs 6 or 7",
                    raw.base_link,
                    raw.tip_link,
                    chain.dof()
                ),
            });
        }
        narrow_limits(&mut chain, &raw.limits).map_err(|(joint, message)| RobotError {
            at: at(&format!("limits.{joint}")),
            message,
        })?;
        if raw.home.len() != chain.dof() {
            return Err(RobotError {
                at: at("home"),
                message: format!("{} values for {} joints", raw.home.len(), chain.dof()),
            });
        }
        if let Some(m) = chain.outside_limits(&raw.home) {
            return Err(RobotError {
                at: at("home"),
                message: m,
            });
        }
        for (i, j) in raw.gripper.joints.iter().enumerate() {
            if !urdf.joints.iter().any(|u| &u.name == j) {
                return Err(RobotError {
                    at: at(&format!("gripper.joints[{i}]")),
                    message: format!("the URDF has no joint `{j}`"),
                });
            }
        }
        if !(raw.gripper.max_opening > 0.0 && raw.gripper.max_opening.is_finite()) {
            return Err(RobotError {
                at: at("gripper.max_opening"),
                message: format!("{}: expected a positive width (m)", raw.gripper.max_opening),
            });
        }
        if raw.gripper.joints.is_empty() && raw.gripper.finger_length.is_none() {
            return Err(RobotError {
                at: at("gripper"),
                message: "an arm without finger joints needs `finger_length` for its kinematic \
                          fingers"
                    .into(),
            });
        }
        let tcp = raw.tcp.clone().unwrap_or(TcpSpec {
            xyz: [0.0; 3],
            rpy: [0.0; 3],
        });
        let packages = raw
            .packages
            .iter()
            .map(|(k, v)| (k.clone(), dir.join(v)))
            .collect();
        let robot = Robot {
            name: raw.name,
            file: path.to_path_buf(),
            urdf_file,
            urdf,
            chain,
            tcp: Isometry3::from_parts(
                Translation3::new(tcp.xyz[0], tcp.xyz[1], tcp.xyz[2]),
                UnitQuaternion::from_euler_angles(tcp.rpy[0], tcp.rpy[1], tcp.rpy[2]),
            ),
            home: raw.home,
            gripper: raw.gripper,
            packages,
            files,
        };
        robot.check_meshes()?;
        Ok(robot)
    }

    /// Loads the robot of a folder held in memory (files a browser opened, a package's files):
    /// each file's path in the folder with its bytes.
    ///
    /// The robot file is the folder's `robot.json` nearest its top, or else the one `.json` file
    /// nearest the top that names a `urdf`.
    pub fn from_folder(files: Vec<(String, Vec<u8>)>) -> Result<Robot, RobotError> {
        let depth = |p: &str| p.matches('/').count();
        let named = |p: &str| p == "robot.json" || p.ends_with("/robot.json");
        let mut candidates: Vec<&str> = files
            .iter()
            .map(|(p, _)| p.as_str())
            .filter(|p| named(p))
            .collect();
        if candidates.is_empty() {
            candidates = files
                .iter()
                .filter(|(p, b)| {
                    p.ends_with(".json")
                        && serde_json::from_slice::<serde_json::Value>(b)
                            .is_ok_and(|v| v.get("urdf").is_some())
                })
                .map(|(p, _)| p.as_str())
                .collect();
        }
        let top = candidates.iter().map(|p| depth(p)).min();
        let at_top: Vec<&str> = candidates
            .into_iter()
            .filter(|p| Some(depth(p)) == top)
            .collect();
        let file = match at_top.as_slice() {
            [one] => one.to_string(),
            [] => {
                return Err(RobotError {
                    at: "robot folder".into(),
                    message: format!(
                        "no robot.json (nor a .json file naming a `urdf`) among its {} files",
                        files.len()
                    ),
                })
            }
            many => {
                return Err(RobotError {
                    at: "robot folder".into(),
                    message: format!(
                        "{} robot files side by side ({}): name one robot.json",
                        many.len(),
                        many.join(", ")
                    ),
                })
            }
        };
        Robot::load_from(Path::new(&file), RobotFiles::memory(files))
    }

    /// The TCP in the base link's frame for joint vector `q`; refused when `q` has the wrong
    /// length or lies outside the joint limits.
    pub fn tcp_pose(&self, q: &[f64]) -> Result<Isometry3<f64>, String> {
        self.chain.check_joints(q)?;
        Ok(self.chain.tip_frame(q) * self.tcp)
    }

    /// Where a mesh `filename` of the URDF is on disk: `package://NAME/rest` through `packages`,
    /// `file://path` as is, anything else relative to the URDF's folder.
    pub fn mesh_path(&self, filename: &str) -> Result<PathBuf, String> {
        if let Some(rest) = filename.strip_prefix("package://") {
            let (name, rest) = rest.split_once('/').unwrap_or((rest, ""));
            let dir = self.packages.get(name).ok_or_else(|| {
                format!(
                    "`{filename}`: no folder for package `{name}` in the robot file's `packages`"
                )
            })?;
            return Ok(dir.join(rest));
        }
        if let Some(p) = filename.strip_prefix("file://") {
            return Ok(PathBuf::from(p));
        }
        Ok(self
            .urdf_file
            .parent()
            .unwrap_or(Path::new("."))
            .join(filename))
    }

    /// Every collision mesh of the chain's links and the gripper resolves to a file that exists.
    fn check_meshes(&self) -> Result<(), RobotError> {
        for link in &self.urdf.links {
            for c in &link.collisions {
                if let Geometry::Mesh { filename, .. } = &c.geometry {
                    let at = format!("{}:{}:1", self.urdf_file.display(), c.line);
                    let p = self.mesh_path(filename).map_err(|m| RobotError {
                        at: at.clone(),
                        message: m,
                    })?;
                    if !self.files.is_file(&p) {
                        return Err(RobotError {
                            at,
                            message: format!(
                                "collision mesh `{filename}`: no file {}",
                                p.display()
                            ),
                        });
                    }
                }
            }
        }
        Ok(())
    }
}

/// Puts the robot file's narrower joint limits (`limits`: joint name → `[lower, upper]`) on the
/// chain; the error names the joint and what is wrong.
fn narrow_limits(
    chain: &mut Chain,
    limits: &BTreeMap<String, [f64; 2]>,
) -> Result<(), (String, String)> {
    for (name, &[lo, hi]) in limits {
        let fail = |m: String| Err((name.clone(), m));
        let Some(j) = chain
            .joints
            .iter_mut()
            .find(|j| j.moves() && &j.name == name)
        else {
            return fail(format!(
                "`{name}` is not a moving joint of the chain from `{}` to `{}`",
                chain.base, chain.tip
            ));
        };
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return fail(format!(
                "[{lo}, {hi}]: expected [lower, upper] with lower < upper"
            ));
        }
        if lo < j.lower || hi > j.upper {
            return fail(format!(
                "[{lo}, {hi}] is not within the URDF's limits [{}, {}]",
                j.lower, j.upper
            ));
        }
        j.lower = lo;
        j.upper = hi;
    }
    Ok(())
}
