//! TAMP: the retry loop's bans, the streams (certified motions, obstructions, placements) and TAMP
//! from scratch. What the executor does with the streams' bindings is tested in `exec`.

mod bans;
mod streams;
