//! Builds the C++ baselines of `verify` (FCL 0.7, libccd 2.1, CGAL 5.5, and OpenCASCADE 7.6
//! when installed; see
//! `docs/verification.md`, "Building the baselines", and `src/baselines/mod.rs`).
//!
//! Layout: the shims are in `cpp/` at the workspace root, one per library
//! (`cpp/include/{fcl,ccd,cgal}_shim.h`, `cpp/src/{fcl,ccd,cgal}_shim.cc`, shared input checks in
//! `cpp/src/common.h`). Two cxx bridges: `src/baselines/mod.rs` (FCL + libccd) and
//! `src/baselines/cgal_ffi.rs` (CGAL).
//!
//! OpenCASCADE is optional: when its headers and libraries are found ([`occt`]), two more
//! static libraries (its bridge and its shim, `cpp/src/occt_shim.cc`) are built and
//! `cfg(revdist_occt)` is set; otherwise a warning says so and `verify` builds without it (the
//! OCCT cross-check then reports "OCCT missing: run scripts/deps.sh"). Debian 12's OCCT 7.6.3
//! has no pkg-config file; its headers are in `/usr/include/opencascade` and one of them
//! (`NCollection_AliasedArray.hxx`) ships only in `libocct-visualization-dev`.
//!
//! Four static libraries (six with OCCT), compiled concurrently, each skipped when a stamp of its inputs (the
//! sources, the cxx-generated headers it includes, the compiler and its flags, the library
//! versions) is unchanged. `cc` itself always recompiles everything, and the CGAL translation
//! unit alone takes ~15 s and ~0.9 GB: the stamps make an edit of the FCL shim (or of the Rust
//! wrappers) cost only what it touches.
//!
//! Flags and pitfalls (notes §1, §5):
//! * `-std=c++17` from `cc` (the pkg-config crate does not forward fcl.pc's `-std=c++11`);
//! * `/usr/include` from pkg-config is skipped (`-isystem/usr/include` breaks libstdc++'s
//!   `#include_next <stdlib.h>`); eigen3 is added as `-isystem`;
//! * no `-march=native`: Eigen's alignment would no longer match libfcl.so's class layout;
//! * ccd.pc says 2.0 for Debian's libccd 2.1; CGAL has no .pc file (header-only) and needs
//!   `-lmpfr -lgmp` and, per CGAL's CMake for GCC, `-frounding-math`;
//! * the shims are always built at -O2 without debug info, whatever the Cargo profile, so the
//!   CGAL exact kernels are not 10x slower in debug test runs.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Minimum FCL version (the API used: `BVHModel<OBBRSSd>`, `DistanceRequestd`, GJKDistance).
const FCL_MIN_VERSION: &str = "0.7";
/// Minimum libccd version as its .pc file states it (Debian's 2.1 ships "Version: 2.0").
const CCD_MIN_VERSION: &str = "2.0";
/// Optimisation level of the shims (independent of the Cargo profile).
const SHIM_OPT_LEVEL: u32 = 2;
/// Name prefix of the generated headers (`#include "verify/src/baselines/mod.rs.h"`).
const BRIDGE_FCL_CCD: &str = "src/baselines/mod.rs";
const BRIDGE_CGAL: &str = "src/baselines/cgal_ffi.rs";
const BRIDGE_OCCT: &str = "src/baselines/occt_ffi.rs";

const INSTALL_HINT: &str = "run scripts/deps.sh (apt-get install libfcl-dev libccd-dev \
                            libcgal-dev libeigen3-dev libgmp-dev libmpfr-dev pkg-config)";

/// One static library to build (or to reuse when its stamp matches).
struct Lib {
    name: &'static str,
    build: cc::Build,
    /// Files whose contents determine the library (besides the compiler command line).
    inputs: Vec<PathBuf>,
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("CARGO_MANIFEST_DIR"));
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    let cpp = manifest.join("../cpp");
    let cpp_include = cpp.join("include");
    let cpp_src = cpp.join("src");

    // pkg-config emits the link lines: fcl, octomap, octomath, ccd, m (and eigen3's include dir).
    let fcl = pkg_config::Config::new()
        .atleast_version(FCL_MIN_VERSION)
        .probe("fcl")
        .unwrap_or_else(|e| {
            panic!("libfcl-dev >= {FCL_MIN_VERSION} not found ({e}); {INSTALL_HINT}")
        });
    let ccd = pkg_config::Config::new()
        .atleast_version(CCD_MIN_VERSION)
        .probe("ccd")
        .unwrap_or_else(|e| panic!("libccd-dev not found ({e}); {INSTALL_HINT}"));
    // CGAL's exact number types: mpfr before gmp (mpfr depends on gmp).
    let mpfr = pkg_config::probe_library("mpfr")
        .unwrap_or_else(|e| panic!("libmpfr-dev not found ({e}); {INSTALL_HINT}"));
    let gmp = pkg_config::probe_library("gmp")
        .unwrap_or_else(|e| panic!("libgmp-dev not found ({e}); {INSTALL_HINT}"));
    let cgal_version = cgal_version().unwrap_or_else(|| {
        panic!("CGAL headers not found (/usr/include/CGAL/version.h); {INSTALL_HINT}")
    });

    let mut include_dirs: Vec<PathBuf> = Vec::new();
    for lib in [&fcl, &ccd] {
        for p in &lib.include_paths {
            if p != Path::new("/usr/include") && !include_dirs.contains(p) {
                include_dirs.push(p.clone());
            }
        }
    }
    let versions = format!(
        "fcl {} ccd {} mpfr {} gmp {} cgal {}",
        fcl.version, ccd.version, mpfr.version, gmp.version, cgal_version
    );

    // The bridges' generated code (cheap) and the generated headers the shims include.
    let bridge_build = cxx_build::bridges([BRIDGE_FCL_CCD, BRIDGE_CGAL]);
    let occt = occt::probe();
    let generated = out_dir.join("cxxbridge/include");
    let gen_header = |bridge: &str| generated.join("verify").join(format!("{bridge}.h"));
    let gen_source = |bridge: &str| {
        out_dir
            .join("cxxbridge/sources/verify")
            .join(format!("{bridge}.cc"))
    };
    let cxx_header = generated.join("rust/cxx.h");

    let configure = |mut b: cc::Build| -> cc::Build {
        b.cpp(true)
            .std("c++17")
            .opt_level(SHIM_OPT_LEVEL)
            .debug(false)
            .include(&cpp_include)
            .include(&generated);
        for dir in &include_dirs {
            b.flag(format!("-isystem{}", dir.display()));
        }
        b
    };
    let common_inputs = vec![
        cxx_header.clone(),
        gen_header(BRIDGE_FCL_CCD),
        gen_header(BRIDGE_CGAL),
        cpp_src.join("common.h"),
    ];

    let bridge = configure(bridge_build);
    let mut fcl_build = configure(cc::Build::new());
    fcl_build.file(cpp_src.join("fcl_shim.cc"));
    let mut ccd_build = configure(cc::Build::new());
    ccd_build.file(cpp_src.join("ccd_shim.cc"));
    let mut cgal_build = configure(cc::Build::new());
    cgal_build
        .file(cpp_src.join("cgal_shim.cc"))
        // CGAL's CMake adds it for GCC: the interval filters change the rounding mode.
        .flag("-frounding-math");

    let with = |extra: &[PathBuf]| {
        let mut v = common_inputs.clone();
        v.extend_from_slice(extra);
        v
    };
    let mut libs = vec![
        Lib {
            name: "revdist_cxxbridge",
            build: bridge,
            // The generated code, not the .rs files: Rust-only edits leave it unchanged.
            inputs: with(&[
                gen_source(BRIDGE_FCL_CCD),
                gen_source(BRIDGE_CGAL),
                cpp_include.join("fcl_shim.h"),
                cpp_include.join("ccd_shim.h"),
                cpp_include.join("cgal_shim.h"),
            ]),
        },
        Lib {
            name: "revdist_fcl_shim",
            build: fcl_build,
            inputs: with(&[cpp_include.join("fcl_shim.h"), cpp_src.join("fcl_shim.cc")]),
        },
        Lib {
            name: "revdist_ccd_shim",
            build: ccd_build,
            inputs: with(&[cpp_include.join("ccd_shim.h"), cpp_src.join("ccd_shim.cc")]),
        },
        Lib {
            name: "revdist_cgal_shim",
            build: cgal_build,
            inputs: with(&[
                cpp_include.join("cgal_shim.h"),
                cpp_src.join("cgal_shim.cc"),
            ]),
        },
    ];
    println!("cargo::rustc-check-cfg=cfg(revdist_occt)");
    match &occt {
        Ok(found) => {
            let bridge = configure(cxx_build::bridge(BRIDGE_OCCT));
            let mut shim = configure(cc::Build::new());
            shim.file(cpp_src.join("occt_shim.cc"))
                .flag(format!("-isystem{}", found.include.display()));
            let occt_inputs = |extra: &[PathBuf]| {
                let mut v = vec![
                    cxx_header.clone(),
                    gen_header(BRIDGE_OCCT),
                    cpp_src.join("common.h"),
                    cpp_include.join("occt_shim.h"),
                    // The version as a pseudo-input: its name is hashed (it is no file).
                    PathBuf::from(format!("occt {}", found.version)),
                ];
                v.extend_from_slice(extra);
                v
            };
            libs.push(Lib {
                name: "revdist_occt_bridge",
                build: bridge,
                inputs: occt_inputs(&[gen_source(BRIDGE_OCCT)]),
            });
            libs.push(Lib {
                name: "revdist_occt_shim",
                build: shim,
                inputs: occt_inputs(&[cpp_src.join("occt_shim.cc")]),
            });
            println!("cargo:rustc-cfg=revdist_occt");
        }
        Err(why) => println!(
            "cargo:warning=OpenCASCADE not found ({why}): verify builds without the OCCT \
             cross-check; run scripts/deps.sh to install it"
        ),
    }

    // The slowest library first, so it starts while the others compile on the other core.
    std::thread::scope(|s| {
        for lib in libs.iter().rev() {
            let (out_dir, versions) = (&out_dir, &versions);
            s.spawn(move || build_cached(lib, out_dir, versions));
        }
    });
    // Link order: the bridge references the shims, which reference the system libraries that
    // the pkg-config probes above already emitted.
    for lib in &libs {
        println!("cargo:rustc-link-lib=static={}", lib.name);
    }
    println!("cargo:rustc-link-search=native={}", out_dir.display());
    if let Ok(found) = &occt {
        println!("cargo:rustc-link-search=native={}", found.lib.display());
        for lib in occt::LIBS {
            println!("cargo:rustc-link-lib=dylib={lib}");
        }
    }
    for f in [
        "../cpp/include/occt_shim.h",
        "../cpp/src/occt_shim.cc",
        BRIDGE_OCCT,
        "../cpp/include/fcl_shim.h",
        "../cpp/include/ccd_shim.h",
        "../cpp/include/cgal_shim.h",
        "../cpp/src/common.h",
        "../cpp/src/fcl_shim.cc",
        "../cpp/src/ccd_shim.cc",
        "../cpp/src/cgal_shim.cc",
        BRIDGE_FCL_CCD,
        BRIDGE_CGAL,
        "build.rs",
    ] {
        println!("cargo:rerun-if-changed={f}");
    }
    for var in ["CXX", "CXXFLAGS", "CC", "CFLAGS", occt::DISABLE_VAR] {
        println!("cargo:rerun-if-env-changed={var}");
    }
}

/// Compiles `lib` into `lib<name>.a` in `out_dir` unless the stamp of its inputs matches the
/// one recorded by the previous build. Link directives are printed by the caller.
fn build_cached(lib: &Lib, out_dir: &Path, versions: &str) {
    let archive = out_dir.join(format!("lib{}.a", lib.name));
    let stamp_path = out_dir.join(format!("{}.stamp", lib.name));
    let stamp = stamp_of(lib, versions);
    let previous = std::fs::read_to_string(&stamp_path).unwrap_or_default();
    if archive.exists() && previous == stamp {
        return;
    }
    let mut build = lib.build.clone();
    // Link directives are emitted once, in order, by `main`.
    build.cargo_metadata(false);
    if let Err(e) = build.try_compile(lib.name) {
        let _ = std::fs::remove_file(&stamp_path);
        panic!("compiling the C++ baseline {}: {e}", lib.name);
    }
    std::fs::write(&stamp_path, stamp).expect("write build stamp");
}

/// Hash of the inputs' contents, the compiler command line and the library versions.
fn stamp_of(lib: &Lib, versions: &str) -> String {
    let mut h = DefaultHasher::new();
    versions.hash(&mut h);
    let compiler = lib.build.get_compiler();
    compiler.path().hash(&mut h);
    for arg in compiler.args() {
        arg.hash(&mut h);
    }
    for input in &lib.inputs {
        input.hash(&mut h);
        std::fs::read(input).unwrap_or_default().hash(&mut h);
    }
    format!("{:016x}\n", h.finish())
}

/// CGAL's version string from its header (CGAL 5.5 is header-only and has no .pc file).
fn cgal_version() -> Option<String> {
    let text = std::fs::read_to_string("/usr/include/CGAL/version.h").ok()?;
    text.lines()
        .find(|l| l.starts_with("#define CGAL_VERSION "))
        .map(|l| {
            l.trim_start_matches("#define CGAL_VERSION ")
                .trim()
                .to_owned()
        })
}

/// Finding OpenCASCADE (no pkg-config file in Debian 12's packages).
mod occt {
    use std::path::{Path, PathBuf};

    /// Setting this variable (to anything) builds `verify` as if OCCT were missing (to check
    /// that path).
    pub const DISABLE_VAR: &str = "REVDIST_NO_OCCT";
    /// Debian's header directory.
    const INCLUDE: &str = "/usr/include/opencascade";
    /// Debian's library directory on x86-64 and arm64.
    const LIB_DIRS: [&str; 2] = ["/usr/lib/x86_64-linux-gnu", "/usr/lib/aarch64-linux-gnu"];
    /// Headers that must be present: the version, what the shim uses, and the one only
    /// `libocct-visualization-dev` ships.
    const HEADERS: [&str; 3] = [
        "Standard_Version.hxx",
        "BRepExtrema_DistShapeShape.hxx",
        "NCollection_AliasedArray.hxx",
    ];
    /// Toolkits linked (BRepExtrema, BRepCheck, BRepBuilderAPI, BRepLib: TKTopAlgo;
    /// BRepPrimAPI: TKPrim; the rest their dependencies).
    pub const LIBS: [&str; 9] = [
        "TKPrim",
        "TKTopAlgo",
        "TKGeomAlgo",
        "TKBRep",
        "TKGeomBase",
        "TKG3d",
        "TKG2d",
        "TKMath",
        "TKernel",
    ];

    pub struct Found {
        pub include: PathBuf,
        pub lib: PathBuf,
        pub version: String,
    }

    pub fn probe() -> Result<Found, String> {
        if std::env::var_os(DISABLE_VAR).is_some() {
            return Err(format!("{DISABLE_VAR} is set"));
        }
        let include = PathBuf::from(INCLUDE);
        for h in HEADERS {
            if !include.join(h).exists() {
                return Err(format!(
                    "{INCLUDE}/{h} is missing; it ships in libocct-modeling-algorithms-dev \
                     and libocct-visualization-dev"
                ));
            }
        }
        let lib = LIB_DIRS
            .iter()
            .map(Path::new)
            .find(|d| LIBS.iter().all(|l| d.join(format!("lib{l}.so")).exists()))
            .ok_or_else(|| format!("the libraries {LIBS:?} (lib*.so) are missing"))?
            .to_path_buf();
        let text = std::fs::read_to_string(include.join("Standard_Version.hxx"))
            .map_err(|e| format!("reading Standard_Version.hxx: {e}"))?;
        let version = text
            .lines()
            .find_map(|l| l.strip_prefix("#define OCC_VERSION_COMPLETE"))
            .map(|v| v.trim().trim_matches('"').to_owned())
            .ok_or("no OCC_VERSION_COMPLETE in Standard_Version.hxx")?;
        Ok(Found {
            include,
            lib,
            version,
        })
    }
}
