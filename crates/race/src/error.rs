//! One error type for everything that reads a race: a sentence naming the file and the line or
//! field at fault, never a panic.

use std::fmt;

/// A race could not be read or assembled. `Display` is one sentence for a person.
#[derive(Debug, Clone, PartialEq)]
pub struct RaceError {
    msg: String,
}

impl RaceError {
    /// An error with a complete sentence (it should already name the file). Control
    /// characters that reach it from the input are escaped here as well, so a message is
    /// always one line whatever a caller forgot to quote.
    pub fn new(msg: impl Into<String>) -> Self {
        let mut msg: String = msg.into();
        // One sentence: no trailing newline, ends with a full stop.
        while msg.ends_with(['\n', ' ']) {
            msg.pop();
        }
        let mut msg = crate::text::escape(&msg);
        if !msg.ends_with('.') {
            msg.push('.');
        }
        RaceError { msg }
    }

    /// An error at `file`, line `line` (1-based).
    pub fn at_line(file: &str, line: u64, what: impl fmt::Display) -> Self {
        RaceError::new(format!("{file} line {line}: {what}"))
    }

    /// An error about a whole file.
    pub fn in_file(file: &str, what: impl fmt::Display) -> Self {
        RaceError::new(format!("{file}: {what}"))
    }

    pub fn message(&self) -> &str {
        &self.msg
    }
}

impl fmt::Display for RaceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.msg)
    }
}

impl std::error::Error for RaceError {}

pub type RaceResult<T> = Result<T, RaceError>;
