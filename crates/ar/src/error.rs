//! The one error type of the crate: a sentence for people, naming the file and line at fault.

use std::fmt;
use std::path::Path;

/// A frame-source error: one sentence naming the file (and line or field) at fault.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ArError {
    message: String,
}

impl ArError {
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }

    /// `"{path} line {line}: {what}"`; `line` counts from 1.
    pub fn at_line(path: &Path, line: usize, what: impl fmt::Display) -> Self {
        Self::new(format!("{} line {line}: {what}", path.display()))
    }

    /// `"{path}: {what}"`.
    pub fn in_file(path: &Path, what: impl fmt::Display) -> Self {
        Self::new(format!("{}: {what}", path.display()))
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
