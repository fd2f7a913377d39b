//! `Far::PatchParam`: the two 32-bit words that locate a patch in its ptex
//! face, packed bit for bit as OpenSubdiv packs them (renderers copy the
//! words to the GPU as they are).

/// A patch's parameterization: its ptex face, its place and depth in that
/// face's quadtree, and its boundary and transition masks — OpenSubdiv's
/// `Far::PatchParam`, the same two words.
///
/// `field0`: ptex face id (bits 0-27), transition mask (bits 28-31).
/// `field1`: depth (bits 0-3), non-quad root (bit 4), regular (bit 5),
/// boundary mask (bits 7-11), v (bits 12-21), u (bits 22-31).
///
/// ```
/// use subdiv::patches::PatchParam;
/// let p = PatchParam { field0: 7 | (0b0101 << 28), field1: (3 << 22) | (1 << 12) | (0b0010 << 7) | (1 << 5) | 2 };
/// assert_eq!((p.face_id(), p.u(), p.v(), p.depth()), (7, 3, 1, 2));
/// assert_eq!((p.transition(), p.boundary()), (0b0101, 0b0010));
/// assert!(p.is_regular() && !p.non_quad_root());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct PatchParam {
    /// Ptex face id and transition mask.
    pub field0: u32,
    /// u, v, boundary mask, regular and non-quad flags, depth.
    pub field1: u32,
}

/// `width` bits of `word` from bit `offset`.
const fn bits(word: u32, width: u32, offset: u32) -> u32 {
    (word >> offset) & ((1 << width) - 1)
}

/// `value`'s low `width` bits, shifted to `offset`.
const fn pack(value: u32, width: u32, offset: u32) -> u32 {
    (value & ((1 << width) - 1)) << offset
}

impl PatchParam {
    /// The two words of a patch (`PatchParam::Set`), each field cut to its
    /// width as OpenSubdiv cuts it.
    ///
    /// ```
    /// use subdiv::patches::PatchParam;
    /// let p = PatchParam::new(7, 3, 1, 2, false, 0b0010, 0b0101, true);
    /// assert_eq!((p.face_id(), p.u(), p.v(), p.depth()), (7, 3, 1, 2));
    /// assert_eq!((p.transition(), p.boundary(), p.is_regular()), (0b0101, 0b0010, true));
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub const fn new(
        face: u32,
        u: u16,
        v: u16,
        depth: u16,
        non_quad_root: bool,
        boundary: u16,
        transition: u16,
        regular: bool,
    ) -> PatchParam {
        PatchParam {
            field0: pack(face, 28, 0) | pack(transition as u32, 4, 28),
            field1: pack(u as u32, 10, 22)
                | pack(v as u32, 10, 12)
                | pack(boundary as u32, 5, 7)
                | pack(regular as u32, 1, 5)
                | pack(non_quad_root as u32, 1, 4)
                | pack(depth as u32, 4, 0),
        }
    }

    /// The ptex face the patch lies in (`GetFaceId`).
    pub const fn face_id(self) -> u32 {
        bits(self.field0, 28, 0)
    }

    /// Which of the patch's four edges border a more refined neighbour
    /// (`GetTransition`).
    pub const fn transition(self) -> u32 {
        bits(self.field0, 4, 28)
    }

    /// The patch's column in its ptex face at its depth (`GetU`): the patch
    /// covers `u / 2^d .. (u + 1) / 2^d` with `d` the depth (one less under
    /// a non-quad root, whose sub-faces are the ptex faces).
    pub const fn u(self) -> u32 {
        bits(self.field1, 10, 22)
    }

    /// The patch's row (`GetV`); see [`PatchParam::u`].
    pub const fn v(self) -> u32 {
        bits(self.field1, 10, 12)
    }

    /// Which of the patch's edges are on the boundary (`GetBoundary`): bit
    /// `k` for edge `k`, as the basis functions read it.
    pub const fn boundary(self) -> u32 {
        bits(self.field1, 5, 7)
    }

    /// Whether the patch descends from a non-quad base face
    /// (`NonQuadRoot`).
    pub const fn non_quad_root(self) -> bool {
        bits(self.field1, 1, 4) != 0
    }

    /// Whether the patch is a regular one (`IsRegular`).
    pub const fn is_regular(self) -> bool {
        bits(self.field1, 1, 5) != 0
    }

    /// The refinement level the patch comes from (`GetDepth`).
    pub const fn depth(self) -> u32 {
        bits(self.field1, 4, 0)
    }
}
