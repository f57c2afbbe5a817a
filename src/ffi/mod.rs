//! The C ABI (see `include/idmesh.h`, generated from these files by cbindgen).
//!
//! [`common`] holds what every entry point shares, once: the status enum, the panic guard, the
//! thread-local last error (with the kind and index of a bad input item), pointer and count
//! checks, the handle lifecycle, lending output arrays, counts, validation and the sizing and
//! progress callback wrappers. [`input_error`] reports the kind and index of a bad input item. [`mesh2d`] and [`mesh3d`] declare the `idm_mesher2d_*` and
//! `idm_mesher3d_*` functions and hold only what differs between the dimensions.
//!
//! Conventions shared by every function returning [`idm_status`]:
//! * the body runs under `catch_unwind`, so a panic becomes [`idm_status::IDM_ERR_INTERNAL`]
//!   instead of unwinding into C (which would be undefined behaviour);
//! * every pointer is checked before use (NULL is allowed for an array whose count is 0), and
//!   every count is checked for overflow before it is turned into a byte length;
//! * inputs are copied, so the caller may free its arrays as soon as the call returns;
//! * out-parameters are written only on success, and a failed call leaves the handle unchanged;
//! * a failure stores a message naming the bad item in a thread-local buffer
//!   ([`idm_last_error`]); success clears it.
//!
//! The C names (`idm_status`, `IDM_OK`, ...) are used on the Rust side too so that cbindgen needs
//! no renaming rules and a reader can grep one name across both languages.

#![allow(non_camel_case_types)]
#![deny(unsafe_op_in_unsafe_fn)]

pub mod common;
pub mod input_error;
pub mod mesh2d;
pub mod mesh3d;
pub mod tetgen;
pub mod triangle;

pub use common::*;
pub use input_error::*;
pub use mesh2d::*;
pub use mesh3d::*;
pub use tetgen::*;
pub use triangle::*;
