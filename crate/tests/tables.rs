//! Table I as the CLI runs it, on a few tasks: Logic-LfD's success is its own when the TAMP
//! fallback is off, every first plan's time splits into search and binding, and the markdown
//! says which way the fallback was set.

use logic_lfd::experiments::tables::table1;
use logic_lfd::lfd::session::SessionParams;
use logic_lfd::lfd::Method;
use logic_lfd::plan::Clock;
use logic_lfd::sim::benchmark::Benchmark;

/// A clock that moves on by a millisecond every time it is read, so every timed span is
/// non-zero and search and binding get different shares.
struct Ticking(std::cell::Cell<f64>);

impl Clock for Ticking {
    fn now_secs(&self) -> f64 {
        let t = self.0.get() + 1e-3;
        self.0.set(t);
        t
    }
}

fn run(tamp_fallback: bool) -> logic_lfd::experiments::tables::Table1 {
    let mut params = SessionParams::default();
    params.control.tamp_fallback = tamp_fallback;
    let clock = Ticking(std::cell::Cell::new(0.0));
    table1(&[Benchmark::B1], 4, 1, params, &clock, &mut |_| {}).expect("table I runs")
}

#[test]
fn table1_counts_logic_lfd_alone_and_splits_planning_time() {
    let t = run(false);
    assert!(!t.tamp_fallback);
    assert_eq!(t.cells.len(), 4, "linear, tamp and Logic-LfD in both modes");
    for c in &t.cells {
        assert_eq!(c.tasks, 4);
        assert_eq!(c.fallbacks, 0, "{}: the fallback is off", c.method_label());
        if c.method == Method::Linear {
            continue;
        }
        assert_eq!(c.plan_ms.len(), 4, "{}", c.method_label());
        assert_eq!(c.search_ms.len(), 4);
        assert_eq!(c.bind_ms.len(), 4);
        for ((p, s), b) in c.plan_ms.iter().zip(&c.search_ms).zip(&c.bind_ms) {
            assert!(
                (s + b - p).abs() < 1e-6,
                "search + binding = first-plan time"
            );
            assert!(
                *s > 0.0 && *b > 0.0,
                "{}: search {s} ms, binding {b} ms",
                c.method_label()
            );
        }
        assert_eq!(c.successes, 4, "{}: {:?}", c.method_label(), c.failures);
    }
    let md = t.markdown();
    assert!(md.contains("TAMP fallback off"), "{md}");
    assert!(
        md.contains("| logic-lfd (paper) | B1 | 100 % (4/4) |"),
        "{md}"
    );
    assert!(md
        .lines()
        .any(|l| l.starts_with("| logic-lfd (paper)") && l.contains("| off |")));
}

#[test]
fn table1_with_the_fallback_reports_its_count() {
    let t = run(true);
    assert!(t.tamp_fallback);
    let md = t.markdown();
    assert!(md.contains("TAMP fallback on"), "{md}");
    let row = md
        .lines()
        .find(|l| l.starts_with("| logic-lfd (paper)"))
        .expect("a Logic-LfD row");
    let cell = t
        .cells
        .iter()
        .find(|c| c.method_label() == "logic-lfd (paper)")
        .unwrap();
    assert!(row.contains(&format!("| {} |", cell.fallbacks)), "{row}");
}
