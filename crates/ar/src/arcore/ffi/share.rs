//! A file handed to Android's share sheet: put into the shared media store (`MediaStore`,
//! API 29+: a pending item with its display name, MIME type and `RELATIVE_PATH`, written
//! through `ContentResolver.openOutputStream`, then published by clearing `IS_PENDING`), then
//! offered with `Intent.createChooser(ACTION_SEND with EXTRA_STREAM = the item's URI and
//! FLAG_GRANT_READ_URI_PERMISSION)` started from the Activity. No Java class of ours: the APK
//! has none. On the phone the app implements [`ShareJni`] with the `jni` crate
//! (`app/src/android/share.rs`); on the host [`ScriptedJni`] plays the media store and records
//! the chooser.

use std::sync::MutexGuard;

use super::jni::{JavaObject, ScriptedJni};
pub use super::share_media::{Chooser, MediaItem, MediaScript, NO_SPACE, StoredMedia};

/// The first Android with `MediaStore.MediaColumns.RELATIVE_PATH` and `IS_PENDING` (10, Q).
pub const MEDIA_STORE_MIN_SDK: u32 = 29;
/// `MediaStore.MediaColumns.DISPLAY_NAME`, `MIME_TYPE`, `RELATIVE_PATH`, `IS_PENDING`.
pub const DISPLAY_NAME: &str = "_display_name";
pub const MIME_TYPE: &str = "mime_type";
pub const RELATIVE_PATH: &str = "relative_path";
pub const IS_PENDING: &str = "is_pending";
/// `Intent.EXTRA_STREAM`.
pub const EXTRA_STREAM: &str = "android.intent.extra.STREAM";
/// `Intent.FLAG_GRANT_READ_URI_PERMISSION`.
pub const FLAG_GRANT_READ_URI_PERMISSION: i32 = 0x0000_0001;

/// The Java calls that share a file.
pub trait ShareJni {
    /// Inserts `item` into `MediaStore.Images.Media.EXTERNAL_CONTENT_URI` with `IS_PENDING` 1
    /// (through `on.getContentResolver()`), writes `bytes` through `openOutputStream`, sets
    /// `IS_PENDING` 0; the item's `content://` URI. A failure after the insert deletes the
    /// item, so no half-written picture is left; the error is one sentence with the Java
    /// exception's class and message, where one was thrown.
    fn insert_media(
        &self,
        on: JavaObject,
        item: &MediaItem,
        bytes: &[u8],
    ) -> Result<String, String>;
    /// `on.startActivity(Intent.createChooser(new Intent(ACTION_SEND).setType(mime)
    /// .putExtra(EXTRA_STREAM, Uri.parse(uri)).addFlags(FLAG_GRANT_READ_URI_PERMISSION),
    /// title))`.
    fn share_chooser(
        &self,
        on: JavaObject,
        uri: &str,
        mime: &str,
        title: &str,
    ) -> Result<(), String>;
}

impl ScriptedJni {
    fn media(&self) -> MutexGuard<'_, MediaScript> {
        self.media.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Changes the media store's script or reads what it holds.
    pub fn script_media<T>(&self, f: impl FnOnce(&mut MediaScript) -> T) -> T {
        f(&mut self.media())
    }
}

impl ShareJni for ScriptedJni {
    fn insert_media(
        &self,
        on: JavaObject,
        item: &MediaItem,
        bytes: &[u8],
    ) -> Result<String, String> {
        use super::jni::Jni;
        self.record("getContentResolver().insert", on);
        if self.sdk_int() < MEDIA_STORE_MIN_SDK {
            // The column names exist from API 29: an older provider rejects them.
            return Err(format!(
                "java.lang.IllegalArgumentException: Unknown column {RELATIVE_PATH}"
            ));
        }
        let mut m = self.media();
        if m.refuse_insert {
            return Err("the media store refused the new item (insert returned null)".into());
        }
        let uri = format!(
            "content://media/external/images/media/{}",
            1000 + m.stored.len()
        );
        m.stored.push(StoredMedia {
            uri: uri.clone(),
            item: item.clone(),
            bytes: Vec::new(),
            pending: true,
        });
        self.record("getContentResolver().openOutputStream", on);
        if let Some(e) = m.write_throws.clone() {
            // Deleted again, as the phone's code does after a failed write.
            m.stored.pop();
            return Err(e);
        }
        let last = m.stored.last_mut().expect("pushed above");
        last.bytes = bytes.to_vec();
        last.pending = false;
        self.record("getContentResolver().update", on);
        Ok(uri)
    }

    fn share_chooser(
        &self,
        on: JavaObject,
        uri: &str,
        mime: &str,
        title: &str,
    ) -> Result<(), String> {
        self.record("startActivity", on);
        Self::activity_only("startActivity", on)?;
        let mut m = self.media();
        if let Some(e) = m.chooser_throws.clone() {
            return Err(e);
        }
        m.choosers.push(Chooser {
            uri: uri.into(),
            mime: mime.into(),
            title: title.into(),
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arcore::ffi::{JavaScript, ScriptedJni};

    fn gif_item() -> MediaItem {
        MediaItem {
            display_name: "clip.gif".into(),
            mime: "image/gif".into(),
            relative_path: "Pictures/Regatta".into(),
        }
    }

    #[test]
    fn the_fake_media_store_keeps_published_items_and_refuses_as_scripted() {
        let jni = ScriptedJni::new(JavaScript::default());
        let uri = jni
            .insert_media(JavaObject::Activity, &gif_item(), b"GIF89a")
            .unwrap();
        assert!(uri.starts_with("content://media/"), "{uri}");
        let stored = jni.script_media(|m| m.stored.clone());
        assert_eq!(stored.len(), 1);
        assert_eq!(
            (stored[0].bytes.as_slice(), stored[0].pending),
            (&b"GIF89a"[..], false)
        );
        jni.share_chooser(JavaObject::Activity, &uri, "image/gif", "Share clip")
            .unwrap();
        // startActivity is the Activity's.
        assert!(
            jni.share_chooser(JavaObject::Application, &uri, "image/gif", "x")
                .is_err()
        );
        // A full disk: the exception's text, and nothing left behind.
        jni.script_media(|m| m.write_throws = Some(NO_SPACE.into()));
        let e = jni
            .insert_media(JavaObject::Activity, &gif_item(), b"GIF89a")
            .unwrap_err();
        assert_eq!(e, NO_SPACE);
        assert_eq!(jni.script_media(|m| m.stored.len()), 1);
        // Below API 29 the provider knows no RELATIVE_PATH.
        jni.script(|s| s.sdk_int = 28);
        let e = jni
            .insert_media(JavaObject::Activity, &gif_item(), b"x")
            .unwrap_err();
        assert!(e.contains(RELATIVE_PATH), "{e}");
    }
}
