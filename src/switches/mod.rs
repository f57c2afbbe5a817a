//! Command-line switch parsers shared by the `idmesh` command line and the C ABI (and through
//! it the source-compatibility shims in `compat/`): one parser per reference program, so the
//! command line and the library always agree on what a switch string means.

pub mod triangle;
