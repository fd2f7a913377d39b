//! Sdf's legacy type names in text layers (`PointFloat[] points`), which
//! Pixar's parser still accepts and the `openusd` crate's does not: every
//! text layer the stage opens goes through [`LegacyTypesResolver`], which
//! rewrites them to their current names before the crate parses the text.

use openusd::ar::{self, Asset, DefaultResolver, ResolvedPath, Resolver};
use std::io;
use std::time::SystemTime;

/// Sdf's legacy value types (`_AddLegacyTypesToRegistry` in
/// `pxr/usd/sdf/schema.cpp`) and the current types with the same value type
/// and role.
const LEGACY_TYPES: &[(&str, &str)] = &[
    ("Vec2i", "int2"),
    ("Vec2h", "half2"),
    ("Vec2f", "float2"),
    ("Vec2d", "double2"),
    ("Vec3i", "int3"),
    ("Vec3h", "half3"),
    ("Vec3f", "float3"),
    ("Vec3d", "double3"),
    ("Vec4i", "int4"),
    ("Vec4h", "half4"),
    ("Vec4f", "float4"),
    ("Vec4d", "double4"),
    ("Point", "point3d"),
    ("PointFloat", "point3f"),
    ("Normal", "normal3d"),
    ("NormalFloat", "normal3f"),
    ("Vector", "vector3d"),
    ("VectorFloat", "vector3f"),
    ("Color", "color3d"),
    ("ColorFloat", "color3f"),
    ("Quath", "quath"),
    ("Quatf", "quatf"),
    ("Quatd", "quatd"),
    ("Matrix2d", "matrix2d"),
    ("Matrix3d", "matrix3d"),
    ("Matrix4d", "matrix4d"),
    ("Frame", "frame4d"),
    ("Transform", "matrix4d"),
    ("PointIndex", "int"),
    ("EdgeIndex", "int"),
    ("FaceIndex", "int"),
];

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}

fn is_ident(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// `text` with every legacy type name in type position replaced by its
/// current name, or `None` when it has none.
///
/// A word is in type position when it stands outside strings (`"…"`, `'…'`,
/// triple-quoted), asset paths (`@…@`, `@@@…@@@`) and comments (`#` to the
/// end of the line), is not part of a longer identifier, namespaced name
/// (`a:Point`) or path, and is followed — after an optional `[]` — by spaces
/// or tabs and the start of an identifier on the same line (the property's
/// name): `PointFloat[] points`, `uniform Vec3f offset`. A prim type
/// (`def Point "P"`), a token value or a property named like a type
/// (`float Color = 1`) is left alone.
pub(super) fn rewrite(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out: Option<String> = None;
    let mut copied = 0; // bytes of `text` already in `out`
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        match b {
            b'#' => i = skip_line(bytes, i),
            b'"' | b'\'' => i = skip_string(bytes, i),
            b'@' => i = skip_asset(bytes, i),
            _ if is_ident_start(b) => {
                let start = i;
                while bytes.get(i).is_some_and(|&c| is_ident(c)) {
                    i += 1;
                }
                let before = start.checked_sub(1).and_then(|p| bytes.get(p)).copied();
                let attached = before.is_some_and(|c| matches!(c, b':' | b'.' | b'/' | b'<'));
                if attached || bytes.get(i) == Some(&b':') {
                    // A namespaced name or a path: skip it whole.
                    while bytes
                        .get(i)
                        .is_some_and(|&c| is_ident(c) || matches!(c, b':' | b'.'))
                    {
                        i += 1;
                    }
                    continue;
                }
                let word = &text[start..i];
                let Some(&(_, current)) = LEGACY_TYPES.iter().find(|(old, _)| *old == word) else {
                    continue;
                };
                if type_position(bytes, i) {
                    let out = out.get_or_insert_with(|| String::with_capacity(text.len()));
                    out.push_str(&text[copied..start]);
                    out.push_str(current);
                    copied = i;
                }
            }
            _ => i += 1,
        }
    }
    out.map(|mut out| {
        out.push_str(&text[copied..]);
        out
    })
}

/// Whether a type name ending before byte `end` is followed by `[]`
/// (optionally), blanks and an identifier on the same line.
fn type_position(bytes: &[u8], mut end: usize) -> bool {
    if bytes.get(end..end + 2) == Some(b"[]") {
        end += 2;
    }
    let blanks = bytes
        .get(end..)
        .unwrap_or(&[])
        .iter()
        .take_while(|&&c| c == b' ' || c == b'\t')
        .count();
    blanks > 0 && bytes.get(end + blanks).is_some_and(|&c| is_ident_start(c))
}

/// The end of the line starting at `i` (the newline's position).
fn skip_line(bytes: &[u8], i: usize) -> usize {
    bytes
        .get(i..)
        .and_then(|rest| rest.iter().position(|&c| c == b'\n'))
        .map_or(bytes.len(), |p| i + p)
}

/// Past the string starting at `i` (single, double or triple quotes, with
/// backslash escapes).
fn skip_string(bytes: &[u8], i: usize) -> usize {
    let quote = bytes[i];
    let triple = [quote; 3];
    if bytes.get(i..i + 3) == Some(&triple[..]) {
        let mut j = i + 3;
        while j < bytes.len() {
            if bytes[j] == b'\\' {
                j += 2;
            } else if bytes.get(j..j + 3) == Some(&triple[..]) {
                return j + 3;
            } else {
                j += 1;
            }
        }
        return bytes.len();
    }
    let mut j = i + 1;
    while let Some(&c) = bytes.get(j) {
        match c {
            b'\\' => j += 2,
            b'\n' => return j,
            _ if c == quote => return j + 1,
            _ => j += 1,
        }
    }
    bytes.len()
}

/// Past the asset path starting at `i` (`@…@` or `@@@…@@@`).
fn skip_asset(bytes: &[u8], i: usize) -> usize {
    let (close, start): (&[u8], usize) = if bytes.get(i..i + 3) == Some(b"@@@") {
        (b"@@@", i + 3)
    } else {
        (b"@", i + 1)
    };
    bytes
        .get(start..)
        .and_then(|rest| rest.windows(close.len()).position(|w| w == close))
        .map_or(bytes.len(), |p| start + p + close.len())
}

/// The default resolver, with text layers' legacy type names rewritten
/// ([`rewrite`]) as they are opened.
pub(super) struct LegacyTypesResolver(DefaultResolver);

impl LegacyTypesResolver {
    pub(super) fn new() -> Self {
        LegacyTypesResolver(DefaultResolver::new())
    }
}

impl Resolver for LegacyTypesResolver {
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
        let mut asset = self.0.open_asset(resolved_path)?;
        let bytes = asset.read_all()?;
        // Only text layers: they start with their `#usda` header.
        let rewritten = match std::str::from_utf8(&bytes) {
            Ok(text) if text.starts_with("#usda") => rewrite(text).map(String::into_bytes),
            _ => None,
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

#[cfg(test)]
mod tests {
    use super::rewrite;

    #[test]
    fn legacy_types_in_type_position_only() {
        let text = "#usda 1.0\ndef Mesh \"PointFloat\" (doc = \"Vec3f[] x\")\n{\n    \
                    PointFloat[] points = [(0, 0, 0)]\n    uniform PointIndex[] idx = [0]\n    \
                    custom ColorFloat[] primvars:c = []\n    Vec3f[] a.timeSamples = {}\n    \
                    float Color = 1 # PointFloat[] x\n    token t = \"Vec3f[] y\"\n    \
                    asset p = @PointFloat[] q@\n    rel Vec3f\n    int primvars:Vec3f x\n}\n";
        let out = rewrite(text).unwrap();
        assert_eq!(
            out,
            "#usda 1.0\ndef Mesh \"PointFloat\" (doc = \"Vec3f[] x\")\n{\n    \
             point3f[] points = [(0, 0, 0)]\n    uniform int[] idx = [0]\n    \
             custom color3f[] primvars:c = []\n    float3[] a.timeSamples = {}\n    \
             float Color = 1 # PointFloat[] x\n    token t = \"Vec3f[] y\"\n    \
             asset p = @PointFloat[] q@\n    rel Vec3f\n    int primvars:Vec3f x\n}\n"
        );
        assert_eq!(
            rewrite("#usda 1.0\ndef Mesh \"M\" { point3f[] points }"),
            None
        );
        // Unterminated strings, assets and comments end the scan quietly.
        assert_eq!(rewrite("\"PointFloat[] x"), None);
        assert_eq!(rewrite("@@@PointFloat[] x@@"), None);
        assert_eq!(rewrite("'''PointFloat[] x\\"), None);
        assert_eq!(rewrite("PointFloat[]").as_deref(), None);
        assert_eq!(rewrite("PointFloat[] p").as_deref(), Some("point3f[] p"));
    }
}
