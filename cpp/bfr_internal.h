// Internals the shim's Bfr files share (cpp/bfr.cpp, cpp/bfr_surface.cpp,
// cpp/bfr_mesh.cpp): the checks made before OpenSubdiv's Bfr sees a face.
// Not part of the C ABI.
#ifndef SUBDIV_SHIM_BFR_INTERNAL_H
#define SUBDIV_SHIM_BFR_INTERNAL_H

#include "internal.h"

#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyLevel.h>

namespace sdv_internal {

// The coordinates Bfr::Tessellation(p, num_rates, rates) will count, on the
// face's boundary and inside it: its initializeRates (every rate clamped to
// 32767, the rates not given inferred) and initializeInventoryFor* replayed
// in 64 bits, so that a pattern too large is refused before OpenSubdiv
// counts it in int. `p` must be valid, `rates` hold `num_rates` rates of at
// least 1, 1 <= num_rates <= face size + 2 (defined in bfr.cpp).
struct BfrInventory {
    long long boundary = 0, interior = 0;
};
BfrInventory bfr_inventory(OpenSubdiv::Bfr::Parameterization const &p, int32_t const *rates, int num_rates);

// What OpenSubdiv's Bfr needs of a base face's topology before its
// SurfaceFactory builds a surface for it (defined in bfr_surface.cpp, where
// the reasons are spelled out): at most SDV_BFR_MAX_SURFACE_FACE_SIZE
// vertices, no corner of more than SDV_BFR_MAX_SURFACE_VALENCE faces
// (SDV_ERR_UNSAFE), and for a surface that is not linear (`nonlinear`) none
// of OpenSubdiv 3.5.0's two valence-2 faults (SDV_ERR_UNSAFE; `channel`: the
// face-varying channel of a face-varying surface, whose subsets may have a
// boundary at any seam, or -1 for a vertex surface).
void check_bfr_surface_face(Far::TopologyLevel const &base, int face, bool nonlinear, int channel);

// Every control point of `surface` (of `face`) names one of `available`
// points; else an internal error (defined in bfr_surface.cpp).
void check_bfr_control_points(OpenSubdiv::Bfr::Surface<double> const &surface, long long available, int32_t face);

}  // namespace sdv_internal

#endif
