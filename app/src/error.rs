//! The app's one error type: a sentence for a person, never a panic. Loading a race, opening a
//! feed, building a renderer or writing a file fails with it wherever it runs (the window, the
//! phone, `render`, the bench); the command line reports it as one `regatta:` line on stderr
//! and exits non-zero, the window and the phone show it in a banner or a panel.

use std::fmt;

/// A failure as one sentence for a person (the command line prints it on stderr and exits
/// non-zero).
#[derive(Debug)]
pub struct AppError(pub String);

impl fmt::Display for AppError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for AppError {}

impl AppError {
    /// A message that may quote input: made one line of safe text ([`input::one_line`]).
    pub fn new(msg: impl AsRef<str>) -> Self {
        AppError(input::one_line(msg.as_ref()))
    }
}

/// Lets `?` turn any domain error whose Display is already a sentence into an AppError.
macro_rules! from_display {
    ($($t:ty),* $(,)?) => {$(
        impl From<$t> for AppError {
            fn from(e: $t) -> Self { AppError::new(e.to_string()) }
        }
    )*};
}
from_display!(std::io::Error, serde_json::Error);

pub type AppResult<T = ()> = Result<T, AppError>;
