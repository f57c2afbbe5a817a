//! Readers and writers for mesh file formats.
//!
//! * [`triangle`]: Shewchuk's Triangle formats (.node, .poly in; .node, .ele, .poly, .edge,
//!   .neigh out).
//!
//! Readers never panic: every problem is a [`ParseError`] naming the file and line. Writers
//! buffer internally and write floats so that they read back bit for bit.
//!
//! The line tokenizer and number formatting are shared so that TetGen's formats can be
//! added beside Triangle's later.

mod error;
mod lines;
mod numfmt;
pub mod triangle;
mod triangle_read;
mod triangle_write;

pub use error::ParseError;
pub use numfmt::Real;
