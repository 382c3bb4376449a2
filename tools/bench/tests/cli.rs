//! The bench program's command line: what `regatta bench ARGS` runs (the app passes the
//! arguments on), so its refusals are the app's one `regatta:` line with exit non-zero.

use std::path::PathBuf;
use std::process::Command;

fn bench(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_regatta-bench"))
        .args(args)
        .output()
        .expect("run regatta-bench");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn an_unknown_section_is_one_line_and_leaves_no_folder() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_unknown_section");
    let _ = std::fs::remove_dir_all(&out);
    let (code, stdout, err) = bench(&["--only", "bogus", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(stdout.is_empty(), "{stdout}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("regatta: --only names the unknown section \"bogus\"; the sections are: "),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn an_unknown_flag_is_one_line_exit_2_and_help_names_the_app_command() {
    let (code, stdout, err) = bench(&["--fast"]);
    assert_eq!(code, 2, "{err}");
    assert!(stdout.is_empty(), "{stdout}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("unexpected argument '--fast'"), "{err}");
    let (code, help, _) = bench(&["--help"]);
    assert_eq!(code, 0);
    assert!(help.contains("Usage: regatta bench [OPTIONS]"), "{help}");
    assert!(help.contains("--only <ONLY>"), "{help}");
}

#[test]
fn a_quick_section_writes_the_report_it_counts_on_stdout() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_waves");
    let _ = std::fs::remove_dir_all(&out);
    let (code, stdout, err) =
        bench(&["--quick", "--only", "waves", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let summary: serde_json::Value = serde_json::from_str(&stdout).expect("JSON summary");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let tables = report["tables"].as_array().expect("tables").len();
    assert!(tables > 0);
    assert_eq!(summary["tables"].as_u64(), Some(tables as u64));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert_eq!(md.matches("\n## ").count(), tables, "{md}");
}
