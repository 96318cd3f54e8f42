//! The motion policy the executor follows and the streams certify: one source for the choices
//! both make, so what the streams certify is what the arm does.

/// Where a joint-space recovery that can take neither of its ways to the roomy solution goes
/// instead: the solution nearest the arm's joints for the first of these fractions of the way
/// from the TCP to the goal that a clear move reaches (the tracker takes it from there).
pub(crate) const NEAR_RECOVERY_FRACTIONS: [f64; 3] = [1.0, 0.5, 0.25];
