//! The file Android started the Activity with: "Open with" (`Intent.ACTION_VIEW`, the file in
//! the intent's data) or "Share" (`Intent.ACTION_SEND`, the file in `Intent.EXTRA_STREAM`),
//! read through the `ContentResolver` — the only way to another app's file since Android 7
//! (a `file://` URI shared across apps throws `FileUriExposedException` in the sender). On the
//! phone the app implements [`IntentJni`] with the `jni` crate (`app/src/android/intents.rs`);
//! on the host [`ScriptedJni`] plays a content provider that holds the files a script shares.

use std::sync::{Mutex, MutexGuard};

pub use super::intent_file::{
    ACTION_SEND, ACTION_VIEW, ContentFile, ContentScript, IntentFile, SIM_AUTHORITY,
};
use super::jni::{JavaObject, ScriptedJni};

/// The Java calls that read an intent's file.
pub trait IntentJni {
    /// `on.getIntent()`'s file: `getData()` for `ACTION_VIEW`, the `EXTRA_STREAM` parcelable
    /// for `ACTION_SEND`; `Ok(None)` for any other intent (the launcher's `MAIN`) or one
    /// without a URI (text shared, not a file).
    fn intent_file(&self, on: JavaObject) -> Result<Option<IntentFile>, String>;
    /// The name the provider shows for `uri` (`OpenableColumns.DISPLAY_NAME`, through
    /// `on.getContentResolver().query(uri, …)`); `Ok(None)` when it gives none.
    fn content_name(&self, on: JavaObject, uri: &str) -> Result<Option<String>, String>;
    /// The bytes of `uri` through `on.getContentResolver().openInputStream(uri)`, reading at
    /// most `max_bytes + 1` (so that a longer file shows as longer without being read whole).
    fn read_content(&self, on: JavaObject, uri: &str, max_bytes: u64) -> Result<Vec<u8>, String>;
}

impl ScriptedJni {
    fn content(&self) -> MutexGuard<'_, ContentScript> {
        lock(&self.content)
    }

    /// Shares a file as a chat or mail app does: the provider holds `bytes` under a new
    /// `content://` URI that shows `name`, and the Activity's intent becomes `ACTION_SEND`
    /// with that URI as `EXTRA_STREAM` and `mime` as its type. Returns the intent.
    pub fn share(&self, name: Option<&str>, bytes: Vec<u8>, mime: Option<&str>) -> IntentFile {
        let mut c = self.content();
        let uri = format!("content://{SIM_AUTHORITY}/shared/{}", c.files.len() + 1);
        c.files.push(ContentFile {
            uri: uri.clone(),
            name: name.map(str::to_owned),
            bytes,
        });
        let intent = IntentFile {
            action: ACTION_SEND.into(),
            uri,
            mime: mime.map(str::to_owned),
        };
        c.intent = Some(intent.clone());
        intent
    }

    /// Changes the intent and the provider directly (an intent whose URI the provider lacks:
    /// a revoked grant, a deleted download).
    pub fn script_content(&self, f: impl FnOnce(&mut ContentScript)) {
        f(&mut self.content());
    }

    fn provider_file(&self, uri: &str) -> Result<ContentFile, String> {
        self.content()
            .files
            .iter()
            .find(|f| f.uri == uri)
            .cloned()
            .ok_or_else(|| format!("java.io.FileNotFoundException: No content provider: {uri}"))
    }
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl IntentJni for ScriptedJni {
    fn intent_file(&self, on: JavaObject) -> Result<Option<IntentFile>, String> {
        self.record("getIntent", on);
        // `getIntent` is the Activity's; the Application has none.
        Self::activity_only("getIntent", on)?;
        Ok(self.content().intent.clone())
    }

    fn content_name(&self, on: JavaObject, uri: &str) -> Result<Option<String>, String> {
        self.record("getContentResolver().query", on);
        Ok(self.provider_file(uri)?.name)
    }

    fn read_content(&self, on: JavaObject, uri: &str, max_bytes: u64) -> Result<Vec<u8>, String> {
        self.record("getContentResolver().openInputStream", on);
        let mut bytes = self.provider_file(uri)?.bytes;
        bytes.truncate(usize::try_from(max_bytes.saturating_add(1)).unwrap_or(usize::MAX));
        Ok(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arcore::ffi::{JavaScript, ScriptedJni};

    #[test]
    fn a_shared_file_is_read_back_through_the_provider_capped() {
        let jni = ScriptedJni::new(JavaScript::default());
        assert_eq!(jni.intent_file(JavaObject::Activity).unwrap(), None);
        let intent = jni.share(Some("boat.gpx"), b"0123456789".to_vec(), Some("text/xml"));
        assert!(intent.uri.starts_with("content://"), "{intent:?}");
        assert_eq!(
            jni.intent_file(JavaObject::Activity).unwrap(),
            Some(intent.clone())
        );
        assert_eq!(
            jni.content_name(JavaObject::Application, &intent.uri)
                .unwrap()
                .as_deref(),
            Some("boat.gpx")
        );
        // At most max + 1 bytes come back: the caller sees "longer than allowed".
        assert_eq!(
            jni.read_content(JavaObject::Application, &intent.uri, 4)
                .unwrap(),
            b"01234"
        );
        assert_eq!(
            jni.read_content(JavaObject::Application, &intent.uri, 100)
                .unwrap(),
            b"0123456789"
        );
        // getIntent is the Activity's, as on Android.
        assert!(jni.intent_file(JavaObject::Application).is_err());
        // A URI the provider does not hold fails as Android's FileNotFoundException.
        let e = jni
            .read_content(JavaObject::Application, "content://x/1", 4)
            .unwrap_err();
        assert!(e.starts_with("java.io.FileNotFoundException"), "{e}");
    }
}
