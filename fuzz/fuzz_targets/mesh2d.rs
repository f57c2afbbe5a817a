//! Structure-aware 2D fuzzing: a seed PSLG, mutated (see `mutate.rs`), meshed with `-p`,
//! `-pq<angle>`, `-Y` and a Steiner budget; a success must validate and no panic may hide.
#![no_main]
mod common;
mod mutate;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|case: mutate::Case2| {
    common::check2(
        &case.run_with_budget(common::FUZZ_BUDGET),
        case.no_boundary_steiner,
    );
});
