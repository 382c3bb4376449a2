//! Compressed race files: gzip (`.gz`, RFC 1952: magic bytes 1F 8B) around any format, by
//! `flate2`; KMZ (a zip archive, magic `PK\x03\x04`, holding `doc.kml`), by `zip`. Both are
//! unpacked in memory up to [`MAX_FILE_BYTES`], so a small file that expands without end is
//! refused instead of filling memory.

use std::io::Read;

use super::MAX_FILE_BYTES;
use crate::error::{RaceError, RaceResult};

pub(crate) fn is_gzip(bytes: &[u8]) -> bool {
    bytes.starts_with(&[0x1F, 0x8B])
}

pub(crate) fn is_zip(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04")
}

fn limited(file: &str, what: &str, r: impl Read) -> RaceResult<Vec<u8>> {
    let mut out = Vec::new();
    r.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut out)
        .map_err(|e| {
            RaceError::in_file(
                file,
                format!(
                    "is {what} but cannot be unpacked ({})",
                    crate::text::cut(&crate::text::escape(&e.to_string()), 60)
                ),
            )
        })?;
    if out.len() as u64 > MAX_FILE_BYTES {
        return Err(RaceError::in_file(
            file,
            format!(
                "unpacks to over {} MB; a race file is at most that",
                MAX_FILE_BYTES / 1_000_000
            ),
        ));
    }
    Ok(out)
}

/// The content of a gzip file (all its members, as `gzip -d` gives them).
pub(crate) fn gunzip(file: &str, bytes: &[u8]) -> RaceResult<Vec<u8>> {
    let out = limited(file, "gzip", flate2::read::MultiGzDecoder::new(bytes))?;
    if out.is_empty() {
        return Err(RaceError::in_file(file, "is gzip of an empty file"));
    }
    Ok(out)
}

/// The KML text of a KMZ: `doc.kml` if present, else its first `.kml` entry.
pub(crate) fn kml_of_kmz(file: &str, bytes: &[u8]) -> RaceResult<String> {
    let bad = |e: &dyn std::fmt::Display| {
        RaceError::in_file(
            file,
            format!(
                "is a zip archive (KMZ?) that cannot be read ({})",
                crate::text::cut(&crate::text::escape(&e.to_string()), 60)
            ),
        )
    };
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| bad(&e))?;
    let names: Vec<String> = zip
        .file_names()
        .filter_map(|n| n.ok().map(|n| n.into_owned()))
        .collect();
    let kml = names
        .iter()
        .find(|n| n.eq_ignore_ascii_case("doc.kml"))
        .or_else(|| {
            names
                .iter()
                .find(|n| n.to_ascii_lowercase().ends_with(".kml"))
        })
        .ok_or_else(|| {
            RaceError::in_file(
                file,
                "is a zip archive without a .kml file; a KMZ holds doc.kml",
            )
        })?
        .clone();
    let entry = zip.by_name(&kml).map_err(|e| bad(&e))?;
    let text = limited(file, "KMZ", entry)?;
    String::from_utf8(text).map_err(|_| {
        RaceError::in_file(
            file,
            format!("{}: the KML is not UTF-8 text", crate::text::quote(&kml)),
        )
    })
}
