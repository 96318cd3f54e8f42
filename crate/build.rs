//! Sets cfg `first_load` for the page's first-load wasm module: feature `wasm-core` without
//! `wasm` (scripts/build-wasm.sh). That module runs B1's template task only and reads JSON
//! without path tracking; the page opens everything else on the full module, which it fetches
//! after its first frame (see `sim::Benchmark::sources`).
fn main() {
    println!("cargo::rustc-check-cfg=cfg(first_load)");
    println!("cargo::rerun-if-changed=build.rs");
    let has = |f: &str| std::env::var_os(format!("CARGO_FEATURE_{f}")).is_some();
    if has("WASM_CORE") && !has("WASM") {
        println!("cargo::rustc-cfg=first_load");
    }
}
