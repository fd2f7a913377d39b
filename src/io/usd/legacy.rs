//! Sdf's legacy type names in text layers (`PointFloat[] points`), which
//! Pixar's parser still accepts and the `openusd` crate's does not: every
//! text layer the stage opens is rewritten with their current names
//! ([`rewrite`]) by [`LayerResolver`](super::resolver::LayerResolver)
//! before the crate parses it.

use super::text::{is_ident, is_ident_start, skip_asset, skip_line, skip_string};

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
