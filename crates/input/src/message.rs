//! Text from untrusted input inside one-line error messages.
//!
//! Every error a Regatta program prints is one line for a person. Input (a JSON key, a file
//! name, a CSV cell, a command-line value) can hold a newline, a carriage return, an escape
//! sequence that drives the terminal, a bell or a NUL, and can be megabytes long. Before such text
//! goes into a message it passes through [`quote`] (a piece of input, cut to
//! [`QUOTE_MAX_CHARS`]) or, for a whole message a library formatted (serde's, clap's),
//! [`one_line`].

/// Longest piece of input quoted in a message, characters: enough to recognise a value, a key or
/// a file name, short enough that the message stays one readable line.
pub const QUOTE_MAX_CHARS: usize = 60;

/// Longest whole message, characters (a last defence: quoted input is already cut).
pub const MESSAGE_MAX_CHARS: usize = 600;

/// Characters that would break a message's line or reorder its text on a terminal: Unicode's
/// control characters (C0, DEL, C1: newline, CR, ESC, BEL, NUL, …), the line and paragraph
/// separators, and the bidirectional overrides and isolates.
pub fn is_unsafe(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{2028}' | '\u{2029}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `s` with each unsafe character ([`is_unsafe`]) written as its Rust escape (`\n`, `\r`,
/// `\t`, `\u{1b}`, `\u{0}`, …); everything else as it is. Applying it twice changes nothing.
pub fn escape_controls(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if is_unsafe(c) {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// `s` cut to `max` characters (an ellipsis marks the cut), then escaped.
pub fn cut(s: &str, max: usize) -> String {
    match s.char_indices().nth(max) {
        Some((end, _)) => format!("{}…", escape_controls(&s[..end])),
        None => escape_controls(s),
    }
}

/// A piece of input for a message: in double quotes, cut to [`QUOTE_MAX_CHARS`], escaped.
pub fn quote(s: &str) -> String {
    format!("\"{}\"", cut(s, QUOTE_MAX_CHARS))
}

/// A whole message made safe to print as one line: trailing white space (some libraries end
/// their messages with a newline) dropped, escaped, cut to [`MESSAGE_MAX_CHARS`].
pub fn one_line(s: &str) -> String {
    cut(s.trim_end(), MESSAGE_MAX_CHARS)
}

/// A number from input for a message: as written for everyday sizes, in exponent form when
/// very large or small (`1e300`, not three hundred digits).
pub fn show_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_become_visible_escapes() {
        assert_eq!(
            escape_controls("a\nb\rc\u{1b}[31md\u{7}e\0f\tg"),
            "a\\nb\\rc\\u{1b}[31md\\u{7}e\\u{0}f\\tg"
        );
        // Unicode line separators and bidi overrides, and C1 controls.
        assert_eq!(
            escape_controls("x\u{2028}y\u{202e}z\u{85}"),
            "x\\u{2028}y\\u{202e}z\\u{85}"
        );
        // Ordinary text, quotes, backslashes and non-ASCII letters stay as they are.
        let plain = r#"Île "d'Yeu" \ 42 °N Σ kA"#;
        assert_eq!(escape_controls(plain), plain);
        // Idempotent: a message escaped at its source is not escaped again by the printer.
        let once = escape_controls("k\ney");
        assert_eq!(escape_controls(&once), once);
    }

    #[test]
    fn numbers_stay_short() {
        assert_eq!(show_number(1e300), "1e300");
        assert_eq!(show_number(-1e-300), "-1e-300");
        assert_eq!(show_number(0.25), "0.25");
        assert_eq!(show_number(5000.0), "5000");
        assert_eq!(show_number(f64::NAN), "NaN");
    }

    #[test]
    fn quotes_are_cut_to_a_readable_length() {
        assert_eq!(quote("\nname"), "\"\\nname\"");
        let long = "é".repeat(1000);
        let q = quote(&long);
        assert_eq!(q.chars().count(), QUOTE_MAX_CHARS + 3);
        assert!(q.ends_with("…\""));
        assert_eq!(
            quote(&"x".repeat(QUOTE_MAX_CHARS)).chars().count(),
            QUOTE_MAX_CHARS + 2
        );
        let m = one_line(&"line\n".repeat(1000));
        assert!(!m.contains('\n'));
        assert!(m.chars().count() <= 2 * MESSAGE_MAX_CHARS + 1);
    }
}
