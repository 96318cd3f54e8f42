//! A task folder: the files that define a robot task of the user's own, read from a directory
//! or given by name (the npm package's `files`), turned into the [`BenchmarkSources`] every
//! episode runs on.
//!
//! A folder holds `domain.pddl`, `problem.pddl`, `motions.json`, `scene.json` and a
//! demonstration: `demo.json`, or `expert.json` (the scripted expert's steps, recorded into a
//! `demo.json` on load; a `demo.plan` beside it must list the same actions). `README.md` is
//! optional; other files are ignored.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::benchmark::BenchmarkSources;

/// The files a task folder must hold.
pub const REQUIRED_FILES: [&str; 4] = ["domain.pddl", "problem.pddl", "motions.json", "scene.json"];

/// Every file a task folder may hold, in the order they are read.
pub const FOLDER_FILES: [&str; 8] = [
    "domain.pddl",
    "problem.pddl",
    "motions.json",
    "scene.json",
    "demo.json",
    "expert.json",
    "demo.plan",
    "README.md",
];

/// A task folder's files by name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TaskFolder {
    /// Where the files come from, as messages name it (`./mine`, `domains/sorting`, `upload`).
    pub dir: String,
    /// Text of each file present, by file name (`domain.pddl`, …).
    pub files: BTreeMap<String, String>,
}

/// A task folder that cannot be read or turned into a task: the file at fault and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{path}: {message}")]
pub struct FolderError {
    /// The file (`DIR/scene.json`), with `:line:col` or a JSON path where one is known.
    pub path: String,
    /// What is wrong or missing.
    pub message: String,
}

/// What an episode log keeps of the task folder it ran on: where it was and each file's hash,
/// and the files themselves when the log must replay without the folder (the page's Save).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "wasm-core", derive(tsify::Tsify), tsify(missing_as_null))]
pub struct FolderRecord {
    /// The folder as messages name it.
    pub dir: String,
    /// [`content_hash`] of each file but `README.md`, by file name.
    pub hashes: BTreeMap<String, String>,
    /// The files' text, by name (absent: replay needs the folder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub files: Option<BTreeMap<String, String>>,
}

/// What a folder's file says differs from a record of it (an episode log's hashes).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileDifference {
    /// The file name.
    pub file: String,
    /// Its hash in the record (`None`: the record has no such file).
    pub recorded: Option<String>,
    /// Its hash now (`None`: the folder has no such file).
    pub now: Option<String>,
}

impl TaskFolder {
    /// A folder from files given by name; `dir` names it in messages. A `dir` without a `/` gets
    /// a leading `./`, so it never reads as one of the shipped `domains/`.
    pub fn new(dir: &str, files: BTreeMap<String, String>) -> TaskFolder {
        let dir = dir.trim_end_matches('/');
        let dir = if dir.contains('/') {
            dir.to_string()
        } else {
            format!("./{dir}")
        };
        TaskFolder { dir, files }
    }

    /// Reads the folder files of directory `dir` (those of [`FOLDER_FILES`] it has).
    pub fn read(dir: &Path) -> Result<TaskFolder, FolderError> {
        let label = dir.display().to_string();
        if !dir.is_dir() {
            return Err(FolderError {
                path: label,
                message: "not a directory (a task folder holds domain.pddl, problem.pddl, \
                          motions.json, scene.json and demo.json or expert.json)"
                    .into(),
            });
        }
        let mut files = BTreeMap::new();
        for name in FOLDER_FILES {
            let p = dir.join(name);
            if p.exists() {
                let text = std::fs::read_to_string(&p).map_err(|e| FolderError {
                    path: p.display().to_string(),
                    message: e.to_string(),
                })?;
                files.insert(name.to_string(), text);
            }
        }
        Ok(TaskFolder::new(&label, files))
    }

    /// The path of one of the folder's files, for messages (`./mine/scene.json`).
    pub fn path(&self, file: &str) -> String {
        format!("{}/{file}", self.dir)
    }

    /// The text of `file`, or an error naming it as missing.
    pub fn text(&self, file: &str) -> Result<&str, FolderError> {
        self.files
            .get(file)
            .map(String::as_str)
            .ok_or_else(|| FolderError {
                path: self.path(file),
                message: format!("missing: a task folder holds {}", required_list()),
            })
    }

    /// The task's files: the demonstration is `demo.json`, or recorded from `expert.json` by the
    /// scripted expert (seed 1) when the folder has no `demo.json`.
    pub fn sources(&self) -> Result<BenchmarkSources, FolderError> {
        for f in REQUIRED_FILES {
            self.text(f)?;
        }
        let demo = match self.files.get("demo.json") {
            Some(d) => d.clone(),
            None => self.record_demo(1)?,
        };
        Ok(BenchmarkSources {
            folder: Some(FolderRecord {
                dir: self.dir.clone(),
                hashes: self.hashes(),
                files: None,
            }),
            dir: self.dir.clone(),
            domain: self.text("domain.pddl")?.to_string(),
            problem: self.text("problem.pddl")?.to_string(),
            scene: self.text("scene.json")?.to_string(),
            demo,
            motions: self.text("motions.json")?.to_string(),
        })
    }

    /// Records the folder's demonstration (`demo.json`'s text) from `expert.json` with the
    /// scripted expert in the folder's scene, checking a `demo.plan` beside it lists the same
    /// actions.
    #[cfg(not(first_load))]
    pub fn record_demo(&self, seed: u64) -> Result<String, FolderError> {
        record::record(self, seed)
    }

    /// Recording needs the scripted expert, which the page's first-load module leaves out.
    #[cfg(first_load)]
    pub fn record_demo(&self, _seed: u64) -> Result<String, FolderError> {
        Err(FolderError {
            path: self.path("expert.json"),
            message: "recording a demonstration runs on the page's full module".into(),
        })
    }

    /// A hash of each file (64-bit FNV-1a, hex): what an episode log records of its folder.
    pub fn hashes(&self) -> BTreeMap<String, String> {
        self.files
            .iter()
            .filter(|(name, _)| name.as_str() != "README.md")
            .map(|(name, text)| (name.clone(), content_hash(text)))
            .collect()
    }

    /// The folder an episode log recorded with its files (`None` when it kept only hashes).
    pub fn from_record(record: &FolderRecord) -> Option<TaskFolder> {
        record.files.as_ref().map(|files| TaskFolder {
            dir: record.dir.clone(),
            files: files.clone(),
        })
    }

    /// Refuses the folder when a file differs from `record` (an episode log's), naming each
    /// file with both hashes.
    pub fn check_against(&self, record: &FolderRecord) -> Result<(), FolderError> {
        let d = self.differences(&record.hashes);
        if d.is_empty() {
            return Ok(());
        }
        let hash = |h: &Option<String>| h.clone().unwrap_or_else(|| "no file".into());
        let files: Vec<String> = d
            .iter()
            .map(|d| {
                format!(
                    "{} (episode: {}, now: {})",
                    self.path(&d.file),
                    hash(&d.recorded),
                    hash(&d.now)
                )
            })
            .collect();
        Err(FolderError {
            path: self.dir.clone(),
            message: format!(
                "differs from the folder the episode ran on (from {}): {}",
                record.dir,
                files.join(", ")
            ),
        })
    }

    /// The files whose hash differs from `recorded` (a file on one side only included).
    pub fn differences(&self, recorded: &BTreeMap<String, String>) -> Vec<FileDifference> {
        let now = self.hashes();
        let mut names: Vec<&String> = now.keys().chain(recorded.keys()).collect();
        names.sort();
        names.dedup();
        names
            .into_iter()
            .filter(|n| now.get(*n) != recorded.get(*n))
            .map(|n| FileDifference {
                file: n.clone(),
                recorded: recorded.get(n).cloned(),
                now: now.get(n).cloned(),
            })
            .collect()
    }
}

fn required_list() -> String {
    format!("{} and demo.json or expert.json", REQUIRED_FILES.join(", "))
}

/// 64-bit FNV-1a of `text`, as 16 hex digits: enough to tell that a file changed.
pub fn content_hash(text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.as_bytes() {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

#[cfg(not(first_load))]
mod record {
    use std::sync::Arc;

    use super::{FolderError, TaskFolder};
    use crate::sim::demo::{record_script, ExpertParams, Script};
    use crate::sim::{goal_facts, Motions, World};

    pub(super) fn record(folder: &TaskFolder, seed: u64) -> Result<String, FolderError> {
        let at = |file: &str, message: String| FolderError {
            path: folder.path(file),
            message,
        };
        let expert = folder.text("expert.json").map_err(|_| {
            at(
                "demo.json",
                "missing: give demo.json, or expert.json to record it from".into(),
            )
        })?;
        let pddl = |e: crate::pddl::PddlError| FolderError {
            path: format!("{}:{}:{}", e.file, e.line, e.col),
            message: e.message,
        };
        let domain_file = folder.path("domain.pddl");
        let problem_file = folder.path("problem.pddl");
        let domain =
            crate::pddl::parse_domain(folder.text("domain.pddl")?, &domain_file).map_err(pddl)?;
        let problem =
            crate::pddl::parse_problem(folder.text("problem.pddl")?, &problem_file, &domain)
                .map_err(pddl)?;
        let motions = Motions::parse(
            folder.text("motions.json")?,
            &folder.path("motions.json"),
            &domain,
        )
        .map_err(|e| FolderError {
            path: format!("{}:{}:{}", e.file, e.line, e.column),
            message: format!("{}: {}", e.path, e.message),
        })?;
        let script: Script = crate::sim::parse_json(expert).map_err(|e| FolderError {
            path: folder.path("expert.json"),
            message: e.to_string(),
        })?;
        if let Some(plan) = folder.files.get("demo.plan") {
            check_plan(folder, plan, &script)?;
        }
        let world = World::from_json(folder.text("scene.json")?)
            .map_err(|e| at("scene.json", e.to_string()))?
            .with_motions(Arc::new(motions));
        let goal = goal_facts(&domain, &problem);
        let name = folder.dir.rsplit('/').next().unwrap_or("").to_string();
        let demo = record_script(world, &script, &goal, &name, seed, &ExpertParams::default())
            .map_err(|e| at("expert.json", format!("recording failed: {e}")))?;
        serde_json::to_string(&demo).map_err(|e| at("demo.json", e.to_string()))
    }

    /// An action as `(name arg …)`: lower case, single spaces.
    fn normalize(action: &str) -> String {
        let spaced = action
            .to_ascii_lowercase()
            .replace('(', " ( ")
            .replace(')', " ) ");
        let words: Vec<&str> = spaced.split_whitespace().collect();
        words.join(" ").replace("( ", "(").replace(" )", ")")
    }

    /// A `demo.plan` beside `expert.json` lists the expert's actions, in order.
    fn check_plan(folder: &TaskFolder, plan: &str, script: &Script) -> Result<(), FolderError> {
        let steps: Vec<String> = plan
            .lines()
            .map(|l| l.split(';').next().unwrap_or("").trim())
            .filter(|l| !l.is_empty())
            .map(normalize)
            .collect();
        let expert: Vec<String> = script.steps.iter().map(|s| normalize(&s.action)).collect();
        let refused = |message: String| FolderError {
            path: folder.path("demo.plan"),
            message,
        };
        if let Some(i) = (0..steps.len().min(expert.len())).find(|&i| steps[i] != expert[i]) {
            return Err(refused(format!(
                "step {}: `{}`, but expert.json's step {} is `{}`",
                i + 1,
                steps[i],
                i + 1,
                expert[i]
            )));
        }
        if steps.len() != expert.len() {
            return Err(refused(format!(
                "{} steps, but expert.json has {}",
                steps.len(),
                expert.len()
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped(name: &str) -> TaskFolder {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../domains")
            .join(name);
        TaskFolder::read(&dir).unwrap()
    }

    #[test]
    fn a_missing_file_is_named() {
        let mut f = shipped("b1-paper-naming");
        f.files.remove("scene.json");
        let e = f.sources().unwrap_err();
        assert!(e.path.ends_with("b1-paper-naming/scene.json"), "{e}");
        assert!(e.message.starts_with("missing"), "{e}");
    }

    #[test]
    fn a_bare_name_reads_as_a_relative_folder() {
        let f = TaskFolder::new("mine", BTreeMap::new());
        assert_eq!(f.path("domain.pddl"), "./mine/domain.pddl");
        assert_eq!(TaskFolder::new("a/b/", BTreeMap::new()).dir, "a/b");
    }

    #[test]
    fn hashes_tell_which_file_changed() {
        let f = shipped("b1-paper-naming");
        let recorded = f.hashes();
        let mut g = f.clone();
        g.files.get_mut("scene.json").unwrap().push(' ');
        g.files.remove("expert.json");
        let d = g.differences(&recorded);
        let names: Vec<&str> = d.iter().map(|d| d.file.as_str()).collect();
        assert_eq!(names, ["expert.json", "scene.json"]);
        assert!(d[0].now.is_none() && d[0].recorded.is_some());
        assert!(f.differences(&recorded).is_empty());
    }

    #[test]
    fn expert_json_records_the_demonstration_of_demo_json() {
        let f = shipped("b1-paper-naming");
        let mut g = f.clone();
        g.files.remove("demo.json");
        let recorded = g.sources().unwrap().demo;
        assert_eq!(recorded.trim(), f.files["demo.json"].trim());
    }

    #[test]
    fn a_broken_domain_met_while_recording_is_located() {
        let mut f = shipped("b1-paper-naming");
        f.files.remove("demo.json");
        let d = f.files.get_mut("domain.pddl").unwrap();
        *d = d.replacen("(:action", "(:actoin", 1);
        let e = f.record_demo(1).unwrap_err();
        assert!(e.path.contains("b1-paper-naming/domain.pddl:"), "{e}");
        assert_eq!(e.path.matches("domain.pddl").count(), 1, "{e}");
    }

    #[test]
    fn a_demo_plan_that_disagrees_with_the_expert_is_refused() {
        let mut f = shipped("b1-paper-naming");
        f.files.remove("demo.json");
        f.files.insert(
            "demo.plan".into(),
            "(pick-up c panda)\n(put-on c a panda)\n".into(),
        );
        let e = f.sources().unwrap_err();
        assert!(e.path.ends_with("demo.plan"), "{e}");
        assert!(e.message.contains("step 2"), "{e}");
    }
}
