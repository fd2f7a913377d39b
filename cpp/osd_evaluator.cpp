// subdiv shim, OpenSubdiv's CPU evaluator: Osd::CpuPatchTable and
// Osd::CpuEvaluator::EvalPatches behind the C ABI of cpp/shim.h — the batch
// limit evaluation Blender's and USD's evaluators call, in float as every
// Osd evaluator is. As everywhere in the shim, every entry point catches
// every exception, and every input that would make OpenSubdiv read or write
// out of bounds is refused before it sees it.

#include "internal.h"

#include <opensubdiv/osd/bufferDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>
#include <opensubdiv/osd/cpuPatchTable.h>
#include <opensubdiv/osd/types.h>

#include <memory>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

struct sdv_cpu_patches {
    const sdv_patches *source = nullptr;
    std::unique_ptr<Osd::CpuPatchTable> table;
};

namespace {

// The tables Osd::CpuPatchTable's constructor copies whole arrays of, per
// patch array: each must hold an entry for every patch (it indexes them
// without checking).
void check_copied_tables(Far::PatchTable const &t) {
    size_t patches = (size_t)t.GetNumPatchesTotal();
    if (t.GetPatchParamTable().size() < patches)
        fail_unsafe("the patch-parameter table is shorter than the patches");
    size_t varying = t.GetVaryingVertices().size();
    if (varying != 0 && varying < patches * (size_t)t.GetVaryingPatchDescriptor().GetNumControlVertices())
        fail_unsafe("the varying control-vertex table is shorter than the patches");
    for (int c = 0; c < t.GetNumFVarChannels(); ++c) {
        size_t values = (size_t)t.GetFVarValues(c).size();
        size_t stride = (size_t)t.GetFVarValueStride(c);
        if (values < patches * stride || (size_t)t.GetFVarPatchParams(c).size() < patches)
            fail_unsafe("face-varying channel " + str(c) + "'s tables are shorter than the patches");
    }
}

const sdv_cpu_patches &need_cpu(const sdv_cpu_patches *c) {
    if (!c || !c->table || !c->source) fail("null CPU patch table");
    return *c;
}

}  // namespace

extern "C" {

int sdv_cpu_patches_create(const sdv_patches *p, sdv_cpu_patches **out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        sdv_patches const &pp = need_patches(p);
        check_copied_tables(*pp.table);
        std::unique_ptr<sdv_cpu_patches> c(new sdv_cpu_patches);
        c->source = p;
        c->table.reset(Osd::CpuPatchTable::Create(pp.table.get()));
        if (!c->table) throw ShimError(SDV_ERR_OSD, "Osd::CpuPatchTable::Create returned no table");
        *out = c.release();
    });
}

void sdv_cpu_patches_destroy(sdv_cpu_patches *c) { delete c; }

int sdv_cpu_patches_evaluate(const sdv_cpu_patches *c, const float *points, size_t num_points, int32_t width,
                             const int32_t *faces, const double *us, const double *vs, size_t n, float *out,
                             float *du, float *dv, float *duu, float *duv, float *dvv, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        sdv_cpu_patches const &cc = need_cpu(c);
        sdv_patches const &pp = need_patches(cc.source);
        EvaluationInputs in = {points, num_points, width, faces, us, vs, n, {out, du, dv, duu, duv, dvv}};
        check_evaluation(*pp.table, in, "EvalPatches");
        if (n > (size_t)INT32_MAX) fail("more locations than EvalPatches counts (" + str((long long)n) + ")");
        // The locations found first (as Blender's evaluator does), each
        // checked before OpenSubdiv's PatchMap reads it.
        std::vector<Osd::PatchCoord> coords(n);
        for (size_t i = 0; i < n; ++i)
            coords[i] = Osd::PatchCoord(*location_patch(pp, in, i), (float)us[i], (float)vs[i]);
        if (n == 0) return;
        Osd::BufferDescriptor desc(0, width, width);
        Osd::CpuPatchTable const &table = *cc.table;
        const Osd::PatchArray *arrays = table.GetPatchArrayBuffer();
        const int *indices = table.GetPatchIndexBuffer();
        const Osd::PatchParam *params = table.GetPatchParamBuffer();
        int count = (int)n;
        bool ok = duu ? Osd::CpuEvaluator::EvalPatches(points, desc, out, desc, du, desc, dv, desc, duu, desc, duv,
                                                       desc, dvv, desc, count, coords.data(), arrays, indices, params)
                  : du ? Osd::CpuEvaluator::EvalPatches(points, desc, out, desc, du, desc, dv, desc, count,
                                                        coords.data(), arrays, indices, params)
                       : Osd::CpuEvaluator::EvalPatches(points, desc, out, desc, count, coords.data(), arrays,
                                                        indices, params);
        if (!ok) throw ShimError(SDV_ERR_OSD, "Osd::CpuEvaluator::EvalPatches failed");
    });
}

}  // extern "C"
