//! The one error type of the crate: a sentence for people, naming the file and line at fault.

use std::fmt;
use std::path::Path;

/// A frame-source error: one sentence naming the file (and line or field) at fault. Input in
/// the message (a file name from `frames.txt`, a field) has its control characters escaped
/// ([`input::one_line`]), and paths are cut to a readable length.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ArError {
    message: String,
}

impl ArError {
    pub fn new(message: impl AsRef<str>) -> Self {
        Self {
            message: input::one_line(message.as_ref()),
        }
    }

    /// `"{path} line {line}: {what}"`; `line` counts from 1.
    pub fn at_line(path: &Path, line: usize, what: impl fmt::Display) -> Self {
        Self::new(format!("{} line {line}: {what}", input::show_path(path)))
    }

    /// `"{path}: {what}"`.
    pub fn in_file(path: &Path, what: impl fmt::Display) -> Self {
        Self::new(format!("{}: {what}", input::show_path(path)))
    }

    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for ArError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ArError {}
