//! The debug signing key: a self-signed ECDSA P-256 certificate generated on first use and kept
//! as one PEM file (private key and certificate), like the SDK's `~/.android/debug.keystore`.

use std::path::Path;

use apk::sign::SigningIdentity;

use crate::ApkError;

/// Distinguished name of the debug certificate, as the Android SDK writes its own.
const DEBUG_DN: &str = "CN=Android Debug,O=Android,C=US";

/// Loads the key at `path`, generating and writing it first when the file does not exist.
/// Returns the identity and whether it was generated now.
pub fn debug_identity(path: &Path) -> Result<(SigningIdentity, bool), ApkError> {
    let generated = !path.exists();
    if generated {
        let pem = generate_debug_pem()?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|e| ApkError(format!("{}: cannot create: {e}", dir.display())))?;
        }
        write_private(path, &pem)?;
    }
    let pem = std::fs::read_to_string(path).map_err(|e| {
        ApkError(format!(
            "{}: cannot read the signing key: {e}",
            path.display()
        ))
    })?;
    let identity = SigningIdentity::from_pem(&pem).map_err(|e| {
        ApkError(format!(
            "{}: not a PEM private key with its certificate: {e}",
            path.display()
        ))
    })?;
    Ok((identity, generated))
}

/// A fresh key pair and self-signed certificate (valid 30 years) as one PEM text.
pub fn generate_debug_pem() -> Result<String, ApkError> {
    let fail = |e: rcgen::Error| ApkError(format!("cannot generate the debug key: {e}"));
    let key = rcgen::KeyPair::generate().map_err(fail)?;
    let mut params = rcgen::CertificateParams::new(Vec::<String>::new()).map_err(fail)?;
    let mut dn = rcgen::DistinguishedName::new();
    for part in DEBUG_DN.split(',') {
        let (k, v) = part.split_once('=').expect("constant DN");
        let ty = match k {
            "CN" => rcgen::DnType::CommonName,
            "O" => rcgen::DnType::OrganizationName,
            _ => rcgen::DnType::CountryName,
        };
        dn.push(ty, v);
    }
    params.distinguished_name = dn;
    params.not_before = rcgen::date_time_ymd(2025, 1, 1);
    params.not_after = rcgen::date_time_ymd(2055, 1, 1);
    let cert = params.self_signed(&key).map_err(fail)?;
    Ok(format!("{}{}", key.serialize_pem(), cert.pem()))
}

fn write_private(path: &Path, text: &str) -> Result<(), ApkError> {
    use std::io::Write;
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o600);
    options
        .open(path)
        .and_then(|mut f| f.write_all(text.as_bytes()))
        .map_err(|e| {
            ApkError(format!(
                "{}: cannot write the debug key: {e}",
                path.display()
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_once_then_reused() {
        let dir = std::env::temp_dir().join(format!("regatta-apk-key-{}", std::process::id()));
        let path = dir.join("debug.pem");
        let _ = std::fs::remove_file(&path);
        let (a, new_a) = debug_identity(&path).unwrap();
        let (b, new_b) = debug_identity(&path).unwrap();
        assert!(new_a && !new_b);
        assert_eq!(a.certificate().der(), b.certificate().der());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn garbage_key_file_is_named() {
        let dir = std::env::temp_dir().join(format!("regatta-apk-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("debug.pem");
        std::fs::write(&path, "not a key").unwrap();
        let e = debug_identity(&path).err().unwrap();
        assert!(
            e.0.starts_with(&format!("{}: not a PEM private key", path.display())),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
