//! Builds `coal_peer` (cpp/coal/coal_peer.cc), the separate program through which the `peers`
//! benchmark calls coal 3, when the libcoal wheel is installed (scripts/deps.sh puts it under
//! `.peers/coal/cmeel.prefix`; `REVDIST_COAL_PREFIX` names another prefix). coal is never
//! linked into a Rust binary: experiments' binaries link Debian's FCL through verify, and one
//! process with both aborts with a double free (two octomap versions).
//!
//! Without coal (or when the shim does not compile) the build still succeeds: the program's
//! path is then absent and `REVDIST_COAL_PEER_MISSING` says why, which the benchmark prints in
//! coal's columns. scripts/deps.sh touches the shim's source after installing coal, so the
//! next build picks it up.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let root = manifest
        .parent()
        .expect("experiments/ sits in the workspace")
        .to_owned();
    let source = root.join("cpp/coal/coal_peer.cc");
    println!("cargo:rerun-if-changed={}", source.display());
    println!("cargo:rerun-if-env-changed=REVDIST_COAL_PREFIX");
    println!("cargo:rerun-if-env-changed=CXX");
    let prefix = std::env::var_os("REVDIST_COAL_PREFIX")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join(".peers/coal/cmeel.prefix"));
    let lib = prefix.join("lib/libcoal.so");
    if lib.exists() {
        println!("cargo:rerun-if-changed={}", lib.display());
    }
    match build(&prefix, &source, &lib) {
        Ok(exe) => println!("cargo:rustc-env=REVDIST_COAL_PEER={}", exe.display()),
        Err(why) => {
            println!("cargo:rustc-env=REVDIST_COAL_PEER_MISSING={why}");
            println!("cargo:warning=coal peer not built: {why}");
        }
    }
}

/// Compiles the shim against the coal under `prefix`; the program's path, or why not.
fn build(prefix: &Path, source: &Path, lib: &Path) -> Result<PathBuf, String> {
    if !lib.exists() || !prefix.join("include/coal/distance.h").exists() {
        return Err(format!(
            "coal missing: run scripts/deps.sh (no {})",
            lib.display()
        ));
    }
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it"));
    let exe = out.join("coal_peer");
    let cxx = std::env::var("CXX").unwrap_or_else(|_| "c++".into());
    let libdir = prefix.join("lib");
    let status = Command::new(&cxx)
        .args(["-O3", "-std=c++17", "-DNDEBUG", "-w"])
        .arg(source)
        .arg(format!("-I{}", prefix.join("include").display()))
        .arg("-I/usr/include/eigen3")
        .arg(format!("-L{}", libdir.display()))
        .arg("-lcoal")
        .arg(format!("-Wl,-rpath,{}", libdir.display()))
        .arg("-o")
        .arg(&exe)
        .status()
        .map_err(|e| {
            format!(
                "coal missing: run scripts/deps.sh (the C++ compiler '{cxx}' did not start: {e})"
            )
        })?;
    if !status.success() {
        return Err(format!(
            "coal missing: {} did not compile against {} ({status}); see the build log",
            source.display(),
            prefix.display()
        ));
    }
    Ok(exe)
}
