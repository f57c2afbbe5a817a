//! Surface formats (`.off .ply .stl .mesh .msh`): any bytes give a parse result or a named
//! error, never a panic; a small parsed surface is also meshed (`-p`).
#![no_main]
mod common;
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
    if let Some(input) = parsed {
        if input.plc.points.len() <= 64 && input.plc.facets.len() <= 64 {
            common::check3(&idmesh::tetrahedralize(
                &input.plc,
                &idmesh::Options3::default(),
            ));
        }
    }
});
