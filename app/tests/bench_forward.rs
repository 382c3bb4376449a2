//! `regatta bench ARGS` runs the `regatta-bench` program beside the executable (app/src/cli/
//! bench.rs). Checked against a stand-in: a copy of the built `regatta` in a folder of its own,
//! next to a shell script named `regatta-bench` that writes down its arguments and exits 3.
#![cfg(unix)]

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder holding a copy of the built `regatta` (a copy, not a link: the program looks
/// beside the file it runs from).
fn folder_with_regatta(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(env!("CARGO_BIN_EXE_regatta"), dir.join("regatta")).unwrap();
    dir
}

fn run(dir: &Path, args: &[&str]) -> (i32, String, String) {
    // A copy just written may be refused for a moment with ETXTBSY ("text file busy"): a
    // process another test thread forked at that moment holds the file's write descriptor
    // until it execs. Try again a few times (Linux's known fork/exec race, not the program).
    let mut tries = 0;
    let o = loop {
        match Command::new(dir.join("regatta")).args(args).output() {
            Err(e) if e.kind() == std::io::ErrorKind::ExecutableFileBusy && tries < 50 => {
                tries += 1;
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            other => break other.expect("run the copied regatta"),
        }
    };
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn bench_arguments_stdio_and_exit_code_pass_through() {
    let dir = folder_with_regatta("bench_forward_fake");
    let log = dir.join("args.txt");
    let script = format!(
        "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\" >> '{}'; done\necho fake-out\necho fake-err >&2\nexit 3\n",
        log.display()
    );
    let fake = dir.join("regatta-bench");
    std::fs::write(&fake, script).unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let args = [
        "--quick",
        "--only",
        "waves",
        "--help",
        "two words",
        "--out=x y",
    ];
    let mut full = vec!["bench"];
    full.extend(args);
    let (code, out, err) = run(&dir, &full);
    assert_eq!(code, 3, "{err}");
    assert_eq!(out, "fake-out\n");
    assert_eq!(err, "fake-err\n");
    let seen = std::fs::read_to_string(&log).unwrap();
    assert_eq!(seen.lines().collect::<Vec<_>>(), args);
}

#[test]
fn a_missing_bench_is_one_line_with_the_build_command() {
    let dir = folder_with_regatta("bench_forward_missing");
    let (code, out, err) = run(&dir, &["bench", "--quick"]);
    assert_eq!(code, 1, "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("regatta: the bench is a program of its own and "),
        "{err}"
    );
    assert!(
        err.contains(&dir.join("regatta-bench").display().to_string()),
        "{err}"
    );
    assert!(
        err.trim_end()
            .ends_with("build it with `cargo build -p regatta-bench`"),
        "{err}"
    );
}
