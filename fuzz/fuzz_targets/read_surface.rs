//! Surface formats (`.off .ply .stl .mesh .msh`): any bytes give a parse result or a named
//! error, never a panic or a hang.
#![no_main]
use idmesh::io::{parse_msh, tetgen};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let parsed = if sel % 5 == 2 {
        tetgen::parse_stl(rest, "f.stl").ok()
    } else {
        let Ok(text) = std::str::from_utf8(rest) else {
            return;
        };
        match sel % 5 {
            0 => tetgen::parse_off(text, "f.off").ok(),
            1 => tetgen::parse_ply(text, "f.ply").ok(),
            3 => tetgen::parse_medit(text, "f.mesh").ok(),
            _ => parse_msh(text, "f.msh").ok(),
        }
    };
    // Parsing only: meshing what the fuzzer writes finds 2D termination bugs (issue 14)
    // that the structure-aware targets chase; here the readers must never panic or hang.
    std::hint::black_box(&parsed);
});
