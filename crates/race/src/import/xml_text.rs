//! A small walk over an XML document for the track formats read element by element (TCX,
//! KML): local names (namespace prefixes dropped, `gx:coord` → `coord`), the text of each
//! element, and one-line errors naming the line.

use quick_xml::XmlVersion;
use quick_xml::events::Event;

use crate::error::{RaceError, RaceResult};

/// What the walk reports.
pub(crate) enum Node<'a> {
    /// An element opens (`path` ends with it); `attrs` are (local name, value).
    Open(&'a [String], &'a [(String, String)]),
    /// The text inside the innermost element of `path`.
    Text(&'a [String], &'a str),
    /// An element closes (`path` still ends with it).
    Close(&'a [String]),
}

fn local(name: &str) -> &str {
    name.rsplit(':').next().unwrap_or(name)
}

/// The open elements: names kept in reused strings (`depth` of them are open), so a long
/// track allocates nothing per element once the path is warm.
struct Path {
    names: Vec<String>,
    depth: usize,
}

impl Path {
    fn push(&mut self, name: &str) {
        if self.depth == self.names.len() {
            self.names.push(String::new());
        }
        let slot = &mut self.names[self.depth];
        slot.clear();
        slot.push_str(local(name));
        self.depth += 1;
    }

    fn open(&self) -> &[String] {
        &self.names[..self.depth]
    }
}

/// 1-based line of a byte offset (every XML reader's error names its line).
pub(crate) fn line_of(text: &str, pos: u64) -> u64 {
    let end = (pos as usize).min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count() as u64
        + 1
}

/// The next event of `r` (reading `text`), or one error naming `file` and the line where the
/// XML breaks (the parser's message escaped and cut to 80 characters).
pub(crate) fn next_event<'a>(
    r: &mut quick_xml::Reader<&'a [u8]>,
    file: &str,
    text: &str,
) -> RaceResult<quick_xml::events::Event<'a>> {
    r.read_event().map_err(|e| {
        RaceError::at_line(
            file,
            line_of(text, r.error_position()),
            format!(
                "not valid XML ({})",
                crate::text::cut(&crate::text::escape(&e.to_string()), 80)
            ),
        )
    })
}

/// Walk `text`, calling `visit` for each node; `visit` returns an error message to stop at
/// that node's line.
pub(crate) fn walk(
    file: &str,
    text: &str,
    mut visit: impl FnMut(Node<'_>) -> Result<(), String>,
) -> RaceResult<()> {
    let mut r = quick_xml::Reader::from_str(text);
    let mut path = Path {
        names: Vec::new(),
        depth: 0,
    };
    let mut attrs: Vec<(String, String)> = Vec::new();
    loop {
        let pos = r.buffer_position();
        let ev = next_event(&mut r, file, text)?;
        let at = |m: String| RaceError::at_line(file, line_of(text, pos), m);
        match ev {
            Event::Start(ref e) | Event::Empty(ref e) => {
                path.push(e.name().as_ref());
                attrs.clear();
                for a in e.attributes().flatten() {
                    if let Ok(v) = a.normalized_value(XmlVersion::Implicit1_0) {
                        attrs.push((local(a.key.as_ref()).to_string(), v.into_owned()));
                    }
                }
                visit(Node::Open(path.open(), &attrs)).map_err(at)?;
                if matches!(ev, Event::Empty(_)) {
                    visit(Node::Close(path.open())).map_err(at)?;
                    path.depth -= 1;
                }
            }
            Event::Text(t) => {
                let s = t.xml10_content();
                if !s.trim().is_empty() && path.depth > 0 {
                    visit(Node::Text(path.open(), s.trim())).map_err(at)?;
                }
            }
            Event::CData(t) => {
                let s = t.xml10_content();
                if !s.trim().is_empty() && path.depth > 0 {
                    visit(Node::Text(path.open(), s.trim())).map_err(at)?;
                }
            }
            Event::End(_) if path.depth > 0 => {
                visit(Node::Close(path.open())).map_err(at)?;
                path.depth -= 1;
            }
            Event::Eof => break,
            _ => {}
        }
    }
    Ok(())
}

/// The last element of a path.
pub(crate) fn last(path: &[String]) -> &str {
    path.last().map_or("", String::as_str)
}

/// The element before the last.
pub(crate) fn parent(path: &[String]) -> &str {
    path.len()
        .checked_sub(2)
        .and_then(|k| path.get(k))
        .map_or("", String::as_str)
}
