//! `subdiv::io::usd::read_usd` on arbitrary bytes as a `.usda` file: no
//! panic, abort or hang; errors are `Error::Usd`; every mesh read is valid
//! with its primvars the size its interpolation says; and what was read
//! is written back by `write_usda_to` and read again (every mesh then
//! skipped as `subdivisionScheme = "none"`).
//!
//! The options come from the input's length: held time or default values,
//! lenient or strict, every mesh or a prim pattern.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::OnceLock;
use subdiv::io::usd::{
    UsdFVarOut, UsdMeshOut, UsdPrimvarOut, UsdReadOptions, read_usd, write_usda_to,
};
use subdiv::{Error, Precision};

/// This process's scratch directory (libFuzzer runs inputs one at a time).
fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("subdiv-fuzz-usd-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the scratch directory");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    let file = scratch().join("input.usda");
    std::fs::write(&file, data).expect("write the input");
    let selector = data.len() % 8;
    let options = UsdReadOptions {
        time: (selector & 1 != 0).then_some(1.5),
        lenient: selector & 2 != 0,
        prims: if selector & 4 != 0 {
            vec!["/**/M*".to_string()]
        } else {
            Vec::new()
        },
    };
    let stage = match read_usd(&file, &options) {
        Ok(stage) => stage,
        Err(Error::Usd(_)) => return,
        Err(e) => panic!("not a USD error: {e}"),
    };
    let right_handed: Vec<_> = stage.meshes.iter().map(|m| m.mesh.right_handed()).collect();
    let mut outs = Vec::new();
    for (m, mesh) in stage.meshes.iter().zip(&right_handed) {
        if let Err(e) = mesh.validate() {
            panic!("{}: read but invalid: {e}", m.path);
        }
        assert_eq!(m.fvar_names.len(), mesh.fvar_channels.len());
        for p in &m.primvars {
            assert_eq!(p.values.len(), p.width * mesh.positions.len(), "{}", p.name);
        }
        outs.push(UsdMeshOut {
            path: &m.path,
            positions: &mesh.positions,
            face_offsets: &mesh.face_offsets,
            face_vertices: &mesh.face_vertices,
            holes: mesh.holes.clone(),
            left_handed: false,
            fvar: mesh
                .fvar_channels
                .iter()
                .zip(&m.fvar_names)
                .map(|(c, name)| UsdFVarOut {
                    name: Cow::Borrowed(name.as_str()),
                    width: c.width,
                    values: &c.values,
                    face_values: &c.indices,
                })
                .collect(),
            primvars: m
                .primvars
                .iter()
                .map(|p| UsdPrimvarOut {
                    name: Cow::Borrowed(p.name.as_str()),
                    interpolation: p.interpolation,
                    width: p.width,
                    values: &p.values,
                })
                .collect(),
        });
    }
    let mut text = Vec::new();
    if let Err(e) = write_usda_to(&mut text, &outs, Precision::F64) {
        panic!("what was read cannot be written: {e}");
    }
    let written = scratch().join("written.usda");
    std::fs::write(&written, &text).expect("write the output");
    match read_usd(&written, &UsdReadOptions::default()) {
        Ok(again) => {
            assert!(again.meshes.is_empty());
            assert_eq!(again.skipped.len(), outs.len());
        }
        Err(e) => panic!(
            "what was written cannot be read: {e}\n{}",
            String::from_utf8_lossy(&text)
        ),
    }
});
