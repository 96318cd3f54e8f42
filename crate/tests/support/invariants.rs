//! The world's invariants as the closed-loop tests hold them: every violation counts except the
//! carried hook sweeping through the shelf's edge, and only to a stated depth.

use logic_lfd::sim::BodyKind;
use logic_lfd::sim::{Violation, World};

/// Deepest the hook may pass through the shelf (m). The hook's stroke along the shelf edge is
/// planned on the blade's centre line and the blade's corner may clip the board's edge; any
/// other body, or a deeper cut, is a real violation.
pub(crate) const HOOK_SHELF_DEPTH: f64 = 0.005;

/// Whether `v` is the one tolerated contact: the hook in the shelf within [`HOOK_SHELF_DEPTH`].
pub(crate) fn tolerated(world: &World, v: &Violation) -> bool {
    let Violation::Interpenetration { a, b, depth } = v else {
        return false;
    };
    let kinds = (world.body_kind(a), world.body_kind(b));
    matches!(
        kinds,
        (Some(BodyKind::Hook), Some(BodyKind::Shelf))
            | (Some(BodyKind::Shelf), Some(BodyKind::Hook))
    ) && *depth <= HOOK_SHELF_DEPTH
}

/// The world's violations that are not [`tolerated`] (empty when every invariant holds).
pub(crate) fn broken(world: &World) -> Vec<Violation> {
    match world.check_invariants() {
        Ok(()) => Vec::new(),
        Err(v) => v.into_iter().filter(|x| !tolerated(world, x)).collect(),
    }
}
