//! Closed-loop soak (CI size), determinism and budgets (issue 8, items 2–4).

mod budgets;
mod determinism;
mod run;
