// subdiv shim: the only C++ of the project. A plain C ABI (cpp/shim.h) over
// OpenSubdiv's Far layer. Every entry point catches every exception, and every
// index of a descriptor is checked before OpenSubdiv sees it.

#include "internal.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/osd/bufferDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>
#include <opensubdiv/version.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

namespace sdv_internal {

void check_channel(const sdv_refiner *r, int32_t channel) {
    int n = need(r).refiner->GetNumFVarChannels();
    if (channel < 0 || channel >= n)
        fail("face-varying channel " + str(channel) + " does not exist (the refiner has " + str(n) + ")");
}

// Sdc's Catmull-Clark smooth vertex mask (sdc/catmarkScheme.h,
// assignSmoothMaskForVertex) weighs each edge and face by 1 / (valence *
// valence) with the product computed in int: from valence 46341 it overflows
// (undefined behaviour; in practice a negative weight and a vertex point far
// from its place). Scheme::ComputeVertexVertexMask uses that mask wherever the
// vertex's rule or its child's is smooth or dart; PrimvarRefiner applies it to
// vertex primvars, and to a face-varying channel where the channel is not
// linear and its topology matches the vertex's at the child. Refuse
// interpolating from `parent` (to parent + 1) where that would happen;
// `channel` -1 for vertex primvars.
const int SMOOTH_MASK_MAX_VALENCE = 46340;  // 46340² < 2³¹ <= 46341²

void check_smooth_vertex_masks(const Far::TopologyRefiner &tr, int parent, int channel) {
    if (tr.GetSchemeType() != Sdc::SCHEME_CATMARK) return;
    if (channel >= 0 && tr.GetFVarLinearInterpolation(channel) == Sdc::Options::FVAR_LINEAR_ALL) return;
    const Far::TopologyLevel &p = tr.GetLevel(parent);
    const Far::TopologyLevel &c = tr.GetLevel(parent + 1);
    for (int v = 0; v < p.GetNumVertices(); ++v) {
        int valence = p.GetVertexFaces(v).size();
        if (valence <= SMOOTH_MASK_MAX_VALENCE) continue;
        Far::Index child = p.GetVertexChildVertex(v);
        if (child < 0) continue;
        auto smooth = [](Sdc::Crease::Rule r) {
            return r == Sdc::Crease::RULE_SMOOTH || r == Sdc::Crease::RULE_DART;
        };
        if (!smooth(p.GetVertexRule(v)) && !smooth(c.GetVertexRule(child))) continue;
        if (channel >= 0 && !c.DoesVertexFVarTopologyMatch(child, channel)) continue;
        fail_unsafe("vertex " + str(v) + " of level " + str(parent) + " has " + str(valence) +
                    " faces; OpenSubdiv 3.5's Catmull-Clark vertex rule computes valence * valence in a 32-bit int, "
                    "which overflows beyond " + str(SMOOTH_MASK_MAX_VALENCE) + " faces (wrong weights)");
    }
}

}  // namespace sdv_internal

namespace {

// Messages OpenSubdiv reports through Far::Error / Far::Warning on this thread.
thread_local std::string t_osd_errors;
thread_local std::string t_osd_warnings;

void on_error(Far::ErrorType, const char *message) {
    if (!t_osd_errors.empty()) t_osd_errors += "; ";
    t_osd_errors += message ? message : "(no message)";
}

void on_warning(const char *message) {
    if (!t_osd_warnings.empty()) t_osd_warnings += "\n";
    t_osd_warnings += message ? message : "(no message)";
}

void install_callbacks() {
    static std::once_flag once;
    std::call_once(once, [] {
        Far::SetErrorCallback(on_error);
        Far::SetWarningCallback(on_warning);
    });
}

}  // namespace

namespace sdv_internal {
std::string &osd_errors() { return t_osd_errors; }
}  // namespace sdv_internal

struct sdv_evaluator {
    Far::StencilTable const *table = nullptr;
    int controls = 0;
    ~sdv_evaluator() { delete table; }
};

namespace {

Far::TopologyLevel const &level_of(const sdv_refiner *r, int32_t level) {
    const sdv_refiner &rr = need(r);
    int max = rr.refiner->GetMaxLevel();
    if (level < 0 || level > max)
        fail("level " + str(level) + " does not exist (refined levels are 0.." + str(max) + ")");
    return rr.refiner->GetLevel(level);
}

bool has_full_topology(const sdv_refiner *r, int32_t level) {
    return level < r->refiner->GetMaxLevel() || r->full_topology_last_level;
}

// The last level of a default uniform refinement holds only the relations
// interpolation needs (face-vertices, vertex-faces): edge-vertices are absent.
void need_full_topology(const sdv_refiner *r, int32_t level, const char *what) {
    if (!has_full_topology(r, level))
        fail(std::string(what) + " of level " + str(level) +
             " are not available: the last level was refined without full topology");
}

void check_len(size_t len, long long need_n, const char *what) {
    if (len != (size_t)need_n)
        fail(std::string(what) + " has " + str((long long)len) + " elements, expected " + str(need_n));
}

void validate(const sdv_mesh_desc &d, const sdv_options &o) {
    if (o.scheme < 0 || o.scheme > 2) fail("scheme " + str(o.scheme) + " is not 0..2");
    if (o.boundary < 0 || o.boundary > 2) fail("boundary interpolation " + str(o.boundary) + " is not 0..2");
    if (o.fvar < 0 || o.fvar > 5) fail("face-varying interpolation " + str(o.fvar) + " is not 0..5");
    if (o.creasing < 0 || o.creasing > 1) fail("creasing method " + str(o.creasing) + " is not 0..1");
    if (o.triangles < 0 || o.triangles > 1) fail("triangle subdivision " + str(o.triangles) + " is not 0..1");
    if (d.num_vertices < 0 || d.num_faces < 0 || d.num_creases < 0 || d.num_corners < 0 ||
        d.num_holes < 0 || d.num_fvar_channels < 0)
        fail("negative count in mesh descriptor");
    if (d.num_faces > 0 && (!d.face_sizes || !d.face_vertices)) fail("null face arrays");
    if (d.num_creases > 0 && (!d.crease_vertex_pairs || !d.crease_sharpness)) fail("null crease arrays");
    if (d.num_corners > 0 && (!d.corner_vertices || !d.corner_sharpness)) fail("null corner arrays");
    if (d.num_holes > 0 && !d.holes) fail("null hole array");
    if (d.num_fvar_channels > 0 && !d.fvar_channels) fail("null face-varying channel array");
    // OpenSubdiv refuses it too, but only after reporting an error through its callback.
    if (d.num_faces == 0) fail("the mesh has no faces: there is nothing to refine");

    long long total = 0;
    for (int f = 0; f < d.num_faces; ++f) {
        int n = d.face_sizes[f];
        if (n < 3) fail("face " + str(f) + " has " + str(n) + " vertices; at least 3 are needed");
        if (n > 65535) fail("face " + str(f) + " has " + str(n) + " vertices; at most 65535 are supported");
        if (o.scheme == 2 && n != 3)
            fail("face " + str(f) + " has " + str(n) + " vertices; the Loop scheme needs triangles");
        for (int j = 0; j < n; ++j) {
            int v = d.face_vertices[total + j];
            if (v < 0 || v >= d.num_vertices)
                fail("face " + str(f) + " corner " + str(j) + ": vertex index " + str(v) +
                     " is out of range (" + str(d.num_vertices) + " vertices)");
        }
        total += n;
        if (total > 0x7fffffffLL) fail("more than 2^31-1 face vertices");
    }
    for (int i = 0; i < d.num_creases; ++i) {
        for (int k = 0; k < 2; ++k) {
            int v = d.crease_vertex_pairs[2 * i + k];
            if (v < 0 || v >= d.num_vertices)
                fail("crease " + str(i) + ": vertex " + str(v) + " is out of range (" + str(d.num_vertices) +
                     " vertices)");
        }
        if (!std::isfinite(d.crease_sharpness[i])) fail("crease " + str(i) + ": sharpness is not finite");
    }
    for (int i = 0; i < d.num_corners; ++i) {
        int v = d.corner_vertices[i];
        if (v < 0 || v >= d.num_vertices)
            fail("corner " + str(i) + ": vertex " + str(v) + " is out of range (" + str(d.num_vertices) +
                 " vertices)");
        if (!std::isfinite(d.corner_sharpness[i])) fail("corner " + str(i) + ": sharpness is not finite");
    }
    for (int i = 0; i < d.num_holes; ++i) {
        int f = d.holes[i];
        if (f < 0 || f >= d.num_faces)
            fail("hole " + str(i) + ": face " + str(f) + " is out of range (" + str(d.num_faces) + " faces)");
    }
    for (int c = 0; c < d.num_fvar_channels; ++c) {
        const sdv_fvar_channel &ch = d.fvar_channels[c];
        if (ch.num_values < 0) fail("face-varying channel " + str(c) + ": negative value count");
        if (total > 0 && !ch.value_indices) fail("face-varying channel " + str(c) + ": null value indices");
        for (long long i = 0; i < total; ++i) {
            int v = ch.value_indices[i];
            if (v < 0 || v >= ch.num_values)
                fail("face-varying channel " + str(c) + ": value index " + str(v) + " at face corner " +
                     str(i) + " is out of range (" + str(ch.num_values) + " values)");
        }
    }
}

// A row of `width` reals inside a caller's buffer, as PrimvarRefiner wants it.
template <class T>
struct Elem {
    T *p;
    int w;
    void Clear(void * = nullptr) {
        for (int i = 0; i < w; ++i) p[i] = 0;
    }
    template <class S, class W>
    void AddWithWeight(S const &src, W weight) {
        for (int i = 0; i < w; ++i) p[i] += src.p[i] * weight;
    }
};

template <class T>
struct Buf {
    T *base;
    int w;
    Elem<T> operator[](int i) const { return Elem<T>{base + (size_t)i * (size_t)w, w}; }
};

// The same for every level up to the last (stencil tables).
void check_smooth_vertex_masks_all_levels(const Far::TopologyRefiner &tr) {
    for (int l = 0; l < tr.GetMaxLevel(); ++l) check_smooth_vertex_masks(tr, l, -1);
}

template <class T>
void interpolate(const sdv_refiner *r, int32_t kind, int32_t channel, int32_t level, int32_t width,
                 const T *src, size_t src_len, T *dst, size_t dst_len) {
    const sdv_refiner &rr = need(r);
    int max = rr.refiner->GetMaxLevel();
    if (level < 1 || level > max)
        fail("cannot interpolate to level " + str(level) + " (refined levels are 1.." + str(max) + ")");
    if (width < 1) fail("primvar width must be at least 1");
    if (!src || !dst) fail("null primvar buffer");
    long long n_src, n_dst;
    if (kind == SDV_FACE_VARYING) {
        check_channel(r, channel);
        n_src = rr.refiner->GetLevel(level - 1).GetNumFVarValues(channel);
        n_dst = rr.refiner->GetLevel(level).GetNumFVarValues(channel);
    } else if (kind == SDV_VERTEX || kind == SDV_VARYING) {
        n_src = rr.refiner->GetLevel(level - 1).GetNumVertices();
        n_dst = rr.refiner->GetLevel(level).GetNumVertices();
    } else {
        fail("unknown primvar kind " + str(kind));
    }
    check_len(src_len, n_src * width, "source primvar buffer");
    check_len(dst_len, n_dst * width, "destination primvar buffer");
    if (kind == SDV_VERTEX) check_smooth_vertex_masks(*rr.refiner, level - 1, -1);
    if (kind == SDV_FACE_VARYING) check_smooth_vertex_masks(*rr.refiner, level - 1, channel);
    Far::PrimvarRefinerReal<T> pr(*rr.refiner);
    Buf<T> s{const_cast<T *>(src), width};
    Buf<T> d{dst, width};
    if (kind == SDV_VERTEX)
        pr.Interpolate(level, s, d);
    else if (kind == SDV_VARYING)
        pr.InterpolateVarying(level, s, d);
    else
        pr.InterpolateFaceVarying(level, s, d, channel);
}

void need_limit_topology(const sdv_refiner &rr) {
    if (rr.refiner->GetMaxLevel() > 0 && !rr.full_topology_last_level)
        fail("limit evaluation needs full topology in the last level "
             "(refine with full_topology_in_last_level)");
}

// OpenSubdiv 3.5's PrimvarRefiner::Limit (far/primvarRefiner.h) sizes its
// buffers by the last level's maximum valence M (TopologyRefiner::
// GetMaxValence: for uniform refinement the last level's, since every level's
// is at least its parent's): one index buffer of 1 + 2M entries holding a
// vertex's edge neighbours then, when a mask has face weights, its face
// neighbours; and per mask (position, and two tangents) 1 + 2M weights laid
// out as [vertex | M edge weights | M face weights]. A refined level's M is
// computed, not counted (vtr/refinement.cpp: max(parent M, 4 or 6,
// 2 + parent max edge-faces (twice that for triangles))), and a non-manifold
// vertex can have more faces than that: then the face weights run into the
// next mask (wrong limits) or past the buffer (heap corruption). The counts
// below are those of Sdc's limit masks (sdc/catmarkScheme.h, loopScheme.h,
// bilinearScheme.h) per rule: a smooth or dart vertex uses its face count for
// both edge and face weights (Catmull-Clark; Loop: edge weights only), with
// two faces Catmull-Clark uses the corner masks; a crease uses its edges
// (tangents also its faces under Catmull-Clark); a corner's position has no
// neighbour and its tangents use its edges (bilinear: two edges, always).
struct MaskCounts {
    int edges = 0, faces = 0;
};

void mask_counts(Sdc::SchemeType scheme, Sdc::Crease::Rule rule, int n_edges, int n_faces, MaskCounts &pos,
                 MaskCounts &tan) {
    bool smooth = rule == Sdc::Crease::RULE_SMOOTH || rule == Sdc::Crease::RULE_DART;
    if (scheme == Sdc::SCHEME_BILINEAR) {
        pos = {0, 0};
        tan = {2, 0};
    } else if (scheme == Sdc::SCHEME_LOOP) {
        if (smooth) {
            pos = {n_faces, 0};
            tan = {n_faces, 0};
        } else if (rule == Sdc::Crease::RULE_CREASE) {
            pos = {n_edges, 0};
            tan = {n_edges, 0};
        } else {
            pos = {0, 0};
            tan = {n_edges, 0};
        }
    } else {
        if (smooth && n_faces != 2) {
            pos = {n_faces, n_faces};
            tan = {n_faces, n_faces};
        } else if (rule == Sdc::Crease::RULE_CREASE) {
            pos = {n_edges, 0};
            tan = {n_edges, n_faces};
        } else {
            pos = {0, 0};
            tan = {n_edges, 0};
        }
    }
}

// Refuses a refiner on which PrimvarRefiner::Limit would overrun its masks;
// `tangents`: Limit with tangents (three masks) or positions only.
void check_limit_masks(const Far::TopologyRefiner &refiner, bool tangents) {
    const int last = refiner.GetMaxLevel();
    const Far::TopologyLevel &l = refiner.GetLevel(last);
    const long long m = refiner.GetMaxValence();
    const Sdc::SchemeType scheme = refiner.GetSchemeType();
    for (int v = 0; v < l.GetNumVertices(); ++v) {
        int n_edges = l.GetVertexEdges(v).size();
        if (n_edges == 0) continue; // Limit copies such a vertex
        int n_faces = l.GetVertexFaces(v).size();
        MaskCounts pos, tan;
        mask_counts(scheme, l.GetVertexRule(v), n_edges, n_faces, pos, tan);
        if (!tangents) tan = {0, 0};
        bool gathers_faces = pos.faces > 0 || tan.faces > 0;
        long long indices = n_edges + (gathers_faces ? n_faces : 0);
        int edge_weights = std::max(pos.edges, tan.edges);
        int face_weights = std::max(pos.faces, tan.faces);
        if (indices > 1 + 2 * m || edge_weights > m || face_weights > m) {
            fail_unsafe("vertex " + str(v) + " of level " + str(last) + " has " + str(n_edges) + " edges and " +
                        str(n_faces) + " faces, more than OpenSubdiv 3.5's PrimvarRefiner::Limit sizes its masks "
                        "for (maximum valence " + str(m) + "): it would write past them");
        }
    }
}

// The same for PrimvarRefiner::LimitFaceVarying (one position mask laid out as
// [vertex | one weight per vertex edge | face weights] in 1 + 2M weights, and
// the vertex's edge values gathered into M entries), at the vertices whose
// values it evaluates with the vertex's own mask: those where the channel's
// topology matches the vertex's (not purely linear channels).
void check_limit_fvar_masks(const Far::TopologyRefiner &refiner, int channel) {
    if (refiner.GetFVarLinearInterpolation(channel) == Sdc::Options::FVAR_LINEAR_ALL) return;
    const int last = refiner.GetMaxLevel();
    const Far::TopologyLevel &l = refiner.GetLevel(last);
    const long long m = refiner.GetMaxValence();
    const Sdc::SchemeType scheme = refiner.GetSchemeType();
    for (int v = 0; v < l.GetNumVertices(); ++v) {
        int n_edges = l.GetVertexEdges(v).size();
        if (n_edges == 0 || !l.DoesVertexFVarTopologyMatch(v, channel)) continue;
        int n_faces = l.GetVertexFaces(v).size();
        MaskCounts pos, tan;
        mask_counts(scheme, l.GetVertexRule(v), n_edges, n_faces, pos, tan);
        if (n_edges > m || pos.edges > n_edges || n_edges + pos.faces > 2 * m) {
            fail_unsafe("vertex " + str(v) + " of level " + str(last) + " has " + str(n_edges) + " edges and " +
                        str(n_faces) + " faces, more than OpenSubdiv 3.5's PrimvarRefiner::LimitFaceVarying "
                        "sizes its masks for (maximum valence " + str(m) + "): it would write past them");
        }
    }
}

template <class T>
void limit(const sdv_refiner *r, int32_t width, const T *src, size_t src_len, T *pos, T *tan1, T *tan2,
           size_t dst_len) {
    const sdv_refiner &rr = need(r);
    need_limit_topology(rr);
    if (width < 1) fail("primvar width must be at least 1");
    if (!src || !pos) fail("null primvar buffer");
    if ((tan1 == nullptr) != (tan2 == nullptr)) fail("give both tangent buffers or neither");
    long long n = rr.refiner->GetLevel(rr.refiner->GetMaxLevel()).GetNumVertices();
    check_len(src_len, n * width, "source primvar buffer");
    check_len(dst_len, n * width, "limit buffer");
    check_limit_masks(*rr.refiner, tan1 != nullptr);
    Far::PrimvarRefinerReal<T> pr(*rr.refiner);
    Buf<T> s{const_cast<T *>(src), width};
    Buf<T> p{pos, width};
    if (tan1) {
        Buf<T> t1{tan1, width}, t2{tan2, width};
        pr.Limit(s, p, t1, t2);
    } else {
        pr.Limit(s, p);
    }
}

// OpenSubdiv 3.5's LimitFaceVarying looks up the tag of a vertex's first
// value with the value's index, as if it were an index into the channel's
// per-vertex values. After refinement the two coincide; in an unrefined base
// level they are the caller's indices, and one at or beyond the number of
// per-vertex values (one per vertex, plus one per extra distinct value at a
// vertex) is read past the end of OpenSubdiv's tag array. Refuse those.
void check_base_fvar_values_for_limit(const Far::TopologyRefiner &refiner, int channel) {
    const Far::TopologyLevel &l = refiner.GetLevel(0);
    // One pass over the vertices: each vertex's distinct values (its
    // "siblings") in the order they first appear around its faces, as
    // Vtr::FVarLevel numbers them (fvarLevel.cpp,
    // completeTopologyFromFaceValues; every vertex counts at least one), found
    // by sorting (value, position) pairs so that a vertex of any valence costs
    // n log n. Their total is the number of per-vertex values; the first
    // vertex whose siblings are not numbered so is kept for the check below.
    long long vertex_values = 0;
    std::string misnumbered;
    std::vector<std::pair<Far::Index, int>> seen;
    for (int v = 0; v < l.GetNumVertices(); ++v) {
        Far::ConstIndexArray faces = l.GetVertexFaces(v);
        Far::ConstLocalIndexArray corners = l.GetVertexFaceLocalIndices(v);
        seen.clear();
        for (int i = 0; i < faces.size(); ++i) {
            Far::ConstIndexArray values = l.GetFaceFVarValues(faces[i], channel);
            if (corners[i] < values.size()) seen.emplace_back(values[corners[i]], i);
        }
        // Distinct values, each with its first position, then in that order.
        std::sort(seen.begin(), seen.end());
        seen.erase(std::unique(seen.begin(), seen.end(),
                               [](const std::pair<Far::Index, int> &a, const std::pair<Far::Index, int> &b) {
                                   return a.first == b.first;
                               }),
                   seen.end());
        std::sort(seen.begin(), seen.end(),
                  [](const std::pair<Far::Index, int> &a, const std::pair<Far::Index, int> &b) {
                      return a.second < b.second;
                  });
        if (misnumbered.empty() && l.GetVertexEdges(v).size() > 0) {
            for (size_t i = 0; i < seen.size(); ++i) {
                if (seen[i].first != vertex_values + (long long)i) {
                    misnumbered = "face-varying channel " + str(channel) + ": value " + str(seen[i].first) +
                                  " (vertex " + str(v) + ") is OpenSubdiv's per-vertex value " +
                                  str(vertex_values + (long long)i) +
                                  " of the unrefined level, whose tags OpenSubdiv 3.5's LimitFaceVarying would "
                                  "read for it (a wrong rule); refine at least one level, or number the values "
                                  "vertex by vertex";
                    break;
                }
            }
        }
        vertex_values += std::max<long long>(1, (long long)seen.size());
    }
    // A value at or beyond the number of per-vertex values is read past the
    // end of OpenSubdiv's tag array.
    for (int f = 0; f < l.GetNumFaces(); ++f) {
        Far::ConstIndexArray values = l.GetFaceFVarValues(f, channel);
        for (int k = 0; k < values.size(); ++k) {
            if (values[k] >= vertex_values) {
                fail("face-varying channel " + str(channel) + ": value " + str(values[k]) + " of face " + str(f) +
                     " is beyond the " + str(vertex_values) +
                     " per-vertex values of the unrefined level; OpenSubdiv's LimitFaceVarying would read out of "
                     "bounds there (refine at least one level, or number the values vertex by vertex)");
            }
        }
    }
    // In range but numbered otherwise, a value reads another value's tags
    // (whether its topology matches the vertex's, whether it is a corner):
    // a wrong rule and a wrong limit (found by the limit_nonmanifold fuzz
    // target). LimitFaceVarying reads the tags of every vertex with edges,
    // unless the channel is linear (values copied).
    if (refiner.GetFVarLinearInterpolation(channel) == Sdc::Options::FVAR_LINEAR_ALL) return;
    if (!misnumbered.empty()) fail_unsafe(misnumbered);
}

template <class T>
void limit_fvar(const sdv_refiner *r, int32_t channel, int32_t width, const T *src, size_t src_len, T *dst,
                size_t dst_len) {
    const sdv_refiner &rr = need(r);
    need_limit_topology(rr);
    check_channel(r, channel);
    if (width < 1) fail("primvar width must be at least 1");
    if (!src || !dst) fail("null primvar buffer");
    long long n = rr.refiner->GetLevel(rr.refiner->GetMaxLevel()).GetNumFVarValues(channel);
    check_len(src_len, n * width, "source face-varying buffer");
    check_len(dst_len, n * width, "limit buffer");
    if (rr.refiner->GetMaxLevel() == 0) check_base_fvar_values_for_limit(*rr.refiner, channel);
    check_limit_fvar_masks(*rr.refiner, channel);
    Far::PrimvarRefinerReal<T> pr(*rr.refiner);
    Buf<T> s{const_cast<T *>(src), width};
    Buf<T> d{dst, width};
    pr.LimitFaceVarying(s, d, channel);
}

// A sparse combination of base vertices, accumulated in insertion order: the
// primvar type that turns PrimvarRefiner into a stencil builder.
struct SparseRow {
    std::vector<std::pair<int32_t, double>> terms;
};

struct SparseElem {
    SparseRow *row;
    void Clear(void * = nullptr) { row->terms.clear(); }
    void AddWithWeight(SparseElem const &src, double weight) {
        for (auto const &t : src.row->terms) {
            bool found = false;
            for (auto &mine : row->terms) {
                if (mine.first == t.first) {
                    mine.second += t.second * weight;
                    found = true;
                    break;
                }
            }
            if (!found) row->terms.emplace_back(t.first, t.second * weight);
        }
    }
};

struct SparseBuf {
    SparseRow *base;
    SparseElem operator[](int i) const { return SparseElem{base + i}; }
};

void append_rows(sdv_stencils &s, std::vector<SparseRow> const &rows) {
    for (auto const &row : rows) {
        s.offsets.push_back((int32_t)s.indices.size());
        s.sizes.push_back((int32_t)row.terms.size());
        for (auto const &t : row.terms) {
            s.indices.push_back(t.first);
            s.weights.push_back(t.second);
        }
    }
}

sdv_stencils *limit_stencils(const sdv_refiner &rr) {
    need_limit_topology(rr);
    Far::TopologyRefiner const &tr = *rr.refiner;
    check_limit_masks(tr, true);
    check_smooth_vertex_masks_all_levels(tr);
    Far::PrimvarRefinerReal<double> pr(tr);
    std::vector<SparseRow> cur(tr.GetLevel(0).GetNumVertices());
    for (size_t i = 0; i < cur.size(); ++i) cur[i].terms.emplace_back((int32_t)i, 1.0);
    for (int level = 1; level <= tr.GetMaxLevel(); ++level) {
        std::vector<SparseRow> next(tr.GetLevel(level).GetNumVertices());
        SparseBuf s{cur.data()}, d{next.data()};
        pr.Interpolate(level, s, d);
        cur.swap(next);
    }
    std::vector<SparseRow> pos(cur.size()), du(cur.size()), dv(cur.size());
    SparseBuf s{cur.data()}, p{pos.data()}, t1{du.data()}, t2{dv.data()};
    pr.Limit(s, p, t1, t2);
    auto *out = new sdv_stencils();
    append_rows(*out, pos);
    append_rows(*out, du);
    append_rows(*out, dv);
    return out;
}

// A double table from OpenSubdiv into the shim's form (the table freed).
sdv_stencils *take_table(Far::StencilTableReal<double> const *table) {
    if (!table) fail("StencilTableFactory::Create failed");
    auto *out = new (std::nothrow) sdv_stencils();
    if (!out) {
        delete table;
        throw std::bad_alloc();
    }
    try {
        out->sizes.assign(table->GetSizes().begin(), table->GetSizes().end());
        out->offsets.assign(table->GetOffsets().begin(), table->GetOffsets().end());
        out->indices.assign(table->GetControlIndices().begin(), table->GetControlIndices().end());
        out->weights.assign(table->GetWeights().begin(), table->GetWeights().end());
    } catch (...) {
        delete table;
        delete out;
        throw;
    }
    delete table;
    // OpenSubdiv's weight and index arrays may be allocated longer than the
    // stencils use: keep exactly the used prefix, and check it is there.
    size_t used = 0;
    for (size_t i = 0; i < out->sizes.size(); ++i) {
        size_t end = (size_t)out->offsets[i] + (size_t)out->sizes[i];
        if (out->offsets[i] < 0 || out->sizes[i] < 0 || end > out->indices.size() || end > out->weights.size()) {
            delete out;
            throw ShimError(SDV_ERR_INTERNAL, "inconsistent stencil table from OpenSubdiv");
        }
        if (end > used) used = end;
    }
    out->indices.resize(used);
    out->weights.resize(used);
    return out;
}

sdv_stencils *refined_stencils(const sdv_refiner &rr) {
    Far::TopologyRefiner const &tr = *rr.refiner;
    check_smooth_vertex_masks_all_levels(tr);
    typedef Far::StencilTableFactoryReal<double> Factory;
    Factory::Options o;
    o.interpolationMode = Factory::INTERPOLATE_VERTEX;
    o.generateOffsets = true;
    o.generateIntermediateLevels = false;
    // With no refinement the table is the identity over the base vertices.
    o.generateControlVerts = tr.GetMaxLevel() == 0;
    o.maxLevel = tr.GetMaxLevel();
    return take_table(Factory::Create(tr, o));
}

sdv_stencils *stencils_with(const sdv_refiner &rr, const sdv_stencil_options &so) {
    Far::TopologyRefiner const &tr = *rr.refiner;
    typedef Far::StencilTableFactoryReal<double> Factory;
    if (so.interpolation < 0 || so.interpolation > 2)
        fail("stencil interpolation mode " + str(so.interpolation) + " is not 0..2");
    if (so.max_level < 0 || so.max_level > 15) fail("stencil max level " + str(so.max_level) + " is not 0..15");
    bool fvar = so.interpolation == 2;
    if (fvar) check_channel(&rr, so.fvar_channel);
    int last = std::min((int)so.max_level, tr.GetMaxLevel());
    // copyStencilData jumps back to the builder's first row after the
    // control vertices: an endless loop writing past its arrays.
    if (last > 0 && so.generate_control_verts && !so.generate_intermediate_levels &&
        !so.factorize_intermediate_levels)
        fail_unsafe("control vertices with neither intermediate levels nor factorization: "
                    "OpenSubdiv 3.5 loops and writes out of bounds on it");
    for (int l = 0; l < last; ++l) {
        if (so.interpolation == 0) check_smooth_vertex_masks(tr, l, -1);
        if (fvar) check_smooth_vertex_masks(tr, l, so.fvar_channel);
    }
    Factory::Options o;
    o.interpolationMode = so.interpolation == 0   ? Factory::INTERPOLATE_VERTEX
                          : so.interpolation == 1 ? Factory::INTERPOLATE_VARYING
                                                  : Factory::INTERPOLATE_FACE_VARYING;
    o.generateOffsets = so.generate_offsets != 0;
    o.generateControlVerts = so.generate_control_verts != 0;
    o.generateIntermediateLevels = so.generate_intermediate_levels != 0;
    o.factorizeIntermediateLevels = so.factorize_intermediate_levels != 0;
    o.maxLevel = (unsigned)so.max_level;
    o.fvarChannel = fvar ? (unsigned)so.fvar_channel : 0u;
    return take_table(Factory::Create(tr, o));
}

// Catmull-Clark's smooth masks assert that a vertex has as many edges as
// faces. A vertex named twice by a face can break that and still be smooth
// once semi-sharp features decay: refuse (and undo the refinement) before
// anything interpolates. Vertices without a child (sparse refinement) are
// never interpolated from.
void check_unpaired_smooth_vertices(sdv_refiner &r) {
    if (r.refiner->GetSchemeType() != Sdc::SCHEME_CATMARK) return;
    Far::TopologyRefiner const &tr = *r.refiner;
    for (int l = 0; l < tr.GetMaxLevel(); ++l) {
        Far::TopologyLevel const &p = tr.GetLevel(l), &c = tr.GetLevel(l + 1);
        for (int v = 0; v < p.GetNumVertices(); ++v) {
            if (p.GetVertexFaces(v).size() == p.GetVertexEdges(v).size()) continue;
            Far::Index child = p.GetVertexChildVertex(v);
            if (child < 0) continue;
            Sdc::Crease::Rule pr = p.GetVertexRule(v), cr = c.GetVertexRule(child);
            bool smooth = pr == Sdc::Crease::RULE_SMOOTH || pr == Sdc::Crease::RULE_DART ||
                          cr == Sdc::Crease::RULE_SMOOTH || cr == Sdc::Crease::RULE_DART;
            if (smooth) {
                r.refiner->Unrefine();
                fail("vertex " + str(v) + " of level " + str(l) +
                     " becomes smooth although its faces and edges do not pair up (a face names it "
                     "twice): OpenSubdiv cannot refine it");
            }
        }
    }
}

// An output buffer of at least `n` elements (non-null when n > 0).
template <class B>
void need_buf(const B &b, long long n, const char *what) {
    check_cap(b.cap, n, what);
    if (n > 0 && !b.data) fail(std::string("null output: ") + what);
}

// The level `level` of a refiner, with a next level (child maps).
Far::TopologyLevel const &parent_level_of(const sdv_refiner *r, int32_t level) {
    const sdv_refiner &rr = need(r);
    int max = rr.refiner->GetMaxLevel();
    if (level < 0 || level >= max)
        fail("level " + str(level) + " has no child level (refined levels are 0.." + str(max) + ")");
    return rr.refiner->GetLevel(level);
}

int32_t rule_code(Sdc::Crease::Rule rule) {
    switch (rule) {
        case Sdc::Crease::RULE_SMOOTH: return SDV_RULE_SMOOTH;
        case Sdc::Crease::RULE_DART: return SDV_RULE_DART;
        case Sdc::Crease::RULE_CREASE: return SDV_RULE_CREASE;
        case Sdc::Crease::RULE_CORNER: return SDV_RULE_CORNER;
        default: return SDV_RULE_UNKNOWN;
    }
}

Far::PtexIndices const &ptex_of(const sdv_refiner &rr) {
    std::call_once(rr.ptex_once, [&] { rr.ptex.reset(new Far::PtexIndices(*rr.refiner)); });
    if (!rr.ptex) throw ShimError(SDV_ERR_INTERNAL, "no ptex indices");
    return *rr.ptex;
}

}  // namespace

extern "C" {

const char *sdv_osd_version(void) {
    static const std::string v = std::to_string(OPENSUBDIV_VERSION_MAJOR) + "." +
                                 std::to_string(OPENSUBDIV_VERSION_MINOR) + "." +
                                 std::to_string(OPENSUBDIV_VERSION_PATCH);
    return v.c_str();
}

int32_t sdv_osd_version_number(void) { return OPENSUBDIV_VERSION_NUMBER; }

int sdv_refiner_create(const sdv_mesh_desc *desc, const sdv_options *opts, sdv_refiner **out, char *err,
                       size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!desc || !opts || !out) fail("null argument");
        *out = nullptr;
        validate(*desc, *opts);
        install_callbacks();

        Far::TopologyDescriptor d;
        d.numVertices = desc->num_vertices;
        d.numFaces = desc->num_faces;
        d.numVertsPerFace = desc->face_sizes;
        d.vertIndicesPerFace = desc->face_vertices;
        d.numCreases = desc->num_creases;
        d.creaseVertexIndexPairs = desc->crease_vertex_pairs;
        d.creaseWeights = desc->crease_sharpness;
        d.numCorners = desc->num_corners;
        d.cornerVertexIndices = desc->corner_vertices;
        d.cornerWeights = desc->corner_sharpness;
        d.numHoles = desc->num_holes;
        d.holeIndices = desc->holes;
        std::vector<Far::TopologyDescriptor::FVarChannel> channels(desc->num_fvar_channels);
        for (int c = 0; c < desc->num_fvar_channels; ++c) {
            channels[c].numValues = desc->fvar_channels[c].num_values;
            channels[c].valueIndices = desc->fvar_channels[c].value_indices;
        }
        d.numFVarChannels = desc->num_fvar_channels;
        d.fvarChannels = channels.empty() ? nullptr : channels.data();
        d.isLeftHanded = desc->is_left_handed != 0;

        Sdc::Options so;
        so.SetVtxBoundaryInterpolation((Sdc::Options::VtxBoundaryInterpolation)opts->boundary);
        so.SetFVarLinearInterpolation((Sdc::Options::FVarLinearInterpolation)opts->fvar);
        so.SetCreasingMethod((Sdc::Options::CreasingMethod)opts->creasing);
        so.SetTriangleSubdivision((Sdc::Options::TriangleSubdivision)opts->triangles);
        Sdc::SchemeType scheme = opts->scheme == 0   ? Sdc::SCHEME_BILINEAR
                                 : opts->scheme == 1 ? Sdc::SCHEME_CATMARK
                                                     : Sdc::SCHEME_LOOP;
        typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;

        t_osd_errors.clear();
        t_osd_warnings.clear();
        Far::TopologyRefiner *tr = Factory::Create(d, Factory::Options(scheme, so));
        if (!tr) {
            throw ShimError(SDV_ERR_OSD, "could not create the refiner: " +
                                             (t_osd_errors.empty() ? std::string("no reason given") : t_osd_errors));
        }
        // OpenSubdiv's smooth masks assume a smooth vertex has as many edges as
        // faces; a face naming a vertex twice can break that without making
        // anything non-manifold, and its assertion then aborts the process.
        Far::TopologyLevel const &base = tr->GetLevel(0);
        for (int v = 0; v < base.GetNumVertices(); ++v) {
            Sdc::Crease::Rule rule = base.GetVertexRule(v);
            if ((rule == Sdc::Crease::RULE_SMOOTH || rule == Sdc::Crease::RULE_DART) &&
                base.GetVertexFaces(v).size() != base.GetVertexEdges(v).size()) {
                std::string msg = "vertex " + str(v) + " has " + str(base.GetVertexFaces(v).size()) + " faces and " +
                                  str(base.GetVertexEdges(v).size()) +
                                  " edges but no sharp feature: OpenSubdiv cannot refine a smooth vertex whose faces "
                                  "and edges do not pair up (a face names it twice)";
                delete tr;
                fail(msg);
            }
        }
        auto *r = new (std::nothrow) sdv_refiner();
        if (!r) {
            delete tr;
            throw std::bad_alloc();
        }
        r->refiner = tr;
        r->warnings = t_osd_warnings;
        if (!t_osd_errors.empty()) {
            if (!r->warnings.empty()) r->warnings += "\n";
            r->warnings += t_osd_errors;
        }
        *out = r;
    });
}

void sdv_refiner_destroy(sdv_refiner *r) { delete r; }

int sdv_refiner_warnings(const sdv_refiner *r, char *buf, size_t buf_len, size_t *needed) {
    return guarded(nullptr, 0, [&] {
        const sdv_refiner &rr = need(r);
        if (needed) *needed = rr.warnings.size() + 1;
        if (buf && buf_len) write_err(buf, buf_len, rr.warnings.c_str());
    });
}

int sdv_refiner_refine_uniform(sdv_refiner *r, int32_t level, int32_t faces_first, int32_t full_topology,
                               char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!r || !r->refiner) fail("null refiner");
        // The level is a 4-bit field in OpenSubdiv: check it here, never let it wrap.
        if (level < 0 || level > 10) fail("refinement level " + str(level) + " is not in 0..10");
        t_osd_errors.clear();
        if (r->refiner->GetMaxLevel() > 0) r->refiner->Unrefine();
        r->full_topology_last_level = true;
        if (level == 0) return;
        Far::TopologyRefiner::UniformOptions uo(level);
        uo.orderVerticesFromFacesFirst = faces_first != 0;
        uo.fullTopologyInLastLevel = full_topology != 0;
        r->refiner->RefineUniform(uo);
        if (!t_osd_errors.empty()) throw ShimError(SDV_ERR_OSD, t_osd_errors);
        check_unpaired_smooth_vertices(*r);
        r->full_topology_last_level = full_topology != 0;
    });
}

int sdv_refiner_refine_adaptive(sdv_refiner *r, const sdv_adaptive_options *opts, const int32_t *faces,
                                size_t num_faces, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!r || !r->refiner) fail("null refiner");
        if (!opts) fail("null adaptive options");
        // OpenSubdiv reports this through its error callback and returns.
        if (r->refiner->GetMaxLevel() > 0)
            fail("the refiner is already refined (to level " + str(r->refiner->GetMaxLevel()) +
                 "): OpenSubdiv refines a refiner once");
        // Both levels are 4-bit fields in OpenSubdiv: never let them wrap.
        if (opts->isolation_level < 0 || opts->isolation_level > 10)
            fail("isolation level " + str(opts->isolation_level) + " is not in 0..10");
        if (opts->secondary_level < 0 || opts->secondary_level > 15)
            fail("secondary level " + str(opts->secondary_level) + " is not in 0..15");
        if (num_faces > 0 && !faces) fail("null face list");
        const int n = r->refiner->GetLevel(0).GetNumFaces();
        if (num_faces > (size_t)std::numeric_limits<int>::max()) fail("more than 2^31-1 selected faces");
        for (size_t i = 0; i < num_faces; ++i) {
            if (faces[i] < 0 || faces[i] >= n)
                fail("selected face " + str(faces[i]) + " (entry " + str((long long)i) + ") is out of range (" +
                     str(n) + " faces)");
        }
        Far::TopologyRefiner::AdaptiveOptions ao(opts->isolation_level);
        ao.SetSecondaryLevel(opts->secondary_level);
        ao.useSingleCreasePatch = opts->single_crease_patch != 0;
        ao.useInfSharpPatch = opts->inf_sharp_patch != 0;
        ao.considerFVarChannels = opts->consider_fvar_channels != 0;
        ao.orderVerticesFromFacesFirst = opts->faces_first != 0;
        t_osd_errors.clear();
        r->full_topology_last_level = true;
        r->refiner->RefineAdaptive(ao, Far::ConstIndexArray(faces, (int)num_faces));
        if (!t_osd_errors.empty()) {
            r->refiner->Unrefine();
            throw ShimError(SDV_ERR_OSD, t_osd_errors);
        }
        check_unpaired_smooth_vertices(*r);
        r->adaptive_faces.assign(num_faces ? (size_t)n : 0, false);
        for (size_t i = 0; i < num_faces; ++i) r->adaptive_faces[(size_t)faces[i]] = true;
    });
}

int32_t sdv_refiner_max_level(const sdv_refiner *r) {
    return (r && r->refiner) ? r->refiner->GetMaxLevel() : -1;
}

int32_t sdv_refiner_num_fvar_channels(const sdv_refiner *r) {
    return (r && r->refiner) ? r->refiner->GetNumFVarChannels() : -1;
}

int sdv_level_counts_get(const sdv_refiner *r, int32_t level, sdv_level_counts *out, char *err,
                         size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Far::TopologyLevel const &l = level_of(r, level);
        out->vertices = l.GetNumVertices();
        out->edges = l.GetNumEdges();
        out->faces = l.GetNumFaces();
        out->face_vertices = l.GetNumFaceVertices();
        out->full_topology = has_full_topology(r, level) ? 1 : 0;
    });
}

int sdv_level_faces(const sdv_refiner *r, int32_t level, int32_t *sizes, size_t sizes_cap, int32_t *verts,
                    size_t verts_cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_cap(sizes_cap, l.GetNumFaces(), "face sizes");
        check_cap(verts_cap, l.GetNumFaceVertices(), "face vertices");
        if ((l.GetNumFaces() && !sizes) || (l.GetNumFaceVertices() && !verts)) fail("null output");
        size_t k = 0;
        for (int f = 0; f < l.GetNumFaces(); ++f) {
            Far::ConstIndexArray fv = l.GetFaceVertices(f);
            sizes[f] = fv.size();
            if (k + (size_t)fv.size() > verts_cap) throw ShimError(SDV_ERR_CAPACITY, "face vertices overflow");
            for (int j = 0; j < fv.size(); ++j) verts[k++] = fv[j];
        }
    });
}

int sdv_level_edge_vertices(const sdv_refiner *r, int32_t level, int32_t *out, size_t cap, char *err,
                            size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        need_full_topology(r, level, "edge vertices");
        check_cap(cap, 2LL * l.GetNumEdges(), "edge vertices");
        for (int e = 0; e < l.GetNumEdges(); ++e) {
            Far::ConstIndexArray ev = l.GetEdgeVertices(e);
            out[2 * e] = ev[0];
            out[2 * e + 1] = ev[1];
        }
    });
}

int sdv_level_edge_sharpness(const sdv_refiner *r, int32_t level, float *out, size_t cap, char *err,
                             size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_cap(cap, l.GetNumEdges(), "edge sharpness");
        for (int e = 0; e < l.GetNumEdges(); ++e) out[e] = l.GetEdgeSharpness(e);
    });
}

int sdv_level_vertex_sharpness(const sdv_refiner *r, int32_t level, float *out, size_t cap, char *err,
                               size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_cap(cap, l.GetNumVertices(), "vertex sharpness");
        for (int v = 0; v < l.GetNumVertices(); ++v) out[v] = l.GetVertexSharpness(v);
    });
}

int sdv_level_face_holes(const sdv_refiner *r, int32_t level, uint8_t *out, size_t cap, char *err,
                         size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_cap(cap, l.GetNumFaces(), "face holes");
        for (int f = 0; f < l.GetNumFaces(); ++f) out[f] = l.IsFaceHole(f) ? 1 : 0;
    });
}

int sdv_level_fvar_value_count(const sdv_refiner *r, int32_t level, int32_t channel, int32_t *out, char *err,
                               size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_channel(r, channel);
        if (!out) fail("null output");
        *out = l.GetNumFVarValues(channel);
    });
}

int sdv_level_fvar_face_values(const sdv_refiner *r, int32_t level, int32_t channel, int32_t *out, size_t cap,
                               char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::TopologyLevel const &l = level_of(r, level);
        check_channel(r, channel);
        check_cap(cap, l.GetNumFaceVertices(), "face-varying values");
        size_t k = 0;
        for (int f = 0; f < l.GetNumFaces(); ++f) {
            Far::ConstIndexArray fv = l.GetFaceFVarValues(f, channel);
            if (k + (size_t)fv.size() > cap) throw ShimError(SDV_ERR_CAPACITY, "face-varying values overflow");
            for (int j = 0; j < fv.size(); ++j) out[k++] = fv[j];
        }
    });
}

int sdv_interpolate_f32(const sdv_refiner *r, int32_t kind, int32_t channel, int32_t level, int32_t width,
                        const float *src, size_t src_len, float *dst, size_t dst_len, char *err,
                        size_t err_len) {
    return guarded(err, err_len, [&] { interpolate<float>(r, kind, channel, level, width, src, src_len, dst, dst_len); });
}

int sdv_interpolate_f64(const sdv_refiner *r, int32_t kind, int32_t channel, int32_t level, int32_t width,
                        const double *src, size_t src_len, double *dst, size_t dst_len, char *err,
                        size_t err_len) {
    return guarded(err, err_len, [&] { interpolate<double>(r, kind, channel, level, width, src, src_len, dst, dst_len); });
}

int sdv_limit_f32(const sdv_refiner *r, int32_t width, const float *src, size_t src_len, float *pos, float *tan1,
                  float *tan2, size_t dst_len, char *err, size_t err_len) {
    return guarded(err, err_len, [&] { limit<float>(r, width, src, src_len, pos, tan1, tan2, dst_len); });
}

int sdv_limit_f64(const sdv_refiner *r, int32_t width, const double *src, size_t src_len, double *pos,
                  double *tan1, double *tan2, size_t dst_len, char *err, size_t err_len) {
    return guarded(err, err_len, [&] { limit<double>(r, width, src, src_len, pos, tan1, tan2, dst_len); });
}

int sdv_limit_fvar_f32(const sdv_refiner *r, int32_t channel, int32_t width, const float *src, size_t src_len,
                       float *dst, size_t dst_len, char *err, size_t err_len) {
    return guarded(err, err_len, [&] { limit_fvar<float>(r, channel, width, src, src_len, dst, dst_len); });
}

int sdv_limit_fvar_f64(const sdv_refiner *r, int32_t channel, int32_t width, const double *src, size_t src_len,
                       double *dst, size_t dst_len, char *err, size_t err_len) {
    return guarded(err, err_len, [&] { limit_fvar<double>(r, channel, width, src, src_len, dst, dst_len); });
}

int sdv_stencils_create(const sdv_refiner *r, int32_t kind, sdv_stencils **out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        const sdv_refiner &rr = need(r);
        if (kind == SDV_STENCIL_REFINED)
            *out = refined_stencils(rr);
        else if (kind == SDV_STENCIL_LIMIT)
            *out = limit_stencils(rr);
        else
            fail("unknown stencil kind " + str(kind));
    });
}

int sdv_stencils_create_with(const sdv_refiner *r, const sdv_stencil_options *o, sdv_stencils **out,
                             char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out || !o) fail("null argument");
        *out = nullptr;
        *out = stencils_with(need(r), *o);
    });
}

void sdv_stencils_destroy(sdv_stencils *s) { delete s; }

void sdv_stencils_size(const sdv_stencils *s, size_t *rows, size_t *nnz) {
    if (rows) *rows = s ? s->sizes.size() : 0;
    if (nnz) *nnz = s ? s->indices.size() : 0;
}

int sdv_stencils_export(const sdv_stencils *s, int32_t *sizes, int32_t *offsets, int32_t *indices,
                        double *weights, size_t rows_cap, size_t nnz_cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!s) fail("null stencil table");
        check_cap(rows_cap, (long long)s->sizes.size(), "stencil rows");
        check_cap(nnz_cap, (long long)s->indices.size(), "stencil weights");
        if (s->weights.size() != s->indices.size() || s->offsets.size() != s->sizes.size())
            throw ShimError(SDV_ERR_INTERNAL, "inconsistent stencil table");
        if (!s->sizes.empty() && (!sizes || !offsets)) fail("null output");
        if (!s->indices.empty() && (!indices || !weights)) fail("null output");
        std::copy(s->sizes.begin(), s->sizes.end(), sizes);
        std::copy(s->offsets.begin(), s->offsets.end(), offsets);
        std::copy(s->indices.begin(), s->indices.end(), indices);
        std::copy(s->weights.begin(), s->weights.begin() + s->indices.size(), weights);
    });
}

int sdv_evaluator_create(const sdv_refiner *r, sdv_evaluator **out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        const sdv_refiner &rr = need(r);
        Far::TopologyRefiner const &tr = *rr.refiner;
        Far::StencilTableFactory::Options o;
        o.interpolationMode = Far::StencilTableFactory::INTERPOLATE_VERTEX;
        o.generateOffsets = true;
        o.generateIntermediateLevels = false;
        o.generateControlVerts = tr.GetMaxLevel() == 0;
        o.maxLevel = tr.GetMaxLevel();
        Far::StencilTable const *table = Far::StencilTableFactory::Create(tr, o);
        if (!table) fail("StencilTableFactory::Create failed");
        auto *e = new (std::nothrow) sdv_evaluator();
        if (!e) {
            delete table;
            throw std::bad_alloc();
        }
        e->table = table;
        e->controls = tr.GetLevel(0).GetNumVertices();
        *out = e;
    });
}

void sdv_evaluator_destroy(sdv_evaluator *e) { delete e; }

void sdv_evaluator_counts(const sdv_evaluator *e, int32_t *controls, int32_t *stencils) {
    if (controls) *controls = e ? e->controls : 0;
    if (stencils) *stencils = (e && e->table) ? e->table->GetNumStencils() : 0;
}

int sdv_evaluator_eval_f32(const sdv_evaluator *e, int32_t width, const float *src, size_t src_len, float *dst,
                           size_t dst_len, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!e || !e->table) fail("null evaluator");
        if (width < 1) fail("primvar width must be at least 1");
        int n = e->table->GetNumStencils();
        check_len(src_len, (long long)e->controls * width, "source primvar buffer");
        check_len(dst_len, (long long)n * width, "destination primvar buffer");
        if (n == 0) return;
        if (!src || !dst) fail("null primvar buffer");
        Osd::BufferDescriptor sd(0, width, width), dd(0, width, width);
        bool ok = Osd::CpuEvaluator::EvalStencils(src, sd, dst, dd, &e->table->GetSizes()[0],
                                                  &e->table->GetOffsets()[0], &e->table->GetControlIndices()[0],
                                                  &e->table->GetWeights()[0], 0, n);
        if (!ok) throw ShimError(SDV_ERR_OSD, "Osd::CpuEvaluator::EvalStencils failed");
    });
}

int sdv_level_child_sizes(const sdv_refiner *r, int32_t level, int32_t *face_child_faces,
                          int32_t *face_child_edges, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!face_child_faces || !face_child_edges) fail("null output");
        Far::TopologyLevel const &l = parent_level_of(r, level);
        long long faces = 0, edges = 0;
        for (int f = 0; f < l.GetNumFaces(); ++f) {
            faces += l.GetFaceChildFaces(f).size();
            edges += l.GetFaceChildEdges(f).size();
        }
        if (faces > std::numeric_limits<int32_t>::max() || edges > std::numeric_limits<int32_t>::max())
            fail("more than 2^31-1 child faces or edges");
        *face_child_faces = (int32_t)faces;
        *face_child_edges = (int32_t)edges;
    });
}

int sdv_level_child_maps(const sdv_refiner *r, int32_t level, const sdv_child_maps *out, char *err,
                         size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Far::TopologyLevel const &l = parent_level_of(r, level);
        Far::TopologyLevel const &c = r->refiner->GetLevel(level + 1);
        const int nf = l.GetNumFaces(), ne = l.GetNumEdges(), nv = l.GetNumVertices();
        need_buf(out->face_child_face_counts, nf, "face child face counts");
        need_buf(out->face_child_edge_counts, nf, "face child edge counts");
        need_buf(out->edge_child_edges, 2LL * ne, "edge child edges");
        need_buf(out->face_child_vertex, nf, "face child vertices");
        need_buf(out->edge_child_vertex, ne, "edge child vertices");
        need_buf(out->vertex_child_vertex, nv, "vertex child vertices");
        need_buf(out->child_face_parent_face, c.GetNumFaces(), "child face parent faces");
        // Loop's split has no face child vertex: OpenSubdiv keeps no table for
        // them, and GetFaceChildVertex would read past an empty vector.
        const bool face_vertices = r->refiner->GetSchemeType() != Sdc::SCHEME_LOOP;
        size_t kf = 0, ke = 0;
        for (int f = 0; f < nf; ++f) {
            Far::ConstIndexArray cf = l.GetFaceChildFaces(f), ce = l.GetFaceChildEdges(f);
            check_cap(out->face_child_faces.cap, (long long)(kf + cf.size()), "face child faces");
            check_cap(out->face_child_edges.cap, (long long)(ke + ce.size()), "face child edges");
            out->face_child_face_counts.data[f] = cf.size();
            out->face_child_edge_counts.data[f] = ce.size();
            for (int i = 0; i < cf.size(); ++i) out->face_child_faces.data[kf++] = cf[i];
            for (int i = 0; i < ce.size(); ++i) out->face_child_edges.data[ke++] = ce[i];
            out->face_child_vertex.data[f] = face_vertices ? l.GetFaceChildVertex(f) : -1;
        }
        for (int e = 0; e < ne; ++e) {
            Far::ConstIndexArray ce = l.GetEdgeChildEdges(e);
            out->edge_child_edges.data[2 * e] = ce[0];
            out->edge_child_edges.data[2 * e + 1] = ce[1];
            out->edge_child_vertex.data[e] = l.GetEdgeChildVertex(e);
        }
        for (int v = 0; v < nv; ++v) out->vertex_child_vertex.data[v] = l.GetVertexChildVertex(v);
        for (int f = 0; f < c.GetNumFaces(); ++f) out->child_face_parent_face.data[f] = c.GetFaceParentFace(f);
    });
}

int sdv_level_relation_sizes(const sdv_refiner *r, int32_t level, int32_t *edge_faces, int32_t *vertex_faces,
                             int32_t *vertex_edges, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!edge_faces || !vertex_faces || !vertex_edges) fail("null output");
        Far::TopologyLevel const &l = level_of(r, level);
        need_full_topology(r, level, "relations");
        long long ef = 0, vf = 0, ve = 0;
        for (int e = 0; e < l.GetNumEdges(); ++e) ef += l.GetEdgeFaces(e).size();
        for (int v = 0; v < l.GetNumVertices(); ++v) {
            vf += l.GetVertexFaces(v).size();
            ve += l.GetVertexEdges(v).size();
        }
        const long long big = std::numeric_limits<int32_t>::max();
        if (ef > big || vf > big || ve > big) fail("more than 2^31-1 relation entries");
        *edge_faces = (int32_t)ef;
        *vertex_faces = (int32_t)vf;
        *vertex_edges = (int32_t)ve;
    });
}

int sdv_level_relations(const sdv_refiner *r, int32_t level, const sdv_relations *out, char *err,
                        size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Far::TopologyLevel const &l = level_of(r, level);
        need_full_topology(r, level, "relations");
        const int nf = l.GetNumFaces(), ne = l.GetNumEdges(), nv = l.GetNumVertices();
        need_buf(out->face_edges, l.GetNumFaceVertices(), "face edges");
        need_buf(out->edge_face_counts, ne, "edge face counts");
        need_buf(out->vertex_face_counts, nv, "vertex face counts");
        need_buf(out->vertex_edge_counts, nv, "vertex edge counts");
        need_buf(out->vertex_rule, nv, "vertex rules");
        need_buf(out->vertex_flags, nv, "vertex flags");
        need_buf(out->edge_flags, ne, "edge flags");
        size_t k = 0;
        for (int f = 0; f < nf; ++f) {
            Far::ConstIndexArray fe = l.GetFaceEdges(f);
            check_cap(out->face_edges.cap, (long long)(k + fe.size()), "face edges");
            for (int i = 0; i < fe.size(); ++i) out->face_edges.data[k++] = fe[i];
        }
        k = 0;
        for (int e = 0; e < ne; ++e) {
            Far::ConstIndexArray ef = l.GetEdgeFaces(e);
            Far::ConstLocalIndexArray loc = l.GetEdgeFaceLocalIndices(e);
            need_buf(out->edge_faces, (long long)(k + ef.size()), "edge faces");
            need_buf(out->edge_face_local, (long long)(k + ef.size()), "edge face local indices");
            out->edge_face_counts.data[e] = ef.size();
            for (int i = 0; i < ef.size(); ++i, ++k) {
                out->edge_faces.data[k] = ef[i];
                out->edge_face_local.data[k] = loc[i];
            }
            out->edge_flags.data[e] = (uint8_t)((l.IsEdgeNonManifold(e) ? SDV_EDGE_NON_MANIFOLD : 0) |
                                                (l.IsEdgeBoundary(e) ? SDV_EDGE_BOUNDARY : 0) |
                                                (l.IsEdgeInfSharp(e) ? SDV_EDGE_INF_SHARP : 0) |
                                                (l.IsEdgeSemiSharp(e) ? SDV_EDGE_SEMI_SHARP : 0));
        }
        size_t kf = 0, ke = 0;
        for (int v = 0; v < nv; ++v) {
            Far::ConstIndexArray vf = l.GetVertexFaces(v), ve = l.GetVertexEdges(v);
            Far::ConstLocalIndexArray vfl = l.GetVertexFaceLocalIndices(v), vel = l.GetVertexEdgeLocalIndices(v);
            need_buf(out->vertex_faces, (long long)(kf + vf.size()), "vertex faces");
            need_buf(out->vertex_face_local, (long long)(kf + vf.size()), "vertex face local indices");
            need_buf(out->vertex_edges, (long long)(ke + ve.size()), "vertex edges");
            need_buf(out->vertex_edge_local, (long long)(ke + ve.size()), "vertex edge local indices");
            out->vertex_face_counts.data[v] = vf.size();
            out->vertex_edge_counts.data[v] = ve.size();
            for (int i = 0; i < vf.size(); ++i, ++kf) {
                out->vertex_faces.data[kf] = vf[i];
                out->vertex_face_local.data[kf] = vfl[i];
            }
            for (int i = 0; i < ve.size(); ++i, ++ke) {
                out->vertex_edges.data[ke] = ve[i];
                out->vertex_edge_local.data[ke] = vel[i];
            }
            out->vertex_rule.data[v] = rule_code(l.GetVertexRule(v));
            out->vertex_flags.data[v] = (uint8_t)((l.IsVertexBoundary(v) ? SDV_VTX_BOUNDARY : 0) |
                                                  (l.IsVertexCorner(v) ? SDV_VTX_CORNER : 0) |
                                                  (l.IsVertexValenceRegular(v) ? SDV_VTX_VALENCE_REGULAR : 0) |
                                                  (l.IsVertexNonManifold(v) ? SDV_VTX_NON_MANIFOLD : 0) |
                                                  (l.IsVertexInfSharp(v) ? SDV_VTX_INF_SHARP : 0) |
                                                  (l.IsVertexSemiSharp(v) ? SDV_VTX_SEMI_SHARP : 0));
        }
    });
}

int sdv_ptex_face_ids(const sdv_refiner *r, int32_t *ids, size_t cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_refiner &rr = need(r);
        const int nf = rr.refiner->GetLevel(0).GetNumFaces();
        check_cap(cap, nf + 1LL, "ptex face ids");
        if (!ids) fail("null output");
        Far::PtexIndices const &p = ptex_of(rr);
        for (int f = 0; f < nf; ++f) ids[f] = p.GetFaceId(f);
        ids[nf] = p.GetNumFaces();
    });
}

int sdv_ptex_adjacency(const sdv_refiner *r, int32_t face, int32_t quadrant, int32_t adj_faces[4],
                       int32_t adj_edges[4], char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_refiner &rr = need(r);
        if (!adj_faces || !adj_edges) fail("null output");
        Far::TopologyLevel const &base = rr.refiner->GetLevel(0);
        if (face < 0 || face >= base.GetNumFaces())
            fail("face " + str(face) + " is out of range (" + str(base.GetNumFaces()) + " faces)");
        const int n = base.GetFaceVertices(face).size();
        const int regular = Sdc::SchemeTypeTraits::GetRegularFaceSize(rr.refiner->GetSchemeType());
        // OpenSubdiv asserts the quadrant (and reads past the face's edges in
        // a release build); it supports irregular faces under quad schemes only.
        if (n != regular && regular != 4) fail("irregular faces have ptex sub-faces only under quad schemes");
        const int quadrants = n == regular ? 1 : n;
        if (quadrant < 0 || quadrant >= quadrants)
            fail("quadrant " + str(quadrant) + " of face " + str(face) + " is out of range (the face has " +
                 str(quadrants) + " ptex faces)");
        Far::PtexIndices const &p = ptex_of(rr);
        int faces[4] = {-1, -1, -1, -1}, edges[4] = {0, 0, 0, 0};
        t_osd_errors.clear();
        p.GetAdjacency(*rr.refiner, face, quadrant, faces, edges);
        if (!t_osd_errors.empty()) throw ShimError(SDV_ERR_OSD, t_osd_errors);
        for (int i = 0; i < 4; ++i) {
            adj_faces[i] = faces[i];
            adj_edges[i] = edges[i];
        }
    });
}

}  // extern "C"
