//! The executor (`lfd::ActionExec`) running single actions in the simulated world: it does
//! what the streams certified, grasps and lifts where a learned path would hit something, and
//! carries and puts down loads from cramped arm postures.

mod certified;
mod grasp;
mod release;
mod skills;
