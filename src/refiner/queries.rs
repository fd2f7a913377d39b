//! Topology queries on every refined level: counts, the relations of
//! `Far::TopologyLevel` (read, or derived where a level leaves them out),
//! whole levels as [`LevelTopology`] and borrowed [`Faces`].

use super::Refiner;
use crate::alloc::{collect_n, copied, vec_or_unwind};
use crate::error::{Element, Error, Result};
use crate::options::Scheme;
use crate::output::{ChildMaps, FVarTopology, INVALID_INDEX, LevelCounts, LevelTopology};
use crate::rules::Rule;
use crate::topology::{Around, AroundBuf, EdgeFaces, Level, Split};

impl Refiner {
    /// Element counts of `level` (`TopologyLevel::GetNumVertices` and friends).
    pub fn level_counts(&self, level: u32) -> Result<LevelCounts> {
        Ok(counts_of(self.internal_level(level)?))
    }

    /// The faces around vertex `v` of `level` and its edges, in OpenSubdiv's
    /// order (`TopologyLevel::GetVertexFaces` and `GetVertexEdges`): read
    /// from the level, or derived from the level before where the level
    /// leaves them out (the level before a minimal last level of a smooth
    /// mesh does not store them). Empty in a minimal last level, which has
    /// no vertex relations, as in OpenSubdiv.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let torus = shapes::torus(6, 4);
    /// let mut refiner = Refiner::new(&torus, &Options::default())?;
    /// refiner.refine_uniform(UniformOptions::new(2))?;
    /// // Level 1 leaves its vertex relations out: level 0 gives them.
    /// let (faces, edges) = refiner.vertex_faces_and_edges(1, 0)?;
    /// assert_eq!((faces.len(), edges.len()), (4, 4));
    /// let level = refiner.level(1)?;
    /// let [a, b] = level.edge_vertices[edges[0] as usize];
    /// let other = if a == 0 { b } else { a };
    /// assert_eq!(refiner.find_edge(1, 0, other)?, Some(edges[0]));
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn vertex_faces_and_edges(&self, level: u32, v: usize) -> Result<(Vec<u32>, Vec<u32>)> {
        let l = self.internal_level(level)?;
        if v >= l.vertex_count {
            return Err(Error::NoSuchElement {
                element: Element::Vertex,
                index: v,
                level,
                count: l.vertex_count,
            });
        }
        let mut buf = AroundBuf::default();
        let (faces, edges) = self.vertex_hood(level as usize, v, &mut buf);
        Ok((faces.to_vec(), edges.to_vec()))
    }

    /// The edge of `level` between vertices `v0` and `v1`
    /// (`TopologyLevel::FindEdge`), or `None` (always in a minimal last
    /// level, which has no edges), also on a level that derives its vertex
    /// relations ([`Refiner::vertex_faces_and_edges`]); a vertex out of range
    /// is an error.
    pub fn find_edge(&self, level: u32, v0: u32, v1: u32) -> Result<Option<u32>> {
        let l = self.internal_level(level)?;
        if v1 as usize >= l.vertex_count {
            return Err(Error::NoSuchElement {
                element: Element::Vertex,
                index: v1 as usize,
                level,
                count: l.vertex_count,
            });
        }
        // Every edge around `v0` has `v0` for an end; the other must be `v1`.
        let (_, edges) = self.vertex_faces_and_edges(level, v0 as usize)?;
        Ok(edges.into_iter().find(|&e| {
            let [a, b] = l.edge_vertices[e as usize];
            if v0 != v1 { a == v1 || b == v1 } else { a == b }
        }))
    }

    /// The faces of edge `e` of `level`, stored or derived
    /// ([`Level::derived_relations`]).
    pub(crate) fn edge_faces_of(&self, level: usize, e: usize) -> EdgeFaces<'_> {
        self.around(level).edge_faces(e)
    }

    /// Level `level`, its relations stored or derived from the level before
    /// ([`Level::derived_relations`]).
    pub(crate) fn around(&self, level: usize) -> Around<'_> {
        around(&self.levels, &self.refinements, level, self.options.scheme)
    }

    /// The faces of edge `e` of `level`, in OpenSubdiv's order
    /// (`TopologyLevel::GetEdgeFaces`): read from the level, or derived from
    /// the level before where the level leaves them out; empty in a minimal
    /// last level.
    pub fn edge_faces(&self, level: u32, e: usize) -> Result<Vec<u32>> {
        let l = self.internal_level(level)?;
        if e >= l.edge_count() {
            return Err(Error::NoSuchElement {
                element: Element::Edge,
                index: e,
                level,
                count: l.edge_count(),
            });
        }
        if !l.derived_relations && l.edge_faces.len() != l.edge_count() {
            return Ok(Vec::new());
        }
        Ok(self.edge_faces_of(level as usize, e).as_slice().to_vec())
    }

    /// The edges of face `f` of `level`, edge `j` from the face's vertex `j`
    /// to vertex `j + 1` (`TopologyLevel::GetFaceEdges`); empty in a minimal
    /// last level, which has no edges.
    pub fn face_edges(&self, level: u32, f: usize) -> Result<Vec<u32>> {
        let l = self.internal_level(level)?;
        if f >= l.face_count() {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: f,
                level,
                count: l.face_count(),
            });
        }
        if l.face_edges.len() != l.face_vertices.members.len() {
            return Ok(Vec::new());
        }
        Ok(l.face_edges_of(f).to_vec())
    }

    /// The subdivision rule of vertex `v` of `level` (smooth, dart, crease
    /// or corner: `TopologyLevel::GetVertexRule`) and whether it lies on a
    /// boundary (`TopologyLevel::IsVertexBoundary`).
    pub fn vertex_rule(&self, level: u32, v: usize) -> Result<(Rule, bool)> {
        let l = self.internal_level(level)?;
        if v >= l.vertex_count {
            return Err(Error::NoSuchElement {
                element: Element::Vertex,
                index: v,
                level,
                count: l.vertex_count,
            });
        }
        let tag = l.vertex_tag(v);
        Ok((tag.rule(), tag.boundary()))
    }

    /// How the components of `level` map to those of `level + 1`
    /// (`Far::TopologyLevel`'s child queries on `level` and
    /// `GetFaceParentFace` on `level + 1`), for `level < max_level()`, in
    /// the uniform numbering: every child exists. A face with `n` corners
    /// has `n` child faces (child `j` at corner `j`) and `n` child edges
    /// inside it, both from its first corner's index; Loop's triangles have
    /// four child faces each (from `4 f`, the middle one last), three child
    /// edges, and no child vertex ([`INVALID_INDEX`], as OpenSubdiv reports
    /// it). The same layout as the `osd` engine's `child_maps`.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let mut r = Refiner::new(&shapes::cube(), &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(1))?;
    /// let maps = r.child_maps(0)?;
    /// // Face 2's four quads are 8..12, in corner order; each knows its parent.
    /// let f = 2;
    /// let range = maps.face_child_face_offsets[f] as usize..maps.face_child_face_offsets[f + 1] as usize;
    /// assert_eq!(maps.face_child_faces[range], [8, 9, 10, 11]);
    /// assert_eq!(maps.child_face_parent_face[9], 2);
    /// // Vertices first: the cube's 8 vertices keep their indices.
    /// assert_eq!(maps.vertex_child_vertex, (0..8).collect::<Vec<u32>>());
    /// assert!(r.child_maps(1).is_err());
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn child_maps(&self, level: u32) -> Result<ChildMaps> {
        let (Some(parent), Some(split)) = (
            self.levels.get(level as usize),
            self.refinements.get(level as usize),
        ) else {
            return Err(Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level().saturating_sub(1),
            });
        };
        crate::alloc::guard(Some(level), || Ok(uniform_child_maps(parent, split)))
    }

    /// The deepest refined level.
    pub fn max_level(&self) -> u32 {
        (self.levels.len() - 1) as u32
    }

    /// Internal topology of `level`.
    pub(crate) fn internal_level(&self, level: u32) -> Result<&Level> {
        self.levels
            .get(level as usize)
            .ok_or_else(|| Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level(),
            })
    }

    /// The topology of `level` as OpenSubdiv reports it (edge-vertices of the
    /// last level only with full topology).
    pub fn level(&self, level: u32) -> Result<LevelTopology> {
        crate::alloc::guard(Some(level), || {
            let l = self.internal_level(level)?;
            let full = level == 0
                || level < self.max_level()
                || self.uniform.is_none_or(|u| u.full_topology_in_last_level);
            let fvar = self
                .fvar
                .iter()
                .map(|channel| FVarTopology {
                    value_count: channel[level as usize].value_count(),
                    face_values: copied(channel[level as usize].face_values()),
                })
                .collect();
            Ok(topology_of(l, full, fvar, || {
                // A minimal last level keeps no edge sharpness: recompute it.
                let parent = &self.levels[level as usize - 1];
                crate::topology::refine::child_edge_sharpness(
                    parent,
                    &self.refinements[level as usize - 1],
                    self.options.creasing,
                    l.edge_count(),
                )
            }))
        })
    }

    /// The faces of `level`, borrowed from the refiner: what a writer of that
    /// level needs, without [`Refiner::level`]'s copy of every table (at
    /// level 4 of a 10,000-quad torus that copy is over 50 MB).
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let mut r = Refiner::new(&shapes::cube(), &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let faces = r.faces(2)?;
    /// assert_eq!(faces.offsets.len(), 6 * 16 + 1);
    /// assert_eq!(faces.vertices[..4], r.level(2)?.face_vertices[..4]);
    /// assert!(faces.holes.is_none());
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn faces(&self, level: u32) -> Result<Faces<'_>> {
        let l = self.internal_level(level)?;
        Ok(Faces {
            offsets: l.face_vertices.offsets_slice(),
            vertices: &l.face_vertices.members,
            // Stored only when some face is a hole.
            holes: (!l.face_holes.is_empty()).then_some(&l.face_holes[..]),
            fvar_face_values: self
                .fvar
                .iter()
                .map(|channel| channel[level as usize].face_values())
                .collect(),
        })
    }
}

/// The faces of one level, borrowed from a [`Refiner`] ([`Refiner::faces`]).
#[derive(Debug, Clone)]
pub struct Faces<'a> {
    /// Start of each face in `vertices`, plus one final entry (built here
    /// when the level's faces all have the same size and store no offsets).
    pub offsets: std::borrow::Cow<'a, [u32]>,
    /// The vertices of every face, concatenated.
    pub vertices: &'a [u32],
    /// One flag per face (`true`: a hole), or `None` when no face is a hole.
    pub holes: Option<&'a [bool]>,
    /// Per face-varying channel, the value index of every face corner
    /// (parallel to `vertices`).
    pub fvar_face_values: Vec<&'a [u32]>,
}

/// The child maps of one uniform step ([`Refiner::child_maps`]), from the
/// numbering of [`Split`].
fn uniform_child_maps(parent: &Level, split: &Split) -> ChildMaps {
    let nf = parent.face_count();
    let corners = parent.face_vertices.members.len() as u32;
    let corner_offsets = parent.face_vertices.offsets_vec();
    // Loop: four child faces per triangle, no face points.
    let triangles = !split.has_face_points() && nf > 0;
    let (child_faces, face_offsets) = if triangles {
        (4 * nf as u32, (0..=nf as u32).map(|f| 4 * f).collect())
    } else {
        (corners, corner_offsets.clone())
    };
    let mut child_face_parent_face = Vec::with_capacity(child_faces as usize);
    for f in 0..nf {
        let n = face_offsets[f + 1] - face_offsets[f];
        child_face_parent_face.extend(std::iter::repeat_n(f as u32, n as usize));
    }
    ChildMaps {
        face_child_faces: (0..child_faces).collect(),
        face_child_face_offsets: face_offsets,
        // The edges inside a face are numbered from its first corner.
        face_child_edges: (0..corners).collect(),
        face_child_edge_offsets: corner_offsets,
        edge_child_edges: (0..parent.edge_count())
            .map(|e| [split.edge_child_edge(e, 0), split.edge_child_edge(e, 1)])
            .collect(),
        face_child_vertex: (0..nf)
            .map(|f| match triangles {
                true => INVALID_INDEX,
                false => split.face_child(f),
            })
            .collect(),
        edge_child_vertex: (0..parent.edge_count())
            .map(|e| split.edge_child(e))
            .collect(),
        vertex_child_vertex: (0..parent.vertex_count)
            .map(|v| split.vertex_child(v))
            .collect(),
        child_face_parent_face,
    }
}

/// Element counts of a level.
pub(crate) fn counts_of(l: &Level) -> LevelCounts {
    LevelCounts {
        vertices: l.vertex_count,
        edges: l.edge_count(),
        faces: l.face_count(),
        face_vertices: l.face_vertices.members.len(),
        full_topology: l.has_full_topology(),
    }
}

/// A level as OpenSubdiv reports it: edge-vertices when `full`, default
/// sharpness, tags and holes expanded; `minimal_edge_sharpness` gives the
/// edge sharpness of a minimal level, which stores none.
pub(crate) fn topology_of(
    l: &Level,
    full: bool,
    fvar: Vec<FVarTopology>,
    minimal_edge_sharpness: impl FnOnce() -> Vec<f32>,
) -> LevelTopology {
    LevelTopology {
        vertex_count: l.vertex_count,
        edge_count: l.edge_count(),
        face_offsets: l.face_vertices.offsets_vec(),
        face_vertices: copied(&l.face_vertices.members),
        edge_vertices: if full {
            copied(&l.edge_vertices)
        } else {
            Vec::new()
        },
        // Tables of default values are stored empty: expand them.
        edge_sharpness: if !l.edge_sharpness.is_empty() {
            copied(&l.edge_sharpness)
        } else if l.has_full_topology() {
            vec_or_unwind(0.0, l.edge_count())
        } else {
            minimal_edge_sharpness()
        },
        vertex_sharpness: collect_n(
            l.vertex_count,
            (0..l.vertex_count).map(|v| l.vertex_sharpness_at(v)),
        ),
        face_holes: collect_n(l.face_count(), (0..l.face_count()).map(|f| l.is_hole(f))),
        fvar,
    }
}

/// Level `level` of `levels` (split into each other by `refinements`), its
/// relations stored or derived from the level before, under `scheme`.
pub(crate) fn around<'a>(
    levels: &'a [Level],
    refinements: &'a [Split],
    level: usize,
    scheme: Scheme,
) -> Around<'a> {
    let before = level.checked_sub(1).map(|p| (&levels[p], &refinements[p]));
    Around::new(&levels[level], before, scheme == Scheme::Loop)
}
