// subdiv shim, limit stencils at locations: Far::LimitStencilTableFactory
// behind the C ABI of cpp/shim.h. As everywhere in the shim, every entry
// point catches every exception, and every input that would make OpenSubdiv
// read out of bounds is refused before it sees it.

#include "internal.h"

#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <memory>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

namespace {

typedef Far::LimitStencilTableFactoryReal<double> Factory;

// For each ptex face, whether its base face is a hole (PatchMap finds no
// patch there, so LimitStencilTableFactory makes no stencil).
std::vector<bool> ptex_holes(Far::TopologyRefiner const &tr) {
    Far::TopologyLevel const &base = tr.GetLevel(0);
    Far::PtexIndices ptex(tr);
    std::vector<bool> holes((size_t)ptex.GetNumFaces(), false);
    int regular = Sdc::SchemeTypeTraits::GetRegularFaceSize(tr.GetSchemeType());
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        if (!base.IsFaceHole(f)) continue;
        int n = base.GetFaceVertices(f).size();
        int first = ptex.GetFaceId(f);
        for (int k = 0; k < (n == regular ? 1 : n); ++k) holes[(size_t)(first + k)] = true;
    }
    return holes;
}

// The whole table read out, weights and derivative weights as double.
sdv_stencils *take_limit_table(Far::LimitStencilTableReal<double> const *raw, bool d1, bool d2) {
    std::unique_ptr<Far::LimitStencilTableReal<double> const> table(raw);
    std::unique_ptr<sdv_stencils> out(new sdv_stencils());
    if (!table) return out.release();
    out->controls = table->GetNumControlVertices();
    out->sizes = table->GetSizes();
    out->offsets = table->GetOffsets();
    out->indices = table->GetControlIndices();
    out->weights = table->GetWeights();
    if (d1 || d2) {
        out->derivatives[0] = table->GetDuWeights();
        out->derivatives[1] = table->GetDvWeights();
    }
    if (d2) {
        out->derivatives[2] = table->GetDuuWeights();
        out->derivatives[3] = table->GetDuvWeights();
        out->derivatives[4] = table->GetDvvWeights();
    }
    return out.release();
}

}  // namespace

extern "C" {

int sdv_limit_stencils_create(const sdv_refiner *r, const sdv_limit_stencil_options *o, const int32_t *faces,
                              const double *us, const double *vs, size_t n, int32_t *found, sdv_stencils **out,
                              char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out || !o) fail("null argument");
        *out = nullptr;
        if (n > 0 && (!faces || !us || !vs || !found)) fail("null location arrays");
        if (n > (size_t)0x7fffffff) fail("too many locations");
        const sdv_refiner &rr = need(r);
        Far::TopologyRefiner const &tr = *rr.refiner;
        if (o->interpolation < 0 || o->interpolation > 2)
            fail("limit stencil interpolation mode " + str(o->interpolation) + " is not 0..2");
        for (int32_t f : {o->first_derivatives, o->second_derivatives})
            if (f != 0 && f != 1) fail("a derivative flag is " + str(f) + ", not 0 or 1");
        bool fvar = o->interpolation == 2;
        if (fvar) check_channel(&rr, o->fvar_channel);
        // BuildUniformPolygons sizes a level-0 table but fills levels from 1:
        // its patches would be left unset.
        if (tr.IsUniform() && tr.GetMaxLevel() == 0)
            fail("limit stencils after uniform refinement need at least one level: OpenSubdiv 3.5's uniform "
                 "patch table of level 0 leaves its patches unset");
        if (!tr.IsUniform()) {
            for (bool selected : rr.adaptive_faces)
                if (!selected)
                    fail("the refiner was refined adaptively around selected faces only: the patches of the "
                         "others, which limit stencils are built from, are undefined");
            check_no_repeated_vertices(tr.GetLevel(0));
            check_loop_folded_triangles(tr);
            check_valence2_source_points(tr);
            // Face-varying stencils over the non-linear face-varying patches
            // of a refinement that considered the channels:
            // appendLocalPointStencilTable reads uninitialised weights there
            // (Valgrind) and the stencils come out wrong (weights summing to
            // 2e-5 instead of 1 on the production-like shape).
            if (fvar && tr.GetAdaptiveOptions().considerFVarChannels)
                fail_unsafe("face-varying limit stencils after adaptive refinement that considered face-varying "
                            "channels: OpenSubdiv 3.5 reads uninitialised local-point weights there and returns "
                            "wrong stencils");
        }
        for (int l = 0; l < tr.GetMaxLevel(); ++l) {
            if (o->interpolation == 0) check_smooth_vertex_masks(tr, l, -1);
            if (fvar) check_smooth_vertex_masks(tr, l, o->fvar_channel);
        }
        std::vector<bool> holes = ptex_holes(tr);
        Factory::LocationArrayVec arrays;
        arrays.reserve(n);
        for (size_t i = 0; i < n; ++i) {
            if (faces[i] < 0 || (size_t)faces[i] >= holes.size())
                fail("location " + str((long long)i) + ": ptex face " + str(faces[i]) + " does not exist (" +
                     str((long long)holes.size()) + " ptex faces)");
            check_unit(us[i], "u");
            check_unit(vs[i], "v");
            found[i] = holes[(size_t)faces[i]] ? 0 : 1;
            // One array per location keeps the stencils in the locations'
            // order.
            Factory::LocationArray a;
            a.ptexIdx = faces[i];
            a.numLocations = 1;
            a.s = us + i;
            a.t = vs + i;
            arrays.push_back(a);
        }
        Factory::Options fo;
        fo.interpolationMode = o->interpolation == 0   ? Factory::INTERPOLATE_VERTEX
                               : o->interpolation == 1 ? Factory::INTERPOLATE_VARYING
                                                       : Factory::INTERPOLATE_FACE_VARYING;
        fo.generate1stDerivatives = o->first_derivatives != 0;
        fo.generate2ndDerivatives = o->second_derivatives != 0;
        fo.fvarChannel = fvar ? (unsigned)o->fvar_channel : 0u;
        osd_errors().clear();
        std::unique_ptr<sdv_stencils> table(take_limit_table(
            Factory::Create(tr, arrays, nullptr, nullptr, fo), fo.generate1stDerivatives, fo.generate2ndDerivatives));
        if (!osd_errors().empty()) throw ShimError(SDV_ERR_OSD, osd_errors());
        size_t expected = 0;
        for (size_t i = 0; i < n; ++i) expected += (size_t)found[i];
        if (table->sizes.size() != expected)
            throw ShimError(SDV_ERR_INTERNAL, "LimitStencilTableFactory made " + str((long long)table->sizes.size()) +
                                                  " stencils for " + str((long long)expected) +
                                                  " locations outside holes");
        table->found.assign(found, found + n);
        *out = table.release();
    });
}

int32_t sdv_stencils_controls(const sdv_stencils *s) { return s ? s->controls : 0; }

int sdv_stencils_derivative(const sdv_stencils *s, int32_t kind, double *out, size_t cap, size_t *len, char *err,
                            size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!s || !len) fail("null argument");
        if (kind < 0 || kind > 4) fail("derivative kind " + str(kind) + " is not 0..4");
        std::vector<double> const &d = s->derivatives[kind];
        *len = d.size();
        if (!out) return;
        check_cap(cap, (long long)d.size(), "derivative weights");
        std::copy(d.begin(), d.end(), out);
    });
}

}  // extern "C"
