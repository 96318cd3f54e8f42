//! LQT-CP case JSON (`lqt::CaseInput::from_json_str` + `lqt::run_case`): mutated cases never
//! panic; a refusal names the key path (`reference.mu[3][1]`, `basis.n_fct`) or the syntax
//! error's line and column; an accepted case solves or fails with a typed numerical error.

use logic_lfd::lqt::case::{run_case, CaseInput};
use logic_lfd::lqt::LqtError;
use proptest::prelude::*;

use super::{json_edit, mutate_json, no_panic, runner};

const TOP_KEYS: [&str; 12] = [
    "dim",
    "order",
    "dt",
    "n_steps",
    "r",
    "basis",
    "x0",
    "targets",
    "tracking",
    "reference",
    "feedback",
    "(root)",
];

#[test]
fn mutated_cases_never_panic_and_refusals_name_their_key() {
    let example = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/lqt-cp-example.json"
    ))
    .unwrap();
    runner(1200, 13)
        .run(&prop::collection::vec(json_edit(), 1..4), |edits| {
            let bytes = mutate_json(&example, &edits);
            let text = String::from_utf8_lossy(&bytes).into_owned();
            match no_panic("CaseInput::from_json_str", || {
                CaseInput::from_json_str(&text)
            })? {
                Err(LqtError::Input { key, message }) => {
                    prop_assert!(
                        key.is_empty() || TOP_KEYS.iter().any(|k| key.starts_with(k)),
                        "unlocated key {key:?}: {message}"
                    );
                    prop_assert!(!message.is_empty());
                }
                Err(LqtError::Json { line, column, .. }) => {
                    let lines = text.split('\n').count();
                    prop_assert!(line >= 1 && line <= lines, "line {line} of {lines}");
                    let _ = column;
                }
                Err(e) => prop_assert!(false, "a parse returned a solver error: {e}"),
                Ok(case) => match no_panic("run_case", || run_case(&case))? {
                    Ok(out) => {
                        let _ = out;
                    }
                    Err(LqtError::Singular(_)) | Err(LqtError::NonFinite(_)) => {}
                    Err(e) => prop_assert!(false, "a valid case failed as input: {e}"),
                },
            }
            Ok(())
        })
        .unwrap();
}
