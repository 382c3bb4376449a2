//! Files read only up to a stated size.
//!
//! `std::fs::read` on `/dev/zero` (or a FIFO nobody closes, or a 50 GB file given by mistake)
//! reads until memory runs out. [`read_capped`] refuses a directory and a regular file over the
//! cap from its metadata before reading anything, checks the first bytes against what the caller
//! expects (a JSON object, text) before reading on, and reads at most `max_bytes + 1` bytes from
//! anything else (a device or pipe reports no length).

use std::fmt;
use std::io::Read;
use std::path::Path;

use crate::message::cut;

/// Longest file name shown in a message, characters (a path is longer than a quoted value).
pub const PATH_MAX_CHARS: usize = 200;

/// How many leading bytes [`read_capped`] shows its `sniff` check.
pub const SNIFF_BYTES: usize = 512;

/// Why a file was not read: one sentence naming it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReadError(pub String);

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ReadError {}

/// A path for a message: control characters escaped, cut to [`PATH_MAX_CHARS`].
pub fn show_path(path: &Path) -> String {
    cut(&path.display().to_string(), PATH_MAX_CHARS)
}

/// Whether `meta` is a named pipe (never on systems without them).
fn is_fifo(meta: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        meta.file_type().is_fifo()
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        false
    }
}

/// A byte count for people: `16 MiB`, `512 KiB`, `300 bytes`.
pub fn show_bytes(n: u64) -> String {
    const KIB: u64 = 1024;
    match n {
        n if n >= KIB * KIB && n % (KIB * KIB) == 0 => format!("{} MiB", n / (KIB * KIB)),
        n if n >= KIB && n % KIB == 0 => format!("{} KiB", n / KIB),
        n => format!("{n} bytes"),
    }
}

/// The bytes of `path`, `what` (for messages, with its article: "a sea file", "an NDBC spectral
/// file") of at most `max_bytes`. `sniff` sees the first [`SNIFF_BYTES`] bytes (fewer for a
/// shorter file) and returns why they are not `what`, if they are not; reading stops there.
pub fn read_capped(
    path: &Path,
    max_bytes: u64,
    what: &str,
    sniff: impl Fn(&[u8]) -> Option<String>,
) -> Result<Vec<u8>, ReadError> {
    let name = show_path(path);
    let cap = show_bytes(max_bytes);
    let meta =
        std::fs::metadata(path).map_err(|e| ReadError(format!("could not read {name}: {e}")))?;
    if meta.is_dir() {
        return Err(ReadError(format!("{name} is a directory, not {what}")));
    }
    if is_fifo(&meta) {
        // Opening a named pipe waits for a writer, maybe forever: refused up front, as a race
        // file that is not a regular file is.
        return Err(ReadError(format!(
            "{name} is a named pipe (FIFO), not {what}: opening it would wait for a writer; give a regular file"
        )));
    }
    if meta.is_file() && meta.len() > max_bytes {
        return Err(ReadError(format!(
            "{name} is {} bytes, but {what} holds at most {cap}",
            meta.len()
        )));
    }
    let file =
        std::fs::File::open(path).map_err(|e| ReadError(format!("could not read {name}: {e}")))?;
    let mut reader = file.take(max_bytes + 1);
    let mut bytes = Vec::new();
    let io = |e: std::io::Error| ReadError(format!("could not read {name}: {e}"));
    (&mut reader)
        .take(SNIFF_BYTES as u64)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if let Some(why) = sniff(&bytes) {
        return Err(ReadError(format!("{name} is not {what}: {why}")));
    }
    reader.read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(ReadError(format!(
            "{name} is larger than {cap}, the most {what} holds (reading stopped there)"
        )));
    }
    Ok(bytes)
}

/// `read_capped`'s check for text: no NUL byte (binary files and `/dev/zero` have them).
pub fn text_sniff(prefix: &[u8]) -> Option<String> {
    prefix
        .iter()
        .position(|&b| b == 0)
        .map(|i| format!("byte {i} is NUL, so it is binary, not text"))
}

/// `read_capped`'s check for a JSON object: after an optional byte-order mark and white space,
/// the first character is `{`.
pub fn json_object_sniff(prefix: &[u8]) -> Option<String> {
    let body = prefix.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(prefix);
    match body.iter().find(|b| !b.is_ascii_whitespace()) {
        None if prefix.len() < SNIFF_BYTES => Some("it is empty".into()),
        None | Some(b'{') => None,
        Some(&b) => Some(format!(
            "it starts with {}, not with the `{{` of a JSON object",
            match b {
                0x21..=0x7e => format!("`{}`", b as char),
                _ => format!("byte 0x{b:02x}"),
            }
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let p = std::env::temp_dir().join(format!("input-read-{}-{name}", std::process::id()));
        std::fs::write(&p, bytes).unwrap();
        p
    }

    #[test]
    fn endless_devices_stop_at_the_first_bytes_or_the_cap() {
        let zero = Path::new("/dev/zero");
        if !zero.exists() {
            return;
        }
        // The sniff refuses it at once…
        let e = read_capped(zero, 1 << 20, "a sea file", json_object_sniff).unwrap_err();
        assert_eq!(
            e.0,
            "/dev/zero is not a sea file: it starts with byte 0x00, not with the `{` of a JSON object"
        );
        // …and without one, the read stops one byte past the cap.
        let e = read_capped(zero, 4096, "a thing", |_| None).unwrap_err();
        assert!(e.0.contains("larger than 4 KiB"), "{e}");
    }

    /// Issue 30: `--sea`, `--ndbc`, `--script` and a `frames.txt` that name a FIFO blocked in
    /// `open()` while `--race` refused it: every capped read refuses it up front now.
    #[test]
    fn a_named_pipe_is_refused_before_it_is_opened() {
        let p = std::env::temp_dir().join(format!("input-read-{}-fifo", std::process::id()));
        let _ = std::fs::remove_file(&p);
        let made = std::process::Command::new("mkfifo").arg(&p).status();
        if !made.is_ok_and(|s| s.success()) {
            eprintln!("mkfifo is not available; skipped");
            return;
        }
        let e = read_capped(&p, 1 << 20, "a sea file", json_object_sniff).unwrap_err();
        std::fs::remove_file(&p).unwrap();
        assert!(
            e.0.ends_with(
                "is a named pipe (FIFO), not a sea file: opening it would wait for a writer; give a regular file"
            ),
            "{e}"
        );
    }

    #[test]
    fn directories_big_files_and_wrong_contents_are_named() {
        let dir = std::env::temp_dir();
        let e = read_capped(&dir, 10, "a sea file", |_| None).unwrap_err();
        assert!(e.0.ends_with("is a directory, not a sea file"), "{e}");
        let big = tmp("big", &[b' '; 300]);
        let e = read_capped(&big, 200, "a sea file", |_| None).unwrap_err();
        assert!(
            e.0.ends_with("is 300 bytes, but a sea file holds at most 200 bytes"),
            "{e}"
        );
        let list = tmp("list", b"\xEF\xBB\xBF  [1, 2]");
        let e = read_capped(&list, 200, "a sea file", json_object_sniff).unwrap_err();
        assert!(
            e.0.ends_with("it starts with `[`, not with the `{` of a JSON object"),
            "{e}"
        );
        let ok = tmp("ok", b"\xEF\xBB\xBF {}");
        assert_eq!(
            read_capped(&ok, 200, "a sea file", json_object_sniff)
                .unwrap()
                .len(),
            6
        );
        let e = read_capped(Path::new("/no/such\nfile"), 200, "x", |_| None).unwrap_err();
        assert!(e.0.starts_with("could not read /no/such\\nfile: "), "{e}");
        let bin = tmp("bin", b"#YY\0");
        assert!(
            read_capped(&bin, 200, "a text", text_sniff)
                .unwrap_err()
                .0
                .contains("byte 3 is NUL")
        );
        for p in [big, list, ok, bin] {
            let _ = std::fs::remove_file(p);
        }
    }
}
