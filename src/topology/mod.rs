//! One refinement level as flat index tables, built from face-vertex lists and
//! split level by level — the native counterpart of OpenSubdiv's `Vtr`
//! (`Vtr::Level`, `Vtr::Refinement` and their face-varying counterparts).
//!
//! Every relation is stored as a flat array plus offsets (no per-element
//! allocation, no pointer graph):
//!
//! | relation | members | local index |
//! | --- | --- | --- |
//! | face → vertices, face → edges | in face order; edge `j` runs from vertex `j` to `j+1` | — |
//! | edge → vertices | the two ends | — |
//! | edge → faces | incident faces | position of the edge in each face |
//! | vertex → faces | counter-clockwise around a manifold vertex | position of the vertex in each face |
//! | vertex → edges | counter-clockwise, interleaved with the faces | 0 or 1: which end of the edge |
//!
//! Base edges are numbered as OpenSubdiv numbers them (order of first
//! appearance while walking the faces), non-manifold features are detected and
//! tagged as OpenSubdiv tags them, and children are numbered in OpenSubdiv's
//! order (see [`refine`]).
//!
//! # Files
//!
//! | file | holds | OpenSubdiv |
//! | --- | --- | --- |
//! | `level.rs` | [`Level`]: one level's relations, sharpness, tags and holes | `vtr/level.h` |
//! | `relation.rs` | [`Relation`]: a relation's members and offsets | (part of `Vtr::Level`) |
//! | `tags.rs` | [`EdgeTag`], [`VertexTag`] | `Level::ETag`, `Level::VTag` |
//! | `table.rs` | [`Table`]: the flat tables, on recycled huge pages when large | — |
//! | `table_pool.rs` | the memory of dropped tables, kept for the next ones without ever raising the peak | — |
//! | `growing.rs` | a table filled by appending, for outputs whose length is found as they are built | — |
//! | `base.rs` | [`build_base_level`]: the base level from face-vertex lists | `far/topologyRefinerFactory.cpp`, `vtr/level.cpp` |
//! | `manifold.rs` | the base level of a mesh whose edges are all manifold, from each vertex's corners (no edge search) | `vtr/level.cpp` (`completeTopologyFromFaceVertices`, `orientIncidentComponents`) |
//! | `lookup.rs` | the base level's lookups (an edge by its ends, a vertex's corner in a face), mapped past 32 edges or corners | `vtr/level.cpp` (`findEdge`) |
//! | `refine/` | [`refine_level`]: one level split into the next ([`refine`] says which file does what) | `vtr/refinement.cpp`, `quadRefinement.cpp`, `triRefinement.cpp` |
//! | `around.rs` | a level's relations around an edge or a vertex as face-varying code reads them: stored, or derived from the level before | — |
//! | `fvar/` | face-varying channels at one level and their split | `vtr/fvarLevel.cpp`, `fvarRefinement.cpp` |
//! | `tests.rs` | which tables each level stores, derived relations | — |

mod around;
mod base;
pub mod fvar;
mod growing;
mod level;
mod lookup;
mod manifold;
pub mod refine;
mod relation;
mod slices;
mod table;
mod table_pool;
mod tags;
#[cfg(test)]
mod tests;

pub(crate) use around::{Around, AroundBuf, EdgeFaces, Hood};
pub use base::build_base_level;
pub(crate) use growing::Growing;
pub use level::{Level, unpaired_smooth_vertex};
pub use refine::{Build, Split, refine_level};
pub(crate) use relation::RelationView;
pub use relation::{Offsets, Relation};
pub(crate) use slices::LevelSlices;
pub use table::{Table, release_table_pool};
pub use tags::{EdgeTag, VertexTag};
