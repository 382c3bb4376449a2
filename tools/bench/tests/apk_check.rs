//! The APK check that keeps the bench out of the Android library (`regatta-apk
//! check-bench-free`, run by scripts/check-apk.sh) finds the bench where it is: in this
//! package's own binary, whose code is all the bench's.
#![cfg(not(target_os = "android"))]

use std::path::Path;

#[test]
fn the_bench_check_refuses_the_bench_binary_and_names_its_symbols() {
    let bin = Path::new(env!("CARGO_BIN_EXE_regatta-bench"));
    let names = regatta_apk::bench_free::defined_symbols(bin).expect("a symbol table");
    let found = regatta_apk::bench_free::bench_symbols(names.iter().map(String::as_str));
    // The bench's crate, its budget model and shader cost, and plotters are all found (the
    // optimiser inlines many functions, so whole modules are looked for, not one function).
    for path in [
        "::regatta_bench::run_all::",
        "::regatta_bench::budget_model::",
        "::regatta_bench::shader_cost::",
        "::plotters::",
    ] {
        assert!(
            found
                .iter()
                .any(|s| regatta_apk::bench_free::readable(s).contains(path)),
            "{path} not found"
        );
    }
    let err = regatta_apk::bench_free::check_bench_free(bin).unwrap_err();
    assert!(err.0.contains("are the bench's code"), "{err}");
}
