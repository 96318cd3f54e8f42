//! `benchRows`: the hot-path rows of `experiments::hot_paths` timed inside the module on
//! `performance.now()`, the wasm side of `npm run bench:wasm` (the native side is
//! `logic-lfd bench wasm-rows`: same code, same inputs, same best-of-N discipline).

use super::args::object_arg;
use super::convert::{from_js, js_err, to_js, PerformanceClock};
use crate::experiments::hot_paths::{run_rows, RowInputs, RowParams};
use wasm_bindgen::prelude::*;

/// Times the hot-path rows: `inputs` holds the IPC texts (`blocksDomain`, `blocks8`, `blocks9`,
/// `logisticsDomain`, `logistics`, `logisticsName`); `params` optionally `warmup`, `warmupSecs`, `runs`,
/// `minRuns`, `budgetSecs` and `only` (row-id fragments). Returns the rows (`id`, `label`, `best_ms`,
/// `per_batch`, `runs`, `digest`); rejects with a message on bad input.
#[wasm_bindgen(js_name = benchRows, unchecked_return_type = "BenchRow[]")]
pub fn bench_rows(
    #[wasm_bindgen(unchecked_param_type = "BenchRowInputs")] inputs: JsValue,
    #[wasm_bindgen(unchecked_param_type = "BenchRowParams | undefined")] params: JsValue,
) -> Result<JsValue, JsValue> {
    object_arg("benchRows", "inputs", &inputs, false)?;
    object_arg("benchRows", "params", &params, true)?;
    let inputs: RowInputs = from_js(&inputs).map_err(|e| js_err(format!("inputs: {e}")))?;
    let params: RowParams = if params.is_undefined() || params.is_null() {
        RowParams::default()
    } else {
        from_js(&params).map_err(|e| js_err(format!("params: {e}")))?
    };
    let rows = run_rows(&inputs, &params, &PerformanceClock).map_err(js_err)?;
    to_js(&rows)
}

// The row types are `experiments::hot_paths`'s, which derive no declarations: these are written
// by hand to match them.
#[wasm_bindgen(typescript_custom_section)]
const TS_BENCH: &'static str = r#"
/** The IPC texts of the planning rows of `benchRows`. */
export interface BenchRowInputs {
  blocksDomain: string; blocks8: string; blocks9: string;
  logisticsDomain: string; logistics: string; logisticsName: string;
}
/** How many times each row of `benchRows` runs (defaults 1, 0 s, 10, 3, 5 s, all rows). */
export interface BenchRowParams { warmup?: number; warmupSecs?: number; runs?: number; minRuns?: number; budgetSecs?: number; only?: string[]; }
/** One timed row: best time of one unit of work (ms) and a digest of the work done. */
export interface BenchRow { id: string; label: string; best_ms: number; per_batch: number; runs: number; digest: string; }
"#;
