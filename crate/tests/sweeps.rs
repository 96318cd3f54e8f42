//! Sweeps on every core and across machines: `soak`, `bench table1|table2|scaling` and
//! `lfd --perturb` print the same report on one thread and on two, and `--shard K/N` runs
//! joined by `logic-lfd merge` print the whole run's report (wall-clock times aside, which no
//! two runs share); merge refuses shards that do not make one sweep, naming the file.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support::cli::run_cli;

/// Keys of wall-clock times in the commands' JSON.
const TIMING_KEYS: [&str; 12] = [
    "plan_ms",
    "search_ms",
    "bind_ms",
    "first_plan_ms_median",
    "first_plan_ms_p95",
    "search_ms_median",
    "bind_ms_median",
    "lfd_ms",
    "scratch_ms",
    "median_lfd_ms",
    "median_scratch_ms",
    "speedup",
];

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("logic-lfd-sweeps-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn domain_file(name: &str) -> String {
    let p = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../domains/delivery")).join(name);
    p.to_str().unwrap().to_string()
}

/// Runs `logic-lfd args… extra…` and returns its stdout; it must exit with `code`.
fn stdout_of(args: &[&str], extra: &[&str], code: i32) -> String {
    let all: Vec<&str> = args.iter().chain(extra).copied().collect();
    let (c, out, err) = run_cli(&all);
    assert_eq!(c, code, "logic-lfd {all:?}: {err}");
    out
}

/// Runs shards 1/n … n/n of `args` into files of `dir` and merges them (files given last
/// first, so merge has to put them in order) with `merge_extra`: merge's stdout.
fn merged(dir: &Path, args: &[&str], n: usize, merge_extra: &[&str], code: i32) -> String {
    let mut files = Vec::new();
    for k in 1..=n {
        let shard = format!("{k}/{n}");
        let out = stdout_of(args, &["--shard", &shard], 0);
        let file = dir.join(format!("shard-{k}-of-{n}.json"));
        std::fs::write(&file, out).unwrap();
        files.push(file.to_str().unwrap().to_string());
    }
    files.reverse();
    let mut merge: Vec<&str> = vec!["merge"];
    merge.extend(files.iter().map(String::as_str));
    stdout_of(&merge, merge_extra, code)
}

/// `json` without its wall-clock times.
fn untimed(json: &str) -> Value {
    fn strip(v: &mut Value) {
        match v {
            Value::Object(m) => {
                m.retain(|k, _| !TIMING_KEYS.contains(&k.as_str()));
                m.values_mut().for_each(strip);
            }
            Value::Array(a) => a.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut v: Value = serde_json::from_str(json).unwrap();
    strip(&mut v);
    v
}

/// Text without its wall-clock times: numbers of three decimals (the milliseconds of Table I,
/// the scaling study and the perturbation study) and of one decimal before `×` (time ratios)
/// become `#`, with the spaces that align them; the study's `median ms:` line goes.
fn untimed_text(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines().filter(|l| !l.starts_with("median ms:")) {
        let mut rest = line;
        while let Some(c) = rest.chars().next() {
            // A '.' after a digit: the length of `.ddd` or of `.d` before `×`, if it is one.
            let timed = (c == '.' && out.ends_with(|p: char| p.is_ascii_digit()))
                .then(|| {
                    let decimals = rest[1..].bytes().take_while(u8::is_ascii_digit).count();
                    let ratio = decimals == 1 && rest[2..].starts_with('×');
                    (decimals == 3 || ratio).then_some(1 + decimals)
                })
                .flatten();
            if let Some(len) = timed {
                let kept = out.trim_end_matches(|p: char| p.is_ascii_digit());
                out.truncate(kept.trim_end_matches(' ').len());
                out.push_str(" #");
                rest = &rest[len..];
            } else {
                out.push(c);
                rest = &rest[c.len_utf8()..];
            }
        }
        out.push('\n');
    }
    out
}

/// One thread against two, and three shards merged against the whole run, for a command
/// whose report holds no wall-clock time: byte for byte, as text and as JSON.
fn assert_sweep_exact(tag: &str, args: &[&str], text_code: i32) {
    let dir = temp_dir(tag);
    let one = stdout_of(args, &["--threads", "1"], text_code);
    assert!(!one.is_empty());
    assert_eq!(stdout_of(args, &["--threads", "2"], text_code), one);
    assert_eq!(merged(&dir, args, 3, &[], text_code), one);
    let json = stdout_of(args, &["--json", "--threads", "2"], text_code);
    assert_eq!(
        stdout_of(args, &["--json", "--threads", "1"], text_code),
        json
    );
    assert_eq!(merged(&dir, args, 3, &["--json"], text_code), json);
    std::fs::remove_dir_all(dir).ok();
}

/// The same for a command whose report holds wall-clock times: JSON without them, text with
/// them masked.
fn assert_sweep_same_untimed(tag: &str, args: &[&str]) {
    let dir = temp_dir(tag);
    let json = untimed(&stdout_of(args, &["--json", "--threads", "1"], 0));
    assert_eq!(
        untimed(&stdout_of(args, &["--json", "--threads", "2"], 0)),
        json
    );
    assert_eq!(untimed(&merged(&dir, args, 3, &["--json"], 0)), json);
    let text = untimed_text(&stdout_of(args, &["--threads", "1"], 0));
    assert_eq!(untimed_text(&stdout_of(args, &["--threads", "2"], 0)), text);
    assert_eq!(untimed_text(&merged(&dir, args, 3, &[], 0)), text);
    std::fs::remove_dir_all(dir).ok();
}

/// Six episodes; seed 5 makes episodes 1 and 2 fail legitimately, in different shards, so the
/// report's list of proofs shows whether episodes are joined in their order.
const SOAK: [&str; 7] = [
    "soak",
    "--episodes",
    "6",
    "--seed",
    "5",
    "--max-disturbances",
    "12",
];

#[test]
fn soak_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let text = stdout_of(&SOAK, &[], 0);
    assert!(
        text.contains("legitimate: episode 1 ") && text.contains("legitimate: episode 2 "),
        "the sweep no longer has its two legitimate failures:\n{text}"
    );
    assert_sweep_exact("soak", &SOAK, 0);
}

#[test]
fn table2_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let args = [
        "bench",
        "table2",
        "--trials",
        "2",
        "--seed",
        "1",
        "--benchmarks",
        "b1,b2",
    ];
    assert_sweep_exact("table2", &args, 0);
    let dir = temp_dir("table2-md");
    let markdown = stdout_of(&args, &["--markdown"], 0);
    assert_eq!(merged(&dir, &args, 2, &["--markdown"], 0), markdown);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn table1_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let args = [
        "bench",
        "table1",
        "--tasks",
        "3",
        "--seed",
        "1",
        "--benchmarks",
        "b1,b3",
    ];
    assert_sweep_same_untimed("table1", &args);
}

#[test]
fn scaling_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let args = [
        "bench", "scaling", "--blocks", "4,5", "--tasks", "2", "--seed", "1",
    ];
    assert_sweep_same_untimed("scaling", &args);
    let dir = temp_dir("scaling-svg");
    let svg = dir.join("merged.svg");
    merged(&dir, &args, 2, &["--svg", svg.to_str().unwrap()], 0);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn perturbation_study_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let (d, p, m) = (
        domain_file("domain.pddl"),
        domain_file("problem.pddl"),
        domain_file("demo.plan"),
    );
    let args = ["lfd", &d, &p, &m, "--perturb", "5", "--seed", "3"];
    assert_sweep_same_untimed("perturb", &args);
}

/// `merge`'s error for `files` (exit 2, nothing on stdout).
fn merge_error(files: &[&Path]) -> String {
    let mut args = vec!["merge"];
    args.extend(files.iter().map(|f| f.to_str().unwrap()));
    let (code, out, err) = run_cli(&args);
    assert_eq!(code, 2, "{args:?}: {out}");
    assert!(out.is_empty(), "{out}");
    err
}

#[test]
fn merge_refuses_shards_that_do_not_make_one_sweep() {
    let dir = temp_dir("merge-errors");
    let shard = |args: &[&str], k_n: &str, name: &str| {
        let file = dir.join(name);
        std::fs::write(&file, stdout_of(args, &["--shard", k_n], 0)).unwrap();
        file
    };
    let soak = ["soak", "--episodes", "4", "--seed", "3"];
    let (s1, s2, s3) = (
        shard(&soak, "1/3", "s1.json"),
        shard(&soak, "2/3", "s2.json"),
        shard(&soak, "3/3", "s3.json"),
    );
    let other_seed = shard(
        &["soak", "--episodes", "4", "--seed", "4"],
        "2/3",
        "seed4.json",
    );
    let other_n = shard(&soak, "2/4", "n4.json");
    let table2 = ["bench", "table2", "--trials", "1", "--benchmarks", "b1"];
    let t2 = shard(&table2, "2/3", "t2.json");

    let err = merge_error(&[&s1, &s3]);
    assert!(err.contains("shard 2/3 missing"), "{err}");
    let err = merge_error(&[&s1, &s2, &s2, &s3]);
    assert!(err.contains("shard 2/3 given twice"), "{err}");
    let err = merge_error(&[&s1, &other_seed, &s3]);
    assert!(
        err.contains("seed4.json: not the same sweep") && err.contains("seed: 4 here, 3 there"),
        "{err}"
    );
    let err = merge_error(&[&s1, &other_n, &s3]);
    assert!(err.contains("n4.json: shard 2/4"), "{err}");
    let err = merge_error(&[&s1, &t2, &s3]);
    assert!(
        err.contains("t2.json: a `bench table2` shard") && err.contains("`soak` shard"),
        "{err}"
    );

    // A shard whose records are not its own items, and files that are no shard files.
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&s2).unwrap()).unwrap();
    v["records"][0]["index"] = 0.into();
    let moved = dir.join("moved.json");
    std::fs::write(&moved, v.to_string()).unwrap();
    let err = merge_error(&[&s1, &moved, &s3]);
    assert!(err.contains("moved.json: holds item 0"), "{err}");
    v["records"] = Value::Array(vec![]);
    let empty = dir.join("empty.json");
    std::fs::write(&empty, v.to_string()).unwrap();
    let err = merge_error(&[&s1, &empty, &s3]);
    assert!(err.contains("empty.json: holds 0 of the 1 items"), "{err}");
    let text = dir.join("report.txt");
    std::fs::write(&text, stdout_of(&soak, &[], 0)).unwrap();
    let err = merge_error(&[&text]);
    assert!(err.contains("report.txt: not a shard file"), "{err}");
    let err = merge_error(&[&dir.join("absent.json")]);
    assert!(err.contains("absent.json: cannot read"), "{err}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn bad_shard_and_thread_counts_are_refused_by_name() {
    for (flag, value, why) in [
        ("--shard", "0/3", "shards count from 1"),
        ("--shard", "4/3", "K is larger than N"),
        ("--shard", "a/b", "expected K/N"),
        ("--shard", "3", "expected K/N"),
        ("--threads", "0", "threads ≥ 1"),
    ] {
        let (code, out, err) = run_cli(&["soak", "--episodes", "1", flag, value]);
        assert_eq!(code, 2, "{flag} {value}: {out}");
        assert!(out.is_empty(), "{out}");
        assert!(
            err.contains(flag) && err.contains(why),
            "{flag} {value}: {err}"
        );
    }
}
