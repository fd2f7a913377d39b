//! The neighbourhood of one corner of a base face, as Bfr describes it
//! (`Bfr::FaceVertex` and `Bfr::FaceVertexSubset`): the faces around the
//! corner's vertex in order, each face's vertices starting at the corner,
//! the sharpness of the edges around it, the tags summarising them, and the
//! subset of those faces the face's limit surface depends on.
//!
//! The faces of a non-manifold vertex come unordered; they are connected
//! through the edges they share, and the subset is the fan of faces joined
//! to the corner's face by manifold edges.

use crate::options::FVarLinearInterpolation;
use crate::rules::crease::{is_infinite, is_semi_sharp, is_sharp};
use crate::topology::Level;

/// What a corner's neighbourhood holds (`Bfr::VertexTag`), or — or-ed over
/// a face's corners — what the whole neighbourhood holds
/// (`Bfr::MultiVertexTag`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct CornerTag {
    /// On a boundary.
    pub boundary: bool,
    /// Infinitely sharp, explicitly or by its edges.
    pub inf_sharp: bool,
    /// Has infinitely sharp interior edges.
    pub inf_sharp_edges: bool,
    /// An interior vertex with exactly one infinitely sharp edge.
    pub inf_sharp_dart: bool,
    /// Semi-sharp.
    pub semi_sharp: bool,
    /// Has semi-sharp interior edges.
    pub semi_sharp_edges: bool,
    /// Its faces are not all of one size.
    pub uncommon_sizes: bool,
    /// A face around it is not of the scheme's regular size.
    pub irregular_sizes: bool,
    /// A boundary whose boundary edges are not both infinitely sharp.
    pub boundary_non_sharp: bool,
    /// Its faces were given unordered (the refiner found the vertex
    /// non-manifold).
    pub unordered: bool,
    /// Its faces do not form one manifold fan.
    pub non_manifold: bool,
}

impl CornerTag {
    /// Both tags combined (`MultiVertexTag::Combine`).
    pub fn or(self, o: CornerTag) -> CornerTag {
        CornerTag {
            boundary: self.boundary | o.boundary,
            inf_sharp: self.inf_sharp | o.inf_sharp,
            inf_sharp_edges: self.inf_sharp_edges | o.inf_sharp_edges,
            inf_sharp_dart: self.inf_sharp_dart | o.inf_sharp_dart,
            semi_sharp: self.semi_sharp | o.semi_sharp,
            semi_sharp_edges: self.semi_sharp_edges | o.semi_sharp_edges,
            uncommon_sizes: self.uncommon_sizes | o.uncommon_sizes,
            irregular_sizes: self.irregular_sizes | o.irregular_sizes,
            boundary_non_sharp: self.boundary_non_sharp | o.boundary_non_sharp,
            unordered: self.unordered | o.unordered,
            non_manifold: self.non_manifold | o.non_manifold,
        }
    }

    /// Any sharp interior edge.
    pub fn sharp_edges(self) -> bool {
        self.inf_sharp_edges || self.semi_sharp_edges
    }

    /// Any sharp vertex.
    pub fn sharp_vertices(self) -> bool {
        self.inf_sharp || self.semi_sharp
    }
}

/// The faces around a corner of a face that its limit surface depends on
/// (`Bfr::FaceVertexSubset`): for a manifold vertex all of them, counted
/// before and after the corner's face in the ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Subset {
    /// Faces before the corner's face (clockwise; boundary rings only).
    pub before: usize,
    /// Faces after the corner's face (counter-clockwise).
    pub after: usize,
    /// All faces, the corner's included.
    pub total: usize,
    /// The corner's tags within the subset (sharpened by the boundary
    /// interpolation rules where they apply).
    pub tag: CornerTag,
    /// A sharpness the subset's corner takes from outside it (0 if none).
    pub local_sharpness: f32,
}

impl Subset {
    /// The corner's face alone (`FaceVertexSubset::Initialize`).
    fn new(tag: CornerTag) -> Subset {
        Subset {
            before: 0,
            after: 0,
            total: 1,
            tag,
            local_sharpness: 0.0,
        }
    }

    /// On a boundary.
    pub fn is_boundary(&self) -> bool {
        self.tag.boundary
    }

    /// Infinitely sharp.
    pub fn is_sharp(&self) -> bool {
        self.tag.inf_sharp
    }

    /// Made infinitely sharp (`FaceVertex::SharpenSubset`).
    pub fn sharpen(&mut self) {
        self.tag.inf_sharp = true;
        self.tag.semi_sharp = false;
    }

    /// Made at least `sharpness` sharp (`FaceVertex::SharpenSubset` with a
    /// sharpness).
    pub fn sharpen_to(&mut self, sharpness: f32) {
        if sharpness > self.local_sharpness {
            self.local_sharpness = sharpness;
            self.tag.inf_sharp = is_infinite(sharpness);
            self.tag.semi_sharp = is_semi_sharp(sharpness);
        }
    }
}

/// One corner of a face and the faces around its vertex.
#[derive(Debug, Clone)]
pub(crate) struct Corner {
    /// Face `i`'s vertices, starting at the corner's vertex, at
    /// `offsets[i]..offsets[i + 1]`.
    offsets: Vec<usize>,
    indices: Vec<u32>,
    /// The sharpness of each face's leading (`2i`) and trailing (`2i + 1`)
    /// edges at the vertex; empty when none is sharp.
    edge_sharpness: Vec<f32>,
    /// The ring's faces and the corner's place in each.
    faces: Vec<u32>,
    locals: Vec<u16>,
    /// For faces given unordered: the face across each face's leading
    /// (`2i`) and trailing (`2i + 1`) edge, if the edge is manifold.
    neighbours: Vec<Option<usize>>,
    /// The size of every face when they are all one size, else 0.
    common_size: usize,
    /// The scheme's regular face size.
    reg_size: usize,
    /// The vertex's own sharpness is infinite.
    explicit_inf: bool,
    /// The vertex's own sharpness is finite and not zero.
    explicit_semi: bool,
    /// Its edges make it infinitely sharp.
    implicit_inf: bool,
    /// Its edges make it semi-sharp.
    implicit_semi: bool,
    /// Where the base face is in the ring.
    pub face_in_ring: usize,
    /// The vertex's own sharpness.
    pub vertex_sharpness: f32,
    /// What the neighbourhood holds.
    pub tag: CornerTag,
}

impl Corner {
    /// Corner `corner` of base face `face` of `level`, under a scheme whose
    /// regular faces have `reg_size` vertices.
    pub fn new(level: &Level, face: usize, corner: usize, reg_size: usize) -> Corner {
        let fverts = level.face_verts(face);
        let v = fverts[corner] as usize;
        let vtag = level.vertex_tag(v);
        let ordered = !vtag.non_manifold();
        let faces = level.vertex_faces_of(v);
        let locals = level.vertex_face_locals(v);
        let n = faces.len();
        // The face's own place in the ring: for a non-manifold vertex the
        // instance at this corner (a face may touch the vertex twice).
        let face_in_ring = faces
            .iter()
            .zip(locals)
            .position(|(&f, &l)| f as usize == face && (ordered || usize::from(l) == corner))
            .unwrap_or(0);
        let mut offsets = Vec::with_capacity(n + 1);
        let mut indices = Vec::new();
        offsets.push(0);
        let first_size = level.face_verts(faces[0] as usize).len();
        let mut uncommon = false;
        for (&f, &l) in faces.iter().zip(locals) {
            let fv = level.face_verts(f as usize);
            let start = usize::from(l);
            indices.extend(fv[start..].iter().chain(&fv[..start]));
            offsets.push(indices.len());
            uncommon |= fv.len() != first_size;
        }
        let common = if uncommon { 0 } else { first_size };
        let boundary = vtag.boundary();
        let mut edge_sharpness = Vec::new();
        if vtag.semi_sharp_edges() || vtag.inf_sharp_edges() {
            edge_sharpness.reserve(2 * n);
            for (&f, &l) in faces.iter().zip(locals) {
                let fe = level.face_edges_of(f as usize);
                let j = usize::from(l);
                let lead = fe[j] as usize;
                let trail = fe[(j + fe.len() - 1) % fe.len()] as usize;
                edge_sharpness.push(level.edge_sharpness_at(lead));
                edge_sharpness.push(level.edge_sharpness_at(trail));
            }
        }
        let vertex_sharpness = if vtag.semi_sharp() || vtag.inf_sharp() {
            level.vertex_sharpness_at(v)
        } else {
            0.0
        };
        let mut c = Corner {
            offsets,
            indices,
            edge_sharpness,
            faces: faces.to_vec(),
            locals: locals.to_vec(),
            neighbours: Vec::new(),
            face_in_ring,
            vertex_sharpness,
            common_size: common,
            reg_size,
            explicit_inf: is_infinite(vertex_sharpness),
            explicit_semi: is_semi_sharp(vertex_sharpness),
            implicit_inf: false,
            implicit_semi: false,
            tag: CornerTag {
                inf_sharp: is_infinite(vertex_sharpness),
                semi_sharp: is_semi_sharp(vertex_sharpness),
                uncommon_sizes: uncommon,
                irregular_sizes: common != reg_size,
                unordered: !ordered,
                ..CornerTag::default()
            },
        };
        if ordered {
            c.finish_ordered(boundary);
        } else {
            c.connect_unordered();
        }
        c
    }

    /// The tags of an ordered ring (`FaceVertex::finalizeOrderedTags`).
    fn finish_ordered(&mut self, boundary: bool) {
        let n = self.face_count();
        let tag = &mut self.tag;
        tag.boundary = boundary;
        tag.boundary_non_sharp = boundary;
        if self.edge_sharpness.is_empty() {
            return;
        }
        let s = &self.edge_sharpness;
        if boundary {
            tag.boundary_non_sharp = !is_infinite(s[0]) || !is_infinite(s[2 * n - 1]);
        }
        let (mut inf, mut semi) = (0, 0);
        for i in usize::from(boundary)..n {
            if is_infinite(s[2 * i]) {
                inf += 1;
            } else if is_sharp(s[2 * i]) {
                semi += 1;
            }
        }
        tag.inf_sharp_edges = inf > 0;
        tag.semi_sharp_edges = semi > 0;
        tag.inf_sharp_dart = inf == 1 && !boundary;
        let inf_total = inf + 2 * usize::from(boundary);
        if inf_total > 2 {
            self.implicit_inf = true;
        } else if inf_total + semi > 2 {
            self.implicit_semi = true;
        }
        if !self.explicit_inf && self.implicit_inf {
            tag.inf_sharp = true;
            tag.semi_sharp = false;
        }
    }

    /// Connects the faces of a vertex the refiner could not order, through
    /// the edges they share, and sets the tags that depend on it
    /// (`FaceVertex::ConnectUnOrderedFaces`).
    fn connect_unordered(&mut self) {
        let n = self.face_count();
        let corner = self.indices[0];
        let mut edges: Vec<RingEdge> = Vec::with_capacity(2 * n);
        let mut face_edges = vec![0usize; 2 * n];
        for (fe, slot) in face_edges.iter_mut().enumerate() {
            let (f, trailing) = (fe / 2, fe % 2 == 1);
            let v = if trailing {
                self.trailing(f)
            } else {
                self.face(f)[1]
            };
            let e = if v == corner {
                edges.push(RingEdge {
                    end: v,
                    state: EdgeState::NonManifold,
                    degenerate: true,
                    ..RingEdge::default()
                });
                edges.len() - 1
            } else if let Some(e) = edges.iter().position(|e| e.end == v) {
                edges[e].add_face(f, trailing);
                e
            } else {
                let mut e = RingEdge {
                    end: v,
                    state: EdgeState::Boundary,
                    ..RingEdge::default()
                };
                e.set_face(f, trailing);
                if !self.edge_sharpness.is_empty() {
                    let s = self.edge_sharpness[fe];
                    e.inf_sharp = is_infinite(s);
                    e.semi_sharp = s > 0.0 && !e.inf_sharp;
                }
                edges.push(e);
                edges.len() - 1
            };
            *slot = e;
        }
        // Edges repeated within one face that the pass above missed.
        if self.common_size != 3 {
            for f in 0..n {
                let fv = self.face(f);
                let size = fv.len();
                if size == 4 {
                    if fv[2] == corner {
                        edges[face_edges[2 * f]].duplicate();
                        edges[face_edges[2 * f + 1]].duplicate();
                    }
                } else if self.common_size != 4 {
                    for j in 2..size.saturating_sub(2) {
                        if fv[j] == corner {
                            if fv[j - 1] == fv[1] {
                                edges[face_edges[2 * f]].duplicate();
                            }
                            if fv[j + 1] == fv[size - 1] {
                                edges[face_edges[2 * f + 1]].duplicate();
                            }
                        }
                    }
                }
            }
        }
        self.neighbours = face_edges
            .iter()
            .enumerate()
            .map(|(fe, &e)| {
                let e = &edges[e];
                match e.state {
                    EdgeState::Interior if fe % 2 == 1 => e.next,
                    EdgeState::Interior => e.prev,
                    _ => None,
                }
            })
            .collect();
        let (mut non_manifold, mut inf, mut semi, mut singular) = (0, 0, 0, 0);
        let (mut has_boundary, mut boundary_not_sharp) = (false, false);
        let (mut degenerate, mut duplicate) = (false, false);
        for e in &edges {
            match e.state {
                EdgeState::Interior => {
                    inf += usize::from(e.inf_sharp);
                    semi += usize::from(e.semi_sharp);
                }
                EdgeState::Boundary => {
                    has_boundary = true;
                    boundary_not_sharp |= !e.inf_sharp;
                }
                EdgeState::NonManifold => {
                    non_manifold += 1;
                    degenerate |= e.degenerate;
                    duplicate |= e.duplicate;
                }
            }
            singular += usize::from(e.state != EdgeState::Interior || e.inf_sharp);
        }
        let mut non_manifold_crease = false;
        let is_non_manifold = if non_manifold > 0 {
            if !degenerate && !duplicate && !has_boundary {
                non_manifold_crease = non_manifold == 2 && n > edges.len();
            }
            true
        } else {
            edges.len() as i64 - n as i64 != i64::from(has_boundary)
                || self.connected_extent().total < n
        };
        let tag = &mut self.tag;
        tag.non_manifold = is_non_manifold;
        tag.boundary = has_boundary;
        tag.boundary_non_sharp = boundary_not_sharp;
        tag.inf_sharp_edges = inf > 0;
        tag.semi_sharp_edges = semi > 0;
        tag.inf_sharp_dart = inf == 1 && !has_boundary;
        if singular > 2 || (is_non_manifold && !non_manifold_crease) {
            self.implicit_inf = true;
        } else if singular + semi > 2 {
            self.implicit_semi = true;
        }
        if !self.explicit_inf && self.implicit_inf {
            tag.inf_sharp = true;
            tag.semi_sharp = false;
        }
    }

    /// The faces connected to the corner's face through manifold edges
    /// (`FaceVertex::findConnectedSubsetExtent`).
    fn connected_extent(&self) -> Subset {
        let mut s = Subset::new(CornerTag {
            non_manifold: false,
            ..self.tag
        });
        let start = self.face_in_ring;
        let n = self.face_count();
        let mut f = self.next(start);
        while let Some(g) = f.filter(|_| s.total <= n) {
            if g == start {
                s.tag.boundary = false;
                return s;
            }
            s.after += 1;
            s.total += 1;
            f = self.next(g);
        }
        let mut f = self.prev(start);
        while let Some(g) = f.filter(|_| s.total < n) {
            s.before += 1;
            s.total += 1;
            f = self.prev(g);
        }
        s.tag.boundary = true;
        s
    }

    /// The number of faces around the vertex.
    pub fn face_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Face `f`'s vertices, starting at the corner's vertex.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.indices[self.offsets[f]..self.offsets[f + 1]]
    }

    /// The number of vertices of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        self.offsets[f + 1] - self.offsets[f]
    }

    /// The face after `f` in the ring (`GetFaceNext`).
    pub fn next(&self, f: usize) -> Option<usize> {
        if self.tag.unordered {
            return self.neighbours[2 * f + 1];
        }
        let n = self.face_count();
        if f + 1 < n {
            Some(f + 1)
        } else if self.tag.boundary {
            None
        } else {
            Some(0)
        }
    }

    /// The face before `f` in the ring (`GetFacePrevious`).
    pub fn prev(&self, f: usize) -> Option<usize> {
        if self.tag.unordered {
            return self.neighbours[2 * f];
        }
        if f > 0 {
            Some(f - 1)
        } else if self.tag.boundary {
            None
        } else {
            Some(self.face_count() - 1)
        }
    }

    /// The face after `f` where the ring goes on (the callers stay within
    /// a subset), else `f`.
    pub fn after_face(&self, f: usize) -> usize {
        if self.tag.unordered {
            self.next(f).unwrap_or(f)
        } else {
            (f + 1) % self.face_count()
        }
    }

    /// The face `step` after the corner's face (`GetFaceAfter`).
    pub fn after(&self, step: usize) -> usize {
        if !self.tag.unordered {
            return (self.face_in_ring + step) % self.face_count();
        }
        (0..step).fold(self.face_in_ring, |f, _| self.after_face(f))
    }

    /// The face `step` before the corner's face (`GetFaceBefore`).
    pub fn before(&self, step: usize) -> usize {
        let n = self.face_count();
        if !self.tag.unordered {
            return (self.face_in_ring + n - step % n) % n;
        }
        (0..step).fold(self.face_in_ring, |f, _| self.prev(f).unwrap_or(f))
    }

    /// The first face of `subset` (`GetFaceFirst`).
    pub fn first(&self, subset: &Subset) -> usize {
        self.before(subset.before)
    }

    /// The last vertex of face `f` (the far end of its trailing edge).
    pub fn trailing(&self, f: usize) -> u32 {
        self.indices[self.offsets[f + 1] - 1]
    }

    /// The sharpness of face `f`'s leading (`false`) or trailing edge.
    pub fn edge_sharpness(&self, f: usize, trailing: bool) -> f32 {
        self.edge_sharpness
            .get(2 * f + usize::from(trailing))
            .copied()
            .unwrap_or(0.0)
    }

    /// The faces the corner's face's limit surface depends on
    /// (`FaceVertex::GetVertexSubset`): all of them around a manifold
    /// vertex; around a non-manifold one, those connected to the face
    /// through manifold edges, sharpened as the vertex's edges make it.
    pub fn subset(&self) -> Subset {
        let n = self.face_count();
        if !self.tag.non_manifold {
            let mut s = Subset::new(self.tag);
            s.total = n;
            if !self.tag.boundary {
                s.after = n - 1;
            } else if !self.tag.unordered {
                s.before = self.face_in_ring;
                s.after = n - 1 - s.before;
            } else {
                let mut f = self.next(self.face_in_ring);
                while let Some(g) = f.filter(|_| s.after + 1 < n) {
                    s.after += 1;
                    f = self.next(g);
                }
                s.before = n - 1 - s.after;
            }
            return s;
        }
        let mut s = self.connected_extent();
        self.adjust_tags(&mut s, None);
        if !s.is_sharp() && (self.implicit_inf || self.implicit_semi) {
            s.sharpen_to(self.implicit_sharpness());
        }
        s
    }

    /// The sharpness the vertex's edges give it
    /// (`FaceVertex::GetImplicitVertexSharpness`).
    fn implicit_sharpness(&self) -> f32 {
        if self.implicit_inf {
            return crate::mesh::SHARPNESS_INFINITE;
        }
        (0..self.face_count())
            .filter(|&f| self.prev(f).is_some())
            .fold(self.vertex_sharpness, |m, f| {
                m.max(self.edge_sharpness(f, false))
            })
    }

    /// The faces of `s` from its first, in order.
    fn subset_faces(&self, s: &Subset) -> impl Iterator<Item = usize> + '_ {
        let first = self.first(s);
        (0..s.total).scan(first, |f, _| {
            let here = *f;
            *f = self.after_face(here);
            Some(here)
        })
    }

    /// The tags of a proper subset of the ring or of `superset`, from its
    /// own faces and edges (`FaceVertex::adjustSubsetTags`).
    fn adjust_tags(&self, s: &mut Subset, superset: Option<&Subset>) {
        if s.tag.boundary {
            s.tag.inf_sharp_dart = false;
        }
        if s.tag.inf_sharp {
            s.tag.semi_sharp = false;
        }
        let (total, boundary) = match superset {
            Some(sup) => (sup.total, sup.tag.boundary),
            None => (self.face_count(), self.tag.boundary),
        };
        if s.total >= total && s.tag.boundary == boundary {
            return;
        }
        if s.tag.irregular_sizes && self.tag.uncommon_sizes {
            s.tag.irregular_sizes = self
                .subset_faces(s)
                .any(|f| self.face_size(f) != self.reg_size);
        }
        // Trailing edges of the subset's faces but a boundary's last: its
        // interior edges.
        let trailing: Vec<f32> = if s.total > 1 {
            self.subset_faces(s)
                .take(s.total - usize::from(s.tag.boundary))
                .map(|f| self.edge_sharpness(f, true))
                .collect()
        } else {
            Vec::new()
        };
        if s.tag.inf_sharp_edges {
            s.tag.inf_sharp_edges = trailing.iter().any(|&x| is_infinite(x));
            if s.tag.inf_sharp_edges && s.tag.boundary {
                s.sharpen();
            }
        }
        if s.tag.semi_sharp_edges {
            s.tag.semi_sharp_edges = trailing.iter().any(|&x| is_semi_sharp(x));
        }
    }

    /// This corner with its faces' indices replaced by the values of a
    /// face-varying channel (`face_values(f)`: face `f`'s values), the
    /// ring's order and connections kept.
    pub fn with_values<'a>(&self, face_values: impl Fn(usize) -> &'a [u32]) -> Corner {
        let mut c = self.clone();
        c.indices.clear();
        for (&f, &l) in self.faces.iter().zip(&self.locals) {
            let fv = face_values(f as usize);
            let start = usize::from(l);
            c.indices.extend(fv[start..].iter().chain(&fv[..start]));
        }
        c
    }

    /// Whether faces `a` and `b` (b after a) share their values along the
    /// edge between them (`FaceIndicesMatchAcrossEdge`).
    fn values_match_across(&self, a: usize, b: usize) -> bool {
        self.face(a)[0] == self.face(b)[0] && self.values_match_at_edge_end(a, b)
    }

    /// `FaceIndicesMatchAtEdgeEnd`.
    fn values_match_at_edge_end(&self, a: usize, b: usize) -> bool {
        self.trailing(a) == self.face(b)[1]
    }

    /// The subset of a face-varying channel within the vertex subset
    /// `vertex`, `self` holding the channel's values
    /// (`FaceVertex::FindFaceVaryingSubset`).
    pub fn fvar_subset(&self, vertex: &Subset) -> Subset {
        let mut s = Subset::new(vertex.tag);
        s.tag.boundary = true;
        if vertex.total > 1 {
            self.fvar_extent(vertex, &mut s);
        }
        let matches = s.total == vertex.total && s.tag.boundary == vertex.tag.boundary;
        if !matches {
            if s.is_sharp() {
                s.tag.inf_sharp = self.explicit_inf;
                s.tag.semi_sharp = self.explicit_semi;
            }
            self.adjust_tags(&mut s, Some(vertex));
        }
        if !s.is_sharp() && self.tag.non_manifold {
            s.sharpen();
        }
        if !s.is_sharp() && s.total < vertex.total {
            // The corner's value used outside the subset: non-manifold.
            let value = self.face(self.face_in_ring)[0];
            let uses = (0..self.face_count())
                .filter(|&f| self.face(f)[0] == value)
                .count();
            if uses > s.total {
                s.sharpen();
            }
        }
        s
    }

    /// `FaceVertex::findFVarSubsetExtent`.
    fn fvar_extent(&self, vertex: &Subset, s: &mut Subset) {
        let corner = self.face_in_ring;
        if vertex.after > 0 {
            let mut this = corner;
            let mut next = self.next(this);
            for _ in 0..vertex.after {
                match next {
                    Some(n) if self.values_match_across(this, n) => {
                        s.after += 1;
                        s.total += 1;
                        this = n;
                        next = self.next(n);
                    }
                    _ => break,
                }
            }
            if next == Some(corner) {
                if self.values_match_at_edge_end(this, corner) {
                    s.tag.boundary = false;
                }
                return;
            }
        }
        let mut before = vertex.before;
        if !vertex.tag.boundary {
            before += vertex.after - s.after;
        }
        let mut this = corner;
        for _ in 0..before {
            match self.prev(this) {
                Some(p) if self.values_match_across(p, this) => {
                    s.before += 1;
                    s.total += 1;
                    this = p;
                }
                _ => break,
            }
        }
    }

    /// Sharpens a face-varying subset on a boundary of its channel as the
    /// linear-interpolation option says
    /// (`FaceSurface::sharpenBySdcFVarLinearInterpolation`); `self` holds
    /// the channel's values.
    pub fn sharpen_fvar(&self, s: &mut Subset, vertex: &Subset, fvar: FVarLinearInterpolation) {
        use FVarLinearInterpolation as F;
        let sharp = match fvar {
            F::None | F::All => false,
            F::CornersOnly => s.total == 1,
            F::Boundaries => true,
            F::CornersPlus1 | F::CornersPlus2 => {
                let mut sharp = s.total == 1 || self.more_than_two_subsets();
                if !sharp {
                    let others = vertex.total - s.total;
                    if fvar == F::CornersPlus2 && others == 0 {
                        sharp = !vertex.tag.boundary;
                    } else if fvar == F::CornersPlus2 && others == 1 {
                        sharp = true;
                    } else if self.dependent_sharpness(s) {
                        s.sharpen_to(self.dependent_sharpness_value(s));
                    }
                }
                sharp
            }
        };
        if sharp {
            s.sharpen();
        }
    }

    /// More than two face-varying subsets meet at the corner, or the one
    /// other subset is broken more than twice
    /// (`fvar_plus::hasMoreThanTwoFVarSubsets`).
    fn more_than_two_subsets(&self) -> bool {
        let corner = self.face(self.face_in_ring)[0];
        let mut other = None;
        let mut breaks = 1;
        for f in 0..self.face_count() {
            let value = self.face(f)[0];
            if value == corner {
                continue;
            }
            if other.is_some_and(|o| o != value) {
                return true;
            }
            other = Some(value);
            breaks += usize::from(self.next(f).is_none_or(|n| !self.values_match_across(f, n)));
            if breaks > 2 {
                return true;
            }
        }
        false
    }

    /// `fvar_plus::hasDependentSharpness`.
    fn dependent_sharpness(&self, s: &Subset) -> bool {
        self.face_count() - s.total > 1 && self.tag.sharp_edges() && !s.tag.sharp_edges()
    }

    /// `fvar_plus::getDependentSharpness`: the sharpest interior edge
    /// outside the subset and off its seams, if sharper than the vertex.
    fn dependent_sharpness_value(&self, s: &Subset) -> f32 {
        let first = self.first(s);
        let last = self.after(s.after);
        let first = self.prev(first).map(|_| first);
        let last = self.next(last);
        let sharp = (0..self.face_count())
            .filter(|&f| self.prev(f).is_some() && Some(f) != first && Some(f) != last)
            .fold(0.0f32, |m, f| m.max(self.edge_sharpness(f, false)));
        if sharp > self.vertex_sharpness {
            sharp
        } else {
            0.0
        }
    }
}

/// How many faces share an edge around a corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum EdgeState {
    #[default]
    Boundary,
    Interior,
    NonManifold,
}

/// An edge at a corner's vertex, while its faces are connected
/// (`FaceVertex::Edge`).
#[derive(Debug, Clone, Copy, Default)]
struct RingEdge {
    /// Its other vertex.
    end: u32,
    state: EdgeState,
    /// Whether the last face added has it as its trailing edge.
    trailing: bool,
    degenerate: bool,
    duplicate: bool,
    inf_sharp: bool,
    semi_sharp: bool,
    /// The face it trails and the face it leads.
    prev: Option<usize>,
    next: Option<usize>,
}

impl RingEdge {
    fn set_face(&mut self, f: usize, trailing: bool) {
        self.trailing = trailing;
        if trailing {
            self.prev = Some(f);
        } else {
            self.next = Some(f);
        }
    }

    fn add_face(&mut self, f: usize, trailing: bool) {
        match self.state {
            EdgeState::Boundary => {
                let other = if self.trailing { self.prev } else { self.next };
                if trailing == self.trailing || other == Some(f) {
                    self.state = EdgeState::NonManifold;
                } else {
                    self.state = EdgeState::Interior;
                    self.set_face(f, trailing);
                }
            }
            EdgeState::Interior => self.state = EdgeState::NonManifold,
            EdgeState::NonManifold => {}
        }
    }

    fn duplicate(&mut self) {
        self.state = EdgeState::NonManifold;
        self.duplicate = true;
    }
}
