//! A task folder is an input wherever a benchmark is: `run --domain DIR` at every level, its
//! episodes replayed from the folder's path, from `--domain` or from the files the log carries
//! (a changed file named with both hashes), `soak --domain DIR` on any number of threads and in
//! shards, `demo record DIR` and `demo segment --domain DIR`. The folder is a copy of
//! `domains/b1-paper-naming` outside the repository, run by a bare relative name.

use std::path::{Path, PathBuf};

use logic_lfd::lfd::EpisodeLog;
use logic_lfd::sim::{content_hash, TaskFolder};

use crate::support::cli::{refused_in, run_cli_in};

const SHIPPED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../domains/b1-paper-naming");
const NAME: &str = "b1-paper-naming";

/// A fresh directory holding a copy of the shipped folder under its own name.
fn workdir(tag: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("logic-lfd-folder-cli-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy_folder(Path::new(SHIPPED), &dir.join(NAME));
    dir
}

fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

/// Stdout of a run that must exit with `code`.
fn stdout_in(cwd: &Path, args: &[&str], code: i32) -> String {
    let (c, out, err) = run_cli_in(cwd, args);
    assert_eq!(c, code, "logic-lfd {args:?}: {err}");
    out
}

fn append(file: &Path, text: &str) {
    let mut t = std::fs::read_to_string(file).unwrap();
    t.push_str(text);
    std::fs::write(file, t).unwrap();
}

#[test]
fn a_task_folder_runs_at_every_level_under_a_bare_name() {
    let dir = workdir("levels");
    for level in ["l1", "l2", "l3", "l4"] {
        let out = stdout_in(
            &dir,
            &["run", "--domain", NAME, "--level", level, "--seed", "2"],
            0,
        );
        assert!(
            out.starts_with(&format!("folder ./{NAME}  level {level} ")),
            "{out}"
        );
        assert!(out.contains("success: true"), "{level}: {out}");
        assert!(out.contains("disturbance: "), "{level}: {out}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_bare_folder_name_is_never_named_as_a_shipped_domain() {
    let dir = workdir("names");
    let err = refused_in(&dir, &["run", "--domain", "nope"]);
    assert!(err.starts_with("./nope: not a directory"), "{err}");
    assert!(!err.contains("domains/"), "{err}");

    // A folder brings its own scene: a missing one is named, no benchmark's stands in.
    copy_folder(&dir.join(NAME), &dir.join("mine"));
    std::fs::remove_file(dir.join("mine/scene.json")).unwrap();
    let err = refused_in(&dir, &["run", "--domain", "mine", "--level", "l1"]);
    assert!(err.starts_with("./mine/scene.json: missing"), "{err}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_benchmark_is_refused_beside_a_task_folder() {
    let dir = workdir("benchmark");
    let err = refused_in(&dir, &["run", "--benchmark", "b2", "--domain", NAME]);
    assert!(
        err.contains(
            "a task folder's own scene and the disturbances drawn in it define the episode"
        ),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_folder_episode_replays_from_its_path_from_domain_and_from_the_files_it_carries() {
    let dir = workdir("replay");
    let episode = stdout_in(
        &dir,
        &[
            "run", "--domain", NAME, "--level", "l3", "--seed", "5", "--json",
        ],
        0,
    );
    std::fs::write(dir.join("ep.json"), &episode).unwrap();
    let replay = ["run", "--replay", "ep.json"];
    assert!(stdout_in(&dir, &replay, 0).starts_with("replayed exactly: "));

    // Moved away: the recorded path no longer holds it; --domain gives it.
    std::fs::rename(dir.join(NAME), dir.join("moved")).unwrap();
    let err = refused_in(&dir, &replay);
    assert!(
        err.contains(&format!("the task folder ./{NAME}")) && err.contains("--domain"),
        "{err}"
    );
    let from_domain = ["run", "--replay", "ep.json", "--domain", "moved"];
    assert!(stdout_in(&dir, &from_domain, 0).starts_with("replayed exactly: "));

    // The files the log carries replay it with no folder at all.
    let report: serde_json::Value = serde_json::from_str(&episode).unwrap();
    let mut log: EpisodeLog = serde_json::from_value(report["log"].clone()).unwrap();
    let folder = TaskFolder::read(&dir.join("moved")).unwrap();
    log.folder.as_mut().unwrap().files = Some(folder.files.clone());
    std::fs::write(
        dir.join("carried.json"),
        serde_json::to_string(&log).unwrap(),
    )
    .unwrap();
    assert!(
        stdout_in(&dir, &["run", "--replay", "carried.json"], 0).starts_with("replayed exactly: ")
    );

    // A log that says another outcome does not reproduce: exit 5.
    let mut wrong = log.clone();
    wrong.final_facts.push("(on-block a b)".into());
    std::fs::write(
        dir.join("wrong.json"),
        serde_json::to_string(&wrong).unwrap(),
    )
    .unwrap();
    let (code, _, err) = run_cli_in(&dir, &["run", "--replay", "wrong.json"]);
    assert_eq!(code, 5, "{err}");
    assert!(err.contains("the replay differs from the log"), "{err}");

    // A changed problem.pddl is named, with its hash in the episode and now.
    let problem = dir.join("moved/problem.pddl");
    let before = content_hash(&std::fs::read_to_string(&problem).unwrap());
    append(&problem, "\n; edited\n");
    let after = content_hash(&std::fs::read_to_string(&problem).unwrap());
    let err = refused_in(&dir, &from_domain);
    assert!(
        err.contains(&format!(
            "moved/problem.pddl (episode: {before}, now: {after})"
        )),
        "{err}"
    );
    assert!(!err.contains("scene.json"), "{err}");

    // A benchmark's episode is not replayed in a task folder.
    let bench = stdout_in(&dir, &["run", "--benchmark", "b1", "--json"], 0);
    std::fs::write(dir.join("b1.json"), bench).unwrap();
    let err = refused_in(&dir, &["run", "--replay", "b1.json", "--domain", "moved"]);
    assert!(
        err.contains("benchmark b1") && err.contains("drop --domain moved"),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

/// Runs shards 1/2 and 2/2 of `args` (given in reverse order to merge) and merges them.
fn merged(dir: &Path, args: &[&str], extra: &[&str]) -> String {
    let mut files = Vec::new();
    for k in [2, 1] {
        let shard = format!("{k}/2");
        let all: Vec<&str> = args.iter().copied().chain(["--shard", &shard]).collect();
        let file = dir.join(format!("shard-{k}.json"));
        std::fs::write(&file, stdout_in(dir, &all, 0)).unwrap();
        files.push(file.to_str().unwrap().to_string());
    }
    let mut merge: Vec<&str> = vec!["merge"];
    merge.extend(files.iter().map(String::as_str));
    merge.extend(extra);
    stdout_in(dir, &merge, 0)
}

#[test]
fn a_folder_soak_is_the_same_on_any_number_of_threads_and_from_merged_shards() {
    let dir = workdir("soak");
    let args = [
        "soak",
        "--domain",
        NAME,
        "--episodes",
        "4",
        "--seed",
        "3",
        "--max-disturbances",
        "8",
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        args.iter()
            .chain(extra)
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = with(extra);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        stdout_in(&dir, &a, 0)
    };
    let one = run(&["--threads", "1"]);
    assert!(
        one.starts_with(&format!("episodes 4 ({{\"./{NAME}\": 4}})")),
        "{one}"
    );
    assert!(one.contains("replays checked 4: mismatches 0"), "{one}");
    assert_eq!(run(&["--threads", "2"]), one);
    assert_eq!(merged(&dir, &args, &[]), one);
    let json = run(&["--json", "--threads", "1"]);
    assert_eq!(run(&["--json", "--threads", "2"]), json);
    assert_eq!(merged(&dir, &args, &["--json"]), json);
    let report: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(report["params"]["folder"]["dir"], format!("./{NAME}"));

    // Shards of a folder whose file changed between them are not one sweep.
    let first = dir.join("first.json");
    let a: Vec<&str> = args.iter().copied().chain(["--shard", "1/2"]).collect();
    std::fs::write(&first, stdout_in(&dir, &a, 0)).unwrap();
    append(&dir.join(NAME).join("problem.pddl"), "\n; edited\n");
    let second = dir.join("second.json");
    let b: Vec<&str> = args.iter().copied().chain(["--shard", "2/2"]).collect();
    std::fs::write(&second, stdout_in(&dir, &b, 0)).unwrap();
    let err = refused_in(
        &dir,
        &["merge", first.to_str().unwrap(), second.to_str().unwrap()],
    );
    assert!(
        err.contains("second.json: not the same sweep") && err.contains("folder: "),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn demo_record_writes_the_committed_demonstration() {
    let dir = workdir("record");
    let committed = std::fs::read_to_string(Path::new(SHIPPED).join("demo.json")).unwrap();
    let (code, out, err) = run_cli_in(&dir, &["demo", "record", NAME, "-o", "-"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, committed);
    assert!(err.starts_with("stdout: 6 actions, "), "{err}");

    std::fs::remove_file(dir.join(NAME).join("demo.json")).unwrap();
    let out = stdout_in(&dir, &["demo", "record", NAME, "--seed", "1"], 0);
    assert!(
        out.starts_with(&format!("./{NAME}/demo.json: 6 actions, ")) && out.contains(" s), seed 1"),
        "{out}"
    );
    let written = std::fs::read_to_string(dir.join(NAME).join("demo.json")).unwrap();
    assert_eq!(written, committed);

    // Another seed varies the expert's motion, not its actions.
    let other = stdout_in(&dir, &["demo", "record", NAME, "--seed", "2", "-o", "-"], 0);
    assert_ne!(other, committed);

    let err = refused_in(&dir, &["demo", "record", "nope"]);
    assert!(err.starts_with("./nope: not a directory"), "{err}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn demo_segment_reads_a_task_folders_domain_problem_and_motions() {
    let dir = workdir("segment");
    let recording = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/recordings/b1-stack-c-on-d.json"
    );
    let out = stdout_in(
        &dir,
        &[
            "demo",
            "segment",
            recording,
            "--domain",
            NAME,
            "--no-skills",
        ],
        0,
    );
    let demo = logic_lfd::sim::demo::from_json(&out).unwrap();
    assert_eq!(demo.plan(), ["(pick-up c panda)", "(put-on c d panda)"]);

    // The domain file alone does not say what its names mean in a benchmark's scene.
    let domain = format!("{NAME}/domain.pddl");
    let err = refused_in(
        &dir,
        &[
            "demo",
            "segment",
            recording,
            "--domain",
            &domain,
            "--no-skills",
        ],
    );
    assert!(err.contains("the scene does not fit the domain"), "{err}");

    // --motions gives the meaning with a domain file.
    let motions = format!("{NAME}/motions.json");
    let problem = format!("{NAME}/problem.pddl");
    let out = stdout_in(
        &dir,
        &[
            "demo",
            "segment",
            recording,
            "--domain",
            &domain,
            "--problem",
            &problem,
            "--motions",
            &motions,
            "--no-skills",
        ],
        0,
    );
    assert_eq!(
        logic_lfd::sim::demo::from_json(&out).unwrap().plan(),
        demo.plan()
    );
    std::fs::remove_dir_all(dir).ok();
}
