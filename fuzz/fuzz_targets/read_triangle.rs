//! Triangle's text formats (`.node .poly .ele`): any bytes give a parse result or a named
//! error, never a panic or a hang.
#![no_main]
use idmesh::io::triangle;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let node = || triangle::parse_node("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", "f.node");
    let pslg = match sel % 3 {
        0 => triangle::parse_node(text, "f.node").ok(),
        1 => triangle::parse_poly(text, "f.poly", node).ok(),
        _ => {
            let _ = triangle::parse_ele(text, "f.ele", (sel >> 2) as u32 & 1, 8);
            None
        }
    };
    // Parsing only: meshing what the fuzzer writes finds 2D termination bugs (issue 14)
    // that the structure-aware targets chase; here the readers must never panic or hang.
    std::hint::black_box(&pslg);
});
