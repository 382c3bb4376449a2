//! One error type for the command line: a sentence for a person, never a panic.

use std::fmt;

/// A failure the command line reports as one sentence on stderr, exiting non-zero.
#[derive(Debug)]
pub struct CliError(pub String);

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CliError {}

impl CliError {
    /// A message that may quote input: made one line of safe text ([`input::one_line`]).
    pub fn new(msg: impl AsRef<str>) -> Self {
        CliError(input::one_line(msg.as_ref()))
    }
}

/// Lets `?` turn any domain error whose Display is already a sentence into a CliError.
macro_rules! from_display {
    ($($t:ty),* $(,)?) => {$(
        impl From<$t> for CliError {
            fn from(e: $t) -> Self { CliError::new(e.to_string()) }
        }
    )*};
}
from_display!(std::io::Error, serde_json::Error);

pub type CliResult<T = ()> = Result<T, CliError>;
