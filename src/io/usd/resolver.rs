//! The asset resolver every stage is opened with: the default resolver,
//! with layers that are not regular files refused, layers that would harm
//! the `openusd` crate refused ([`check_text`]: prim names and paths
//! Pixar's USD refuses, brackets nested too deep), and text layers' legacy
//! type names rewritten ([`rewrite`]), as they are opened.

use super::is_identifier;
use super::legacy::rewrite;
use super::text::check_text;
use openusd::ar::{self, Asset, DefaultResolver, ResolvedPath, Resolver};
use openusd::sdf::{AbstractData, SpecType};
use openusd::usdc::CrateData;
use std::io;
use std::path::PathBuf;
use std::time::SystemTime;

/// The default resolver, with layers that are not regular files or that
/// have prims with names that are not identifiers refused, and text layers'
/// legacy type names rewritten.
pub(super) struct LayerResolver(DefaultResolver);

impl LayerResolver {
    pub(super) fn new() -> Self {
        LayerResolver(DefaultResolver::new())
    }
}

impl Resolver for LayerResolver {
    fn create_identifier(&self, asset_path: &str, anchor: Option<&ResolvedPath>) -> String {
        self.0.create_identifier(asset_path, anchor)
    }

    fn resolve(&self, asset_path: &str) -> Option<ResolvedPath> {
        self.0.resolve(asset_path)
    }

    fn resolve_for_new_asset(&self, asset_path: &str) -> Option<ResolvedPath> {
        self.0.resolve_for_new_asset(asset_path)
    }

    fn open_asset(&self, resolved_path: &ResolvedPath) -> io::Result<Box<dyn Asset>> {
        // A layer (or package) must be a regular file: `@/dev/zero@` as a
        // reference or sublayer would otherwise be read forever.
        let text = resolved_path.to_string_lossy();
        let file = match ar::split_package_relative_path_outer(&text) {
            Some((package, _)) => PathBuf::from(package),
            None => resolved_path.to_path_buf(),
        };
        if !std::fs::metadata(&file)?.is_file() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{} is not a regular file", file.display()),
            ));
        }
        let mut asset = self.0.open_asset(resolved_path)?;
        let bytes = asset.read_all()?;
        let refuse = |message: String| {
            io::Error::new(
                io::ErrorKind::InvalidData,
                format!("{resolved_path}: {message}"),
            )
        };
        let rewritten = if bytes.starts_with(b"PXR-USDC") {
            check_crate_prim_names(&bytes).map_err(refuse)?;
            None
        } else {
            match std::str::from_utf8(&bytes) {
                // Text layers start with their `#usda` header.
                Ok(text) if text.starts_with("#usda") => {
                    check_text(text).map_err(refuse)?;
                    rewrite(text).map(String::into_bytes)
                }
                _ => None,
            }
        };
        Ok(Box::new(io::Cursor::new(rewritten.unwrap_or(bytes))))
    }

    fn get_extension<'a>(&self, asset_path: &'a str) -> &'a str {
        self.0.get_extension(asset_path)
    }

    fn get_asset_info(&self, asset_path: &str, resolved_path: &ResolvedPath) -> ar::AssetInfo {
        self.0.get_asset_info(asset_path, resolved_path)
    }

    fn get_modification_timestamp(
        &self,
        asset_path: &str,
        resolved_path: &ResolvedPath,
    ) -> Option<SystemTime> {
        self.0.get_modification_timestamp(asset_path, resolved_path)
    }

    fn identity(&self) -> String {
        self.0.identity()
    }
}

/// [`check_text`]'s prim name check for a binary (crate) layer: every prim
/// spec's name
/// must be an identifier. A layer the crate cannot index passes, for its
/// reader to report.
fn check_crate_prim_names(bytes: &[u8]) -> Result<(), String> {
    let Ok(data) = CrateData::open(io::Cursor::new(bytes), true) else {
        return Ok(());
    };
    for path in data.spec_paths() {
        if data.spec_type(&path) != Some(SpecType::Prim) {
            continue;
        }
        let text = path.as_str();
        if let Some(segment) = text.split('/').skip(1).find(|s| !prim_segment(s)) {
            return Err(format!(
                "the prim path {text:?} has a name that is not an identifier ({segment:?})"
            ));
        }
    }
    Ok(())
}

/// Whether one `/`-separated segment of a prim spec's path is a prim name,
/// possibly after variant selections of its parent (`A{shape=round}B`).
/// The crate's own path functions split names at `}` and cannot tell.
fn prim_segment(segment: &str) -> bool {
    let variant = |c: char| c.is_alphanumeric() || matches!(c, '_' | '|' | '-' | '.');
    let mut rest = segment;
    while let Some(open) = rest.find('{') {
        let (parent, selection) = rest.split_at(open);
        let Some(close) = selection.find('}') else {
            return false;
        };
        let valid = is_identifier(parent)
            && selection[1..close]
                .split_once('=')
                .is_some_and(|(set, chosen)| is_identifier(set) && chosen.chars().all(variant));
        if !valid {
            return false;
        }
        rest = &selection[close + 1..];
    }
    is_identifier(rest)
}

#[cfg(test)]
mod tests {
    use super::prim_segment;

    #[test]
    fn prim_segments() {
        for good in [
            "Body",
            "_a1",
            "A{shape=round}B",
            "A{s=}B",
            "A{s=x-y.z}B{t=u}C",
        ] {
            assert!(prim_segment(good), "{good}");
        }
        for bad in [
            "Bo}dy",
            "",
            "1a",
            "a.b",
            "A{shape=round}",
            "A{shape}B",
            "A{s=x}}B",
            "A{s=x",
        ] {
            assert!(!prim_segment(bad), "{bad}");
        }
    }
}
