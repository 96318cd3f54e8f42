//! The demonstration recorder: segmentation of recordings into the domain's actions, refusal of
//! recordings the PDDL model cannot explain, the quick (drag) teaching mode, undo, and the
//! `logic-lfd demo segment` CLI.

use logic_lfd::recorder::synth::{recording_from_demo, Edit};
use logic_lfd::recorder::{
    segment_recording, ArmRef, RawRecording, RawSample, Recorder, RecorderError, RecorderParams,
    RecordingScene,
};
use logic_lfd::sim::benchmark::Benchmark;
use logic_lfd::sim::demo;

fn quick_params() -> RecorderParams {
    RecorderParams {
        learn_skills: false,
        ..RecorderParams::default()
    }
}

fn segment(rec: &RawRecording, b: Benchmark) -> Result<logic_lfd::recorder::Taught, RecorderError> {
    segment_recording(rec, b.domain_pddl(), "domain.pddl", None, quick_params())
}

/// Segmenting a recording replayed from each benchmark's scripted demo gives back its actions.
#[test]
fn segmentation_reproduces_each_scripted_demo() {
    for b in Benchmark::ALL {
        let d = demo::committed(b).unwrap();
        let rec = recording_from_demo(b, &d).unwrap();
        let taught = segment(&rec, b).unwrap_or_else(|e| panic!("{}: {e}", b.id()));
        let got: Vec<&str> = taught.demo.demo.plan();
        assert_eq!(got, d.plan(), "{}", b.id());
        assert_eq!(taught.states.len(), d.actions.len() + 1);
        for g in b.goal() {
            assert!(
                taught.demo.goal.contains(&g.to_string()),
                "{}: goal {g}",
                b.id()
            );
        }
    }
}
