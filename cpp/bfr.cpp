// subdiv shim, Bfr: Bfr::Tessellation and Bfr::Parameterization behind the C
// ABI of cpp/shim.h, so that the native tessellation patterns and face
// parameterizations can be compared with OpenSubdiv's. As everywhere in the
// shim, every entry point catches every exception, and every input that
// would make OpenSubdiv read or write out of bounds, divide by zero,
// overflow an int or allocate without bound is refused before it sees it.
//
// What OpenSubdiv 3.5 does with the inputs refused here (bfr/tessellation.cpp,
// bfr/parameterization.cpp):
// * face sizes: Parameterization stores the size in an unsigned short and
//   leaves faces of fewer than 3 or more than Limits::MaxFaceSize() (65535)
//   vertices invalid. A face of a quad scheme that is not a quad is split
//   into sub-faces laid out on a grid 1 + sqrt(N - 1) wide, kept in an
//   unsigned char: from N = 65026 on the width is 256, stored as 0, and
//   every sub-face coordinate (GetVertexCoord, the tessellation's boundary)
//   is computed modulo 0.
// * rates: the constructor reads `numRates` rates and holds any count >= 1
//   valid (1, 2 for quads, N, N + 1 and N + 2 for quads are documented; the
//   others are read and partly ignored), GetRates writes `numRates` values,
//   and a rate below 1 makes the tessellation invalid. Rates are clamped to
//   32767 (SHRT_MAX), but the counts of coordinates and facets are products
//   of rates (and of the face size) computed in int: a quad at 32767 has
//   2^30 coordinates, a large polygon's count overflows.
// * Options::SetFacetSize takes anything other than 4 as 3.
// * GetNumEdgeCoords(edge) indexes its rates unchecked; GetEdgeCoord of a
//   quad or triangle leaves the output unwritten for an edge beyond its
//   size; the sub-face conversions assert HasSubFaces() (compiled out) and
//   then divide by the grid width, 0 without sub-faces; GetSubFace and the
//   conversions to sub-faces convert coordinates to int.
// * TransformFacetCoordIndices reads the index arrays at every boundary and
//   interior coordinate index of the facets, and adds offsets in int.

#include "bfr_internal.h"

#include <opensubdiv/bfr/limits.h>
#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/tessellation.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

struct sdv_tessellation {
    std::unique_ptr<Bfr::Tessellation> t;
};

namespace {

// Tessellation's clamp of every rate (tessellation.cpp, initializeRates).
const long long MAX_RATE = SHRT_MAX;

Sdc::SchemeType scheme_of(int32_t scheme) {
    if (scheme < 0 || scheme > 2) fail("scheme " + str(scheme) + " is not 0..2");
    return scheme == 0 ? Sdc::SCHEME_BILINEAR : scheme == 1 ? Sdc::SCHEME_CATMARK : Sdc::SCHEME_LOOP;
}

const char *scheme_name(int32_t scheme) { return scheme == 0 ? "bilinear" : scheme == 1 ? "Catmull-Clark" : "Loop"; }

// The face sizes Parameterization(scheme, faceSize) may see: 3..65535, and
// under a quad scheme none whose sub-face grid width wraps to 0.
void check_face_size(int32_t scheme, int32_t n) {
    Sdc::SchemeType s = scheme_of(scheme);
    int max = Bfr::Limits::MaxFaceSize();
    if (n < 3 || n > max)
        fail("face size " + str(n) + " is not 3.." + str(max) +
             " (Bfr::Limits::MaxFaceSize; OpenSubdiv's Parameterization stores it in an unsigned short and "
             "holds it invalid)");
    int regular = Sdc::SchemeTypeTraits::GetRegularFaceSize(s);
    if (regular == 4 && n != 4) {
        // Parameterization's own formula for the width of the sub-face grid.
        int udim = (n < 10) ? 2 + (n > 4) : 1 + (int)std::sqrt((float)(n - 1));
        if (udim > UCHAR_MAX)
            fail_unsafe("face size " + str(n) + " under " + scheme_name(scheme) +
                        ": OpenSubdiv's sub-face grid is " + str(udim) +
                        " wide, which its unsigned char stores as " + str(udim & UCHAR_MAX) +
                        ", and its sub-face coordinates divide by it (the largest such face it "
                        "parameterizes safely has 65025 vertices)");
    }
}

long long clamp_rate(int32_t r) { return std::min<long long>(r, MAX_RATE); }

}  // namespace

// The rates Tessellation infers from the given ones (initializeRates,
// replayed in 64 bits), and from them the number of coordinates it will
// count (initializeInventoryFor*), so that a pattern too large is refused
// before OpenSubdiv counts it in int (shared: see bfr_internal.h).
BfrInventory sdv_internal::bfr_inventory(Bfr::Parameterization const &p, int32_t const *rates, int num_rates) {
    int n = p.GetFaceSize();
    bool quad = (n == 4);
    std::vector<long long> outer((size_t)n);
    long long inner[2];
    bool uniform = true;
    long long total = 0;
    if (num_rates < n) {
        if (num_rates == 2 && quad) {
            inner[0] = clamp_rate(rates[0]);
            inner[1] = clamp_rate(rates[1]);
            outer[0] = outer[2] = inner[0];
            outer[1] = outer[3] = inner[1];
            uniform = inner[0] == inner[1];
            total = 2 * (inner[0] + inner[1]);
        } else {
            inner[0] = inner[1] = clamp_rate(rates[0]);
            std::fill(outer.begin(), outer.end(), inner[0]);
            total = inner[0] * n;
        }
    } else {
        for (int i = 0; i < n; ++i) {
            outer[(size_t)i] = clamp_rate(rates[i]);
            uniform = uniform && outer[(size_t)i] == outer[0];
            total += outer[(size_t)i];
        }
        if (num_rates > n) {
            inner[0] = clamp_rate(rates[n]);
            inner[1] = (num_rates == 6 && quad) ? clamp_rate(rates[5]) : inner[0];
            uniform = uniform && inner[0] == outer[0] && inner[1] == outer[0];
        } else if (quad) {
            inner[0] = (outer[0] + outer[2]) / 2;
            inner[1] = (outer[1] + outer[3]) / 2;
        } else {
            inner[0] = inner[1] = total / n;
        }
    }
    BfrInventory inv;
    inv.boundary = total;
    long long r = inner[0];
    // qsub::countUniformCoords and tri::countUniformCoords.
    auto qsub_coords = [n](long long res) {
        long long h = res / 2;
        return (res & 1) ? (h + 1) * (h + 1) * n + (n == 3 ? 0 : 1) : h * (h + 1) * n + 1;
    };
    auto tri_coords = [](long long res) { return res * (res + 1) / 2; };
    switch (p.GetType()) {
        case Bfr::Parameterization::QUAD:
            if (uniform) {
                inv.interior = r > 1 ? (r - 1) * (r - 1) : 0;
            } else if (inner[0] > 1 && inner[1] > 1) {
                inv.interior = (inner[0] - 1) * (inner[1] - 1);
            } else {
                bool segmented = outer[0] == inner[0] && inner[0] == outer[2] && outer[1] == inner[1] &&
                                 inner[1] == outer[3];
                inv.interior = segmented ? 0 : 1;
            }
            break;
        case Bfr::Parameterization::TRI:
            if (uniform)
                inv.interior = r > 1 ? tri_coords(r - 2) : 0;
            else
                inv.interior = r > 2 ? tri_coords(r - 2) : 1;
            break;
        case Bfr::Parameterization::QUAD_SUBFACES:
            if (r > 1)
                inv.interior = qsub_coords(r - 2);
            else
                inv.interior = (uniform && n == 3) ? 0 : 1;
            break;
    }
    return inv;
}

namespace {

Bfr::Tessellation &need_valid(const sdv_tessellation *t) {
    if (!t || !t->t) fail("null tessellation");
    return *t->t;
}

// Coordinates the sub-face queries convert to int: finite and well inside
// its range (every coordinate of a face lies in [0, 256]).
const double MAX_QUERY_COORD = 1 << 20;

template <typename REAL>
void check_real(REAL x, size_t i, const char *what) {
    if (!std::isfinite((double)x) || std::fabs((double)x) > MAX_QUERY_COORD)
        fail("query " + str((long long)i) + ": " + what + " " + std::to_string((double)x) +
             " is not finite or beyond +-2^20");
}

template <typename REAL>
void query(int32_t scheme, int32_t face_size, int32_t kind, size_t n, const int32_t *index, const REAL *t,
           const REAL *uv_in, int32_t *index_out, REAL *uv_out) {
    check_face_size(scheme, face_size);
    Bfr::Parameterization p(scheme_of(scheme), face_size);
    if (!p.IsValid())
        fail("the parameterization of a " + str(face_size) + "-sided face under " + scheme_name(scheme) +
             " is invalid (OpenSubdiv's IsValid is false): it answers no query");
    bool needs_index = false, needs_t = false, needs_uv_in = false, gives_index = false, gives_uv = false;
    bool sub_face = false;
    switch (kind) {
        case SDV_PARAM_VERTEX_COORD:
        case SDV_PARAM_EDGE_COORD:
            needs_index = gives_uv = true;
            needs_t = kind == SDV_PARAM_EDGE_COORD;
            break;
        case SDV_PARAM_CENTER_COORD:
            gives_uv = true;
            break;
        case SDV_PARAM_SUB_FACE:
            needs_uv_in = gives_index = true;
            break;
        case SDV_PARAM_COORD_TO_SUB_FACE:
        case SDV_PARAM_COORD_TO_NORMALIZED_SUB_FACE:
            needs_uv_in = gives_index = gives_uv = sub_face = true;
            break;
        case SDV_PARAM_SUB_FACE_TO_COORD:
        case SDV_PARAM_NORMALIZED_SUB_FACE_TO_COORD:
            needs_index = needs_uv_in = gives_uv = sub_face = true;
            break;
        default:
            fail("unknown parameterization query " + str(kind));
    }
    if (sub_face && !p.HasSubFaces())
        fail(std::string("this parameterization (a ") + str(face_size) + "-sided face under " +
             scheme_name(scheme) +
             ") has no sub-faces: OpenSubdiv's sub-face conversions assert that and divide by its sub-face "
             "grid width, 0");
    if (n == 0) return;
    if ((needs_index && !index) || (needs_t && !t) || (needs_uv_in && !uv_in) || (gives_index && !index_out) ||
        (gives_uv && !uv_out))
        fail("null argument");
    // Every input is checked before anything is written.
    for (size_t i = 0; i < n; ++i) {
        if (needs_index && (index[i] < 0 || index[i] >= face_size)) {
            const char *what = kind == SDV_PARAM_VERTEX_COORD ? "vertex" : kind == SDV_PARAM_EDGE_COORD ? "edge" : "sub-face";
            fail("query " + str((long long)i) + ": " + what + " " + str(index[i]) + " does not exist (the face has " +
                 str(face_size) + ")");
        }
        if (needs_t) check_real(t[i], i, "edge parameter t");
        if (needs_uv_in) {
            check_real(uv_in[2 * i], i, "u");
            check_real(uv_in[2 * i + 1], i, "v");
        }
    }
    for (size_t i = 0; i < n; ++i) {
        REAL *uv = gives_uv ? uv_out + 2 * i : nullptr;
        const REAL *in = needs_uv_in ? uv_in + 2 * i : nullptr;
        switch (kind) {
            case SDV_PARAM_VERTEX_COORD:
                p.GetVertexCoord(index[i], uv);
                break;
            case SDV_PARAM_EDGE_COORD:
                p.GetEdgeCoord(index[i], t[i], uv);
                break;
            case SDV_PARAM_CENTER_COORD:
                p.GetCenterCoord(uv);
                break;
            case SDV_PARAM_SUB_FACE:
                index_out[i] = p.GetSubFace(in);
                break;
            case SDV_PARAM_COORD_TO_SUB_FACE:
                index_out[i] = p.ConvertCoordToSubFace(in, uv);
                break;
            case SDV_PARAM_COORD_TO_NORMALIZED_SUB_FACE:
                index_out[i] = p.ConvertCoordToNormalizedSubFace(in, uv);
                break;
            case SDV_PARAM_SUB_FACE_TO_COORD:
                p.ConvertSubFaceToCoord(index[i], in, uv);
                break;
            case SDV_PARAM_NORMALIZED_SUB_FACE_TO_COORD:
                p.ConvertNormalizedSubFaceToCoord(index[i], in, uv);
                break;
        }
    }
}

// The largest index the facets of `t` hold (coordinates are 0..N-1).
long long max_coord_index(Bfr::Tessellation const &t) { return (long long)t.GetNumCoords() - 1; }

}  // namespace

extern "C" {

int sdv_tessellation_create(int32_t scheme, int32_t face_size, const int32_t *rates, size_t num_rates,
                            int32_t preserve_quads, int32_t facet_size, sdv_tessellation **out, char *err,
                            size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        check_face_size(scheme, face_size);
        if (preserve_quads != 0 && preserve_quads != 1)
            fail("preserve quads is " + str(preserve_quads) + ", not 0 or 1");
        if (facet_size != 3 && facet_size != 4)
            fail("facet size " + str(facet_size) + " is not 3 or 4 (OpenSubdiv's Options::SetFacetSize takes "
                 "anything but 4 as 3)");
        if (num_rates < 1 || num_rates > (size_t)face_size + 2)
            fail(str((long long)num_rates) + " rates given for a " + str(face_size) +
                 "-sided face: OpenSubdiv takes 1 to " + str(face_size + 2) +
                 " (one inner rate, two for quads; one per edge; one per edge and one or two inner rates)");
        if (!rates) fail("null rates");
        for (size_t i = 0; i < num_rates; ++i)
            if (rates[i] < 1)
                fail("rate " + str((long long)i) + " is " + str(rates[i]) +
                     ": rates must be positive (OpenSubdiv's Tessellation would be invalid)");
        Bfr::Parameterization p(scheme_of(scheme), face_size);
        std::unique_ptr<sdv_tessellation> h(new sdv_tessellation());
        Bfr::Tessellation::Options o;
        o.SetFacetSize(facet_size);
        o.PreserveQuads(preserve_quads != 0);
        if (p.IsValid()) {
            BfrInventory inv = bfr_inventory(p, rates, (int)num_rates);
            long long coords = inv.boundary + inv.interior;
            if (coords > SDV_BFR_MAX_COORDS)
                fail("these rates give " + str(coords) + " coordinates (" + str(inv.boundary) + " on the boundary, " +
                     str(inv.interior) + " inside; rates clamped to 32767 as OpenSubdiv clamps them), beyond the "
                     "bridge's bound of 2^24 (" + str(SDV_BFR_MAX_COORDS) +
                     "; OpenSubdiv counts them in int, which overflows beyond 2^31)");
            h->t.reset(new Bfr::Tessellation(p, (int)num_rates, rates, o));
            Bfr::Tessellation const &t = *h->t;
            if (!t.IsValid())
                throw ShimError(SDV_ERR_INTERNAL, "OpenSubdiv holds a tessellation the bridge checked invalid");
            if (t.GetNumBoundaryCoords() != inv.boundary || t.GetNumInteriorCoords() != inv.interior)
                throw ShimError(SDV_ERR_INTERNAL,
                                "OpenSubdiv counts " + str(t.GetNumBoundaryCoords()) + " + " +
                                    str(t.GetNumInteriorCoords()) + " coordinates, the bridge expected " +
                                    str(inv.boundary) + " + " + str(inv.interior));
            if (t.GetNumFacets() < 0 || t.GetNumFacets() > SDV_BFR_MAX_FACETS)
                fail("these rates give " + str(t.GetNumFacets()) + " facets, beyond the bridge's bound of 2^25");
        } else {
            // An invalid Parameterization (a non-triangle under Loop): the
            // Tessellation is invalid too, and only IsValid may be asked.
            h->t.reset(new Bfr::Tessellation(p, (int)num_rates, rates, o));
            if (h->t->IsValid())
                throw ShimError(SDV_ERR_INTERNAL, "OpenSubdiv holds a tessellation of an invalid face valid");
        }
        *out = h.release();
    });
}

void sdv_tessellation_destroy(sdv_tessellation *t) { delete t; }

int sdv_tessellation_counts(const sdv_tessellation *t, sdv_tess_counts *out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Bfr::Tessellation const &tt = need_valid(t);
        *out = sdv_tess_counts();
        out->is_valid = tt.IsValid() ? 1 : 0;
        if (!tt.IsValid()) return;
        out->is_uniform = tt.IsUniform() ? 1 : 0;
        out->face_size = tt.GetFaceSize();
        std::vector<int> rates((size_t)tt.GetFaceSize() + 2);
        out->num_rates = tt.GetRates(rates.data());
        out->num_boundary_coords = tt.GetNumBoundaryCoords();
        out->num_interior_coords = tt.GetNumInteriorCoords();
        out->num_facets = tt.GetNumFacets();
        out->facet_size = tt.GetFacetSize();
        long long edge = 0;
        for (int e = 0; e < tt.GetFaceSize(); ++e) edge += tt.GetNumEdgeCoords(e);
        out->num_edge_coords = (int32_t)edge;
    });
}

int sdv_tessellation_data(const sdv_tessellation *t, const sdv_tess_data *out, char *err,
                          size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        Bfr::Tessellation const &tt = need_valid(t);
        if (!tt.IsValid()) return;
        int n = tt.GetFaceSize();
        long long coords = tt.GetNumCoords();
        long long facets = (long long)tt.GetNumFacets() * tt.GetFacetSize();
        long long edge_total = 0;
        for (int e = 0; e < n; ++e) edge_total += tt.GetNumEdgeCoords(e);
        std::vector<int> rates((size_t)n + 2);
        int num_rates = tt.GetRates(rates.data());
        check_cap(out->rates.cap, num_rates, "rates");
        check_cap(out->coords_f64_cap, 2 * coords, "coordinates (f64)");
        check_cap(out->coords_f32_cap, 2 * coords, "coordinates (f32)");
        check_cap(out->facets.cap, facets, "facets");
        check_cap(out->edge_coord_counts.cap, n, "edge coordinate counts");
        check_cap(out->edge_coords_f64_cap, 2 * edge_total, "edge coordinates (f64)");
        check_cap(out->edge_coords_f32_cap, 2 * edge_total, "edge coordinates (f32)");
        check_cap(out->vertex_coords_cap, 2 * (long long)n, "vertex coordinates");
        if (!out->rates.data || !out->coords_f64 || !out->coords_f32 || (facets && !out->facets.data) ||
            !out->edge_coord_counts.data || (edge_total && (!out->edge_coords_f64 || !out->edge_coords_f32)) ||
            !out->vertex_coords)
            fail("null output");
        std::copy(rates.begin(), rates.begin() + num_rates, out->rates.data);
        int got = tt.GetCoords(out->coords_f64);
        if (got != coords || tt.GetCoords(out->coords_f32) != coords)
            throw ShimError(SDV_ERR_INTERNAL, "GetCoords returned " + str(got) + " coordinates, GetNumCoords " +
                                                  str(coords));
        if (facets && tt.GetFacets(out->facets.data) != tt.GetNumFacets())
            throw ShimError(SDV_ERR_INTERNAL, "GetFacets returned another count than GetNumFacets");
        long long at = 0;
        for (int e = 0; e < n; ++e) {
            int k = tt.GetNumEdgeCoords(e);
            out->edge_coord_counts.data[e] = k;
            if (k == 0) continue;
            if (tt.GetEdgeCoords(e, out->edge_coords_f64 + 2 * at) != k ||
                tt.GetEdgeCoords(e, out->edge_coords_f32 + 2 * at) != k)
                throw ShimError(SDV_ERR_INTERNAL, "GetEdgeCoords(" + str(e) +
                                                      ") returned another count than GetNumEdgeCoords");
            at += k;
        }
        for (int v = 0; v < n; ++v) tt.GetVertexCoord(v, out->vertex_coords + 2 * v);
    });
}

int sdv_tessellation_transform_facets(sdv_tessellation *t, int32_t kind, int32_t offset, const int32_t *boundary,
                                      size_t num_boundary, const int32_t *interior, size_t num_interior,
                                      int32_t *facets, size_t facets_cap, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        Bfr::Tessellation &tt = need_valid(t);
        if (kind < SDV_FACETS_OFFSET || kind > SDV_FACETS_BOUNDARY_INTERIOR)
            fail("unknown facet transformation " + str(kind));
        // An invalid tessellation has no facets: there is nothing to transform.
        if (!tt.IsValid()) return;
        long long nb = tt.GetNumBoundaryCoords(), ni = tt.GetNumInteriorCoords();
        long long len = (long long)tt.GetNumFacets() * tt.GetFacetSize();
        check_cap(facets_cap, len, "facets");
        if (len && !facets) fail("null output");
        // The offsets are added to coordinate indices in int.
        if (kind == SDV_FACETS_OFFSET && offset > INT_MAX - max_coord_index(tt))
            fail_unsafe("offset " + str(offset) + " added to coordinate index " + str(max_coord_index(tt)) +
                        " overflows an int");
        if (kind == SDV_FACETS_BOUNDARY_OFFSET && ni > 0 && offset > INT_MAX - max_coord_index(tt))
            fail_unsafe("interior offset " + str(offset) + " added to coordinate index " +
                        str(max_coord_index(tt)) + " overflows an int");
        if (kind != SDV_FACETS_OFFSET) {
            if (num_boundary != (size_t)nb)
                fail("boundary index map has " + str((long long)num_boundary) + " entries, the tessellation has " +
                     str(nb) + " boundary coordinates");
            if (nb && !boundary) fail("null boundary index map");
        }
        if (kind == SDV_FACETS_BOUNDARY_INTERIOR) {
            if (num_interior != (size_t)ni)
                fail("interior index map has " + str((long long)num_interior) + " entries, the tessellation has " +
                     str(ni) + " interior coordinates");
            if (ni && !interior) fail("null interior index map");
        }
        if (!len) return;
        tt.GetFacets(facets);
        if (kind == SDV_FACETS_OFFSET)
            tt.TransformFacetCoordIndices(facets, offset);
        else if (kind == SDV_FACETS_BOUNDARY_OFFSET)
            tt.TransformFacetCoordIndices(facets, boundary, offset);
        else
            tt.TransformFacetCoordIndices(facets, boundary, interior);
    });
}

int sdv_parameterization_info(int32_t scheme, int32_t face_size, sdv_param_info *out, char *err,
                              size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        check_face_size(scheme, face_size);
        Bfr::Parameterization p(scheme_of(scheme), face_size);
        out->is_valid = p.IsValid() ? 1 : 0;
        out->type = (int32_t)p.GetType();
        out->has_sub_faces = p.HasSubFaces() ? 1 : 0;
        out->face_size = p.GetFaceSize();
    });
}

int sdv_parameterization_query_f64(int32_t scheme, int32_t face_size, int32_t kind, size_t n, const int32_t *index,
                                   const double *t, const double *uv_in, int32_t *index_out, double *uv_out,
                                   char *err, size_t err_len) {
    return guarded(err, err_len, [&] { query<double>(scheme, face_size, kind, n, index, t, uv_in, index_out, uv_out); });
}

int sdv_parameterization_query_f32(int32_t scheme, int32_t face_size, int32_t kind, size_t n, const int32_t *index,
                                   const float *t, const float *uv_in, int32_t *index_out, float *uv_out,
                                   char *err, size_t err_len) {
    return guarded(err, err_len, [&] { query<float>(scheme, face_size, kind, n, index, t, uv_in, index_out, uv_out); });
}

}  // extern "C"
