// subdiv shim, Bfr limit surfaces: a Bfr::RefinerSurfaceFactory<> over the
// base level of a Far::TopologyRefiner built by sdv_refiner_create (the same
// refiner every other part of the bridge builds from a subdiv::Mesh), and
// Bfr::Surface<double> built per call for one face: its properties, control
// points, evaluation at a batch of coordinates and limit stencils. As
// everywhere in the shim, every entry point catches every exception, and
// every input that would make OpenSubdiv read or write out of bounds is
// refused before it sees it.
//
// What OpenSubdiv 3.5.0 does with the inputs refused here (bfr/*.cpp):
// * coordinates off the face's domain: Surface::Evaluate and EvaluateStencil
//   of an n-gon under a quad scheme convert (u, v) to a sub-face with
//   Parameterization::ConvertCoordToNormalizedSubFace (a tile index from the
//   integer parts, an adjacent tile when a fraction exceeds 0.75) and index
//   the irregular patch's quadtree roots (PatchTree::searchQuadtree,
//   _treeNodes[subFace]) or the linear patch points (N + 1 + subFace) with
//   it unchecked; a tile beyond the grid, or beyond the last sub-face, is out
//   of bounds, and converting a coordinate too large for an int is
//   undefined. Inside a quad or triangle the quadtree descends into an
//   existing child at every level, so coordinates just off the unit domain
//   only extrapolate; the bridge refuses every coordinate off the domain by
//   more than COORD_SLACK all the same (an evaluation there is not of the
//   face's surface).
// * high valence and large faces: Bfr::VertexDescriptor holds a vertex's
//   face count in a short (Initialize accepts up to 65535 and wraps from
//   32768 on, then sizes its arrays with the negative count), FaceVertex
//   numbers the 2 * valence face-edges of an unordered (non-manifold)
//   vertex in shorts, and FaceVertex keeps the face's size in a short.
// * valence-2 interior vertices: IrregularPatchBuilder::Build, for a face
//   with an interior corner of valence 2 (its control faces may overlap), a
//   boundary corner and sharp interior edges, appends the sharpened boundary
//   edges with sharpenBoundaryControlEdges -- which in 3.5.0 writes them
//   over the first sharp edges gathered instead of after them, yet counts
//   them all: the local TopologyDescriptor then hands as many crease vertex
//   pairs and weights as there were sharp edges from never-written
//   (uninitialised) stack or heap memory to TopologyRefinerFactory, which
//   looks each pair up with Level::findEdge(v0, v1) -- reading the vertex
//   arrays at whatever indices that memory holds. 3.5.1 fixed it (commit
//   51eb6a04, "Fix bug in Bfr::SurfaceFactory with valence-2 interior
//   vertex", four lines: the pointers advance past the gathered edges).
//   The bridge refuses such faces conservatively (see check_valence2).
// * valence-2 interior vertices with an infinitely sharp edge (a dart, or a
//   face-varying seam): the Gregory patches next to such a vertex in a
//   face's refined neighbourhood have a corner ring that names one point
//   past the patch's source points (Far::SourcePatch counts the points of
//   a corner beside a valence-2 corner one short when that corner's span
//   stops at the sharp edge). Far's PatchTableFactory gathers the points
//   into a 64-entry stack buffer, so the extra one lands there and is read
//   back; Bfr's PatchTreeBuilder::getIrregularPatchConversion sizes a
//   std::vector to the point count, so PatchBuilder::
//   GetIrregularPatchSourcePoints writes one past its end (out of bounds
//   unless the vector has spare capacity from a previous patch), and the
//   conversion then reads that point without the level's offset, as a
//   control point it is not. Unchanged in 3.6.0. Refused conservatively
//   (see check_valence2_dart).
// * approximation levels: the levels are unsigned chars and the adaptive
//   refinement of a face's neighbourhood goes that deep; its patches'
//   Far::PatchParam hold 10 bits of u and v, which wrap beyond level 10 and
//   build a quadtree with unset children.
// * points: PreparePatchPoints reads the points at the surface's control
//   indices with int arithmetic (stride * index).
//
// OpenSubdiv's own slip kept out of the results: PatchTree::
// EvalSubPatchStencils passes its duv output twice (for duv and dvv) when
// the irregular patch is a single regular interior patch at depth 0, so
// the dvv weights are never written and duv receives dvv's. The bridge
// fills the outputs with NaN first, and where dvv is left unwritten it
// computes the duv and dvv weights by evaluating the surface on the
// control points' unit vectors (the stencil's definition).

#include "bfr_internal.h"

#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyLevel.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

typedef Bfr::RefinerSurfaceFactory<> Factory;
typedef Bfr::Surface<double> Surface;

struct sdv_surfaces {
    const sdv_refiner *refiner = nullptr;  // not owned: outlives the factory
    std::unique_ptr<Factory> factory;
    bool linear_scheme = false;  // bilinear: vertex surfaces are linear
    bool linear_fvar = false;    // face-varying surfaces are linear
};

namespace {

// How far off its domain a coordinate may lie (in the face's (u, v); twice
// that in a sub-face's normalized coordinates): the rounding of coordinates
// computed on the domain's edges (tessellation patterns, conversions).
const double COORD_SLACK = 1e-9;  // (the messages below say 1e-9)

// Far::PatchParam holds 10 bits of a patch's u and v index.
const int MAX_APPROX_LEVEL = 10;

const sdv_surfaces &need_surfaces(const sdv_surfaces *s) {
    if (!s || !s->factory || !s->refiner || !s->refiner->refiner) fail("null surfaces");
    return *s;
}

Far::TopologyLevel const &base_of(const sdv_surfaces &s) { return s.refiner->refiner->GetLevel(0); }

const char *kind_name(int32_t kind) {
    return kind == SDV_SURFACE_VERTEX ? "vertex" : kind == SDV_SURFACE_VARYING ? "varying" : "face-varying";
}

void check_face(const sdv_surfaces &s, int32_t face) {
    int n = s.factory->GetNumFaces();
    if (face < 0 || face >= n) fail("face " + str(face) + " does not exist (the mesh has " + str(n) + ")");
}

void check_kind(const sdv_surfaces &s, int32_t kind, int32_t channel) {
    if (kind != SDV_SURFACE_VERTEX && kind != SDV_SURFACE_VARYING && kind != SDV_SURFACE_FACE_VARYING)
        fail("unknown surface kind " + str(kind));
    if (kind == SDV_SURFACE_FACE_VARYING) {
        int n = s.factory->GetNumFVarChannels();
        if (channel < 0 || channel >= n)
            fail("face-varying channel " + str(channel) + " does not exist (the mesh has " + str(n) + ")");
    }
}

// A vertex whose faces are not one closed fan: a boundary, or non-manifold
// (one of its fans may be open).
bool may_be_boundary(Far::TopologyLevel const &base, Far::Index v) {
    return base.IsVertexBoundary(v) || base.IsVertexNonManifold(v);
}

// An edge at `v` that is sharp (semi-sharp or infinitely, non-manifold
// edges included) and not a boundary edge (those have one face): what
// Bfr's corner tags count as sharp edges. -1 if none.
Far::Index sharp_interior_edge(Far::TopologyLevel const &base, Far::Index v) {
    Far::ConstIndexArray ve = base.GetVertexEdges(v);
    for (int k = 0; k < ve.size(); ++k)
        if (base.GetEdgeSharpness(ve[k]) > 0.0f && base.GetEdgeFaces(ve[k]).size() >= 2) return ve[k];
    return -1;
}

// The 3.5.0 fault of IrregularPatchBuilder (see the top of this file) needs
// three things of a face's surface: a corner subset that is interior with
// two faces (control faces overlap), a boundary corner subset
// (sharpenBoundaryControlEdges runs and sharpens its edge) and sharp edges
// gathered (the ones it overwrites and then counts twice). Refused here on
// the base level's topology, conservatively: an interior valence-2 corner,
// a boundary or non-manifold corner (for a face-varying surface any corner
// may bound its channel's subset at a seam, so this is not required), and
// a sharp interior edge at any corner.
void check_valence2(Far::TopologyLevel const &base, int face, bool fvar) {
    Far::ConstIndexArray fv = base.GetFaceVertices(face);
    int n = fv.size();
    int val2 = -1, boundary = -1;
    Far::Index sharp = -1, sharp_at = -1;
    for (int i = 0; i < n; ++i) {
        if (val2 < 0 && is_valence2_corner(base, face, i)) val2 = i;
        if (boundary < 0 && may_be_boundary(base, fv[i])) boundary = i;
        if (sharp < 0) {
            sharp = sharp_interior_edge(base, fv[i]);
            if (sharp >= 0) sharp_at = fv[i];
        }
    }
    if (val2 < 0 || sharp < 0 || (!fvar && boundary < 0)) return;
    std::string where = fvar ? std::string("its face-varying subsets may have a boundary at a seam")
                             : "its corner vertex " + str(fv[boundary]) + " is on a boundary or non-manifold";
    fail_unsafe("face " + str(face) + ": its corner vertex " + str(fv[val2]) +
                " is an interior vertex of valence 2 (two faces folded onto each other), " + where +
                ", and edge " + str(sharp) + " at vertex " + str(sharp_at) +
                " is sharp: OpenSubdiv 3.5.0's Bfr (IrregularPatchBuilder::sharpenBoundaryControlEdges, fixed in "
                "3.5.1) then reads crease vertex indices from uninitialised memory and looks edges up with "
                "them, out of bounds");
}

// OpenSubdiv's second valence-2 fault (see the top of this file) needs an
// interior corner of valence 2 whose span, in the refined neighbourhood,
// meets a corner whose own span stops at an infinitely sharp edge: the
// children of the corner's two edges, sharp when the edge is infinitely
// sharp or, for a face-varying surface, a seam (face-varying topology that
// differs from the vertices' at the edge or at the corner's vertex).
// Refused on the base level's topology: such a corner with such an edge.
void check_valence2_dart(Far::TopologyLevel const &base, int face, int channel) {
    Far::ConstIndexArray fv = base.GetFaceVertices(face);
    Far::ConstIndexArray fe = base.GetFaceEdges(face);
    int n = fv.size();
    for (int i = 0; i < n; ++i) {
        if (!is_valence2_corner(base, face, i)) continue;
        bool vertex_seam = channel >= 0 && !base.DoesVertexFVarTopologyMatch(fv[i], channel);
        for (Far::Index e : {fe[i], fe[(i + n - 1) % n]}) {
            bool inf_sharp = Sdc::Crease::IsInfinite(base.GetEdgeSharpness(e));
            bool seam = channel >= 0 && (vertex_seam || !base.DoesEdgeFVarTopologyMatch(e, channel));
            if (!inf_sharp && !seam) continue;
            fail_unsafe("face " + str(face) + ": its corner vertex " + str(fv[i]) +
                        " is an interior vertex of valence 2 (two faces folded onto each other) and its edge " +
                        str(e) + (inf_sharp ? " is infinitely sharp" : " is a face-varying seam") +
                        ": OpenSubdiv's Bfr (PatchTreeBuilder::getIrregularPatchConversion) then writes a source "
                        "point past the end of its array and reads it as a control point it is not");
        }
    }
}

}  // namespace

// What a surface of `face` needs of its topology before OpenSubdiv builds
// it (shared: see bfr_internal.h).
void sdv_internal::check_bfr_surface_face(Far::TopologyLevel const &base, int face, bool nonlinear, int channel) {
    Far::ConstIndexArray fv = base.GetFaceVertices(face);
    if (fv.size() > SDV_BFR_MAX_SURFACE_FACE_SIZE)
        fail_unsafe("face " + str(face) + " has " + str(fv.size()) + " vertices: Bfr keeps a face's size in a short "
                    "(the bridge takes faces of up to " + str(SDV_BFR_MAX_SURFACE_FACE_SIZE) + ")");
    for (int i = 0; i < fv.size(); ++i) {
        int valence = base.GetVertexFaces(fv[i]).size();
        if (valence > SDV_BFR_MAX_SURFACE_VALENCE)
            fail_unsafe("face " + str(face) + ": its corner vertex " + str(fv[i]) + " has " + str(valence) +
                        " faces: Bfr keeps a vertex's face count in a short, and numbers an unordered vertex's "
                        "2 * valence face-edges in shorts (the bridge takes up to " +
                        str(SDV_BFR_MAX_SURFACE_VALENCE) + " faces at a vertex)");
    }
    if (!nonlinear) return;
    check_valence2(base, face, channel >= 0);
    check_valence2_dart(base, face, channel);
}

namespace {

// What every surface of `face` needs of its topology before OpenSubdiv
// builds it.
void check_face_topology(const sdv_surfaces &s, int32_t face, int32_t kind, int32_t channel) {
    bool nonlinear = kind == SDV_SURFACE_VERTEX ? !s.linear_scheme
                     : kind == SDV_SURFACE_FACE_VARYING ? !s.linear_fvar
                                                        : false;
    check_bfr_surface_face(base_of(s), face, nonlinear, kind == SDV_SURFACE_FACE_VARYING ? channel : -1);
}

// Builds the surface of `face` (false: no limit surface). OpenSubdiv's
// errors while building (its local refiners report through Far::Error)
// fail the call.
bool init_surface(const sdv_surfaces &s, int32_t face, int32_t kind, int32_t channel, Surface &surface) {
    check_face_topology(s, face, kind, channel);
    osd_errors().clear();
    bool ok = kind == SDV_SURFACE_VERTEX    ? s.factory->InitVertexSurface<double>(face, &surface)
              : kind == SDV_SURFACE_VARYING ? s.factory->InitVaryingSurface<double>(face, &surface)
                                            : s.factory->InitFaceVaryingSurface<double>(face, &surface, channel);
    if (!osd_errors().empty())
        throw ShimError(SDV_ERR_OSD, "OpenSubdiv reported errors building the " + std::string(kind_name(kind)) +
                                         " surface of face " + str(face) + ": " + osd_errors());
    return ok && surface.IsValid();
}

Surface need_surface(const sdv_surfaces &s, int32_t face, int32_t kind, int32_t channel) {
    Surface surface;
    if (!init_surface(s, face, kind, channel, surface))
        fail("face " + str(face) + " has no " + kind_name(kind) +
             " limit surface (a hole, or a face OpenSubdiv's Bfr finds no limit for, such as a boundary face "
             "under boundary interpolation \"none\")");
    return surface;
}

// The width of Parameterization's sub-face grid, read from OpenSubdiv: the
// first vertex placed on the grid's second row.
int sub_face_grid_width(Bfr::Parameterization const &p) {
    int n = p.GetFaceSize();
    for (int k = 1; k < n; ++k) {
        double uv[2];
        p.GetVertexCoord(k, uv);
        if (uv[1] >= 1.0) return k;
    }
    throw ShimError(SDV_ERR_INTERNAL, "a " + str(n) + "-sided face's sub-face grid has one row");
}

// Whether (u, v) lies on one of the sub-faces of `p`, in the tile
// Parameterization::ConvertCoordToNormalizedSubFace picks for it (replayed
// here, its integer conversions made defined by the range check first).
bool on_sub_face(Bfr::Parameterization const &p, int udim, double u, double v) {
    const double s = COORD_SLACK;
    if (u < -s || v < -s || u > udim + s || v > udim + s) return false;
    int ut = (int)u, vt = (int)v;
    double uf = u - (double)ut, vf = v - (double)vt;
    if (uf > 0.75) {
        ++ut;
        uf -= 1.0;
    }
    if (vf > 0.75) {
        ++vt;
        vf -= 1.0;
    }
    if (ut >= udim || (long long)vt * udim + ut >= p.GetFaceSize()) return false;
    double su = 2.0 * uf, sv = 2.0 * vf;
    return su >= -2 * s && su <= 1 + 2 * s && sv >= -2 * s && sv <= 1 + 2 * s;
}

void check_coords(Bfr::Parameterization const &p, int32_t face, const double *uv, size_t n) {
    if (n && !uv) fail("null coordinates");
    const double s = COORD_SLACK;
    int udim = p.HasSubFaces() ? sub_face_grid_width(p) : 0;
    for (size_t i = 0; i < n; ++i) {
        double u = uv[2 * i], v = uv[2 * i + 1];
        if (!std::isfinite(u) || !std::isfinite(v))
            fail("coordinate " + str((long long)i) + " (" + std::to_string(u) + ", " + std::to_string(v) +
                 ") is not finite");
        bool ok = false;
        const char *domain = "";
        switch (p.GetType()) {
            case Bfr::Parameterization::QUAD:
                ok = u >= -s && u <= 1 + s && v >= -s && v <= 1 + s;
                domain = "the unit square";
                break;
            case Bfr::Parameterization::TRI:
                ok = u >= -s && v >= -s && u + v <= 1 + s;
                domain = "the unit triangle (u, v >= 0, u + v <= 1)";
                break;
            case Bfr::Parameterization::QUAD_SUBFACES:
                ok = on_sub_face(p, udim, u, v);
                domain = "any of its sub-faces (each a half-unit square at the corner of a unit tile, "
                         "one tile per vertex)";
                break;
        }
        if (!ok) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", u, v);
            fail("coordinate " + str((long long)i) + " " + buf + " is off face " + str(face) + "'s domain, " + domain +
                 " (by more than 1e-9): Bfr evaluates only inside it");
        }
    }
}

// The number of points the surface's indices reach into (the mesh's
// vertices, or the channel's values).
long long point_count(const sdv_surfaces &s, int32_t kind, int32_t channel) {
    Far::TopologyLevel const &base = base_of(s);
    return kind == SDV_SURFACE_FACE_VARYING ? base.GetNumFVarValues(channel) : base.GetNumVertices();
}

}  // namespace

void sdv_internal::check_bfr_control_points(Surface const &surface, long long available, int32_t face) {
    std::vector<int> cvs((size_t)surface.GetNumControlPoints());
    if (!cvs.empty()) surface.GetControlPointIndices(cvs.data());
    for (size_t i = 0; i < cvs.size(); ++i)
        if (cvs[i] < 0 || cvs[i] >= available)
            throw ShimError(SDV_ERR_INTERNAL, "face " + str(face) + "'s surface names control point " +
                                                  str(cvs[i]) + " of " + str(available));
}

namespace {

int columns_of(int32_t derivatives) {
    if (derivatives < 0 || derivatives > 2) fail("derivatives " + str(derivatives) + " is not 0, 1 or 2");
    return derivatives == 0 ? 1 : derivatives == 1 ? 3 : 6;
}

void evaluate(const sdv_surfaces &s, int32_t face, const sdv_surface_eval &e) {
    check_face(s, face);
    check_kind(s, e.kind, e.channel);
    int columns = columns_of(e.derivatives);
    if (e.width < 1) fail("width " + str(e.width) + " is not positive");
    long long needed = point_count(s, e.kind, e.channel);
    if ((long long)e.num_points < needed || e.num_points > (size_t)LLONG_MAX)
        fail(str((long long)e.num_points) + " points given, the " + kind_name(e.kind) + " surfaces read " +
             str(needed));
    if (e.num_points > (size_t)INT_MAX || (long long)e.num_points * e.width > INT_MAX)
        fail(str((long long)e.num_points) + " points of " + str(e.width) +
             " reals: OpenSubdiv indexes them in int, which holds 2^31 - 1");
    if (e.num_points && !e.points) fail("null points");
    if (e.n > (size_t)INT_MAX) fail("too many coordinates");
    long long out_len = (long long)e.n * e.width;
    for (int c = 0; c < columns; ++c) {
        check_cap(e.cap, out_len, "evaluation output");
        if (out_len && !e.out[c]) fail("null output");
    }
    Surface surface = need_surface(s, face, e.kind, e.channel);
    check_coords(surface.GetParameterization(), face, e.uv, e.n);
    check_bfr_control_points(surface, needed, face);
    long long patch_points = surface.GetNumPatchPoints();
    if (patch_points < 1 || patch_points * e.width > INT_MAX)
        fail("face " + str(face) + "'s surface has " + str(patch_points) + " patch points of " + str(e.width) +
             " reals, which OpenSubdiv cannot index in int");
    std::vector<double> points((size_t)(patch_points * e.width));
    Surface::PointDescriptor desc(e.width);
    surface.PreparePatchPoints(e.points, desc, points.data(), desc);
    size_t w = (size_t)e.width;
    for (size_t i = 0; i < e.n; ++i) {
        const double *uv = e.uv + 2 * i;
        size_t at = i * w;
        if (columns == 1)
            surface.Evaluate(uv, points.data(), desc, e.out[0] + at);
        else if (columns == 3)
            surface.Evaluate(uv, points.data(), desc, e.out[0] + at, e.out[1] + at, e.out[2] + at);
        else
            surface.Evaluate(uv, points.data(), desc, e.out[0] + at, e.out[1] + at, e.out[2] + at, e.out[3] + at,
                             e.out[4] + at, e.out[5] + at);
    }
}

// PreparePatchPoints of `face`'s surface from `points` (e's points, kind,
// channel and width; its coordinates and outputs unused): the count always,
// the points into `out` when it is not null (cap reals).
void patch_points(const sdv_surfaces &s, int32_t face, const sdv_surface_eval &e, double *out, size_t cap,
                  int32_t *count) {
    check_face(s, face);
    check_kind(s, e.kind, e.channel);
    if (!count) fail("null patch point count");
    if (e.width < 1) fail("width " + str(e.width) + " is not positive");
    long long needed = point_count(s, e.kind, e.channel);
    if ((long long)e.num_points < needed || e.num_points > (size_t)INT_MAX ||
        (long long)e.num_points * e.width > INT_MAX)
        fail(str((long long)e.num_points) + " points given, the " + kind_name(e.kind) + " surfaces read " +
             str(needed) + " (OpenSubdiv indexes them in int)");
    if (e.num_points && !e.points) fail("null points");
    Surface surface = need_surface(s, face, e.kind, e.channel);
    check_bfr_control_points(surface, needed, face);
    long long n = surface.GetNumPatchPoints();
    if (n < 1 || n * e.width > INT_MAX)
        fail("face " + str(face) + "'s surface has " + str(n) + " patch points of " + str(e.width) +
             " reals, which OpenSubdiv cannot index in int");
    *count = (int32_t)n;
    if (!out) return;
    check_cap(cap, n * e.width, "patch point output");
    Surface::PointDescriptor desc(e.width);
    surface.PreparePatchPoints(e.points, desc, out, desc);
}

// The duv and dvv stencil weights of `surface` at `uv` computed as the
// stencil's definition has them: the surface evaluated on the control
// points' unit vectors (control point j has a 1 in component j).
void second_stencils_by_evaluation(Surface const &surface, const double *uv, double *duv, double *dvv) {
    int ncp = surface.GetNumControlPoints();
    long long patch_points = surface.GetNumPatchPoints();
    if (patch_points * ncp > (long long)INT_MAX)
        fail("the surface has " + str(patch_points) + " patch points over " + str(ncp) +
             " control points: too many to evaluate its stencils point by point");
    std::vector<double> points((size_t)(patch_points * ncp), 0.0);
    for (int j = 0; j < ncp; ++j) points[(size_t)j * ncp + j] = 1.0;
    Surface::PointDescriptor desc(ncp);
    surface.ComputePatchPoints(points.data(), desc);
    std::vector<double> p((size_t)ncp), du((size_t)ncp), dv((size_t)ncp), duu((size_t)ncp);
    surface.Evaluate(uv, points.data(), desc, p.data(), du.data(), dv.data(), duu.data(), duv, dvv);
}

void stencils(const sdv_surfaces &s, int32_t face, int32_t kind, int32_t channel, const double *uv, size_t n,
              int32_t derivatives, double *out, size_t cap, int32_t *num_control_points) {
    check_face(s, face);
    check_kind(s, kind, channel);
    int columns = columns_of(derivatives);
    if (!num_control_points) fail("null control point count");
    if (n > (size_t)INT_MAX) fail("too many coordinates");
    Surface surface = need_surface(s, face, kind, channel);
    check_coords(surface.GetParameterization(), face, uv, n);
    int ncp = surface.GetNumControlPoints();
    *num_control_points = ncp;
    if (!out) return;
    long long row = (long long)columns * ncp;
    check_cap(cap, (long long)n * row, "stencil output");
    std::fill(out, out + n * (size_t)row, std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < n; ++i) {
        const double *c = uv + 2 * i;
        double *o = out + i * (size_t)row;
        int got;
        if (columns == 1)
            got = surface.EvaluateStencil(c, o);
        else if (columns == 3)
            got = surface.EvaluateStencil(c, o, o + ncp, o + 2 * ncp);
        else
            got = surface.EvaluateStencil(c, o, o + ncp, o + 2 * ncp, o + 3 * ncp, o + 4 * ncp, o + 5 * ncp);
        if (got != ncp)
            throw ShimError(SDV_ERR_INTERNAL, "EvaluateStencil returned " + str(got) + " weights for " + str(ncp) +
                                                  " control points");
        if (columns == 6 && std::any_of(o + 5 * ncp, o + 6 * ncp, [](double x) { return std::isnan(x); }))
            second_stencils_by_evaluation(surface, c, o + 4 * ncp, o + 5 * ncp);
        for (long long k = 0; k < row; ++k)
            if (std::isnan(o[k]))
                throw ShimError(SDV_ERR_INTERNAL, "EvaluateStencil left weight " + str(k % ncp) + " of column " +
                                                      str(k / ncp) + " unwritten");
    }
}

}  // namespace

extern "C" {

int sdv_surfaces_create(const sdv_refiner *r, int32_t approx_level_smooth, int32_t approx_level_sharp,
                        sdv_surfaces **out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        const sdv_refiner &rr = sdv_internal::need(r);
        for (int32_t level : {approx_level_smooth, approx_level_sharp})
            if (level < 0 || level > MAX_APPROX_LEVEL)
                fail("approximation level " + str(level) + " is not 0.." + str(MAX_APPROX_LEVEL) +
                     " (the patches of a face's refined neighbourhood hold 10 bits of u and v)");
        Far::TopologyRefiner const &tr = *rr.refiner;
        Factory::Options o;
        o.SetApproxLevelSmooth(approx_level_smooth);
        o.SetApproxLevelSharp(approx_level_sharp);
        o.SetDefaultFVarID(0);
        o.EnableCaching(false);
        std::unique_ptr<sdv_surfaces> h(new sdv_surfaces());
        h->refiner = r;
        h->factory.reset(new Factory(tr, o));
        h->linear_scheme = tr.GetSchemeType() == Sdc::SCHEME_BILINEAR;
        h->linear_fvar =
            h->linear_scheme || tr.GetSchemeOptions().GetFVarLinearInterpolation() == Sdc::Options::FVAR_LINEAR_ALL;
        if (h->factory->GetNumFaces() != tr.GetLevel(0).GetNumFaces())
            throw ShimError(SDV_ERR_INTERNAL, "the surface factory counts another number of faces");
        *out = h.release();
    });
}

void sdv_surfaces_destroy(sdv_surfaces *s) { delete s; }

int32_t sdv_surfaces_face_count(const sdv_surfaces *s) { return (s && s->factory) ? s->factory->GetNumFaces() : 0; }

int sdv_surface_info_get(const sdv_surfaces *s, int32_t face, int32_t kind, int32_t channel, sdv_surface_info *out,
                         int32_t *control_points, size_t cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_surfaces &ss = need_surfaces(s);
        if (!out) fail("null output");
        check_face(ss, face);
        check_kind(ss, kind, channel);
        *out = sdv_surface_info();
        Surface surface;
        if (!init_surface(ss, face, kind, channel, surface)) {
            Bfr::Parameterization p = ss.factory->GetFaceParameterization(face);
            out->param_type = (int32_t)p.GetType();
            out->face_size = base_of(ss).GetFaceVertices(face).size();
            return;
        }
        Bfr::Parameterization p = surface.GetParameterization();
        out->is_valid = 1;
        out->is_regular = surface.IsRegular() ? 1 : 0;
        out->is_linear = surface.IsLinear() ? 1 : 0;
        out->num_control_points = surface.GetNumControlPoints();
        out->num_patch_points = surface.GetNumPatchPoints();
        out->param_type = (int32_t)p.GetType();
        out->face_size = p.GetFaceSize();
        check_bfr_control_points(surface, point_count(ss, kind, channel), face);
        if (control_points && cap >= (size_t)out->num_control_points && out->num_control_points > 0)
            surface.GetControlPointIndices(control_points);
    });
}

int sdv_surface_evaluate(const sdv_surfaces *s, int32_t face, const sdv_surface_eval *e, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_surfaces &ss = need_surfaces(s);
        if (!e) fail("null evaluation");
        evaluate(ss, face, *e);
    });
}

int sdv_surface_patch_points(const sdv_surfaces *s, int32_t face, const sdv_surface_eval *e, double *out,
                             size_t cap, int32_t *count, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_surfaces &ss = need_surfaces(s);
        if (!e) fail("null arguments");
        patch_points(ss, face, *e, out, cap, count);
    });
}

int sdv_surface_stencils(const sdv_surfaces *s, int32_t face, int32_t kind, int32_t channel, const double *uv,
                         size_t n, int32_t derivatives, double *out, size_t cap, int32_t *num_control_points,
                         char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_surfaces &ss = need_surfaces(s);
        stencils(ss, face, kind, channel, uv, n, derivatives, out, cap, num_control_points);
    });
}

}  // extern "C"
