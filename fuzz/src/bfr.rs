//! The Bfr checks (`fuzz_targets/bfr_differential.rs`): tessellation
//! patterns and limit surfaces, native against OpenSubdiv.

use crate::MeshCase;
use arbitrary::Unstructured;
use subdiv::bfr::{
    FacetSize, LimitSurfaces, MeshSurfaces, Parameterization, SurfaceOptions, TessellateOptions,
    Tessellation, TessellationOptions,
};
use subdiv::patches::Derivatives;
use subdiv::{Error, Scheme, osd};

/// A pattern from the bytes, made by both engines: both refuse, or both
/// give the same pattern.
pub fn check_bfr_pattern(u: &mut Unstructured<'_>) {
    let Ok(pick) = u.int_in_range(0u8..=2) else {
        return;
    };
    let scheme = [Scheme::Bilinear, Scheme::Catmark, Scheme::Loop][pick as usize];
    let (Ok(n), Ok(count), Ok(four), Ok(keep)) = (
        u.int_in_range(1usize..=40),
        u.int_in_range(0usize..=8),
        u.arbitrary::<bool>(),
        u.arbitrary::<bool>(),
    ) else {
        return;
    };
    let rates: Vec<u32> = (0..count)
        .map(|_| u.int_in_range(0u32..=40).unwrap_or(1))
        .collect();
    let size = if four {
        FacetSize::Four
    } else {
        FacetSize::Three
    };
    let options = TessellationOptions {
        preserve_quads: keep,
        facet_size: size,
    };
    let ours = Parameterization::new(scheme, n).and_then(|p| Tessellation::new(p, &rates, options));
    let irates: Vec<i32> = rates.iter().map(|&r| r as i32).collect();
    let theirs = osd::bfr::tessellate(scheme, n, &irates, keep, size.indices());
    match (ours, theirs) {
        (Ok(t), Ok(o)) if o.is_valid => {
            let r: Vec<i32> = t.rates().iter().map(|&r| r as i32).collect();
            assert_eq!(r, o.rates);
            assert_eq!(t.coords::<f64>().unwrap(), o.coords_f64);
            assert_eq!(t.coords::<f32>().unwrap(), o.coords_f32);
            assert_eq!(t.facets().unwrap(), o.facets);
            assert_eq!(t.num_boundary_coords(), o.num_boundary_coords);
        }
        // A rate count beyond N + 2: natively the extra rates are ignored
        // (as by OpenSubdiv), the bridge refuses them.
        (Ok(_), Err(_)) => assert!(
            count > n + 2,
            "{scheme} {n} {rates:?}: refused by the bridge only"
        ),
        (Ok(_), Ok(o)) => panic!("{scheme} {n} {rates:?}: OpenSubdiv finds it invalid: {o:?}"),
        (Err(e), Ok(o)) => assert!(
            !o.is_valid,
            "{scheme} {n} {rates:?}: refused natively only: {e}"
        ),
        (Err(_), Err(_)) => {}
    }
}

/// The limit surfaces of `case`'s mesh at coordinates from the bytes, by
/// both engines: both refuse, or the values agree.
pub fn check_bfr_surfaces(case: &MeshCase, u: &mut Unstructured<'_>) {
    if crate::osd_may_abort(&case.mesh) || case.mesh.validate().is_err() {
        return;
    }
    let so = SurfaceOptions {
        approx_level_smooth: u.int_in_range(1u32..=3).unwrap_or(2),
        approx_level_sharp: u.int_in_range(1u32..=4).unwrap_or(4),
        ..SurfaceOptions::default()
    };
    let native = match LimitSurfaces::new(&case.mesh, &case.options, &so) {
        Ok(n) => n,
        Err(e) => {
            // Whatever the native engine refuses, OpenSubdiv's refiner
            // refuses too (an invalid mesh, a refinement too large).
            assert!(
                osd::bfr::Surfaces::new(&case.mesh, &case.options, &so).is_err(),
                "{e}"
            );
            return;
        }
    };
    let Ok(theirs) = osd::bfr::Surfaces::new(&case.mesh, &case.options, &so) else {
        return;
    };
    let size = 1.0
        + case
            .mesh
            .positions
            .iter()
            .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    for face in 0..case.mesh.face_count().min(8) {
        let info = theirs.face_info(face);
        let Ok(info) = info else {
            continue; // refused by the bridge (OpenSubdiv faults)
        };
        assert_eq!(native.has_surface(face), info.valid, "face {face}");
        if !info.valid {
            continue;
        }
        // A face naming a vertex twice is degenerate: Bfr's neighbourhoods
        // of it and of the faces around it differ from the mesh's
        // refinement (docs/CONFORMANCE.md); both must still evaluate
        // without fault.
        let degenerate = case
            .mesh
            .faces()
            .any(|f| f.iter().enumerate().any(|(i, v)| f[i + 1..].contains(v)));
        let coords: Vec<[f64; 2]> = (0..4)
            .map(|_| {
                let c = |u: &mut Unstructured<'_>| {
                    f64::from(u.int_in_range(0u16..=1200).unwrap_or(0)) / 1000.0
                };
                [c(u), c(u)]
            })
            .collect();
        let a = native.evaluate(face, &coords, Derivatives::First);
        let b = theirs.evaluate(face, &coords, Derivatives::First);
        match (a, b) {
            (Ok(_), Ok(_)) if degenerate => {}
            (Ok(a), Ok(b)) => {
                for (x, y) in a.values.point.iter().zip(&b.values.point) {
                    assert!(
                        (x - y).abs() <= 1e-9 * size,
                        "face {face} {coords:?}: {x} against {y}"
                    );
                }
            }
            (Err(_), Err(_)) => {}
            // The bridge refuses what OpenSubdiv would fault on (valence-2
            // corners and the like): those are not evaluated natively
            // differently, only refused.
            (Ok(_), Err(Error::Osd(e))) if e.kind == subdiv::OsdErrorKind::Unsafe => {}
            (a, b) => panic!("face {face} {coords:?}: native {a:?}, OpenSubdiv {b:?}"),
        }
    }
    check_mesh_surfaces(case, &so, u);
}

/// The per-face surfaces (`MeshSurfaces`, what `subdiv tessellate` uses):
/// each face evaluated twice at a pattern's coordinates — the second time
/// through an evaluation plan when another face of its hull or kind was
/// evaluated there — agrees with itself and with its own patch points; the
/// watertight mesher over them succeeds or refuses, never faults.
fn check_mesh_surfaces(case: &MeshCase, so: &SurfaceOptions, u: &mut Unstructured<'_>) {
    let Ok(surfaces) = MeshSurfaces::new(&case.mesh, &case.options, so) else {
        return;
    };
    let points = case.mesh.flat_positions::<f64>();
    let size = 1.0 + points.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let rate = u.int_in_range(1u32..=6).unwrap_or(3);
    for face in 0..case.mesh.face_count().min(8) {
        let Ok(s) = surfaces.factory().vertex_surface(face) else {
            continue;
        };
        if !s.is_valid() {
            continue;
        }
        let Ok(pattern) =
            Tessellation::uniform(s.parameterization(), rate, TessellationOptions::default())
        else {
            continue;
        };
        let coords = pattern
            .coords::<f64>()
            .expect("a valid pattern's coordinates");
        let patch = s.patch_points(&points, 3).expect("patch points");
        let expected = s
            .evaluate_patch_points(&patch, 3, &coords, Derivatives::First)
            .expect("evaluation from patch points");
        for pass in 0..2 {
            let got = s
                .evaluate(&points, 3, &coords, Derivatives::First)
                .expect("evaluation");
            for (x, y) in got.values.point.iter().zip(&expected.values.point) {
                assert!(
                    (x - y).abs() <= 1e-9 * size,
                    "face {face} pass {pass}: {x} against {y}"
                );
            }
        }
    }
    let tess = TessellateOptions {
        rate,
        normals: true,
        ..TessellateOptions::default()
    };
    if let Ok(mesh) = subdiv::bfr::tessellate(&case.mesh, &surfaces, &tess) {
        let points = mesh.positions.len() as u32;
        assert!(mesh.face_vertices.iter().all(|&p| p < points));
        assert_eq!(mesh.face_offsets.len(), mesh.facet_faces.len() + 1);
    }
}
