//! Keeps `include/idmesh.h` in sync with the C ABI sources (`src/ffi/` and every
//! `src/ffi_*.rs`): regenerates the header with the cbindgen library and fails when the
//! checked-in file differs.
//! `IDMESH_UPDATE_HEADER=1 cargo test --test header` rewrites the file instead.

use std::path::{Path, PathBuf};

/// The files cbindgen reads, in a fixed order: `src/ffi/mod.rs` (cbindgen follows its `mod`
/// items, so every file of `src/ffi/` comes in declaration order: `common.rs`, with the status
/// enum, first), then every `src/ffi_*.rs` sorted by name.
fn sources(root: &Path) -> Vec<PathBuf> {
    let src = root.join("src");
    let entries = std::fs::read_dir(&src).unwrap_or_else(|e| panic!("cannot list {src:?}: {e}"));
    let mut extra: Vec<PathBuf> = entries
        .map(|e| {
            e.unwrap_or_else(|e| panic!("cannot list {src:?}: {e}"))
                .path()
        })
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.starts_with("ffi_") && name.ends_with(".rs")
        })
        .collect();
    extra.sort();
    let mut files = vec![src.join("ffi/mod.rs")];
    files.extend(extra);
    files
}

/// The header as cbindgen generates it from [`sources`] with `cbindgen.toml`.
fn generate() -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml"))
        .unwrap_or_else(|e| panic!("cannot read cbindgen.toml: {e}"));
    // Parsing only the FFI modules keeps generation independent of the rest of the crate (and
    // avoids running `cargo metadata` inside the test).
    let mut builder = cbindgen::Builder::new().with_config(config);
    let files = sources(root);
    for f in &files {
        builder = builder.with_src(f);
    }
    let bindings = builder
        .generate()
        .unwrap_or_else(|e| panic!("cbindgen failed on {files:?}: {e}"));
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
        "typedef enum idm_input_error {",
        "IDM_INPUT_OK = 0",
        "IDM_INPUT_CROSSING_SEGMENTS = 11",
        "enum idm_input_error idm_last_error_item(int64_t *item, int64_t *part, int64_t *other);",
        "size_t struct_size;",
        "void idm_options2d_default_sized(struct idm_options2d *out,",
        "void idm_options3d_default_sized(struct idm_options3d *out,",
        "#define idm_options2d_default(out) idm_options2d_default_sized(",
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
        "typedef struct idm_triangle_switches",
        "enum idm_status idm_triangle_parse_switches(",
        "enum idm_status idm_triangle_fail(",
        "enum idm_status idm_triangle_edges(",
        "enum idm_status idm_triangle_segments(",
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
