//! `logic-lfd merge SHARD… [--json] [--markdown] [--svg FILE]`: joins the shard files of one
//! sweep (each printed by a run with `--shard K/N`, see [`crate::sweep`]) into the report the
//! whole sweep prints: the same text, `--json`, `--markdown` or `--svg` as the command's, byte
//! for byte apart from wall-clock times, and the same exit code.
//!
//! Before joining, every file is checked, and a failed check is an error naming the file (exit
//! 2): it is a shard file of this layout's version; all come from one program and one sweep (the
//! same command and parameters, the same N and number of items); every shard 1 … N is given
//! exactly once; each holds exactly the items of its slice.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use serde::de::DeserializeOwned;
use serde_json::Value;

use logic_lfd::experiments::scaling::ScalingSweep;
use logic_lfd::experiments::SoakParams;
use logic_lfd::experiments::{Table1Sweep, Table2Sweep};

use crate::exit;
use crate::sweep::{ShardFile, FORMAT, FORMAT_VERSION};
use crate::{cmd_bench, cmd_lfd_perturb, cmd_soak, cmd_tables};

/// Arguments of `merge`.
#[derive(clap::Args)]
pub struct Args {
    /// The shard files of one sweep, in any order.
    #[arg(required = true, value_name = "SHARD")]
    shards: Vec<PathBuf>,
    /// Print JSON, as the command's `--json` does.
    #[arg(long)]
    json: bool,
    /// Print markdown (`bench table1` and `table2`: their default).
    #[arg(long)]
    markdown: bool,
    /// Write the SVG plot, as `bench scaling --svg` does.
    #[arg(long)]
    svg: Option<PathBuf>,
}

/// A shard file as read, with its name.
struct Loaded {
    path: PathBuf,
    file: ShardFile<Value, Value>,
}

impl Loaded {
    fn name(&self) -> String {
        self.path.display().to_string()
    }
}

/// Reads `path` and checks it is a shard file holding exactly the items of its slice.
fn load(path: &Path) -> Result<Loaded, String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    let value: Value = serde_json::from_str(&text).map_err(|e| {
        format!(
            "{name}: not a shard file (not JSON: {e}); shard files are what `--shard K/N` prints"
        )
    })?;
    if value.get("format").and_then(Value::as_str) != Some(FORMAT) {
        return Err(format!(
            "{name}: not a shard file (no \"format\": \"{FORMAT}\"); shard files are what `--shard K/N` prints"
        ));
    }
    match value.get("version").and_then(Value::as_u64) {
        Some(v) if v == u64::from(FORMAT_VERSION) => {}
        v => {
            return Err(format!(
                "{name}: shard file version {}; this logic-lfd reads version {FORMAT_VERSION}",
                v.map_or("missing".into(), |v| v.to_string())
            ))
        }
    }
    let file: ShardFile<Value, Value> =
        serde_json::from_value(value).map_err(|e| format!("{name}: malformed shard file: {e}"))?;
    let (shard, items) = (file.shard, file.items);
    if shard.n == 0 || !(1..=shard.n).contains(&shard.k) {
        return Err(format!(
            "{name}: shard {shard} is not a shard K/N with 1 ≤ K ≤ N"
        ));
    }
    let expected = shard.indices(items);
    for (p, r) in file.records.iter().enumerate() {
        if r.index >= items || !shard.holds(r.index) {
            return Err(format!(
                "{name}: holds item {} which is not an item of shard {shard} of {items}",
                r.index
            ));
        }
        if expected.get(p) != Some(&r.index) {
            let missing = expected.get(p).map_or(r.index, |&i| i);
            return Err(format!(
                "{name}: item {missing} of shard {shard} is missing or out of order"
            ));
        }
    }
    if let Some(&missing) = expected.get(file.records.len()) {
        return Err(format!(
            "{name}: holds {} of the {} items of shard {shard}: item {missing} is missing",
            file.records.len(),
            expected.len()
        ));
    }
    Ok(Loaded {
        path: path.to_path_buf(),
        file,
    })
}

/// The parameters in which two sweeps differ, as `key: A here, B there`.
fn differences(here: &Value, there: &Value) -> String {
    let (Some(h), Some(t)) = (here.as_object(), there.as_object()) else {
        return format!("{here} here, {there} there");
    };
    let mut keys: Vec<&String> = h.keys().chain(t.keys()).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .filter(|k| h.get(*k) != t.get(*k))
        .map(|k| {
            let show = |v: Option<&Value>| v.map_or("absent".into(), Value::to_string);
            format!("{k}: {} here, {} there", show(h.get(k)), show(t.get(k)))
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// Checks that `other` belongs to the sweep of `first`.
fn same_sweep(first: &Loaded, other: &Loaded) -> Result<(), String> {
    let (f, o) = (&first.file, &other.file);
    let (fname, oname) = (first.name(), other.name());
    if o.program != f.program {
        return Err(format!(
            "{oname}: written by {}, but {fname} by {}: the shards of a sweep come from one program",
            o.program, f.program
        ));
    }
    if o.command != f.command {
        return Err(format!(
            "{oname}: a `{}` shard, but {fname} is a `{}` shard",
            o.command, f.command
        ));
    }
    if o.sweep != f.sweep {
        return Err(format!(
            "{oname}: not the same sweep as {fname} ({})",
            differences(&o.sweep, &f.sweep)
        ));
    }
    if o.shard.n != f.shard.n || o.items != f.items {
        return Err(format!(
            "{oname}: shard {} of {} items, but {fname} is shard {} of {} items: the shards of a sweep split the same items into the same N",
            o.shard, o.items, f.shard, f.items
        ));
    }
    Ok(())
}

/// Reads and checks every shard: the first file and every item's record in item order, each
/// with the file it came from.
fn join(paths: &[PathBuf]) -> Result<(Loaded, Vec<(Value, String)>), String> {
    let mut loaded = paths
        .iter()
        .map(|p| load(p))
        .collect::<Result<Vec<_>, _>>()?;
    for other in &loaded[1..] {
        same_sweep(&loaded[0], other)?;
    }
    let n = loaded[0].file.shard.n;
    let mut by_k: Vec<Option<String>> = vec![None; n];
    for l in &loaded {
        let slot = &mut by_k[l.file.shard.k - 1];
        if let Some(before) = slot {
            return Err(format!(
                "shard {} given twice: {before} and {}",
                l.file.shard,
                l.name()
            ));
        }
        *slot = Some(l.name());
    }
    let missing: Vec<String> = (1..=n)
        .filter(|k| by_k[k - 1].is_none())
        .map(|k| format!("{k}/{n}"))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "shard{} {} missing: every shard 1/{n} … {n}/{n} is needed once",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        ));
    }
    let items = loaded[0].file.items;
    let mut records: Vec<Option<(Value, String)>> = vec![None; items];
    for l in &mut loaded {
        let name = l.name();
        for r in std::mem::take(&mut l.file.records) {
            records[r.index] = Some((r.record, name.clone()));
        }
    }
    let records = records.into_iter().flatten().collect();
    let first = loaded.swap_remove(0);
    Ok((first, records))
}

/// The sweep's parameters and its records, typed.
fn typed<H: DeserializeOwned, R: DeserializeOwned>(
    first: &Loaded,
    records: Vec<(Value, String)>,
) -> Result<(H, Vec<R>), String> {
    let header = serde_json::from_value(first.file.sweep.clone())
        .map_err(|e| format!("{}: the sweep's parameters: {e}", first.name()))?;
    let records = records
        .into_iter()
        .enumerate()
        .map(|(i, (v, file))| {
            serde_json::from_value(v).map_err(|e| format!("{file}: item {i}: {e}"))
        })
        .collect::<Result<_, _>>()?;
    Ok((header, records))
}

/// Runs the subcommand.
pub fn run(a: Args) -> ExitCode {
    match merge(&a) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("merge: {e}");
            ExitCode::from(exit::BAD_INPUT)
        }
    }
}

fn merge(a: &Args) -> Result<ExitCode, String> {
    let (first, records) = join(&a.shards)?;
    let command = first.file.command.as_str();
    let tables = command == cmd_tables::TABLE1 || command == cmd_tables::TABLE2;
    if a.markdown && !tables {
        return Err(format!("--markdown: `{command}` has no markdown output"));
    }
    if a.svg.is_some() && command != cmd_bench::SCALING {
        return Err(format!("--svg: `{command}` draws no plot"));
    }
    Ok(match command {
        cmd_soak::COMMAND => {
            let (params, eps): (SoakParams, _) = typed(&first, records)?;
            cmd_soak::print_report(&params.report(eps), a.json)
        }
        cmd_tables::TABLE1 => {
            let (sweep, tasks): (Table1Sweep, _) = typed(&first, records)?;
            cmd_tables::print_table1(&sweep.report(tasks), a.json)
        }
        cmd_tables::TABLE2 => {
            let (sweep, trials): (Table2Sweep, _) = typed(&first, records)?;
            cmd_tables::print_table2(&sweep.report(trials), a.json)
        }
        cmd_bench::SCALING => {
            let (sweep, tasks): (ScalingSweep, _) = typed(&first, records)?;
            cmd_bench::print_scaling(&sweep.report(tasks), a.json, a.svg.as_deref())
        }
        cmd_lfd_perturb::COMMAND => {
            let (study, rows): (cmd_lfd_perturb::Study, Vec<_>) = typed(&first, records)?;
            cmd_lfd_perturb::print_study(&study, &rows, a.json)
        }
        other => {
            return Err(format!(
                "{}: shards of `{other}`, which merge does not join (soak, bench table1|table2|scaling, lfd --perturb)",
                first.name()
            ))
        }
    })
}
