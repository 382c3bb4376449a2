//! Input text inside messages: control characters escaped, long values cut, counts grouped.
//!
//! Every message that quotes a file's content (a JSON key, a cell, a mark name, a file name)
//! goes through [`quote`] or [`escape`], so an error is always one printable line.

/// The longest quoted value shown in a message, in characters; longer ones end in "…".
pub const QUOTE_MAX_CHARS: usize = 40;

/// `s` with every control character written as an escape (`\n`, `\r`, `\t`, `\u{0}`,
/// `\u{1b}`, …): what a terminal shows is then exactly one line with no hidden effects. The
/// one rule of every Regatta program (`input::escape_controls`); applying it twice changes
/// nothing.
pub use input::escape_controls as escape;

/// `s` escaped and cut to [`QUOTE_MAX_CHARS`] characters (with "…"), in double quotes.
pub fn quote(s: &str) -> String {
    format!("\"{}\"", cut(s, QUOTE_MAX_CHARS))
}

/// `s` escaped and cut like [`quote`], without the quotes (for column names).
pub fn plain(s: &str) -> String {
    cut(s, QUOTE_MAX_CHARS)
}

/// The first `max` characters of `s` (with "…" when something was cut), escaped.
pub use input::message::cut;

/// A number read from a file, for a message: as written for ordinary magnitudes, in exponent
/// form beyond 1e9 or below 1e-4 (a latitude of 1e308 is "1e308", not 309 digits).
pub use input::show_number as number;

/// A count with thousands grouped by commas: 11977 → "11,977".
pub fn count(n: usize) -> String {
    let d = n.to_string();
    let mut out = String::with_capacity(d.len() + d.len() / 3);
    for (i, c) in d.chars().enumerate() {
        if i > 0 && (d.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A serde message with the values it quotes in backticks cut to a readable length and its
/// Rust type names ("struct JsonRace") replaced by what a person calls them.
pub fn serde_message(msg: &str, types: &[(&str, &str)]) -> String {
    let mut m = msg.to_string();
    for (rust, domain) in types {
        m = m.replace(rust, domain);
    }
    // Cut every `quoted` piece (serde quotes keys and variants in backticks).
    let mut out = String::with_capacity(m.len());
    let mut rest = m.as_str();
    while let Some(a) = rest.find('`') {
        out.push_str(&rest[..=a]);
        rest = &rest[a + 1..];
        match rest.find('`') {
            Some(b) => {
                out.push_str(&cut(&rest[..b], QUOTE_MAX_CHARS));
                out.push('`');
                rest = &rest[b + 1..];
            }
            None => break,
        }
    }
    out.push_str(rest);
    escape(&out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_are_escaped_and_long_values_cut() {
        assert_eq!(
            escape("a\nb\r\u{1b}[31m\u{7}\0"),
            "a\\nb\\r\\u{1b}[31m\\u{7}\\u{0}"
        );
        assert_eq!(quote(&"x".repeat(50)), format!("\"{}…\"", "x".repeat(40)));
        assert_eq!(count(11_977), "11,977");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_000_000), "1,000,000");
        assert_eq!(number(1e308), "1e308");
        assert_eq!(number(-91.5), "-91.5");
        assert_eq!(number(f64::INFINITY), "inf");
        assert_eq!(
            serde_message(
                "unknown field `\nname`, expected struct JsonRace",
                &[("struct JsonRace", "a race")]
            ),
            "unknown field `\\nname`, expected a race"
        );
    }
}
