//! Checks of a task folder before anything runs: the scene names exactly the problem's
//! physical objects and shows what its `:init` states, every block and hook lies within an
//! arm's reach, and every block has room around it for a grasp from above. Each finding names
//! the file, where in it (JSON path or `line:col`) and what is wrong.
//!
//! [`check_names`] is what a session refuses a folder for (a scene that contradicts its problem
//! cannot run); [`check_sources`] adds the layout advice of `logic-lfd scene check`.

mod finding;
mod layout;
mod names;

pub use finding::Finding;
pub use layout::MIN_GAP_MM;

use crate::sim::BenchmarkSources;

/// The findings a task must not start with: files that do not parse, scene objects the
/// problem does not declare, physical problem objects the scene lacks, and a scene that does
/// not show what `:init` states.
pub fn check_names(sources: &BenchmarkSources) -> Vec<Finding> {
    let loaded = match names::load(sources) {
        Ok(l) => l,
        Err(f) => return vec![f],
    };
    let found = names::check_names(&loaded, sources);
    if !found.is_empty() {
        // With the names wrong, every fact about them differs too: say the names first.
        return found;
    }
    names::check_init(&loaded, sources)
}

/// [`check_names`] of files that parse (empty when one does not: its reader says why).
pub fn check_scene_against_problem(sources: &BenchmarkSources) -> Vec<Finding> {
    match names::load(sources) {
        Ok(l) => {
            let found = names::check_names(&l, sources);
            if found.is_empty() {
                names::check_init(&l, sources)
            } else {
                found
            }
        }
        Err(_) => vec![],
    }
}

/// Every check: [`check_names`], then bodies no arm can work where they lie and blocks too
/// close to another body for a grasp from above.
pub fn check_sources(sources: &BenchmarkSources) -> Vec<Finding> {
    let mut out = check_names(sources);
    let Ok(loaded) = names::load(sources) else {
        return out;
    };
    let scene_file = sources.file("scene.json");
    out.extend(layout::check_reach(
        &loaded.world,
        &loaded.snapshot,
        &scene_file,
    ));
    out.extend(layout::check_grasp_room(
        &loaded.world,
        &loaded.snapshot,
        &scene_file,
    ));
    out
}
