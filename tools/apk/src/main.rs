//! `regatta-apk`: packages and signs Regatta's APK (see the crate docs). Called by
//! `scripts/build-apk.sh`; prints a JSON summary on stdout, one-sentence errors on stderr.

#[cfg(not(target_os = "android"))]
fn main() -> std::process::ExitCode {
    host::main()
}

#[cfg(target_os = "android")]
fn main() {
    eprintln!("regatta-apk runs on the build host, not on Android");
    std::process::exit(2);
}

#[cfg(not(target_os = "android"))]
mod host {
    use std::path::PathBuf;
    use std::process::ExitCode;

    use clap::Parser;
    use regatta_apk::ApkError;
    use regatta_apk::key::debug_identity;
    use regatta_apk::metadata::CrateAndroid;
    use regatta_apk::package::{ApkInputs, write_apk};
    use regatta_apk::symbols::{SymbolMaps, check, read_undefined};

    /// Packages Regatta's APK and checks its native library.
    #[derive(Parser, Debug)]
    #[command(name = "regatta-apk", version)]
    enum Cli {
        /// Package, align and sign the APK from the cargo-apk metadata of a Cargo.toml.
        Package(Args),
        /// Check the library's undefined dynamic symbols against Android's symbol maps at the
        /// manifest's minSdk.
        CheckSymbols(SymbolArgs),
        /// Refuse a library whose symbol table names the bench's code (tools/bench).
        CheckBenchFree(BenchFreeArgs),
        /// Read a built APK back: refuse ARCore's library without ARCore's classes (DEX) and
        /// code declared but absent; print its libraries, DEX files and intent filters.
        Check(CheckArgs),
    }

    #[derive(clap::Args, Debug)]
    struct BenchFreeArgs {
        /// The native library to check.
        #[arg(long)]
        lib: PathBuf,
    }

    #[derive(clap::Args, Debug)]
    struct CheckArgs {
        /// The APK to check.
        #[arg(long)]
        apk: PathBuf,
    }

    #[derive(clap::Args, Debug)]
    struct SymbolArgs {
        /// The Cargo.toml whose [package.metadata.android] gives minSdk.
        #[arg(long, default_value = "app/Cargo.toml")]
        manifest: PathBuf,
        /// The native library to check.
        #[arg(long)]
        lib: PathBuf,
        /// Folders of AOSP `*.map.txt` symbol maps (repeat the option for more).
        #[arg(long, required = true)]
        maps: Vec<PathBuf>,
    }

    #[derive(clap::Args, Debug)]
    struct Args {
        /// The Cargo.toml whose [package.metadata.android] describes the app.
        #[arg(long, default_value = "app/Cargo.toml")]
        manifest: PathBuf,
        /// The app's native library (lib<crate>.so built for aarch64-linux-android).
        #[arg(long)]
        lib: PathBuf,
        /// More arm64-v8a libraries to package (e.g. ARCore's libarcore_sdk_c.so).
        #[arg(long = "extra-lib")]
        extra_libs: Vec<PathBuf>,
        /// DEX files to package (e.g. ARCore's classes, dexed with d8).
        #[arg(long)]
        dex: Vec<PathBuf>,
        /// Library manifests to merge into the app's (e.g. the AndroidManifest.xml of
        /// ARCore's AAR: its meta-data, InstallActivity and queries).
        #[arg(long = "merge-manifest")]
        merge_manifests: Vec<PathBuf>,
        /// Signing key (PEM: private key and certificate); generated here when missing.
        #[arg(long)]
        key: PathBuf,
        /// The APK to write.
        #[arg(long)]
        out: PathBuf,
    }

    pub fn main() -> ExitCode {
        let result = match Cli::parse() {
            Cli::Package(args) => run(&args),
            Cli::CheckSymbols(args) => check_symbols(&args),
            Cli::CheckBenchFree(args) => regatta_apk::bench_free::check_bench_free(&args.lib)
                .map(|n| serde_json::json!({ "lib": args.lib, "symbols_checked": n }).to_string()),
            Cli::Check(args) => regatta_apk::check::check_apk(&args.apk).and_then(|report| {
                serde_json::to_string_pretty(&report).map_err(|e| ApkError(e.to_string()))
            }),
        };
        match result {
            Ok(json) => {
                println!("{json}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("regatta-apk: {e}");
                ExitCode::FAILURE
            }
        }
    }

    fn check_symbols(args: &SymbolArgs) -> Result<String, ApkError> {
        let app = CrateAndroid::read(&args.manifest)?;
        let min_sdk = app.android.sdk.min_sdk_version;
        let dirs: Vec<&std::path::Path> = args.maps.iter().map(PathBuf::as_path).collect();
        let maps = SymbolMaps::read_dirs(&dirs)?;
        let (undefined, versions) = read_undefined(&args.lib)?;
        let report = check(&maps, &undefined, &versions, min_sdk);
        let json = serde_json::to_string_pretty(&report).map_err(|e| ApkError(e.to_string()))?;
        if report.problems.is_empty() {
            Ok(json)
        } else {
            println!("{json}");
            Err(ApkError(format!(
                "{}: {} undefined symbol problem(s) at minSdk {min_sdk}: {}",
                args.lib.display(),
                report.problems.len(),
                report.problems.join("; ")
            )))
        }
    }

    fn run(args: &Args) -> Result<String, ApkError> {
        let app = CrateAndroid::read(&args.manifest)?;
        let (identity, generated) = debug_identity(&args.key)?;
        if generated {
            eprintln!("regatta-apk: generated debug key {}", args.key.display());
        }
        let inputs = ApkInputs {
            app,
            library: args.lib.clone(),
            extra_libraries: args.extra_libs.clone(),
            dex: args.dex.clone(),
            library_manifests: args.merge_manifests.clone(),
        };
        let summary = write_apk(&inputs, &args.manifest, identity, &args.out)?;
        serde_json::to_string_pretty(&summary).map_err(|e| ApkError(e.to_string()))
    }
}
