//! Logic-LfD on a domain that is not about blocks: the delivery example of `domains/delivery`.
//!
//! ```sh
//! cargo run --release --example your_own_domain
//! ```
//!
//! Reads the domain, the problem and the demonstration (a plan file), then a disturbed state
//! (`disturbed.facts`: a parcel went back to the depot after it was loaded), and prints the
//! demonstration state the plan joins, the new prefix and the merged plan in both modes.

use logic_lfd::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains/delivery");
    let read = |f: &str| Source::read(format!("{dir}/{f}"));
    let lfd = LogicLfd::named(
        &read("domain.pddl")?,
        &read("problem.pddl")?,
        &read("demo.plan")?,
    )?;
    println!(
        "demonstration: {} actions, states L_0 … L_{}",
        lfd.demo_actions().len(),
        lfd.demo_states().len() - 1
    );
    let now = lfd.state_in("disturbed.facts", &read("disturbed.facts")?.text)?;
    match now.logic_in() {
        Some(k) => println!("LogicIn: L_{k} ⊆ S_C, the rest of the demonstration applies"),
        None => println!("LogicIn: no demonstration state holds, one multi-goal search"),
    }
    let config = SearchConfig::new(Algorithm::Astar, HeuristicKind::LmCut);
    for mode in [Mode::Paper, Mode::Prioritised] {
        let plan = now.replan(mode, &config, &NoClock)?;
        let joins = plan
            .k
            .map_or("G directly".to_string(), |k| format!("L_{k}"));
        println!(
            "\n{}: joins {joins} after {} new actions; {} actions, cost {}, {} states expanded",
            mode.as_str(),
            plan.prefix().len(),
            plan.names.len(),
            plan.cost,
            plan.stats.expanded
        );
        for (i, action) in plan.names.iter().enumerate() {
            let tag = if i < plan.prefix_len { "new " } else { "demo" };
            println!("  {tag} {action}");
        }
        // The lifted validator replays the merged plan from S_C, independently of grounding.
        assert!(now.validate(&plan.names)?.is_valid());
    }
    Ok(())
}
