//! LQT-CP case JSON (`lqt::CaseInput::from_json_str` + `lqt::run_case`): mutated cases never
//! panic; a refusal names the key path (`reference.mu[3][1]`, `basis.n_fct`) or the syntax
//! error's line; an accepted case solves or fails with a typed numerical error (oracle:
//! `experiments::fuzz::check`, target `case`).

use logic_lfd::experiments::fuzz::FuzzTarget;

use super::run_target;

#[test]
fn mutated_cases_never_panic_and_refusals_name_their_key() {
    let (accepted, refused) = run_target(FuzzTarget::Case, 1200, 13, 3);
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}
