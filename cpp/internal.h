// Internals the shim's C++ files share (cpp/shim.cpp, cpp/patches.cpp,
// cpp/osd_evaluator.cpp, ...): the
// opaque types behind cpp/shim.h and the error machinery every entry point
// uses. Not part of the C ABI.
#ifndef SUBDIV_SHIM_INTERNAL_H
#define SUBDIV_SHIM_INTERNAL_H

#include "shim.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyRefiner.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

struct sdv_refiner {
    OpenSubdiv::Far::TopologyRefiner *refiner = nullptr;
    std::string warnings;
    bool full_topology_last_level = true;  // level 0 always has full topology
    // Far::PtexIndices of the base level (which never changes), built on
    // first use; call_once makes that safe from several threads.
    mutable std::once_flag ptex_once;
    mutable std::unique_ptr<OpenSubdiv::Far::PtexIndices> ptex;
    // The base faces RefineAdaptive was given (empty: every face): patches
    // of other faces are undefined, so patch tables refuse them.
    std::vector<bool> adaptive_faces;
    ~sdv_refiner() { delete refiner; }
};

struct sdv_patches {
    std::unique_ptr<OpenSubdiv::Far::PatchTable> table;
    std::unique_ptr<OpenSubdiv::Far::PatchMap> map;
};

struct sdv_stencils {
    std::vector<int32_t> sizes, offsets, indices;
    std::vector<double> weights;
    // Limit stencils at locations: the derivative weights asked for
    // (du, dv, duu, duv, dvv; empty when not generated), and for each
    // location whether it has a stencil (0 in a hole).
    std::vector<double> derivatives[5];
    std::vector<int32_t> found;
    int32_t controls = 0;
};

namespace sdv_internal {

using namespace OpenSubdiv;

// Messages OpenSubdiv reported through Far::Error on this thread since they
// were last cleared (defined in shim.cpp, which installs the callbacks).
std::string &osd_errors();

// An error with a status, thrown inside the shim and turned into a return code.
struct ShimError : std::runtime_error {
    int status;
    ShimError(int s, const std::string &m) : std::runtime_error(m), status(s) {}
};

[[noreturn]] inline void fail(const std::string &msg) { throw ShimError(SDV_ERR_INVALID, msg); }
[[noreturn]] inline void fail_unsafe(const std::string &msg) { throw ShimError(SDV_ERR_UNSAFE, msg); }

inline void write_err(char *err, size_t err_len, const char *msg) {
    if (!err || err_len == 0) return;
    size_t n = std::strlen(msg);
    if (n >= err_len) n = err_len - 1;
    std::memcpy(err, msg, n);
    err[n] = '\0';
}

template <class F>
int guarded(char *err, size_t err_len, F &&body) {
    if (err && err_len) err[0] = '\0';
    try {
        body();
        return SDV_OK;
    } catch (const ShimError &e) {
        write_err(err, err_len, e.what());
        return e.status;
    } catch (const std::bad_alloc &) {
        write_err(err, err_len, "out of memory");
        return SDV_ERR_INTERNAL;
    } catch (const std::exception &e) {
        write_err(err, err_len, (std::string("C++ exception: ") + e.what()).c_str());
        return SDV_ERR_INTERNAL;
    } catch (...) {
        write_err(err, err_len, "unknown C++ exception");
        return SDV_ERR_INTERNAL;
    }
}

inline std::string str(long long v) { return std::to_string(v); }

inline const sdv_refiner &need(const sdv_refiner *r) {
    if (!r || !r->refiner) fail("null refiner");
    return *r;
}

inline void check_cap(size_t cap, long long need_n, const char *what) {
    if (need_n < 0 || cap < (size_t)need_n)
        throw ShimError(SDV_ERR_CAPACITY, std::string(what) + ": buffer holds " + str((long long)cap) +
                                              " elements but " + str(need_n) + " are needed");
}

// Checks shared by the shim's files (each fails with a message naming what
// is refused). shim.cpp: a face-varying channel that exists; Sdc's
// Catmull-Clark smooth vertex mask, whose valence * valence overflows an
// int beyond 46,340 faces, not used from level `parent` (`channel` -1 for
// vertex data). patches.cpp: no face of the base level repeating a vertex
// (OpenSubdiv's adaptive patch builders overrun on them); a parametric
// coordinate in [0, 1]; is_valence2_corner: whether corner `i` of `face`
// is an interior corner of valence 2 (two faces folded onto each other
// there); no irregular patch next to one whose source points overflow the
// 64 entries OpenSubdiv gathers them into.
void check_channel(const sdv_refiner *r, int32_t channel);
bool is_valence2_corner(Far::TopologyLevel const &base, int face, int i);
void check_valence2_source_points(Far::TopologyRefiner const &tr);
void check_smooth_vertex_masks(const Far::TopologyRefiner &tr, int parent, int channel);
void check_no_repeated_vertices(Far::TopologyLevel const &base);
void check_loop_folded_triangles(Far::TopologyRefiner const &tr);
void check_unit(double x, const char *name);

// Patch tables (patches.cpp): the table behind a handle (refusing a null
// one); its PatchMap (refusing a table without one: every level of a
// uniform table); whether EvaluateBasis has a basis for a patch type.
const sdv_patches &need_patches(const sdv_patches *p);
Far::PatchMap const &need_map(sdv_patches const &p);
bool evaluable(Far::PatchDescriptor::Type t);

// An evaluation at n locations (faces[i], us[i], vs[i]) over num_points
// points of `width` values, into the outputs asked for (values, then du,
// dv, duu, duv, dvv; NULL when not asked for).
struct EvaluationInputs {
    const void *points;
    size_t num_points;
    int32_t width;
    const int32_t *faces;
    const double *us;
    const double *vs;
    size_t n;
    const void *outputs[6];
};
// Refuses, before OpenSubdiv sees them: a width that is not positive, null
// arrays, derivatives asked for in part, a patch type `evaluator` has no
// basis for, a control vertex beyond the points.
void check_evaluation(Far::PatchTable const &t, EvaluationInputs const &in, const char *evaluator);
// The patch of location i, refusing a location off the ptex faces or the
// unit square, or in a hole (the error names the location).
Far::PatchTable::PatchHandle const *location_patch(sdv_patches const &p, EvaluationInputs const &in, size_t i);

}  // namespace sdv_internal

#endif
