//! The limit on high-valence non-manifold meshes (issue 20): "books" of
//! pages sharing spine edges, where OpenSubdiv 3.5's `PrimvarRefiner::Limit`
//! overran its masks (a crash from 14 pages on one edge), and wheels and
//! n-gons near the Catmull-Clark vertex rule's int overflow.
//!
//! Random bytes give the number of spines and of pages on each (2 to 40),
//! each page's corner count, sharpness on the spines, extra faces joining
//! pages, a UV channel, the scheme, the options and the level; then both
//! engines refine and evaluate the limit (positions and tangents, the
//! face-varying limit, limit stencils). The bridge must refuse exactly with
//! `OsdErrorKind::Unsafe` or agree with the native engine within 1e-9 of the
//! mesh's size; the native engine must always evaluate.

use crate::pick;
use arbitrary::{Result as AResult, Unstructured};
use glam::DVec3;
use subdiv::refiner::Refiner;
use subdiv::{
    BoundaryInterpolation, Crease, Error, FVarChannel, FVarLinearInterpolation, Mesh, Options,
    Scheme, UniformOptions,
};

/// The most pages on one spine.
pub const MAX_PAGES: u32 = 40;

/// A book and how to refine it.
#[derive(Debug, Clone)]
pub struct BookCase {
    /// The mesh.
    pub mesh: Mesh,
    /// The options.
    pub options: Options,
    /// The level, 0 to 3.
    pub level: u32,
}

/// A book from the bytes: 1 to 3 spines, each with 2 to [`MAX_PAGES`] pages
/// of 3 to 6 corners (triangles only for Loop), some pages joined.
pub fn book_case(u: &mut Unstructured<'_>) -> AResult<BookCase> {
    let scheme = pick(u, Scheme::ALL)?;
    let options = Options {
        scheme,
        boundary: pick(u, BoundaryInterpolation::ALL)?,
        fvar: pick(u, FVarLinearInterpolation::ALL)?,
        ..Options::shape_file_defaults()
    };
    let mut mesh = Mesh::default();
    let spines = u.int_in_range(1..=3u32)?;
    for s in 0..spines {
        let a = mesh.positions.len() as u32;
        let z = f64::from(s) * 3.0;
        mesh.positions.push(DVec3::new(0.0, 0.0, z));
        mesh.positions.push(DVec3::new(1.0, 0.0, z));
        let pages = u.int_in_range(2..=MAX_PAGES)?;
        let mut previous_tip = None;
        for p in 0..pages {
            let corners = if scheme == Scheme::Loop {
                3
            } else {
                u.int_in_range(3..=6u32)?
            };
            let angle = std::f64::consts::TAU * f64::from(p) / f64::from(pages);
            let mut face = vec![a, a + 1];
            for k in 0..corners - 2 {
                let t = f64::from(k + 1) / f64::from(corners - 1);
                face.push(mesh.positions.len() as u32);
                mesh.positions.push(DVec3::new(
                    1.0 - t,
                    angle.cos() * (1.0 + f64::from(u.int_in_range(0..=3u8)?) * 0.25),
                    z + angle.sin(),
                ));
            }
            // Now and then a triangle joins this page's tip to the last one's.
            let tip = *face.last().unwrap_or(&a);
            if let Some(prev) = previous_tip
                && u.ratio(1u8, 6u8)?
            {
                mesh.add_face(&[a, prev, tip]);
            }
            previous_tip = Some(tip);
            mesh.add_face(&face);
        }
        if u.arbitrary()? {
            mesh.creases.push(Crease {
                vertices: [a, a + 1],
                sharpness: f32::from(u.int_in_range(0..=20u8)?) * 0.25,
            });
        }
    }
    if u.arbitrary()? {
        // One UV per vertex (the channel's topology matches the vertices'),
        // or a seam: a distinct value per face corner.
        let seams: bool = u.arbitrary()?;
        let mut values = Vec::new();
        let mut indices = Vec::new();
        for (c, &v) in mesh.face_vertices.iter().enumerate() {
            let p = mesh.positions[v as usize];
            if seams {
                indices.push(c as u32);
                values.extend([p.x + 0.01 * c as f64, p.y]);
            } else {
                indices.push(v);
            }
        }
        if !seams {
            values = mesh.positions.iter().flat_map(|p| [p.x, p.z]).collect();
        }
        mesh.fvar_channels.push(FVarChannel {
            width: 2,
            values,
            indices,
        });
    }
    Ok(BookCase {
        mesh,
        options,
        level: u.int_in_range(0..=3u32)?,
    })
}

/// Both engines' limits on one book: the native one evaluates; the bridge
/// refuses with `Unsafe` or agrees with it.
#[cfg(feature = "osd")]
pub fn check_book(case: &BookCase) {
    use subdiv::OsdErrorKind;
    use subdiv::osd::TopologyRefiner;
    let mesh = &case.mesh;
    if mesh.validate().is_err() {
        return;
    }
    let uniform = UniformOptions::new(case.level).full_topology(true);
    let mut n = Refiner::new(mesh, &case.options).expect("native refiner");
    n.refine_uniform(uniform).expect("native refinement");
    let base: Vec<f64> = mesh.flat_positions();
    let last = n.interpolate_last(3, &base).expect("native interpolation");
    let native = n.limit(3, &last).expect("native limit");
    let mut o = match TopologyRefiner::new(mesh, &case.options) {
        Ok(o) => o,
        Err(e) => panic!("osd refiner: {e:?}"),
    };
    o.refine_uniform(uniform).expect("osd refinement");
    let unsafe_refusal = |e: &Error| matches!(e, Error::Osd(x) if x.kind == OsdErrorKind::Unsafe);
    let osd_last = match o.interpolate_last(3, &base) {
        Ok(l) => l,
        Err(e) if unsafe_refusal(&e) => return,
        Err(e) => panic!("osd interpolation: {e:?}"),
    };
    let scale = mesh
        .positions
        .iter()
        .fold(1.0f64, |m, p| m.max(p.abs().max_element()));
    let agree = |a: &[f64], b: &[f64], what: &str| {
        assert_eq!(a.len(), b.len(), "{what}: lengths");
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x - y).abs() <= 1e-9 * scale,
                "{what} {i}: native {x}, OpenSubdiv {y}"
            );
        }
    };
    agree(&last, &osd_last, "refined position");
    match o.limit(3, &osd_last) {
        Ok(l) => {
            agree(&native.positions, &l.positions, "limit position");
            agree(&native.du, &l.du, "limit du");
            agree(&native.dv, &l.dv, "limit dv");
        }
        Err(e) => assert!(unsafe_refusal(&e), "osd limit: {e:?}"),
    }
    assert!(
        match o.limit_stencil_table() {
            Ok(_) => true,
            Err(e) => unsafe_refusal(&e),
        },
        "osd limit stencils"
    );
    for (c, ch) in mesh.fvar_channels.iter().enumerate() {
        // Both engines' refined values, compared level by level, then limits.
        let (mut nv, mut ov) = (ch.values.clone(), ch.values.clone());
        for level in 1..=case.level {
            nv = n
                .interpolate_face_varying(c, level, ch.width, &nv)
                .expect("native face-varying")
                .to_vec();
            ov = match o.interpolate_face_varying(c, level, ch.width, &ov) {
                Ok(v) => v,
                Err(e) if unsafe_refusal(&e) => return,
                Err(e) => panic!("osd face-varying: {e:?}"),
            };
            agree(&nv, &ov, "refined face-varying value");
        }
        // The whole-refinement call gives the level-by-level values.
        let last = n
            .interpolate_face_varying_last(c, ch.width, &ch.values)
            .expect("native face-varying, last level");
        assert!(
            last.iter()
                .zip(&nv)
                .all(|(a, b)| a.to_bits() == b.to_bits())
                && last.len() == nv.len(),
            "interpolate_face_varying_last differs from the level-by-level values"
        );
        let native_fv = n
            .limit_face_varying(c, ch.width, &nv)
            .expect("native face-varying limit");
        match o.limit_face_varying(c, ch.width, &ov) {
            Ok(v) => agree(&native_fv, &v, "face-varying limit"),
            Err(e) => assert!(unsafe_refusal(&e), "osd face-varying limit: {e:?}"),
        }
    }
}
