//! The skill library: one learned skill per demonstrated action schema and segment, keyed by
//! the domain's names; schemas the demo does not show move as the first demonstrated schema with
//! the same declared motion.

use logic_lfd::lfd::{skill_key, SegmentKind};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

use crate::support::bench::{b1_skills, b2_skills};

fn pose(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
}

#[test]
fn b2_learns_a_skill_per_demonstrated_schema_the_hooks_apart_and_a_via_point_stroke() {
    let skills = b2_skills();
    let keys: Vec<&str> = skills.keys().collect();
    for key in [
        "pick/approach",
        "pick/retreat",
        "pick/approach@hook",
        "place/approach@hook",
        "place-on-shelf/approach",
        "pull/stroke",
    ] {
        assert!(keys.contains(&key), "{key} missing from {keys:?}");
    }
    assert_eq!(skill_key("pull", SegmentKind::Stroke, false), "pull/stroke");
    // The stroke passes its two via-points wherever the stroke lies.
    let (contact, pulled) = (Point3::new(0.6, 0.1, 0.05), Point3::new(0.3, 0.05, 0.05));
    let start = Point3::new(0.62, 0.05, 0.16);
    let plan = skills
        .stroke_plan("pull/stroke", &start, &contact, &pulled)
        .expect("a stroke plan");
    assert_eq!(plan.via_points.len(), 2);
    for v in &plan.via_points {
        let at = plan.trajectory.positions[v.step];
        assert!(
            (at - v.position).norm() < 0.005,
            "{}: {at} vs {}",
            v.label,
            v.position
        );
    }
    assert!((plan.trajectory.positions.last().unwrap() - pulled).norm() < 0.005);
    // The bottom edge is the contact itself, the top edge above it.
    assert!((plan.via_points[1].position - contact).norm() < 0.002);
    assert!(plan.via_points[0].position.z > contact.z + 0.02);
}

#[test]
fn an_undemonstrated_schema_moves_as_the_first_demonstrated_one_with_its_motion() {
    // B1's demo picks and stacks: unstack moves as pick does, place as stack does.
    let skills = b1_skills();
    let start = pose(0.3, 0.0, 0.3);
    let goal = pose(0.5, 0.1, 0.05);
    let anchor = pose(0.5, 0.1, 0.03);
    for (undemonstrated, demonstrated) in [("unstack", "pick"), ("place", "stack")] {
        for segment in [SegmentKind::Approach, SegmentKind::Retreat] {
            let (u, d) = (
                skill_key(undemonstrated, segment, false),
                skill_key(demonstrated, segment, false),
            );
            assert!(skills.has(&u) && skills.has(&d), "{u} / {d}");
            let path = |k: &str| {
                let seg = skills.segment(k, &start, &goal, Some(&anchor), 2);
                (0..seg.len())
                    .map(|t| seg.planned(t))
                    .collect::<Vec<Vector3<f64>>>()
            };
            assert_eq!(path(&u), path(&d));
        }
    }
    assert!(!skills.has("pull/stroke"));
}
