//! Builds the C++ shim over OpenSubdiv (feature `osd`, on by default).
//!
//! * `cc` compiles `cpp/shim.cpp`, `cpp/patches.cpp`,
//!   `cpp/osd_evaluator.cpp`, `cpp/limit_stencils.cpp`, `cpp/bfr.cpp`,
//!   `cpp/bfr_surface.cpp` and `cpp/bfr_mesh.cpp` (their shared internals in `cpp/internal.h` and
//!   `cpp/bfr_internal.h`); `bindgen` binds `cpp/shim.h` only.
//! * OpenSubdiv is found in `SUBDIV_OSD_DIR` (with `include/` and `lib/`) when
//!   set, else in the system paths where Debian's `libosd-dev` installs it.
//! * A missing OpenSubdiv fails early, naming the package and the way out.

fn main() {
    #[cfg(feature = "osd")]
    osd::build();
}

#[cfg(feature = "osd")]
mod osd {
    use std::env;
    use std::path::{Path, PathBuf};

    pub fn build() {
        println!("cargo:rerun-if-changed=cpp/shim.h");
        println!("cargo:rerun-if-changed=cpp/shim.cpp");
        println!("cargo:rerun-if-changed=cpp/patches.cpp");
        println!("cargo:rerun-if-changed=cpp/osd_evaluator.cpp");
        println!("cargo:rerun-if-changed=cpp/limit_stencils.cpp");
        println!("cargo:rerun-if-changed=cpp/bfr.cpp");
        println!("cargo:rerun-if-changed=cpp/bfr_surface.cpp");
        println!("cargo:rerun-if-changed=cpp/bfr_mesh.cpp");
        println!("cargo:rerun-if-changed=cpp/internal.h");
        println!("cargo:rerun-if-changed=cpp/bfr_internal.h");
        println!("cargo:rerun-if-env-changed=SUBDIV_OSD_DIR");

        let (include_dir, lib_dir) = match env::var_os("SUBDIV_OSD_DIR") {
            Some(dir) => {
                let dir = PathBuf::from(dir);
                (dir.join("include"), Some(dir.join("lib")))
            }
            None => (PathBuf::from("/usr/include"), None),
        };
        let header = include_dir.join("opensubdiv/far/topologyRefiner.h");
        if !header.exists() {
            panic!(
                "\n\nsubdiv: OpenSubdiv was not found ({} is missing).\n\
                 Install Debian's package with `apt-get install libosd-dev` (or run `make test`,\n\
                 which installs it), point SUBDIV_OSD_DIR at an OpenSubdiv 3.5 install prefix,\n\
                 or build the pure-Rust part alone with `cargo build --no-default-features`.\n",
                header.display()
            );
        }

        let mut build = cc::Build::new();
        build
            .cpp(true)
            .std("c++14")
            .file("cpp/shim.cpp")
            .file("cpp/patches.cpp")
            .file("cpp/osd_evaluator.cpp")
            .file("cpp/limit_stencils.cpp")
            .file("cpp/bfr.cpp")
            .file("cpp/bfr_surface.cpp")
            .file("cpp/bfr_mesh.cpp")
            .include("cpp")
            .include(&include_dir)
            .warnings(true)
            .flag_if_supported("-Wno-unused-parameter");
        if env::var_os("SUBDIV_ASAN").is_some() {
            build
                .flag("-fsanitize=address")
                .flag("-fno-omit-frame-pointer");
        }
        println!("cargo:rerun-if-env-changed=SUBDIV_ASAN");
        build.compile("subdiv_shim");

        // GNU ld resolves left to right: OpenSubdiv must come after the shim.
        if let Some(lib_dir) = lib_dir {
            println!("cargo:rustc-link-search=native={}", lib_dir.display());
        }
        println!("cargo:rustc-link-lib=dylib=osdCPU");

        let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
        bindgen::Builder::default()
            .header(Path::new("cpp/shim.h").to_string_lossy())
            .allowlist_function("sdv_.*")
            .allowlist_type("sdv_.*")
            .allowlist_var("SDV_.*")
            .default_enum_style(bindgen::EnumVariation::Consts)
            .layout_tests(true)
            .generate()
            .unwrap_or_else(|e| panic!("subdiv: bindgen failed on cpp/shim.h: {e}"))
            .write_to_file(out.join("shim_bindings.rs"))
            .expect("subdiv: cannot write the shim bindings");
    }
}
