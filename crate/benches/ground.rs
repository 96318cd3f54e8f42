//! Parse + ground the largest IPC problems of each family (`cargo bench --bench ground`).
#![allow(missing_docs)] // criterion_group! generates undocumented items

use criterion::{criterion_group, criterion_main, Criterion};
use logic_lfd::pddl::{parse_domain, parse_problem};
use logic_lfd::plan::ground;

fn ipc(dir: &str, file: &str) -> (String, String) {
    let base = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ipc/");
    let read = |f: &str| std::fs::read_to_string(format!("{base}{dir}/{f}")).unwrap();
    (read("domain.pddl"), read(file))
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("parse+ground");
    g.sample_size(20);
    for (dir, file) in [
        ("blocks-typed", "probblocks-50-0.pddl"),
        ("depot-typed", "p22.pddl"),
        ("logistics00", "probLOGISTICS-15-1.pddl"),
        ("gripper", "prob20.pddl"),
    ] {
        let (dt, pt) = ipc(dir, file);
        let d = parse_domain(&dt, "domain.pddl").unwrap();
        let p = parse_problem(&pt, file, &d).unwrap();
        let t = ground(&d, &p).unwrap();
        eprintln!(
            "{dir}/{file}: {} facts, {} operators",
            t.facts.len(),
            t.operators.len()
        );
        g.bench_function(format!("{dir}/{file}"), |b| {
            b.iter(|| {
                let d = parse_domain(&dt, "domain.pddl").unwrap();
                let p = parse_problem(&pt, file, &d).unwrap();
                ground(&d, &p).unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
