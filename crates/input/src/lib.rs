//! `input`: what every Regatta program does with untrusted input before trusting it.
//!
//! - [`message`]: input quoted in a one-line error message, its control characters escaped
//!   and its length cut;
//! - [`read`]: a file read only up to a stated size, refused early when it is a directory, a
//!   device that never ends, or not the kind of file expected.
//!
//! Invariant: no dependencies; the domain crates (ocean, ar, race) and the app share it.

pub mod message;
pub mod read;

pub use message::{escape_controls, one_line, quote, show_number};
pub use read::{ReadError, json_object_sniff, read_capped, show_path, text_sniff};
