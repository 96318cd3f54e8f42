//! `benchmark`: a benchmark's initial scene and PDDL files, which the page reads on its first load;
//! `blockRange`: the block counts of its generated N-block tower task.

use super::args::string_arg;
use super::convert::{js_err, to_js};
use crate::sim::Benchmark;
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// A benchmark's initial scene and PDDL files (see [`benchmark()`]).
#[derive(Debug, Serialize, Tsify)]
pub struct BenchmarkInfo {
    /// The benchmark.
    pub id: Benchmark,
    /// The directory name, e.g. `b1-tower`.
    pub name: &'static str,
    /// The initial world, as the page draws it.
    pub scene: crate::sim::WorldSnapshot,
    /// `domains/<name>/domain.pddl`.
    pub domain: &'static str,
    /// `domains/<name>/problem.pddl`.
    pub problem: &'static str,
    /// The demonstration's actions (`domains/<name>/demo.json`) as an IPC plan, one a line.
    #[serde(rename = "demoPlan")]
    pub demo_plan: String,
}

/// One of the paper's benchmarks (`b1` tower, `b2` workspace reach, `b3` two arms): its initial
/// scene and its PDDL domain and problem. Rejects an unknown id.
#[wasm_bindgen(unchecked_return_type = "BenchmarkInfo")]
pub fn benchmark(
    #[wasm_bindgen(unchecked_param_type = "Benchmark")] id: JsValue,
) -> Result<JsValue, JsValue> {
    let b = benchmark_arg("benchmark", &id)?;
    b.available().map_err(|e| js_err(e.message))?;
    to_js(&BenchmarkInfo {
        id: b,
        name: b.dir_name(),
        scene: b.scene_snapshot(),
        domain: b.domain_pddl(),
        problem: b.problem_pddl(),
        demo_plan: crate::lfd::demo_actions(b.demo_json())
            .map_err(js_err)?
            .iter()
            .map(|a| format!("{a}\n"))
            .collect(),
    })
}

/// The block counts `[fewest, most]` that a benchmark's generated N-block tower task takes (the
/// `blocks` option of `Session`, from `sim::block_range`), or `null` for a benchmark
/// without one (B2). Rejects an unknown id.
#[wasm_bindgen(js_name = blockRange, unchecked_return_type = "[number, number] | null")]
pub fn block_range(
    #[wasm_bindgen(unchecked_param_type = "Benchmark")] id: JsValue,
) -> Result<JsValue, JsValue> {
    let b = benchmark_arg("blockRange", &id)?;
    // B2's "no N-block variant" is an answer here, not an error.
    let range = crate::sim::block_range(b)
        .ok()
        .map(|r| [*r.start(), *r.end()]);
    to_js(&range)
}

/// The benchmark `id` names (argument `id` of `func`), or a `TypeError` / `Error` saying why not.
fn benchmark_arg(func: &str, id: &JsValue) -> Result<Benchmark, JsValue> {
    let id = string_arg(func, "id", id)?;
    Benchmark::parse(&id)
        .ok_or_else(|| js_err(format!("unknown benchmark `{id}` (expected b1, b2 or b3)")).into())
}
