// subdiv shim, patch tables: Far::PatchTableFactory, Far::PatchTable and
// Far::PatchMap behind the C ABI of cpp/shim.h. As everywhere in the shim,
// every entry point catches every exception, and every input that would make
// OpenSubdiv read out of bounds, assert or loop is refused before it sees it.

#include "internal.h"

#include <opensubdiv/far/patchDescriptor.h>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTable.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

namespace sdv_internal {

// Whether corner `i` of `face` is, as Bfr and Far's patch builder see it,
// an interior corner of valence 2: both of the face's edges at the corner
// are shared with one and the same other face and with no third, so the
// corner's fan is that pair of faces, closed (two faces folded onto each
// other there). A manifold interior vertex of two faces is one whatever
// its edges.
bool is_valence2_corner(Far::TopologyLevel const &base, int face, int i) {
    Far::ConstIndexArray fv = base.GetFaceVertices(face);
    Far::ConstIndexArray fe = base.GetFaceEdges(face);
    int n = fv.size();
    Far::Index v = fv[i];
    if (!base.IsVertexNonManifold(v) && !base.IsVertexBoundary(v) && base.GetVertexFaces(v).size() == 2) return true;
    Far::ConstIndexArray lead = base.GetEdgeFaces(fe[i]);
    Far::ConstIndexArray trail = base.GetEdgeFaces(fe[(i + n - 1) % n]);
    if (lead.size() != 2 || trail.size() != 2) return false;
    Far::Index a = lead[0] == face ? lead[1] : lead[0];
    Far::Index b = trail[0] == face ? trail[1] : trail[0];
    return a == b && a != face;
}

// Next to an interior corner of valence 2, Far::SourcePatch can count a
// neighbouring corner's ring one point short (where that corner's span
// stops at an infinitely sharp edge, a boundary or a seam), and a ring then
// names a point past the patch's count: PatchBuilder::
// GetIrregularPatchSourcePoints writes it there. PatchTableFactory gathers
// the points into a StackBuffer of 64 inline entries sized to the count:
// beyond 63 points the buffer is on the heap and the write is out of bounds
// (Valgrind: a 40-gon beside an infinitely sharp dart of valence 2, one
// level of isolation). Refused, conservatively, wherever a patch with such
// a corner may have 64 points or more: the face itself (a patch of the base
// level when it is a quad or triangle: four points and each corner's ring,
// at most 2 * faces + 1) or its child at the corner (the corner, two edge
// children of four faces and the face's centre of as many faces as the
// face has vertices). Deeper patches there have small rings throughout.
void check_valence2_source_points(Far::TopologyRefiner const &tr) {
    const int inline_points = 64;
    Far::TopologyLevel const &base = tr.GetLevel(0);
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        int n = fv.size();
        int corner = -1;
        for (int i = 0; i < n && corner < 0; ++i)
            if (is_valence2_corner(base, f, i)) corner = i;
        if (corner < 0) continue;
        long long at_base = 4;
        for (int i = 0; i < n; ++i) at_base += 2LL * base.GetVertexFaces(fv[i]).size() + 1;
        long long child = 4 + 5 + 9 + 9 + 2LL * n + 1;
        long long bound = std::max(n <= 4 ? at_base : 0, child);
        if (bound >= inline_points)
            fail_unsafe("face " + str(f) + ": its corner vertex " + str(fv[corner]) +
                        " is an interior vertex of valence 2 (two faces folded onto each other) and a patch there "
                        "may gather up to " + str(bound) + " source points: OpenSubdiv's patch builder can write "
                        "one past them, out of bounds beyond 63");
    }
}

// OpenSubdiv's patch builders assume faces without repeated vertices: on a
// face that uses a vertex twice, the B-spline end-cap converter writes out
// of bounds and the legacy Gregory tables read and write past their
// vectors (found by fuzzing under Valgrind).
void check_no_repeated_vertices(Far::TopologyLevel const &base) {
    std::vector<Far::Index> verts;
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        verts.assign(fv.begin(), fv.end());
        std::sort(verts.begin(), verts.end());
        auto dup = std::adjacent_find(verts.begin(), verts.end());
        if (dup != verts.end())
            fail_unsafe("face " + str(f) + " uses vertex " + str(*dup) +
                        " more than once: OpenSubdiv's patch tables read and write out of bounds on such faces");
    }
}

// Loop end caps (every type) gather a triangle's source points corner by
// corner; at a corner of two faces whose previous corner is an interior
// vertex of valence 2 the patch's ring is one point longer than the ring
// gathered from the level, and OpenSubdiv reads that point from
// uninitialised memory (found by the adaptive_differential fuzz target: a
// local-point stencil naming vertex 941292184, and LimitStencilTableFactory
// reading out of bounds through it). Two such corners share a face only in
// two triangles folded onto each other, in the base level (refinement
// separates them): refused while such a face is left unrefined.
void check_loop_folded_triangles(Far::TopologyRefiner const &tr) {
    if (tr.GetSchemeType() != Sdc::SCHEME_LOOP || tr.IsUniform()) return;
    Far::TopologyLevel const &base = tr.GetLevel(0);
    auto folded = [&](Far::Index v) {
        return base.GetVertexEdges(v).size() == 2 && base.GetVertexFaces(v).size() == 2 &&
               !base.IsVertexBoundary(v);
    };
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        int count = 0;
        for (int k = 0; k < fv.size(); ++k) count += folded(fv[k]) ? 1 : 0;
        if (count < 2) continue;
        bool refined = tr.GetMaxLevel() > 0 && base.GetFaceChildFaces(f).size() > 0 &&
                       Far::IndexIsValid(base.GetFaceChildFaces(f)[0]);
        if (!refined)
            fail_unsafe("Loop end caps are not available on base face " + str(f) +
                        ", left unrefined with two interior vertices of valence 2 (OpenSubdiv reads its source "
                        "points from uninitialised memory there)");
    }
}

void check_unit(double x, const char *name) {
    if (!std::isfinite(x) || x < 0.0 || x > 1.0) fail(std::string(name) + " " + std::to_string(x) + " is not in [0, 1]");
}

}  // namespace sdv_internal

namespace sdv_internal {

// The table's PatchMap, which a uniform table of every level does not have.
Far::PatchMap const &need_map(sdv_patches const &p) {
    if (!p.map)
        fail_unsafe("this table holds every refined level, whose patches overlap: OpenSubdiv's PatchMap "
                    "writes out of bounds on it, so it has none (build the table of the last level)");
    return *p.map;
}

const sdv_patches &need_patches(const sdv_patches *p) {
    if (!p || !p->table) fail("null patch table");
    return *p;
}

bool evaluable(Far::PatchDescriptor::Type t) {
    switch (t) {
        case Far::PatchDescriptor::REGULAR:
        case Far::PatchDescriptor::LOOP:
        case Far::PatchDescriptor::GREGORY_BASIS:
        case Far::PatchDescriptor::GREGORY_TRIANGLE:
        case Far::PatchDescriptor::QUADS:
        case Far::PatchDescriptor::TRIANGLES:
            return true;
        default:
            return false;
    }
}

void check_evaluation(Far::PatchTable const &t, EvaluationInputs const &in, const char *evaluator) {
    if (in.width <= 0) fail("width " + str(in.width) + " is not positive");
    if (in.n > 0 && (!in.faces || !in.us || !in.vs || !in.outputs[0])) fail("null argument");
    const void *const *o = in.outputs;
    if ((o[1] == nullptr) != (o[2] == nullptr)) fail("first derivatives come in pairs");
    if ((o[3] == nullptr) != (o[4] == nullptr) || (o[3] == nullptr) != (o[5] == nullptr))
        fail("second derivatives come in threes");
    if (o[3] && !o[1]) fail("second derivatives need the first");
    if (in.num_points > 0 && !in.points) fail("null points");
    for (int a = 0; a < t.GetNumPatchArrays(); ++a)
        if (t.GetNumPatches(a) > 0 && !evaluable(t.GetPatchArrayDescriptor(a).GetType()))
            fail("patches of type " + str((int)t.GetPatchArrayDescriptor(a).GetType()) + " cannot be evaluated (" +
                 evaluator + " has no basis for them)");
    for (Far::Index cv : t.GetPatchControlVerticesTable())
        if (cv < 0 || (size_t)cv >= in.num_points)
            fail("a patch names point " + str(cv) + ", beyond the " + str((long long)in.num_points) + " given");
}

Far::PatchTable::PatchHandle const *location_patch(sdv_patches const &p, EvaluationInputs const &in, size_t i) {
    int ptex = p.table->GetNumPtexFaces();
    if (in.faces[i] < 0 || in.faces[i] >= ptex)
        fail("location " + str((long long)i) + ": ptex face " + str(in.faces[i]) + " does not exist (" + str(ptex) +
             " ptex faces)");
    check_unit(in.us[i], "u");
    check_unit(in.vs[i], "v");
    Far::PatchTable::PatchHandle const *h = need_map(p).FindPatch(in.faces[i], in.us[i], in.vs[i]);
    if (!h) fail("location " + str((long long)i) + " is in a hole");
    return h;
}

}  // namespace sdv_internal

namespace {

bool flag(int32_t v, const char *name) {
    if (v != 0 && v != 1) fail(std::string("patch option ") + name + " is " + str(v) + ", not 0 or 1");
    return v != 0;
}

Far::PatchTableFactory::Options factory_options(const sdv_patch_options &o) {
    if (o.end_cap_type < 0 || o.end_cap_type > 4) fail("end-cap type " + str(o.end_cap_type) + " is not 0..4");
    // The field is 4 bits wide: 11..15 would be taken as they are, 16 and
    // more wrap; OpenSubdiv isolates 10 levels at most.
    if (o.max_isolation_level < 0 || o.max_isolation_level > 10)
        fail("maximum isolation level " + str(o.max_isolation_level) + " is not 0..10");
    Far::PatchTableFactory::Options f(o.max_isolation_level);
    f.endCapType = (unsigned)o.end_cap_type;
    f.shareEndCapPatchPoints = flag(o.share_end_cap_patch_points, "shareEndCapPatchPoints");
    f.generateAllLevels = flag(o.generate_all_levels, "generateAllLevels");
    f.includeBaseLevelIndices = flag(o.include_base_level_indices, "includeBaseLevelIndices");
    f.includeFVarBaseLevelIndices = flag(o.include_fvar_base_level_indices, "includeFVarBaseLevelIndices");
    f.triangulateQuads = flag(o.triangulate_quads, "triangulateQuads");
    f.useSingleCreasePatch = flag(o.use_single_crease_patch, "useSingleCreasePatch");
    f.useInfSharpPatch = flag(o.use_inf_sharp_patch, "useInfSharpPatch");
    f.generateVaryingTables = flag(o.generate_varying_tables, "generateVaryingTables");
    f.generateVaryingLocalPoints = flag(o.generate_varying_local_points, "generateVaryingLocalPoints");
    f.generateFVarTables = flag(o.generate_fvar_tables, "generateFVarTables");
    f.patchPrecisionDouble = flag(o.patch_precision_double, "patchPrecisionDouble");
    f.fvarPatchPrecisionDouble = flag(o.fvar_patch_precision_double, "fvarPatchPrecisionDouble");
    f.generateFVarLegacyLinearPatches =
        flag(o.generate_fvar_legacy_linear_patches, "generateFVarLegacyLinearPatches");
    f.generateLegacySharpCornerPatches =
        flag(o.generate_legacy_sharp_corner_patches, "generateLegacySharpCornerPatches");
    return f;
}

// A local-point stencil table of either precision, weights as double.
template <typename REAL>
sdv_stencils *copy_stencils(Far::StencilTableReal<REAL> const *t) {
    std::unique_ptr<sdv_stencils> out(new sdv_stencils());
    if (t) {
        int n = t->GetNumStencils();
        out->sizes.reserve(n);
        out->offsets.reserve(n);
        for (int i = 0; i < n; ++i) {
            auto s = t->GetStencil(i);
            out->offsets.push_back((int32_t)out->indices.size());
            out->sizes.push_back(s.GetSize());
            for (int k = 0; k < s.GetSize(); ++k) {
                out->indices.push_back(s.GetVertexIndices()[k]);
                out->weights.push_back((double)s.GetWeights()[k]);
            }
        }
    }
    return out.release();
}

// The B-spline end-cap converter (end caps B-spline or unspecified) writes
// past its matrix on an irregular corner at an interior vertex of valence 2
// (two faces folded onto each other: found by fuzzing, with infinitely
// sharp and single-crease patches, under Valgrind). Such vertices only
// exist where the base level has them.
void check_bspline_end_caps(Far::TopologyLevel const &base) {
    for (int v = 0; v < base.GetNumVertices(); ++v)
        if (base.GetVertexEdges(v).size() == 2 && base.GetVertexFaces(v).size() == 2 && !base.IsVertexBoundary(v))
            fail_unsafe("B-spline end caps are not available with interior vertex " + str(v) +
                        " of valence 2 (OpenSubdiv's end-cap converter writes out of bounds there); use Gregory "
                        "or bilinear end caps");
}

// The legacy Gregory tables (quad offsets, vertex valences) are built from
// the last level alone: OpenSubdiv takes every irregular patch's face as a
// face of that level and gathers a quad ring around each of its vertices.
// An irregular patch of an earlier level (a secondary level below the
// isolation level, a maximum isolation below the refinement's) makes it
// read and write out of bounds, and so do a face of the last level that is
// not a quad (a base level left unrefined) and a non-manifold vertex there
// (more faces than its ring has room for). The irregular patches are those
// of the same table with Gregory basis end caps (the end-cap type changes
// how they are represented, not which they are): built first, checked.
void check_legacy_gregory(Far::TopologyRefiner const &tr, Far::PatchTableFactory::Options f,
                          Far::ConstIndexArray selected) {
    int max = tr.GetMaxLevel();
    Far::TopologyLevel const &last = tr.GetLevel(max);
    for (int face = 0; face < last.GetNumFaces(); ++face)
        if (last.GetFaceVertices(face).size() != 4)
            fail_unsafe("legacy Gregory end caps need quads in the last level; face " + str(face) + " of level " +
                        str(max) + " has " + str(last.GetFaceVertices(face).size()) +
                        " vertices (OpenSubdiv would read out of bounds)");
    for (int v = 0; v < last.GetNumVertices(); ++v)
        if (last.IsVertexNonManifold(v))
            fail_unsafe("legacy Gregory end caps need a manifold last level; vertex " + str(v) + " of level " +
                        str(max) + " is non-manifold (OpenSubdiv would write out of bounds)");
    f.endCapType = Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS;
    f.numFVarChannels = 0;
    f.fvarChannelIndices = nullptr;
    f.generateFVarTables = false;
    std::unique_ptr<Far::PatchTable> probe(Far::PatchTableFactory::Create(tr, f, selected));
    if (!probe) throw ShimError(SDV_ERR_OSD, "PatchTableFactory::Create returned no table");
    for (int a = 0; a < probe->GetNumPatchArrays(); ++a) {
        if (probe->GetPatchArrayDescriptor(a).GetType() != Far::PatchDescriptor::GREGORY_BASIS) continue;
        for (int p = 0; p < probe->GetNumPatches(a); ++p) {
            int depth = probe->GetPatchParam(a, p).GetDepth();
            if (depth != max)
                fail_unsafe("legacy Gregory end caps need every irregular patch in the last level (" + str(max) +
                            "); one is at level " + str(depth) +
                            " (secondary or maximum isolation level below it: OpenSubdiv would read out of bounds)");
        }
    }
}

}  // namespace

extern "C" {

int sdv_patches_create(const sdv_refiner *r, const sdv_patch_options *o, const int32_t *fvar_channels,
                       size_t num_fvar_channels, const int32_t *faces, size_t num_faces, sdv_patches **out,
                       char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out || !o) fail("null argument");
        *out = nullptr;
        const sdv_refiner &rr = need(r);
        Far::TopologyRefiner const &tr = *rr.refiner;
        Far::PatchTableFactory::Options f = factory_options(*o);
        bool legacy = f.endCapType == Far::PatchTableFactory::Options::ENDCAP_LEGACY_GREGORY;
        if (legacy && tr.GetSchemeType() != Sdc::SCHEME_CATMARK)
            fail("legacy Gregory end caps exist for Catmull-Clark only");
        // Uniform tables list faces; only adaptive ones run the patch
        // builders that overrun on repeated vertices.
        if (!tr.IsUniform()) check_no_repeated_vertices(tr.GetLevel(0));
        if (!legacy) check_loop_folded_triangles(tr);
        if (!legacy && !tr.IsUniform()) check_valence2_source_points(tr);
        if (f.endCapType == Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS ||
            f.endCapType == Far::PatchTableFactory::Options::ENDCAP_NONE)
            check_bspline_end_caps(tr.GetLevel(0));
        int channels = tr.GetNumFVarChannels();
        if (num_fvar_channels > 0 && !fvar_channels) fail("null face-varying channel list");
        if (num_fvar_channels > (size_t)channels)
            fail(str((long long)num_fvar_channels) + " face-varying channels asked for, the refiner has " +
                 str(channels));
        for (size_t i = 0; i < num_fvar_channels; ++i)
            if (fvar_channels[i] < 0 || fvar_channels[i] >= channels)
                fail("face-varying channel " + str(fvar_channels[i]) + " does not exist (the refiner has " +
                     str(channels) + ")");
        f.numFVarChannels = (int)num_fvar_channels;
        f.fvarChannelIndices = num_fvar_channels ? fvar_channels : nullptr;
        int base_faces = tr.GetLevel(0).GetNumFaces();
        if (num_faces > 0 && !faces) fail("null face list");
        if (num_faces > (size_t)0x7fffffff) fail("too many selected faces");
        for (size_t i = 0; i < num_faces; ++i)
            if (faces[i] < 0 || faces[i] >= base_faces)
                fail("selected face " + str(faces[i]) + " is out of range (" + str(base_faces) + " faces)");
        if (num_faces > 0 && !tr.IsUniform() && !rr.adaptive_faces.empty()) {
            // OpenSubdiv leaves patches of faces it did not refine undefined.
            for (size_t i = 0; i < num_faces; ++i)
                if (!rr.adaptive_faces[(size_t)faces[i]])
                    fail("selected face " + str(faces[i]) +
                         " was not among the faces refined adaptively: its patches are undefined");
        }
        Far::ConstIndexArray selected(faces, (int)num_faces);
        if (legacy) check_legacy_gregory(tr, f, selected);
        std::unique_ptr<sdv_patches> p(new sdv_patches());
        osd_errors().clear();
        p->table.reset(Far::PatchTableFactory::Create(tr, f, selected));
        if (!osd_errors().empty()) throw ShimError(SDV_ERR_OSD, osd_errors());
        if (!p->table) throw ShimError(SDV_ERR_OSD, "PatchTableFactory::Create returned no table");
        // A uniform table of every refined level holds overlapping patches
        // (each face and its children): PatchMap's quadtree writes past its
        // nodes on them (found under Valgrind), so such a table has no map.
        bool overlapping = tr.IsUniform() && p->table->GetNumPatchArrays() > 1;
        if (!overlapping) p->map.reset(new Far::PatchMap(*p->table));
        *out = p.release();
    });
}

void sdv_patches_destroy(sdv_patches *p) { delete p; }

int sdv_patches_counts(const sdv_patches *p, sdv_patch_counts *out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Far::PatchTable const &t = *need_patches(p).table;
        out->num_arrays = t.GetNumPatchArrays();
        out->num_patches = t.GetNumPatchesTotal();
        out->num_control_vertices = (int32_t)t.GetPatchControlVerticesTable().size();
        out->num_local_points = t.GetNumLocalPoints();
        out->num_local_points_varying = t.GetNumLocalPointsVarying();
        out->max_valence = t.GetMaxValence();
        out->num_ptex_faces = t.GetNumPtexFaces();
        out->num_quad_offsets = (int32_t)t.GetQuadOffsetsTable().size();
        out->num_valence_entries = (int32_t)t.GetVertexValenceTable().size();
        out->feature_adaptive = t.IsFeatureAdaptive() ? 1 : 0;
        out->varying_type = (int32_t)t.GetVaryingPatchDescriptor().GetType();
        out->num_varying_vertices = t.GetVaryingVertices().size();
        out->num_fvar_channels = t.GetNumFVarChannels();
    });
}

int sdv_patches_array(const sdv_patches *p, int32_t array, int32_t *type, int32_t *num_patches, int32_t *num_cvs,
                      char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!type || !num_patches || !num_cvs) fail("null output");
        Far::PatchTable const &t = *need_patches(p).table;
        if (array < 0 || array >= t.GetNumPatchArrays())
            fail("patch array " + str(array) + " does not exist (" + str(t.GetNumPatchArrays()) + " arrays)");
        Far::PatchDescriptor d = t.GetPatchArrayDescriptor(array);
        *type = (int32_t)d.GetType();
        *num_patches = t.GetNumPatches(array);
        *num_cvs = d.GetNumControlVertices();
    });
}

int sdv_patches_tables(const sdv_patches *p, const sdv_patch_tables *out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Far::PatchTable const &t = *need_patches(p).table;
        auto const &cvs = t.GetPatchControlVerticesTable();
        auto const &params = t.GetPatchParamTable();
        auto const &sharp_index = t.GetSharpnessIndexTable();
        auto const &sharp_values = t.GetSharpnessValues();
        auto const &quad = t.GetQuadOffsetsTable();
        auto const &valence = t.GetVertexValenceTable();
        size_t patches = params.size();
        check_cap(out->cvs.cap, (long long)cvs.size(), "patch control vertices");
        check_cap(out->params_cap, 2 * (long long)patches, "patch params");
        check_cap(out->sharpness_cap, (long long)patches, "patch sharpness");
        check_cap(out->quad_offsets_cap, (long long)quad.size(), "quad offsets");
        check_cap(out->valence.cap, (long long)valence.size(), "vertex valence table");
        Far::ConstIndexArray varying = t.GetVaryingVertices();
        check_cap(out->varying.cap, (long long)varying.size(), "varying vertices");
        if (varying.size() > 0 && !out->varying.data) fail("null output");
        std::copy(varying.begin(), varying.end(), out->varying.data);
        if ((!cvs.empty() && !out->cvs.data) || (patches && (!out->params || !out->sharpness)) ||
            (!quad.empty() && !out->quad_offsets) || (!valence.empty() && !out->valence.data))
            fail("null output");
        std::copy(cvs.begin(), cvs.end(), out->cvs.data);
        for (size_t i = 0; i < patches; ++i) {
            out->params[2 * i] = params[i].field0;
            out->params[2 * i + 1] = params[i].field1;
            // No sharpness table (single-crease patches off), or no entry.
            float s = 0.0f;
            if (i < sharp_index.size()) {
                Far::Index k = sharp_index[i];
                if (k != Far::INDEX_INVALID) {
                    if (k < 0 || (size_t)k >= sharp_values.size())
                        throw ShimError(SDV_ERR_INTERNAL, "patch sharpness index out of range");
                    s = sharp_values[(size_t)k];
                }
            }
            out->sharpness[i] = s;
        }
        std::copy(quad.begin(), quad.end(), out->quad_offsets);
        std::copy(valence.begin(), valence.end(), out->valence.data);
    });
}

int sdv_patches_fvar(const sdv_patches *p, int32_t channel, sdv_fvar_patches *info, int32_t *values,
                     size_t values_cap, uint32_t *params, size_t params_cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!info) fail("null output");
        Far::PatchTable const &t = *need_patches(p).table;
        if (channel < 0 || channel >= t.GetNumFVarChannels())
            fail("face-varying patch channel " + str(channel) + " does not exist (the table has " +
                 str(t.GetNumFVarChannels()) + ")");
        Far::ConstIndexArray v = t.GetFVarValues(channel);
        Far::ConstPatchParamArray pp = t.GetFVarPatchParams(channel);
        info->regular_type = (int32_t)t.GetFVarPatchDescriptorRegular(channel).GetType();
        info->irregular_type = (int32_t)t.GetFVarPatchDescriptorIrregular(channel).GetType();
        info->stride = t.GetFVarValueStride(channel);
        info->num_values = v.size();
        info->num_params = pp.size();
        if (!values && !params) return;
        check_cap(values_cap, (long long)v.size(), "face-varying patch values");
        check_cap(params_cap, 2 * (long long)pp.size(), "face-varying patch params");
        if ((v.size() > 0 && !values) || (pp.size() > 0 && !params)) fail("null output");
        std::copy(v.begin(), v.end(), values);
        for (int i = 0; i < pp.size(); ++i) {
            params[2 * i] = pp[i].field0;
            params[2 * i + 1] = pp[i].field1;
        }
    });
}

int sdv_patches_local_stencils(const sdv_patches *p, int32_t kind, sdv_stencils **out, char *err,
                               size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        Far::PatchTable const &t = *need_patches(p).table;
        // PatchTable's accessors assert that the precision asked for is the
        // table's: ask for the one it has.
        if (kind == 0) {
            if (t.LocalPointStencilPrecisionMatchesType<double>())
                *out = copy_stencils(t.GetLocalPointStencilTable<double>());
            else
                *out = copy_stencils(t.GetLocalPointStencilTable<float>());
        } else if (kind == 1) {
            if (t.LocalPointVaryingStencilPrecisionMatchesType<double>())
                *out = copy_stencils(t.GetLocalPointVaryingStencilTable<double>());
            else
                *out = copy_stencils(t.GetLocalPointVaryingStencilTable<float>());
        } else if (kind >= 2 && kind - 2 < t.GetNumFVarChannels()) {
            if (t.LocalPointFaceVaryingStencilPrecisionMatchesType<double>())
                *out = copy_stencils(t.GetLocalPointFaceVaryingStencilTable<double>(kind - 2));
            else
                *out = copy_stencils(t.GetLocalPointFaceVaryingStencilTable<float>(kind - 2));
        } else {
            fail("unknown local-point stencil kind " + str(kind));
        }
    });
}

int sdv_patches_find(const sdv_patches *p, int32_t face, double u, double v, int32_t *found, int32_t *array,
                     int32_t *patch, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!found || !array || !patch) fail("null output");
        const sdv_patches &pp = need_patches(p);
        int faces = pp.table->GetNumPtexFaces();
        if (face < 0 || face >= faces) fail("ptex face " + str(face) + " does not exist (" + str(faces) + " ptex faces)");
        check_unit(u, "u");
        check_unit(v, "v");
        Far::PatchTable::PatchHandle const *h = need_map(pp).FindPatch(face, u, v);
        *found = h ? 1 : 0;
        *array = h ? h->arrayIndex : -1;
        if (h) {
            // The handle's patch index counts over all arrays.
            Far::PatchTable const &t = *pp.table;
            int first = 0;
            for (int a = 0; a < h->arrayIndex; ++a) first += t.GetNumPatches(a);
            *patch = h->patchIndex - first;
        } else {
            *patch = -1;
        }
    });
}

int sdv_patches_evaluate_basis(const sdv_patches *p, int32_t array, int32_t patch, double u, double v, double *w,
                               double *du, double *dv, double *duu, double *duv, double *dvv, size_t cap,
                               char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        Far::PatchTable const &t = *need_patches(p).table;
        if (array < 0 || array >= t.GetNumPatchArrays())
            fail("patch array " + str(array) + " does not exist (" + str(t.GetNumPatchArrays()) + " arrays)");
        if (patch < 0 || patch >= t.GetNumPatches(array))
            fail("patch " + str(patch) + " does not exist in array " + str(array) + " (" +
                 str(t.GetNumPatches(array)) + " patches)");
        Far::PatchDescriptor d = t.GetPatchArrayDescriptor(array);
        if (!evaluable(d.GetType()))
            fail("patches of type " + str((int)d.GetType()) + " cannot be evaluated (EvaluateBasis has no basis for them)");
        check_unit(u, "u");
        check_unit(v, "v");
        if (!w) fail("null output");
        if ((du == nullptr) != (dv == nullptr)) fail("first derivatives come in pairs");
        if ((duu == nullptr) != (duv == nullptr) || (duu == nullptr) != (dvv == nullptr))
            fail("second derivatives come in threes");
        if (duu && !du) fail("second derivatives need the first");
        // The basis functions write up to 20 weights whatever the patch's size.
        check_cap(cap, 20, "basis weights");
        Far::PatchTable::PatchHandle h;
        h.arrayIndex = array;
        int first = 0;
        for (int a = 0; a < array; ++a) first += t.GetNumPatches(a);
        h.patchIndex = first + patch;
        h.vertIndex = patch * d.GetNumControlVertices();
        t.EvaluateBasis<double>(h, u, v, w, du, dv, duu, duv, dvv);
    });
}

int sdv_patches_evaluate_points(const sdv_patches *p, const double *points, size_t num_points, int32_t width,
                                const int32_t *faces, const double *us, const double *vs, size_t n,
                                double *out, double *du, double *dv, double *duu, double *duv, double *dvv,
                                char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        sdv_patches const &pp = need_patches(p);
        Far::PatchTable const &t = *pp.table;
        EvaluationInputs in = {points, num_points, width, faces, us, vs, n, {out, du, dv, duu, duv, dvv}};
        check_evaluation(t, in, "EvaluateBasis");
        size_t w = (size_t)width;
        double bw[6][20];
        double *outs[6] = {out, du, dv, duu, duv, dvv};
        int kinds = duu ? 6 : du ? 3 : 1;
        for (size_t i = 0; i < n; ++i) {
            Far::PatchTable::PatchHandle const *h = location_patch(pp, in, i);
            t.EvaluateBasis<double>(*h, us[i], vs[i], bw[0], du ? bw[1] : nullptr, du ? bw[2] : nullptr,
                                    duu ? bw[3] : nullptr, duu ? bw[4] : nullptr, duu ? bw[5] : nullptr);
            Far::ConstIndexArray cvs = t.GetPatchVertices(*h);
            for (int k = 0; k < kinds; ++k) {
                double *o = outs[k] + i * w;
                for (size_t j = 0; j < w; ++j) o[j] = 0.0;
                for (int c = 0; c < cvs.size(); ++c) {
                    double const *src = points + (size_t)cvs[c] * w;
                    double wt = bw[k][c];
                    for (size_t j = 0; j < w; ++j) o[j] += wt * src[j];
                }
            }
        }
    });
}

}  // extern "C"
