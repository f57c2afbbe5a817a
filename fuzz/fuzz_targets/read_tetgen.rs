//! TetGen's text formats (`.node .poly .smesh .ele .face .edge .neigh`): any bytes give a
//! parse result or a named error, never a panic or a hang.
#![no_main]
use idmesh::io::tetgen;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    // A `.poly` or `.smesh` that lists no points of its own reads them from a `.node`.
    let node = || tetgen::parse_node("4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "f.node");
    let plc = match sel % 7 {
        0 => tetgen::parse_node(text, "f.node").ok(),
        1 => tetgen::parse_poly(text, "f.poly", node).ok(),
        2 => tetgen::parse_smesh(text, "f.smesh", node).ok(),
        3 => {
            let _ = tetgen::parse_ele(text, "f.ele", (sel >> 3) as u32 & 1, 8);
            None
        }
        4 => {
            let _ = tetgen::parse_face(text, "f.face", (sel >> 3) as u32 & 1, 8);
            None
        }
        5 => {
            let _ = tetgen::parse_edge(text, "f.edge", (sel >> 3) as u32 & 1, 8);
            None
        }
        _ => {
            let _ = tetgen::parse_neigh(text, "f.neigh", (sel >> 3) as u32 & 1, 8);
            None
        }
    };
    // Parsing only: meshing what the fuzzer writes finds 2D termination bugs (issue 14)
    // that the structure-aware targets chase; here the readers must never panic or hang.
    std::hint::black_box(&plc);
});
