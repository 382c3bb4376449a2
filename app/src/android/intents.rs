//! [`IntentJni`] on the phone: the file of the intent the Activity was started with ("Open
//! with": `ACTION_VIEW` and `getData()`; "Share": `ACTION_SEND` and `EXTRA_STREAM`), its
//! display name from the provider (`OpenableColumns.DISPLAY_NAME`) and its bytes through
//! `ContentResolver.openInputStream`, read in 64 KiB blocks and stopped one byte past the cap.
//! A Java exception (a revoked grant: `SecurityException`; a deleted file:
//! `FileNotFoundException`) is caught and cleared here and becomes the error's text, so none is
//! left pending. The host runs `ar::arcore::ffi::ScriptedJni` in its place.

use ar::arcore::ffi::intent::{ACTION_SEND, ACTION_VIEW};
use ar::arcore::ffi::{IntentFile, IntentJni, JavaObject};
use jni::objects::{JObject, JString};
use jni::refs::Reference;
use jni::{Env, JValue, jni_sig, jni_str};

use super::jni_calls::AndroidJni;

/// Bytes read per `InputStream.read` call.
const BLOCK: usize = 64 * 1024;

/// `body`, with a Java exception it left pending caught and cleared: the error then carries
/// the exception's class and message.
pub(super) fn caught<'local, T>(
    env: &mut Env<'local>,
    body: impl FnOnce(&mut Env<'local>) -> jni::errors::Result<T>,
) -> jni::errors::Result<T> {
    let result = body(env);
    if result.is_err() && env.exception_check() {
        env.exception_catch()?;
    }
    result
}

/// A Java string as Rust's, `None` for `null`.
fn string(env: &mut Env<'_>, obj: JObject<'_>) -> jni::errors::Result<Option<String>> {
    if obj.is_null() {
        return Ok(None);
    }
    let s = env.cast_local::<JString>(obj)?;
    Ok(Some(s.try_to_string(env)?))
}

/// `uri.toString()` (a `android.net.Uri`), `None` for a `null` string.
pub(super) fn uri_text(
    env: &mut Env<'_>,
    uri: &JObject<'_>,
) -> jni::errors::Result<Option<String>> {
    let text = env
        .call_method(
            uri,
            jni_str!("toString"),
            jni_sig!("()Ljava/lang/String;"),
            &[],
        )?
        .l()?;
    string(env, text)
}

/// `Uri.parse(uri)`.
pub(super) fn parse_uri<'local>(
    env: &mut Env<'local>,
    uri: &str,
) -> jni::errors::Result<JObject<'local>> {
    let text = env.new_string(uri)?;
    env.call_static_method(
        jni_str!("android/net/Uri"),
        jni_str!("parse"),
        jni_sig!("(Ljava/lang/String;)Landroid/net/Uri;"),
        &[JValue::Object(&text)],
    )?
    .l()
}

/// `receiver.getContentResolver()`.
pub(super) fn resolver<'local>(
    env: &mut Env<'local>,
    receiver: &JObject<'_>,
) -> jni::errors::Result<JObject<'local>> {
    env.call_method(
        receiver,
        jni_str!("getContentResolver"),
        jni_sig!("()Landroid/content/ContentResolver;"),
        &[],
    )?
    .l()
}

impl IntentJni for AndroidJni {
    fn intent_file(&self, on: JavaObject) -> Result<Option<IntentFile>, String> {
        self.attached(on, |env, receiver| {
            caught(env, |env| {
                let intent = env
                    .call_method(
                        &receiver,
                        jni_str!("getIntent"),
                        jni_sig!("()Landroid/content/Intent;"),
                        &[],
                    )?
                    .l()?;
                if intent.is_null() {
                    return Ok(None);
                }
                let action = env
                    .call_method(
                        &intent,
                        jni_str!("getAction"),
                        jni_sig!("()Ljava/lang/String;"),
                        &[],
                    )?
                    .l()?;
                let Some(action) = string(env, action)? else {
                    return Ok(None);
                };
                let uri = if action == ACTION_VIEW {
                    env.call_method(
                        &intent,
                        jni_str!("getData"),
                        jni_sig!("()Landroid/net/Uri;"),
                        &[],
                    )?
                    .l()?
                } else if action == ACTION_SEND {
                    let key = env.new_string("android.intent.extra.STREAM")?;
                    env.call_method(
                        &intent,
                        jni_str!("getParcelableExtra"),
                        jni_sig!("(Ljava/lang/String;)Landroid/os/Parcelable;"),
                        &[JValue::Object(&key)],
                    )?
                    .l()?
                } else {
                    return Ok(None);
                };
                if uri.is_null() {
                    return Ok(None);
                }
                let Some(uri) = uri_text(env, &uri)? else {
                    return Ok(None);
                };
                let mime = env
                    .call_method(
                        &intent,
                        jni_str!("getType"),
                        jni_sig!("()Ljava/lang/String;"),
                        &[],
                    )?
                    .l()?;
                let mime = string(env, mime)?;
                Ok(Some(IntentFile { action, uri, mime }))
            })
        })
    }

    fn content_name(&self, on: JavaObject, uri: &str) -> Result<Option<String>, String> {
        self.attached(on, |env, receiver| {
            caught(env, |env| {
                let resolver = resolver(env, &receiver)?;
                let uri = parse_uri(env, uri)?;
                let column = env.new_string("_display_name")?;
                let string_class = env.find_class(jni_str!("java/lang/String"))?;
                let projection = env.new_object_array(1, &string_class, &column)?;
                let null = JObject::null();
                let cursor = env
                    .call_method(
                        &resolver,
                        jni_str!("query"),
                        jni_sig!(
                            "(Landroid/net/Uri;[Ljava/lang/String;Ljava/lang/String;[Ljava/lang/String;Ljava/lang/String;)Landroid/database/Cursor;"
                        ),
                        &[
                            JValue::Object(&uri),
                            JValue::Object(&projection),
                            JValue::Object(&null),
                            JValue::Object(&null),
                            JValue::Object(&null),
                        ],
                    )?
                    .l()?;
                if cursor.is_null() {
                    return Ok(None);
                }
                let first = env
                    .call_method(&cursor, jni_str!("moveToFirst"), jni_sig!("()Z"), &[])?
                    .z()?;
                let name = if first {
                    let s = env
                        .call_method(
                            &cursor,
                            jni_str!("getString"),
                            jni_sig!("(I)Ljava/lang/String;"),
                            &[JValue::Int(0)],
                        )?
                        .l()?;
                    string(env, s)?
                } else {
                    None
                };
                env.call_method(&cursor, jni_str!("close"), jni_sig!("()V"), &[])?;
                Ok(name)
            })
        })
    }

    fn read_content(&self, on: JavaObject, uri: &str, max_bytes: u64) -> Result<Vec<u8>, String> {
        let limit = usize::try_from(max_bytes.saturating_add(1)).unwrap_or(usize::MAX);
        self.attached(on, |env, receiver| {
            caught(env, |env| {
                let resolver = resolver(env, &receiver)?;
                let uri = parse_uri(env, uri)?;
                let stream = env
                    .call_method(
                        &resolver,
                        jni_str!("openInputStream"),
                        jni_sig!("(Landroid/net/Uri;)Ljava/io/InputStream;"),
                        &[JValue::Object(&uri)],
                    )?
                    .l()?;
                if stream.is_null() {
                    return Ok(Vec::new());
                }
                let block = env.new_byte_array(BLOCK)?;
                let mut bytes = Vec::new();
                while bytes.len() < limit {
                    let want = (limit - bytes.len()).min(BLOCK) as i32;
                    let n = env
                        .call_method(
                            &stream,
                            jni_str!("read"),
                            jni_sig!("([BII)I"),
                            &[JValue::Object(&block), JValue::Int(0), JValue::Int(want)],
                        )?
                        .i()?;
                    if n < 0 {
                        break;
                    }
                    let read = env.convert_byte_array(&block)?;
                    bytes.extend_from_slice(&read[..n as usize]);
                }
                env.call_method(&stream, jni_str!("close"), jni_sig!("()V"), &[])?;
                Ok(bytes)
            })
        })
    }
}
