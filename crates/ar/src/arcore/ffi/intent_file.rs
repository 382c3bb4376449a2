//! The data of a shared file: the intent that carries it and, for the host's fake
//! (`ScriptedJni`), the content provider that holds it. A module of its own so that the JNI
//! fake (`jni`) and the intent's Java calls (`intent`) both use it and neither imports the
//! other.

/// `Intent.ACTION_VIEW` ("Open with").
pub const ACTION_VIEW: &str = "android.intent.action.VIEW";
/// `Intent.ACTION_SEND` ("Share").
pub const ACTION_SEND: &str = "android.intent.action.SEND";

/// The file an intent carries, before it is read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IntentFile {
    /// `ACTION_VIEW` or `ACTION_SEND`.
    pub action: String,
    /// `content://…` (as `Uri.toString()` gives it).
    pub uri: String,
    /// The intent's MIME type (`Intent.getType()`), where the sender gave one.
    pub mime: Option<String>,
}

/// One file the host's content provider holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ContentFile {
    pub uri: String,
    /// `DISPLAY_NAME`; `None`: the provider gives no name.
    pub name: Option<String>,
    pub bytes: Vec<u8>,
}

/// The host fake's intent and content provider.
#[derive(Debug, Default)]
pub struct ContentScript {
    /// The intent the Activity holds now (`None`: started from the launcher).
    pub intent: Option<IntentFile>,
    /// The provider's files, by URI.
    pub files: Vec<ContentFile>,
}

/// The authority of the host's provider (Android's `FileProvider` URIs look the same).
pub const SIM_AUTHORITY: &str = "org.regatta.sim.provider";
