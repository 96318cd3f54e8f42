//! The collision part of `logic-lfd robot check`: each link's shapes with their sizes, the
//! self-collision pairs and what touches at the home posture.

use logic_lfd::sim::{PairExclusion, Robot, RobotCollision, ShapeKind};
use serde::Serialize;

/// One collision shape as `robot check --json` prints it.
#[derive(Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub(crate) enum ShapeRow {
    Box {
        size: [f64; 3],
    },
    Cylinder {
        radius: f64,
        length: f64,
    },
    Sphere {
        radius: f64,
    },
    Hull {
        file: String,
        vertices: usize,
        aabb_min: [f64; 3],
        aabb_max: [f64; 3],
    },
}

impl ShapeRow {
    fn of(k: &ShapeKind) -> ShapeRow {
        match k {
            ShapeKind::Box { size } => ShapeRow::Box { size: *size },
            ShapeKind::Cylinder { radius, length } => ShapeRow::Cylinder {
                radius: *radius,
                length: *length,
            },
            ShapeKind::Sphere { radius } => ShapeRow::Sphere { radius: *radius },
            ShapeKind::Hull {
                file,
                vertices,
                aabb,
            } => ShapeRow::Hull {
                file: file.display().to_string(),
                vertices: *vertices,
                aabb_min: aabb.0,
                aabb_max: aabb.1,
            },
        }
    }

    /// One line of text: kind and size.
    pub(crate) fn text(&self) -> String {
        match self {
            ShapeRow::Box { size } => format!("box {} × {} × {} m", size[0], size[1], size[2]),
            ShapeRow::Cylinder { radius, length } => {
                format!("cylinder r {radius} m, length {length} m")
            }
            ShapeRow::Sphere { radius } => format!("sphere r {radius} m"),
            ShapeRow::Hull {
                file,
                vertices,
                aabb_min: lo,
                aabb_max: hi,
            } => format!(
                "hull of {}: {vertices} vertices, {:.3} × {:.3} × {:.3} m",
                file.rsplit(['/', '\\']).next().unwrap_or(file),
                hi[0] - lo[0],
                hi[1] - lo[1],
                hi[2] - lo[2]
            ),
        }
    }
}

/// A pair of links and a distance (m; negative or depth as the field says).
#[derive(Serialize)]
pub(crate) struct PairRow {
    links: [String; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    metres: Option<f64>,
}

/// Self-collision at home: which pairs are checked and which touch.
#[derive(Serialize)]
pub(crate) struct SelfCollisionRow {
    /// Number of link pairs checked.
    checked_pairs: usize,
    /// Pairs left out and why (`adjacent`, `touch at home`).
    excluded_pairs: Vec<PairRow>,
    /// Checked pairs touching at home with the gripper half open: `metres` is the depth.
    at_home: Vec<PairRow>,
    /// The closest checked pair at home: `metres` is their distance.
    closest_at_home: Option<PairRow>,
}

/// A link of the collision model with its shapes.
pub(crate) struct ModelLink {
    pub(crate) name: String,
    pub(crate) shapes: Vec<ShapeRow>,
}

/// The collision model's links with their shapes, and self-collision at home.
pub(crate) fn collision_summary(r: &Robot) -> Result<(Vec<ModelLink>, SelfCollisionRow), String> {
    let m = RobotCollision::new(r).map_err(|e| e.to_string())?;
    let links = m
        .links()
        .iter()
        .map(|l| ModelLink {
            name: l.name.clone(),
            shapes: l.shapes.iter().map(|s| ShapeRow::of(&s.kind)).collect(),
        })
        .collect();
    let pair = |a: &str, b: &str, reason, metres| PairRow {
        links: [a.to_string(), b.to_string()],
        reason,
        metres,
    };
    let half = 0.5 * r.gripper.max_opening;
    let row = SelfCollisionRow {
        checked_pairs: m.checked_pairs().len(),
        excluded_pairs: m
            .excluded_pairs()
            .into_iter()
            .map(|(a, b, why)| {
                let reason = match why {
                    PairExclusion::Adjacent => "adjacent",
                    PairExclusion::TouchAtHome => "touch at home",
                };
                pair(a, b, Some(reason), None)
            })
            .collect(),
        at_home: m
            .self_collisions(&r.home, half)?
            .iter()
            .map(|(a, b, d)| pair(a, b, None, Some(*d)))
            .collect(),
        closest_at_home: m
            .closest_pair(&r.home, half)?
            .map(|(a, b, d)| pair(&a, &b, None, Some(d))),
    };
    Ok((links, row))
}

/// The text lines of the self-collision report.
pub(crate) fn print_self_collision(s: &SelfCollisionRow) {
    let count = |reason: &str| {
        s.excluded_pairs
            .iter()
            .filter(|p| p.reason == Some(reason))
            .count()
    };
    println!(
        "  self-collision: {} link pairs checked ({} adjacent, {} touching at home left out)",
        s.checked_pairs,
        count("adjacent"),
        count("touch at home")
    );
    let names = |p: &PairRow| format!("{}–{}", p.links[0], p.links[1]);
    if s.at_home.is_empty() {
        let closest = s.closest_at_home.as_ref().map_or(String::new(), |p| {
            format!(
                " (closest: {}, {:.1} mm)",
                names(p),
                1000.0 * p.metres.unwrap_or(0.0)
            )
        });
        println!("  no self-collision at home{closest}");
    } else {
        for p in &s.at_home {
            println!(
                "  self-collision at home: {}, {:.1} mm deep",
                names(p),
                1000.0 * p.metres.unwrap_or(0.0)
            );
        }
    }
    for p in s
        .excluded_pairs
        .iter()
        .filter(|p| p.reason == Some("touch at home"))
    {
        println!("  touching at home, not checked: {}", names(p));
    }
}
