//! [`ShareJni`] on the phone: a clip into `MediaStore.Images` (API 29+: `DISPLAY_NAME`,
//! `MIME_TYPE`, `RELATIVE_PATH`, `IS_PENDING` 1 → bytes through
//! `ContentResolver.openOutputStream` → `IS_PENDING` 0) and the share sheet
//! (`Intent.createChooser` of an `ACTION_SEND` with `EXTRA_STREAM` and the read grant, started
//! from the Activity). No Java class of ours: every call is a framework method through the
//! `jni` crate. A Java exception is caught and cleared ([`super::intents::caught`]) and becomes
//! the error's text; after a failed write the pending item is deleted. The host runs
//! `ar::arcore::ffi::ScriptedJni` in its place.

use ar::arcore::ffi::intent::ACTION_SEND;
use ar::arcore::ffi::share::{
    DISPLAY_NAME, EXTRA_STREAM, FLAG_GRANT_READ_URI_PERMISSION, IS_PENDING, MIME_TYPE,
    RELATIVE_PATH,
};
use ar::arcore::ffi::{JavaObject, MediaItem, ShareJni};
use jni::objects::JObject;
use jni::{Env, JValue, jni_sig, jni_str};

use super::intents::{caught, parse_uri, resolver, uri_text};
use super::jni_calls::AndroidJni;

/// Bytes written per `OutputStream.write` call.
const BLOCK: usize = 64 * 1024;

/// `values.put(key, text)`.
fn put_string(
    env: &mut Env<'_>,
    values: &JObject<'_>,
    key: &str,
    text: &str,
) -> jni::errors::Result<()> {
    let (k, v) = (env.new_string(key)?, env.new_string(text)?);
    env.call_method(
        values,
        jni_str!("put"),
        jni_sig!("(Ljava/lang/String;Ljava/lang/String;)V"),
        &[JValue::Object(&k), JValue::Object(&v)],
    )?;
    Ok(())
}

/// `values.put(key, Integer.valueOf(n))`.
fn put_int(env: &mut Env<'_>, values: &JObject<'_>, key: &str, n: i32) -> jni::errors::Result<()> {
    let k = env.new_string(key)?;
    let boxed = env
        .call_static_method(
            jni_str!("java/lang/Integer"),
            jni_str!("valueOf"),
            jni_sig!("(I)Ljava/lang/Integer;"),
            &[JValue::Int(n)],
        )?
        .l()?;
    env.call_method(
        values,
        jni_str!("put"),
        jni_sig!("(Ljava/lang/String;Ljava/lang/Integer;)V"),
        &[JValue::Object(&k), JValue::Object(&boxed)],
    )?;
    Ok(())
}

/// `new ContentValues()`.
fn content_values<'local>(env: &mut Env<'local>) -> jni::errors::Result<JObject<'local>> {
    env.new_object(
        jni_str!("android/content/ContentValues"),
        jni_sig!("()V"),
        &[],
    )
}

/// Writes `bytes` to `uri` through `resolver.openOutputStream(uri)` and publishes the item
/// (`IS_PENDING` 0).
fn write_and_publish(
    env: &mut Env<'_>,
    resolver: &JObject<'_>,
    uri: &JObject<'_>,
    bytes: &[u8],
) -> jni::errors::Result<()> {
    let stream = env
        .call_method(
            resolver,
            jni_str!("openOutputStream"),
            jni_sig!("(Landroid/net/Uri;)Ljava/io/OutputStream;"),
            &[JValue::Object(uri)],
        )?
        .l()?;
    if stream.is_null() {
        return Err(jni::errors::Error::NullPtr(
            "openOutputStream returned null",
        ));
    }
    for chunk in bytes.chunks(BLOCK) {
        let block = env.byte_array_from_slice(chunk)?;
        env.call_method(
            &stream,
            jni_str!("write"),
            jni_sig!("([BII)V"),
            &[
                JValue::Object(&block),
                JValue::Int(0),
                JValue::Int(chunk.len() as i32),
            ],
        )?;
        env.delete_local_ref(block);
    }
    env.call_method(&stream, jni_str!("close"), jni_sig!("()V"), &[])?;
    let done = content_values(env)?;
    put_int(env, &done, IS_PENDING, 0)?;
    let null = JObject::null();
    env.call_method(
        resolver,
        jni_str!("update"),
        jni_sig!(
            "(Landroid/net/Uri;Landroid/content/ContentValues;Ljava/lang/String;[Ljava/lang/String;)I"
        ),
        &[
            JValue::Object(uri),
            JValue::Object(&done),
            JValue::Object(&null),
            JValue::Object(&null),
        ],
    )?;
    Ok(())
}

impl ShareJni for AndroidJni {
    fn insert_media(
        &self,
        on: JavaObject,
        item: &MediaItem,
        bytes: &[u8],
    ) -> Result<String, String> {
        self.attached(on, |env, receiver| {
            caught(env, |env| {
                let resolver = resolver(env, &receiver)?;
                let collection = env
                    .get_static_field(
                        jni_str!("android/provider/MediaStore$Images$Media"),
                        jni_str!("EXTERNAL_CONTENT_URI"),
                        jni_sig!("Landroid/net/Uri;"),
                    )?
                    .l()?;
                let values = content_values(env)?;
                put_string(env, &values, DISPLAY_NAME, &item.display_name)?;
                put_string(env, &values, MIME_TYPE, &item.mime)?;
                put_string(env, &values, RELATIVE_PATH, &item.relative_path)?;
                put_int(env, &values, IS_PENDING, 1)?;
                let uri = env
                    .call_method(
                        &resolver,
                        jni_str!("insert"),
                        jni_sig!(
                            "(Landroid/net/Uri;Landroid/content/ContentValues;)Landroid/net/Uri;"
                        ),
                        &[JValue::Object(&collection), JValue::Object(&values)],
                    )?
                    .l()?;
                if uri.is_null() {
                    return Ok(Err(
                        "the media store refused the new item (insert returned null)".to_string(),
                    ));
                }
                if let Err(e) = write_and_publish(env, &resolver, &uri, bytes) {
                    // The exception's text first, then the half-written item goes.
                    let why = match env.exception_catch() {
                        Err(thrown) => thrown.to_string(),
                        Ok(()) => e.to_string(),
                    };
                    let null = JObject::null();
                    let _ = env.call_method(
                        &resolver,
                        jni_str!("delete"),
                        jni_sig!("(Landroid/net/Uri;Ljava/lang/String;[Ljava/lang/String;)I"),
                        &[
                            JValue::Object(&uri),
                            JValue::Object(&null),
                            JValue::Object(&null),
                        ],
                    );
                    if env.exception_check() {
                        let _ = env.exception_catch();
                    }
                    return Ok(Err(why));
                }
                let text = uri_text(env, &uri)?;
                Ok(Ok(text.ok_or(jni::errors::Error::NullPtr("Uri.toString"))?))
            })
        })?
    }

    fn share_chooser(
        &self,
        on: JavaObject,
        uri: &str,
        mime: &str,
        title: &str,
    ) -> Result<(), String> {
        self.attached(on, |env, receiver| {
            caught(env, |env| {
                let action = env.new_string(ACTION_SEND)?;
                let send = env.new_object(
                    jni_str!("android/content/Intent"),
                    jni_sig!("(Ljava/lang/String;)V"),
                    &[JValue::Object(&action)],
                )?;
                let mime = env.new_string(mime)?;
                env.call_method(
                    &send,
                    jni_str!("setType"),
                    jni_sig!("(Ljava/lang/String;)Landroid/content/Intent;"),
                    &[JValue::Object(&mime)],
                )?;
                let key = env.new_string(EXTRA_STREAM)?;
                let uri = parse_uri(env, uri)?;
                env.call_method(
                    &send,
                    jni_str!("putExtra"),
                    jni_sig!(
                        "(Ljava/lang/String;Landroid/os/Parcelable;)Landroid/content/Intent;"
                    ),
                    &[JValue::Object(&key), JValue::Object(&uri)],
                )?;
                env.call_method(
                    &send,
                    jni_str!("addFlags"),
                    jni_sig!("(I)Landroid/content/Intent;"),
                    &[JValue::Int(FLAG_GRANT_READ_URI_PERMISSION)],
                )?;
                let title = env.new_string(title)?;
                let chooser = env
                    .call_static_method(
                        jni_str!("android/content/Intent"),
                        jni_str!("createChooser"),
                        jni_sig!(
                            "(Landroid/content/Intent;Ljava/lang/CharSequence;)Landroid/content/Intent;"
                        ),
                        &[JValue::Object(&send), JValue::Object(&title)],
                    )?
                    .l()?;
                env.call_method(
                    &receiver,
                    jni_str!("startActivity"),
                    jni_sig!("(Landroid/content/Intent;)V"),
                    &[JValue::Object(&chooser)],
                )?;
                Ok(())
            })
        })
    }
}
