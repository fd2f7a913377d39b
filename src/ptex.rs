//! Ptex face indices of a base mesh (OpenSubdiv's `Far::PtexIndices`): one
//! ptex face per regular face (a quad under Catmull-Clark and bilinear, a
//! triangle under Loop) and one per corner of every other face (its
//! "quadrants", the quads the first refinement splits it into), numbered face
//! by face; and the ptex faces adjacent to each ptex face.
//!
//! [`PtexIndices::new`] computes them natively from a
//! [`Refiner`]'s base level; the bridge gives OpenSubdiv's own
//! (`osd::TopologyRefiner::ptex_indices` and `ptex_adjacency`, feature
//! `osd`).
//!
//! ```
//! use subdiv::{ptex::PtexIndices, refiner::Refiner, shapes, Options, INVALID_INDEX};
//! // A pyramid: a square base and four triangles, under Catmull-Clark.
//! let refiner = Refiner::new(&shapes::pyramid(4), &Options::default())?;
//! let ptex = PtexIndices::new(&refiner)?;
//! assert_eq!(ptex.num_faces(), 1 + 4 * 3);
//! let first = ptex.face_id(1)?;
//! // Quadrant 0 of a triangle: its sub-faces 1 and 2 neighbour it inside the face.
//! let adj = ptex.adjacency(&refiner, 1, 0)?;
//! assert_eq!((adj.faces[1], adj.faces[2]), (first + 1, first + 2));
//! assert!(adj.faces.iter().all(|&f| f != INVALID_INDEX));
//! # Ok::<(), subdiv::Error>(())
//! ```

use crate::error::{Element, Error, Result};
use crate::options::Scheme;
use crate::output::INVALID_INDEX;
use crate::refiner::Refiner;

/// The ptex faces of a base mesh: the first ptex face of every base face
/// (`Far::PtexIndices::GetFaceId`) and their number (`GetNumFaces`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PtexIndices {
    /// The first ptex face of every base face, plus the number of ptex faces.
    first: Vec<u32>,
    /// The scheme's regular face size (4, or 3 under Loop).
    regular: usize,
}

/// The neighbours of one ptex face across its four edges
/// (`Far::PtexIndices::GetAdjacency`).
///
/// Edge `i` of a regular quad is the base face's edge `i`; a triangle (Loop)
/// has three edges and its fourth entries are empty. A quadrant `q` of an
/// irregular face is a quad whose edge 0 lies on the face's edge `q`, edge 1
/// and edge 2 inside the face (towards quadrants `q + 1` and `q - 1`), and
/// edge 3 on the face's edge `q - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PtexAdjacency {
    /// The ptex face across each edge, or [`INVALID_INDEX`] (OpenSubdiv's -1)
    /// across a boundary or non-manifold edge.
    pub faces: [u32; 4],
    /// For each neighbour, the edge of that ptex face which is shared (0
    /// where there is no neighbour, as OpenSubdiv).
    pub edges: [u32; 4],
}

impl PtexIndices {
    /// The ptex faces of `refiner`'s base mesh, computed natively.
    pub fn new(refiner: &Refiner) -> Result<PtexIndices> {
        let faces = refiner.faces(0)?;
        let regular = regular_face_size(refiner.options().scheme);
        let mut first = Vec::with_capacity(faces.offsets.len());
        let mut id = 0u64;
        for w in faces.offsets.windows(2) {
            first.push(fit(id)?);
            let n = (w[1] - w[0]) as u64;
            id += if n as usize == regular { 1 } else { n };
        }
        first.push(fit(id)?);
        Ok(PtexIndices { first, regular })
    }

    /// Builds the indices from the first ptex face of every base face plus
    /// the total (the bridge's `Far::PtexIndices`).
    #[cfg_attr(not(feature = "osd"), allow(dead_code))]
    pub(crate) fn from_first(first: Vec<u32>, scheme: Scheme) -> PtexIndices {
        PtexIndices {
            first,
            regular: regular_face_size(scheme),
        }
    }

    /// The number of ptex faces (`GetNumFaces`).
    pub fn num_faces(&self) -> usize {
        self.first.last().copied().unwrap_or(0) as usize
    }

    /// The number of base faces.
    pub fn base_face_count(&self) -> usize {
        self.first.len().saturating_sub(1)
    }

    /// The first ptex face of base face `face` (`GetFaceId`): its only one
    /// when the face is regular, that of its quadrant 0 otherwise.
    pub fn face_id(&self, face: usize) -> Result<u32> {
        if face >= self.base_face_count() {
            return Err(no_face(face, self.base_face_count()));
        }
        Ok(self.first[face])
    }

    /// The number of ptex faces of base face `face`: 1 for a regular face,
    /// one per corner otherwise.
    pub fn face_ptex_count(&self, face: usize) -> Result<usize> {
        let first = self.face_id(face)?;
        Ok((self.first[face + 1] - first) as usize)
    }

    /// The ptex faces adjacent to ptex face `quadrant` of base face `face`
    /// (`GetAdjacency`), from the base level of `refiner` (the refiner these
    /// indices were computed from). `quadrant` is 0 for a regular face and
    /// `0..n` for an irregular face of `n` corners; anything else is an
    /// error. With a refiner of another mesh the result is meaningless (but
    /// an index beyond either mesh is still an error, never a panic).
    pub fn adjacency(
        &self,
        refiner: &Refiner,
        face: usize,
        quadrant: usize,
    ) -> Result<PtexAdjacency> {
        let quadrants = self.face_ptex_count(face)?;
        if quadrant >= quadrants {
            // A quadrant beyond the face's ptex faces: its ptex face does not exist.
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: self.first[face] as usize + quadrant,
                level: 0,
                count: self.num_faces(),
            });
        }
        let edges = refiner.face_edges(0, face)?;
        let n = edges.len();
        let mut adj = PtexAdjacency {
            faces: [INVALID_INDEX; 4],
            edges: [0; 4],
        };
        if n == self.regular {
            // One ptex face: its edges are the face's.
            for (i, &e) in edges.iter().enumerate() {
                if let Some(other) = self.across(refiner, face, e)? {
                    adj.faces[i] = other.0;
                    adj.edges[i] = other.1;
                }
            }
            return Ok(adj);
        }
        // Quadrant `q` of an irregular face: its neighbours inside the face
        // first, then across the face's edges `q` (its edge 0) and `q - 1`
        // (its edge 3).
        let first = self.first[face];
        let next = (quadrant + 1) % n;
        let prev = (quadrant + n - 1) % n;
        adj.faces[1] = first + next as u32;
        adj.edges[1] = 2;
        adj.faces[2] = first + prev as u32;
        adj.edges[2] = 1;
        for (slot, e) in [(0, edges[quadrant]), (3, edges[prev])] {
            if let Some((f, edge)) = self.across_quadrant(refiner, face, e, slot == 0)? {
                adj.faces[slot] = f;
                adj.edges[slot] = edge;
            }
        }
        Ok(adj)
    }

    /// The base face across edge `e` from `face`: the other of exactly two
    /// faces (`face` itself when it uses the edge twice); `None` on a
    /// boundary or non-manifold edge.
    fn neighbour(refiner: &Refiner, face: usize, e: u32) -> Result<Option<(usize, Vec<u32>)>> {
        let faces = refiner.edge_faces(0, e as usize)?;
        let &[a, b] = faces.as_slice() else {
            return Ok(None);
        };
        let other = if a as usize == face { b } else { a } as usize;
        let other_edges = refiner.face_edges(0, other)?;
        Ok(Some((other, other_edges)))
    }

    /// The ptex face and edge across edge `e` seen from a regular face: a
    /// regular neighbour's own edge, or the irregular neighbour's quadrant
    /// that follows the edge, whose edge 3 lies on it.
    fn across(&self, refiner: &Refiner, face: usize, e: u32) -> Result<Option<(u32, u32)>> {
        let Some((other, other_edges)) = Self::neighbour(refiner, face, e)? else {
            return Ok(None);
        };
        let k = local(&other_edges, e);
        let first = self.first_of(other)?;
        Ok(Some(if other_edges.len() == self.regular {
            (first, k)
        } else {
            (first + (k + 1) % other_edges.len() as u32, 3)
        }))
    }

    /// The ptex face and edge across edge `e` seen from a quadrant of an
    /// irregular face (a quad scheme): a quad neighbour's own edge; or, in
    /// an irregular neighbour, across the quadrant's edge 0 the neighbour's
    /// quadrant after the edge (its edge 3), across its edge 3 the
    /// neighbour's quadrant at the edge (its edge 0).
    fn across_quadrant(
        &self,
        refiner: &Refiner,
        face: usize,
        e: u32,
        edge0: bool,
    ) -> Result<Option<(u32, u32)>> {
        let Some((other, other_edges)) = Self::neighbour(refiner, face, e)? else {
            return Ok(None);
        };
        let k = local(&other_edges, e);
        let first = self.first_of(other)?;
        let n = other_edges.len() as u32;
        Ok(Some(if n == 4 {
            (first, k)
        } else if edge0 {
            (first + (k + 1) % n, 3)
        } else {
            (first + k, 0)
        }))
    }

    fn first_of(&self, face: usize) -> Result<u32> {
        self.face_id(face)
    }
}

/// The first position of edge `e` among a face's edges (present by
/// construction: the face is one of the edge's faces).
fn local(edges: &[u32], e: u32) -> u32 {
    edges.iter().position(|&x| x == e).unwrap_or(0) as u32
}

fn regular_face_size(scheme: Scheme) -> usize {
    match scheme {
        Scheme::Loop => 3,
        _ => 4,
    }
}

fn fit(id: u64) -> Result<u32> {
    u32::try_from(id)
        .ok()
        .filter(|&i| i != INVALID_INDEX)
        .ok_or(Error::TooLarge {
            what: "ptex faces",
            count: id as usize,
            bits: 32,
        })
}

fn no_face(face: usize, count: usize) -> Error {
    Error::NoSuchElement {
        element: Element::Face,
        index: face,
        level: 0,
        count,
    }
}
