//! `logic-lfd bench planner [DIR…] [--configs ALG:H,…] [--time-limit S] [--max-nodes N]
//! [--markdown]`: runs planner configurations over IPC folders (`domain.pddl` + problem files)
//! and prints, per problem and configuration, the result, plan length, expansions and end-to-end
//! time (parse + ground + search), then totals per configuration and domain.
//!
//! Defaults: every folder of `tests/data/ipc` (the vendored IPC benchmarks), configuration `lazy-gbfs:hff`, 60 s per problem.
//! Every plan found is replayed on the grounded task; an invalid plan is reported and the command
//! exits with 5. Run it in release.
//!
//! `bench table1`, `table2` and `scaling` take `--threads N` and `--shard K/N`
//! ([`crate::sweep`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use logic_lfd::plan::{search, Algorithm, Clock, HeuristicKind, SearchConfig, SearchOutcome, Task};

use crate::cmd_plan::{load, outcome_name, WallClock};
use crate::exit;
use crate::sweep::{print_shard, SweepArgs};

/// `bench scaling`'s name in shard files.
pub const SCALING: &str = "bench scaling";

/// Arguments of `bench`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    which: Which,
}

#[derive(clap::Subcommand)]
enum Which {
    /// Planner configurations over IPC benchmark folders.
    Planner(PlannerArgs),
    /// The paper's Table I: generalisation over random initial states (linear, tamp, logic-lfd).
    Table1(crate::cmd_tables::Table1Args),
    /// The paper's Table II: reactivity to disturbances L1–L4 (linear, rlds, logic-lfd).
    Table2(crate::cmd_tables::Table2Args),
    /// Scaling study: B1 tower tasks with N blocks, first-plan time per method.
    Scaling(ScalingArgs),
    /// The paper's Fig. 4: LQT-CP against the DMP, picking B2's hook and pulling its block.
    Fig4(Fig4Args),
    /// The hot paths of `npm run bench:wasm`, timed natively (best of N after a warm-up).
    WasmRows(crate::cmd_bench_rows::Args),
}

/// Arguments of `bench fig4`.
#[derive(clap::Args)]
pub struct Fig4Args {
    /// Print JSON (with every path) instead of markdown tables.
    #[arg(long)]
    json: bool,
    /// Write an SVG of the figure (view from above) to this file.
    #[arg(long)]
    svg: Option<PathBuf>,
}

fn fig4(a: Fig4Args) -> ExitCode {
    use logic_lfd::experiments::fig4;
    let f = match fig4::fig4() {
        Ok(f) => f,
        Err(e) => {
            eprintln!("bench fig4: {e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    report(
        a.svg.as_deref().map(|p| (p, fig4::plot::svg(&f))),
        a.json,
        &f,
        || fig4::markdown(&f),
    )
}

/// Writes an experiment's SVG (`svg`: the file and the document) and prints its result as JSON
/// or as `markdown`.
fn report<T: serde::Serialize>(
    svg: Option<(&Path, String)>,
    json: bool,
    value: &T,
    markdown: impl FnOnce() -> String,
) -> ExitCode {
    if let Some((path, doc)) = svg {
        if let Err(e) = std::fs::write(path, doc) {
            eprintln!("{}: {e}", path.display());
            return ExitCode::from(exit::BAD_INPUT);
        }
    }
    if json {
        match serde_json::to_string_pretty(value) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("cannot write JSON: {e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    } else {
        print!("{}", markdown());
    }
    ExitCode::from(exit::OK)
}

/// Arguments of `bench scaling`.
#[derive(clap::Args)]
pub struct ScalingArgs {
    /// Comma-separated block counts of B1's generated tower tasks (`sim::block_range`).
    #[arg(long, help = scaling_blocks_help(), value_delimiter = ',',
          default_value = default_scaling_blocks())]
    blocks: Vec<usize>,
    /// Tasks (random L3 initial states) per block count.
    #[arg(long, default_value_t = 50)]
    tasks: usize,
    /// Seed of the tasks and episodes.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Print JSON instead of a markdown table.
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    /// Write an SVG plot of the median first-plan time against N to this file.
    #[arg(long, conflicts_with = "shard")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    sweep: SweepArgs,
}

/// `bench scaling`'s default block counts, comma-separated as the option takes them.
fn default_scaling_blocks() -> &'static str {
    static TEXT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    TEXT.get_or_init(|| {
        logic_lfd::experiments::scaling::DEFAULT_BLOCKS
            .map(|n| n.to_string())
            .join(",")
    })
}

/// Help of `bench scaling --blocks`, with the block counts B1 takes.
fn scaling_blocks_help() -> String {
    use logic_lfd::sim::{block_range, Benchmark};
    match block_range(Benchmark::B1) {
        Ok(r) => format!(
            "Comma-separated block counts (B1: {} to {})",
            r.start(),
            r.end()
        ),
        Err(e) => format!("Comma-separated block counts ({e})"),
    }
}

fn scaling(a: ScalingArgs) -> ExitCode {
    use logic_lfd::experiments::scaling::ScalingSweep;
    let sweep = ScalingSweep {
        blocks: a.blocks,
        tasks: a.tasks,
        seed: a.seed,
    };
    let clock = WallClock::start();
    let indices = a.sweep.indices(sweep.items());
    let tasks = match a.sweep.map(&indices, |i| sweep.run(i, &clock)) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    match a.sweep.shard {
        Some(shard) => print_shard(SCALING, &sweep, sweep.items(), shard, &indices, tasks),
        None => print_scaling(&sweep.report(tasks), a.json, a.svg.as_deref()),
    }
}

/// Prints the scaling study's rows as JSON or markdown, and writes its plot to `svg`.
pub fn print_scaling(
    rows: &[logic_lfd::experiments::scaling::ScalingRow],
    json: bool,
    svg: Option<&Path>,
) -> ExitCode {
    use logic_lfd::experiments::scaling;
    report(
        svg.map(|p| (p, scaling::plot::svg(&scaling::series(rows)))),
        json,
        &rows,
        || scaling::markdown(rows),
    )
}

/// Arguments of `bench planner`.
#[derive(clap::Args)]
pub struct PlannerArgs {
    /// Benchmark folders, each with a `domain.pddl` and problem files (default: tests/data/ipc/*).
    dirs: Vec<PathBuf>,
    /// Comma-separated `algorithm:heuristic` pairs.
    #[arg(long, default_value = "lazy-gbfs:hff", value_delimiter = ',')]
    configs: Vec<String>,
    /// Time limit per problem and configuration, seconds.
    #[arg(long, default_value_t = 60.0)]
    time_limit: f64,
    /// Node (expansion) limit per problem and configuration.
    #[arg(long)]
    max_nodes: Option<u64>,
    /// Only the problems whose file name contains this text.
    #[arg(long)]
    filter: Option<String>,
    /// Print markdown tables (default: the same tables, which are markdown anyway, plus progress
    /// lines on stderr).
    #[arg(long)]
    markdown: bool,
}

/// Runs the subcommand.
pub fn run(args: Args) -> ExitCode {
    match args.which {
        Which::Planner(a) => planner(a),
        Which::Table1(a) => crate::cmd_tables::run_table1(a),
        Which::Table2(a) => crate::cmd_tables::run_table2(a),
        Which::Scaling(a) => scaling(a),
        Which::Fig4(a) => fig4(a),
        Which::WasmRows(a) => crate::cmd_bench_rows::run(a),
    }
}

struct Row {
    domain: String,
    problem: String,
    config: usize,
    status: &'static str,
    length: Option<usize>,
    expanded: u64,
    secs: f64,
}

/// Splits a name into text and number chunks so that `prob10` sorts after `prob9`.
fn natural_key(s: &str) -> Vec<(String, u64)> {
    let mut out = Vec::new();
    let mut text = String::new();
    let mut num: Option<u64> = None;
    for c in s.chars() {
        if let Some(d) = c.to_digit(10) {
            num = Some(num.unwrap_or(0).saturating_mul(10).saturating_add(d as u64));
        } else {
            if let Some(n) = num.take() {
                out.push((std::mem::take(&mut text), n));
            }
            text.push(c);
        }
    }
    out.push((text, num.unwrap_or(0)));
    out
}

fn problems(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let rd = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut v: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|x| x == "pddl")
                && p.file_name().is_some_and(|n| n != "domain.pddl")
        })
        .collect();
    v.sort_by_key(|p| natural_key(&p.file_name().unwrap_or_default().to_string_lossy()));
    Ok(v)
}

fn parse_config(s: &str) -> Result<SearchConfig, String> {
    let (a, h) = s.split_once(':').unwrap_or((s, "blind"));
    let a: Algorithm = a.trim().parse().map_err(|e| format!("--configs: {e}"))?;
    let h: HeuristicKind = h.trim().parse().map_err(|e| format!("--configs: {e}"))?;
    Ok(SearchConfig::new(a, h))
}

/// The folders of `tests/data/ipc` (relative to the working directory, else to the workspace).
fn default_dirs() -> Vec<PathBuf> {
    let here = PathBuf::from("tests/data/ipc");
    let root = if here.is_dir() {
        here
    } else {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/ipc")
    };
    let mut v: Vec<PathBuf> = std::fs::read_dir(&root)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.join("domain.pddl").is_file())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

fn valid(task: &Task, ops: &[usize]) -> bool {
    let mut s = task.init.clone();
    for &o in ops {
        let op = &task.operators[o];
        if !op.applicable(&s) {
            return false;
        }
        s = op.apply(&s);
    }
    task.goal.holds(&s)
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    })
}

fn planner(args: PlannerArgs) -> ExitCode {
    if args.time_limit.is_nan() || args.time_limit < 0.0 {
        eprintln!("--time-limit: expected a non-negative number of seconds");
        return ExitCode::from(exit::BAD_INPUT);
    }
    let mut configs = Vec::new();
    for c in &args.configs {
        match parse_config(c) {
            Ok(mut cfg) => {
                cfg.time_limit_secs = Some(args.time_limit);
                cfg.max_nodes = args.max_nodes;
                configs.push((c.clone(), cfg));
            }
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        }
    }
    let dirs = if args.dirs.is_empty() {
        default_dirs()
    } else {
        args.dirs.clone()
    };
    if dirs.is_empty() {
        eprintln!(
            "bench planner: no benchmark folders: give DIR arguments, each with a domain.pddl and problems, or run in the repository (tests/data/ipc)"
        );
        return ExitCode::from(exit::BAD_INPUT);
    }
    let mut rows = Vec::new();
    let mut invalid = false;
    for dir in &dirs {
        let domain_name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| dir.display().to_string());
        let domain = dir.join("domain.pddl");
        let probs = match problems(dir) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(exit::BAD_INPUT);
            }
        };
        for prob in probs {
            let pname = prob
                .file_stem()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            if args.filter.as_ref().is_some_and(|f| !pname.contains(f)) {
                continue;
            }
            for (ci, (_, cfg)) in configs.iter().enumerate() {
                let clock = WallClock::start();
                let (status, length, expanded) = match load(&domain, &prob) {
                    Err(e) => {
                        eprintln!("{e}");
                        ("bad input", None, 0)
                    }
                    Ok((_, _, task)) => {
                        let r = search(&task, cfg, &clock);
                        let mut status = outcome_name(&r.outcome);
                        if let SearchOutcome::Plan(p) = &r.outcome {
                            if !valid(&task, &p.operators) {
                                status = "INVALID";
                                invalid = true;
                            }
                        }
                        (status, r.stats.plan_length, r.stats.expanded)
                    }
                };
                let secs = clock.now_secs();
                if !args.markdown {
                    eprintln!(
                        "{domain_name}/{pname} {}: {status} len {length:?} expanded {expanded} {secs:.3} s",
                        configs[ci].0
                    );
                }
                rows.push(Row {
                    domain: domain_name.clone(),
                    problem: pname.clone(),
                    config: ci,
                    status,
                    length,
                    expanded,
                    secs,
                });
            }
        }
    }
    print_tables(&rows, &configs, args.time_limit);
    ExitCode::from(if invalid {
        exit::INVALID_PLAN
    } else {
        exit::OK
    })
}

fn print_tables(rows: &[Row], configs: &[(String, SearchConfig)], limit: f64) {
    println!("| domain | problem | config | result | length | expanded | time (s) |");
    println!("|---|---|---|---|---:|---:|---:|");
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {} | {:.3} |",
            r.domain,
            r.problem,
            configs[r.config].0,
            r.status,
            r.length.map_or("–".to_string(), |l| l.to_string()),
            r.expanded,
            r.secs
        );
    }
    println!();
    println!(
        "Totals (time limit {limit} s per problem; times end to end: parse + ground + search):"
    );
    println!();
    println!("| config | domain | solved | median time solved (s) | max time solved (s) | total time (s) |");
    println!("|---|---|---:|---:|---:|---:|");
    let mut domains: Vec<&str> = rows.iter().map(|r| r.domain.as_str()).collect();
    domains.dedup();
    for (ci, (name, _)) in configs.iter().enumerate() {
        for d in &domains {
            let sel: Vec<&Row> = rows
                .iter()
                .filter(|r| r.config == ci && r.domain == *d)
                .collect();
            let solved: Vec<f64> = sel
                .iter()
                .filter(|r| r.status == "solved")
                .map(|r| r.secs)
                .collect();
            let total: f64 = sel.iter().map(|r| r.secs).sum();
            let max = solved
                .iter()
                .copied()
                .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
            println!(
                "| {name} | {d} | {}/{} | {} | {} | {total:.2} |",
                solved.len(),
                sel.len(),
                median(solved.clone()).map_or("–".into(), |m| format!("{m:.4}")),
                max.map_or("–".into(), |m| format!("{m:.3}")),
            );
        }
    }
}
