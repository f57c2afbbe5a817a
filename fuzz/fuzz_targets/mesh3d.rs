//! Structure-aware 3D fuzzing: a seed PLC, mutated (see `mutate.rs`), meshed with `-p`,
//! `-pq<ratio>`, `-Y` and a Steiner budget; a success must validate and no panic may hide.
#![no_main]
mod common;
mod mutate;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|case: mutate::Case3| {
    common::check3(&case.run_with_budget(common::FUZZ_BUDGET));
});
