//! Closed-loop soak (CI size), determinism and budgets.

mod budgets;
mod determinism;
mod run;
