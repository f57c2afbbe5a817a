//! Gives the shared library (`cdylib`) a versioned SONAME on ELF platforms, so programs linked
//! against an installed `libidmesh.so` record `libidmesh.so.<soversion>` and keep working
//! across compatible upgrades. Rust sets none by default. The soversion follows Cargo's
//! compatibility rule: the major version, or `0.<minor>` while the major version is 0 (where
//! every minor release may break the API). CMakeLists.txt computes the same name for the
//! installed file and its symlinks.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if matches!(os.as_str(), "macos" | "ios" | "windows") {
        return;
    }
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_default();
    let minor = std::env::var("CARGO_PKG_VERSION_MINOR").unwrap_or_default();
    let soversion = if major == "0" {
        format!("0.{minor}")
    } else {
        major
    };
    // Only the cdylib: executables, tests and the staticlib are unaffected.
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libidmesh.so.{soversion}");
}
