//! Fig. 4: the learned pull stroke passes its via-points with LQT-CP and pulls the block to each
//! goal in the simulator; the classic DMP, which cannot encode via-points, misses them.

use logic_lfd::experiments::fig4::{fig4, plot, PULL_GOAL_TURNS};

/// LQT-CP passes the via-points within this distance (mm): the paper's "goal-level precision".
const VIA_PRECISION_MM: f64 = 5.0;

#[test]
fn lqt_cp_passes_the_pull_via_points_and_reaches_every_goal_where_the_dmp_misses_them() {
    let f = fig4().expect("fig4 runs");
    println!("{}", logic_lfd::experiments::fig4::markdown(&f));
    assert_eq!(f.via_labels, ["top-edge", "bottom-edge"]);
    assert_eq!(f.pull.len(), 2 * PULL_GOAL_TURNS.len());
    for goal in 0..PULL_GOAL_TURNS.len() {
        let row = |m: &str| {
            f.pull
                .iter()
                .find(|r| r.goal == goal && r.method == m)
                .expect("a row per method and goal")
        };
        let (lqt, dmp) = (row("lqt-cp"), row("dmp"));
        assert_eq!(lqt.via_errors_mm.len(), 2);
        for e in &lqt.via_errors_mm {
            assert!(
                *e < VIA_PRECISION_MM,
                "goal {goal}: LQT-CP via error {e} mm"
            );
        }
        assert!(lqt.goal_error_mm < VIA_PRECISION_MM, "goal {goal}: {lqt:?}");
        assert!(
            lqt.reached,
            "goal {goal}: block {} mm off",
            lqt.block_error_mm
        );
        let worst = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        assert!(
            worst(&dmp.via_errors_mm) > 2.0 * worst(&lqt.via_errors_mm).max(1.0),
            "goal {goal}: DMP {:?} vs LQT-CP {:?}",
            dmp.via_errors_mm,
            lqt.via_errors_mm
        );
    }
    // Both methods pick the hook wherever it lies.
    assert_eq!(f.pick.len(), 6);
    for r in &f.pick {
        assert!(
            r.goal_error_mm < 10.0,
            "{} pick {}: {}",
            r.method,
            r.position,
            r.goal_error_mm
        );
    }
    let svg = plot::svg(&f);
    assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    assert_eq!(svg.matches("<text").count(), svg.matches("</text>").count());
}
