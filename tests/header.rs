//! Keeps `include/idmesh.h` in sync with `src/ffi.rs`, `src/ffi3d.rs` and `src/ffi_tetgen.rs`: regenerates the
//! header with the cbindgen library and fails when the checked-in file differs.
//! `IDMESH_UPDATE_HEADER=1 cargo test --test header` rewrites the file instead.

use std::path::Path;

/// The header as cbindgen generates it from `src/ffi.rs`, `src/ffi3d.rs` and `src/ffi_tetgen.rs` (in that order)
/// with `cbindgen.toml`.
fn generate() -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml"))
        .unwrap_or_else(|e| panic!("cannot read cbindgen.toml: {e}"));
    // Parsing only the FFI modules keeps generation independent of the rest of the crate (and
    // avoids running `cargo metadata` inside the test).
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(root.join("src/ffi.rs"))
        .with_src(root.join("src/ffi3d.rs"))
        .with_src(root.join("src/ffi_tetgen.rs"))
        .generate()
        .unwrap_or_else(|e| panic!("cbindgen failed on the FFI modules: {e}"));
    let mut out = Vec::new();
    bindings.write(&mut out);
    String::from_utf8(out).expect("cbindgen wrote non-UTF-8 text")
}

#[test]
fn header_is_up_to_date() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/idmesh.h");
    let fresh = generate();
    if std::env::var_os("IDMESH_UPDATE_HEADER").is_some_and(|v| v == "1") {
        std::fs::write(&path, &fresh).unwrap_or_else(|e| panic!("cannot write {path:?}: {e}"));
        eprintln!("wrote {}", path.display());
        return;
    }
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    if current != fresh {
        let line = current
            .lines()
            .zip(fresh.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| current.lines().count().min(fresh.lines().count()));
        panic!(
            "include/idmesh.h is stale (first difference at line {}); refresh it with\n    \
             IDMESH_UPDATE_HEADER=1 cargo test --test header\nand commit the result.",
            line + 1
        );
    }
}

#[test]
fn header_declares_the_whole_api() {
    let h = generate();
    for name in [
        "#ifndef IDMESH_H",
        "extern \"C\"",
        "typedef enum idm_status {",
        "} idm_status;",
        "#define IDM_NONE UINT32_MAX",
        "IDM_OK = 0",
        "IDM_INCOMPLETE = 1",
        "IDM_ERR_NULL_POINTER = 2",
        "IDM_ERR_INVALID_ARGUMENT = 3",
        "IDM_ERR_INVALID_INPUT = 4",
        "IDM_ERR_NO_MESH = 5",
        "IDM_ERR_UNSUPPORTED = 6",
        "IDM_ERR_INTERNAL = 7",
        "typedef struct idm_options2d",
        "typedef struct idm_mesher2d idm_mesher2d;",
        "typedef int32_t (*idm_sizing2d_fn)(",
        "void idm_options2d_default(",
        "const char *idm_last_error(void);",
        "const char *idm_version(void);",
        "enum idm_status idm_mesher2d_new(struct idm_mesher2d **out);",
        "void idm_mesher2d_free(struct idm_mesher2d *m);",
        "enum idm_status idm_mesher2d_add_points(",
        "enum idm_status idm_mesher2d_add_segments(",
        "enum idm_status idm_mesher2d_add_holes(",
        "enum idm_status idm_mesher2d_add_regions(",
        "enum idm_status idm_mesher2d_set_options(",
        "enum idm_status idm_mesher2d_set_sizing(",
        "enum idm_status idm_mesher2d_refine(struct idm_mesher2d *m);",
        "enum idm_status idm_mesher2d_counts(",
        "enum idm_status idm_mesher2d_vertices(",
        "enum idm_status idm_mesher2d_vertex_markers(",
        "enum idm_status idm_mesher2d_triangles(",
        "enum idm_status idm_mesher2d_neighbors(",
        "enum idm_status idm_mesher2d_triangle_attributes(",
        "enum idm_status idm_mesher2d_segments(",
        "enum idm_status idm_mesher2d_validate(const struct idm_mesher2d *m);",
        "size_t count",
        "typedef struct idm_options3d",
        "typedef struct idm_stats3d",
        "typedef struct idm_mesher3d idm_mesher3d;",
        "typedef int32_t (*idm_sizing3d_fn)(",
        "void idm_options3d_default(",
        "enum idm_status idm_mesher3d_new(struct idm_mesher3d **out);",
        "void idm_mesher3d_free(struct idm_mesher3d *m);",
        "enum idm_status idm_mesher3d_add_points(",
        "enum idm_status idm_mesher3d_add_segments(",
        "enum idm_status idm_mesher3d_add_facet(",
        "enum idm_status idm_mesher3d_add_hole(",
        "enum idm_status idm_mesher3d_add_region(",
        "enum idm_status idm_mesher3d_set_options(",
        "enum idm_status idm_mesher3d_set_sizing(",
        "enum idm_status idm_mesher3d_refine(struct idm_mesher3d *m);",
        "enum idm_status idm_mesher3d_delaunay(struct idm_mesher3d *m);",
        "enum idm_status idm_mesher3d_counts(",
        "enum idm_status idm_mesher3d_vertices(",
        "enum idm_status idm_mesher3d_vertex_markers(",
        "enum idm_status idm_mesher3d_tets(",
        "enum idm_status idm_mesher3d_neighbors(",
        "enum idm_status idm_mesher3d_tet_attributes(",
        "enum idm_status idm_mesher3d_faces(",
        "enum idm_status idm_mesher3d_edges(",
        "enum idm_status idm_mesher3d_stats(",
        "enum idm_status idm_mesher3d_validate(const struct idm_mesher3d *m);",
        "typedef struct idm_tetgen_switches",
        "typedef struct idm_plc3d idm_plc3d;",
        "enum idm_status idm_tetgen_parse_switches(",
        "enum idm_status idm_tetgen_resolve(",
        "enum idm_status idm_tetgen_read(",
        "enum idm_status idm_plc3d_arrays(",
        "void idm_plc3d_free(struct idm_plc3d *p);",
        "enum idm_status idm_tetgen_report(const char *message);",
        "enum idm_status idm_mesher3d_tetgen(",
        "enum idm_status idm_mesher3d_write_tetgen(",
    ] {
        assert!(h.contains(name), "generated header lacks `{name}`:\n{h}");
    }
    // The ownership/threading block comes first, before the include guard.
    assert!(
        h.starts_with("/*\n * idmesh"),
        "header must open with the doc block"
    );
    assert!(h.find("Ownership").unwrap() < h.find("#ifndef IDMESH_H").unwrap());
}
