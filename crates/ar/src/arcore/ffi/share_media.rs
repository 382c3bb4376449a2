//! The data of a shared clip: the media store item and, for the host's fake (`ScriptedJni`),
//! the media store that holds it and the choosers it was asked to show. A module of its own so
//! that the JNI fake (`jni`) and the share's Java calls (`share`) both use it and neither
//! imports the other.

/// What the media store item is called and where it goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MediaItem {
    /// `DISPLAY_NAME`, e.g. `regatta-580-600s.gif`.
    pub display_name: String,
    /// `MIME_TYPE`, e.g. `image/gif`.
    pub mime: String,
    /// `RELATIVE_PATH`, e.g. `Pictures/Regatta`.
    pub relative_path: String,
}

/// One item the host's media store holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StoredMedia {
    pub uri: String,
    pub item: MediaItem,
    pub bytes: Vec<u8>,
    /// `IS_PENDING` as it was left.
    pub pending: bool,
}

/// One chooser the host fake was asked to show.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chooser {
    pub uri: String,
    pub mime: String,
    pub title: String,
}

/// The host fake's media store and what it is scripted to do.
#[derive(Debug, Default)]
pub struct MediaScript {
    /// `insert` returns `null` (the provider refuses: no external volume mounted).
    pub refuse_insert: bool,
    /// Writing throws this Java exception (`class: message`), e.g. a full disk's
    /// `java.io.IOException: No space left on device`.
    pub write_throws: Option<String>,
    /// `startActivity` throws this (e.g. `android.content.ActivityNotFoundException`).
    pub chooser_throws: Option<String>,
    pub stored: Vec<StoredMedia>,
    pub choosers: Vec<Chooser>,
}

/// The Java exception a full disk throws from `OutputStream.write`.
pub const NO_SPACE: &str = "java.io.IOException: No space left on device";
