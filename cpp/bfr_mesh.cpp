// subdiv shim, a whole mesh tessellated with Bfr: what a C++ program over
// OpenSubdiv runs to mesh a limit surface watertight (the approach of
// OpenSubdiv's bfr tutorial 2_2, extended to a rate per edge, normals,
// texture coordinates and non-manifold edges), in one call, so that the
// native mesher (subdiv::bfr::tessellate) can be checked against, and timed
// against, an independent OpenSubdiv program.
//
// One Bfr::RefinerSurfaceFactory<> over the base level of the refiner
// sdv_refiner_create built, with its topology cache off (as in
// bfr_surface.cpp: the cache is keyed by a 64-bit hash alone, and a
// collision would hand a face another topology's patch); the faces visited
// in index order, single-threaded, one Surface<double> (and one for UVs)
// reused from face to face, as the tutorial does.
//
// As everywhere in the shim, every entry point catches every exception,
// and every input that would make OpenSubdiv read or write out of bounds is
// refused first: the faces sdv_surface_evaluate refuses (the checks are
// bfr_surface.cpp's, shared through bfr_internal.h), patterns beyond the
// tessellation bridge's bounds (bfr.cpp's count of coordinates, shared
// likewise), and meshes whose tessellation exceeds the bounds of shim.h --
// all counted in 64 bits before the first surface is built.

#include "bfr_internal.h"

#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>
#include <opensubdiv/far/topologyLevel.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

using namespace OpenSubdiv;
using namespace sdv_internal;

typedef Bfr::RefinerSurfaceFactory<> Factory;
typedef Bfr::Surface<double> Surface;

struct sdv_bfr_mesh {
    std::vector<double> positions, normals, uvs;
    std::vector<uint32_t> face_offsets, face_vertices, uv_indices, facet_faces;
};

namespace {

// As in bfr_surface.cpp: Far::PatchParam holds 10 bits of a patch's u and v.
const int MAX_APPROX_LEVEL = 10;

// Tessellation's clamp of every rate (SHRT_MAX), and the native mesher's
// cap of the rates it computes from edge lengths.
const int MAX_RATE = SHRT_MAX;

// The base edges of the mesh, told apart by their unordered pair of
// vertices (as the native mesher does), numbered in order of first use.
struct Edges {
    std::vector<size_t> face_first;  // per face: its first corner in of_corner
    std::vector<int> of_corner;      // per face corner: the edge from it to the next corner
    std::vector<int> rate;           // per edge
};

// The native mesher's rate of an edge from its control points' distance:
// 1 + floor(length / edge_length), at most MAX_RATE (the length computed
// as glam's DVec3::distance computes it, in the same order).
int rate_of_length(const double *a, const double *b, double edge_length) {
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    double len = std::sqrt((dx * dx + dy * dy) + dz * dz);
    return (int)std::fmin(1.0 + std::floor(len / edge_length), (double)MAX_RATE);
}

Edges base_edges(Far::TopologyLevel const &base, const sdv_bfr_mesh_input &in) {
    Edges e;
    int nf = base.GetNumFaces();
    e.face_first.resize((size_t)nf + 1);
    e.of_corner.resize((size_t)base.GetNumFaceVertices());
    e.rate.reserve((size_t)base.GetNumEdges());
    std::unordered_map<uint64_t, int> by_pair;
    by_pair.reserve((size_t)base.GetNumEdges());
    size_t corner = 0;
    for (int f = 0; f < nf; ++f) {
        e.face_first[(size_t)f] = corner;
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        int n = fv.size();
        for (int i = 0; i < n; ++i, ++corner) {
            uint32_t a = (uint32_t)fv[i], b = (uint32_t)fv[(i + 1) % n];
            uint64_t key = ((uint64_t)std::min(a, b) << 32) | std::max(a, b);
            auto found = by_pair.emplace(key, (int)e.rate.size());
            if (found.second)
                e.rate.push_back(in.use_edge_length ? rate_of_length(in.positions + 3 * (size_t)a,
                                                                     in.positions + 3 * (size_t)b, in.edge_length)
                                                    : in.rate);
            e.of_corner.at(corner) = found.first->second;
        }
    }
    e.face_first[(size_t)nf] = corner;
    return e;
}

// The rates of `face`'s edges, in its order.
void face_rates(const Edges &e, int face, std::vector<int> &rates) {
    size_t first = e.face_first[(size_t)face], n = e.face_first[(size_t)face + 1] - first;
    rates.resize(n);
    for (size_t i = 0; i < n; ++i) rates[i] = e.rate[(size_t)e.of_corner[first + i]];
}

std::string count_str(size_t n) { return str((long long)std::min<size_t>(n, LLONG_MAX)); }

void check_input(Far::TopologyRefiner const &tr, const sdv_bfr_mesh_input &in) {
    for (int32_t level : {in.approx_level_smooth, in.approx_level_sharp})
        if (level < 0 || level > MAX_APPROX_LEVEL)
            fail("approximation level " + str(level) + " is not 0.." + str(MAX_APPROX_LEVEL) +
                 " (the patches of a face's refined neighbourhood hold 10 bits of u and v)");
    Far::TopologyLevel const &base = tr.GetLevel(0);
    long long nv = base.GetNumVertices();
    if (in.num_vertices < (size_t)nv || (nv && !in.positions))
        fail(count_str(in.num_vertices) + " positions given for " + str(nv) + " base vertices");
    if (in.num_vertices > (size_t)(INT_MAX / 3))
        fail(count_str(in.num_vertices) + " positions of 3 reals: OpenSubdiv indexes them in int");
    if (in.uvs) {
        if (tr.GetNumFVarChannels() < 1) fail("texture coordinates given for a mesh without face-varying channels");
        long long nuv = base.GetNumFVarValues(0);
        if (in.uv_width < 1) fail("texture coordinate width " + str(in.uv_width) + " is not positive");
        if (in.num_uv_values < (size_t)nuv)
            fail(count_str(in.num_uv_values) + " texture coordinate values given, face-varying channel 0 has " +
                 str(nuv));
        if (in.num_uv_values > (size_t)(INT_MAX / in.uv_width))
            fail(count_str(in.num_uv_values) + " texture coordinate values of " + str(in.uv_width) +
                 " reals: OpenSubdiv indexes them in int");
    }
    if (in.use_edge_length != 0 && in.use_edge_length != 1) fail("use_edge_length is not 0 or 1");
    if (in.quads != 0 && in.quads != 1) fail("quads is not 0 or 1");
    if (in.normals != 0 && in.normals != 1) fail("normals is not 0 or 1");
    if (in.use_edge_length) {
        if (!(std::isfinite(in.edge_length) && in.edge_length > 0.0))
            fail("edge length " + std::to_string(in.edge_length) + " is not a positive number");
    } else if (in.rate < 1 || in.rate > MAX_RATE) {
        fail("tessellation rate " + str(in.rate) + " is not 1.." + str(MAX_RATE) +
             " (Bfr::Tessellation clamps rates to 32767)");
    }
}

// What the loop needs of a face before asking for its surfaces: not a hole
// (InitSurfaces returns false for a hole before it gathers anything), the
// checks sdv_surface_evaluate makes (refusing the face and so the mesh),
// and a valid parameterization (a triangle under Loop).
bool may_have_surface(Far::TopologyLevel const &base, Factory const &factory, int face, bool linear_scheme,
                      bool linear_fvar, bool uvs) {
    if (base.IsFaceHole(face)) return false;
    check_bfr_surface_face(base, face, !linear_scheme, -1);
    if (uvs) check_bfr_surface_face(base, face, !linear_fvar, 0);
    return factory.GetFaceParameterization(face).IsValid();
}

// The largest counts the tessellation may reach, in 64 bits: every face
// that may have a surface counted (faces InitSurfaces then finds no limit
// for only make the mesh smaller). Refuses every face and pattern the
// bridge refuses, and meshes beyond shim.h's bounds, before any surface is
// built.
struct Totals {
    long long points = 0, facets = 0, corners = 0, uvs = 0;
    std::vector<char> candidate;  // per face: may_have_surface
};

Totals plan(Far::TopologyLevel const &base, Factory const &factory, const Edges &edges, bool linear_scheme,
            bool linear_fvar, bool uvs, Bfr::Tessellation::Options const &topts) {
    Totals t;
    std::vector<char> vertex_seen((size_t)base.GetNumVertices(), 0), edge_seen(edges.rate.size(), 0);
    std::vector<int> rates;
    t.candidate.assign((size_t)base.GetNumFaces(), 0);
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        if (!may_have_surface(base, factory, f, linear_scheme, linear_fvar, uvs)) continue;
        t.candidate[(size_t)f] = 1;
        Bfr::Parameterization p = factory.GetFaceParameterization(f);
        face_rates(edges, f, rates);
        int n = (int)rates.size();
        if (p.GetFaceSize() != n)
            throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + "'s parameterization has another size");
        BfrInventory inv = bfr_inventory(p, rates.data(), n);
        long long coords = inv.boundary + inv.interior;
        if (coords > SDV_BFR_MAX_COORDS)
            fail("face " + str(f) + ": its rates give " + str(coords) + " coordinates (" + str(inv.boundary) +
                 " on the boundary, " + str(inv.interior) + " inside), beyond the bridge's bound of 2^24 (" +
                 str(SDV_BFR_MAX_COORDS) + "; OpenSubdiv counts them in int, which overflows beyond 2^31)");
        Bfr::Tessellation tess(p, n, rates.data(), topts);
        if (!tess.IsValid() || tess.GetNumBoundaryCoords() != inv.boundary ||
            tess.GetNumInteriorCoords() != inv.interior)
            throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + ": OpenSubdiv's tessellation is invalid or counts " +
                                                  "other coordinates than the bridge expected");
        long long facets = tess.GetNumFacets();
        if (facets < 0 || facets > SDV_BFR_MAX_FACETS)
            fail("face " + str(f) + ": its rates give " + str(facets) + " facets, beyond the bridge's bound of 2^25");
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        size_t first = edges.face_first[(size_t)f];
        for (int i = 0; i < n; ++i) {
            char &v = vertex_seen[(size_t)fv[i]];
            if (!v) ++t.points;
            v = 1;
            int e = edges.of_corner[first + (size_t)i];
            if (!edge_seen[(size_t)e]) t.points += edges.rate[(size_t)e] - 1;
            edge_seen[(size_t)e] = 1;
        }
        t.points += inv.interior;
        t.facets += facets;
        t.corners += facets * tess.GetFacetSize();
        if (uvs) t.uvs += coords;
    }
    if (t.points > SDV_BFR_MESH_MAX_POINTS)
        fail("the mesh's tessellation has " + str(t.points) + " points, beyond the bridge's bound of 2^25 (" +
             str(SDV_BFR_MESH_MAX_POINTS) + ")");
    if (t.facets > SDV_BFR_MESH_MAX_FACETS)
        fail("the mesh's tessellation has " + str(t.facets) + " facets, beyond the bridge's bound of 2^26 (" +
             str(SDV_BFR_MESH_MAX_FACETS) + ")");
    if (t.uvs > SDV_BFR_MESH_MAX_UVS)
        fail("the mesh's tessellation has " + str(t.uvs) +
             " texture coordinates (each face its own), beyond the bridge's bound of 2^26 (" +
             str(SDV_BFR_MESH_MAX_UVS) + ")");
    return t;
}

// normalize(cross(du, dv)) as glam computes DVec3::cross(..).normalize_or_zero()
// (the same operations in the same order), zero where the inverse length is
// not finite and positive.
void push_normal(std::vector<double> &out, const double du[3], const double dv[3]) {
    double n[3] = {du[1] * dv[2] - dv[1] * du[2], du[2] * dv[0] - dv[2] * du[0], du[0] * dv[1] - dv[0] * du[1]};
    double rcp = 1.0 / std::sqrt((n[0] * n[0] + n[1] * n[1]) + n[2] * n[2]);
    bool ok = std::isfinite(rcp) && rcp > 0.0;
    for (int k = 0; k < 3; ++k) out.push_back(ok ? n[k] * rcp : 0.0);
}

// Gathers `surface`'s control points from `points` (`size` reals of each
// of `available` points, `stride` apart) into its patch points.
void prepare(Surface const &surface, const double *points, long long available, int size, int stride, int face,
             std::vector<double> &patch) {
    check_bfr_control_points(surface, available, face);
    long long n = surface.GetNumPatchPoints();
    if (n < 1 || n * size > INT_MAX)
        fail("face " + str(face) + "'s surface has " + str(n) + " patch points of " + str(size) +
             " reals, which OpenSubdiv cannot index in int");
    patch.resize((size_t)(n * size));
    surface.PreparePatchPoints(points, Surface::PointDescriptor(size, stride), patch.data(),
                               Surface::PointDescriptor(size));
}

void tessellate(const sdv_refiner &rr, const sdv_bfr_mesh_input &in, sdv_bfr_mesh &m) {
    Far::TopologyRefiner const &tr = *rr.refiner;
    check_input(tr, in);
    Far::TopologyLevel const &base = tr.GetLevel(0);
    bool uvs = in.uvs != nullptr;
    bool linear_scheme = tr.GetSchemeType() == Sdc::SCHEME_BILINEAR;
    bool linear_fvar =
        linear_scheme || tr.GetSchemeOptions().GetFVarLinearInterpolation() == Sdc::Options::FVAR_LINEAR_ALL;

    Factory::Options fo;
    fo.SetApproxLevelSmooth(in.approx_level_smooth);
    fo.SetApproxLevelSharp(in.approx_level_sharp);
    fo.SetDefaultFVarID(0);
    fo.EnableCaching(false);
    Factory factory(tr, fo);
    if (factory.GetNumFaces() != base.GetNumFaces())
        throw ShimError(SDV_ERR_INTERNAL, "the surface factory counts another number of faces");

    Bfr::Tessellation::Options topts;
    topts.SetFacetSize(in.quads ? 4 : 3);
    topts.PreserveQuads(in.quads != 0);

    Edges edges = base_edges(base, in);
    Totals totals = plan(base, factory, edges, linear_scheme, linear_fvar, uvs, topts);
    m.positions.reserve((size_t)(3 * totals.points));
    if (in.normals) m.normals.reserve((size_t)(3 * totals.points));
    m.face_offsets.reserve((size_t)totals.facets + 1);
    m.face_vertices.reserve((size_t)totals.corners);
    m.facet_faces.reserve((size_t)totals.facets);
    if (uvs) {
        m.uvs.reserve((size_t)(2 * totals.uvs));
        m.uv_indices.reserve((size_t)totals.corners);
    }
    m.face_offsets.push_back(0);

    // The mesh point of every base vertex, and every base edge's first inner
    // point and the vertex its points run from (-1: none yet).
    std::vector<int> vertex_point((size_t)base.GetNumVertices(), -1);
    std::vector<int> edge_first(edges.rate.size(), -1), edge_start(edges.rate.size(), -1);
    long long num_points = 0;

    Surface surface, uv_surface;
    const Factory::FVarID uv_channel = 0;
    const int uv_size = std::min(in.uv_width, 2);
    std::vector<double> patch, uv_patch, coords, uv_out;
    std::vector<int> rates, boundary, facets, uv_facets;
    double p[3], du[3], dv[3];

    for (int f = 0; f < base.GetNumFaces(); ++f) {
        if (!totals.candidate[(size_t)f]) continue;
        osd_errors().clear();
        bool ok = uvs ? factory.InitSurfaces(f, &surface, &uv_surface, &uv_channel, 1)
                      : factory.InitVertexSurface(f, &surface);
        if (!osd_errors().empty())
            throw ShimError(SDV_ERR_OSD,
                            "OpenSubdiv reported errors building the surfaces of face " + str(f) + ": " + osd_errors());
        if (!ok || !surface.IsValid()) continue;
        if (uvs && !uv_surface.IsValid())
            throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + " has a vertex surface but no face-varying one");
        prepare(surface, in.positions, base.GetNumVertices(), 3, 3, f, patch);
        Surface::PointDescriptor desc(3);

        Bfr::Parameterization param = surface.GetParameterization();
        face_rates(edges, f, rates);
        int n = (int)rates.size();
        Bfr::Tessellation tess(param, n, rates.data(), topts);
        if (!tess.IsValid()) throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + "'s tessellation is invalid");
        int nc = tess.GetNumCoords(), nb = tess.GetNumBoundaryCoords();
        coords.resize(2 * (size_t)nc);
        tess.GetCoords(coords.data());

        // The new points this face evaluates, appended to the mesh's.
        auto evaluate = [&](int coord) {
            const double *uv = coords.data() + 2 * (size_t)coord;
            if (in.normals) {
                surface.Evaluate(uv, patch.data(), desc, p, du, dv);
                push_normal(m.normals, du, dv);
            } else {
                surface.Evaluate(uv, patch.data(), desc, p);
            }
            m.positions.insert(m.positions.end(), p, p + 3);
            return (int)num_points++;
        };

        // The boundary: each corner's point and each edge's inner points,
        // created by the first face using them.
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        size_t first = edges.face_first[(size_t)f];
        boundary.resize((size_t)nb);
        int b = 0;
        for (int i = 0; i < n; ++i) {
            Far::Index v = fv[i];
            int &vp = vertex_point[(size_t)v];
            if (vp < 0) vp = evaluate(b);
            boundary.at((size_t)b++) = vp;
            size_t e = (size_t)edges.of_corner[first + (size_t)i];
            int inner = rates[(size_t)i] - 1;
            if (b + inner > nb)
                throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + "'s tessellation has fewer boundary points");
            if (edge_first[e] < 0) {
                edge_first[e] = (int)num_points;
                edge_start[e] = v;
                for (int k = 0; k < inner; ++k, ++b) boundary[(size_t)b] = evaluate(b);
            } else if (edge_start[e] == v) {
                for (int k = 0; k < inner; ++k) boundary[(size_t)b++] = edge_first[e] + k;
            } else {
                for (int k = inner - 1; k >= 0; --k) boundary[(size_t)b++] = edge_first[e] + k;
            }
        }
        if (b != nb)
            throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + "'s tessellation has more boundary points");
        // The interior points, the face's own.
        int first_interior = (int)num_points;
        for (int k = nb; k < nc; ++k) evaluate(k);
        if (num_points > totals.points)
            throw ShimError(SDV_ERR_INTERNAL, "the tessellation has more points than counted");

        // Texture coordinates at every coordinate of the face.
        int uv_base = (int)(m.uvs.size() / 2);
        if (uvs) {
            prepare(uv_surface, in.uvs, base.GetNumFVarValues(0), uv_size, in.uv_width, f, uv_patch);
            Surface::PointDescriptor uv_desc(uv_size);
            uv_out.resize((size_t)uv_size);
            for (int k = 0; k < nc; ++k) {
                uv_surface.Evaluate(coords.data() + 2 * (size_t)k, uv_patch.data(), uv_desc, uv_out.data());
                m.uvs.push_back(uv_out[0]);
                m.uvs.push_back(uv_size > 1 ? uv_out[1] : 0.0);
            }
        }

        // The facets, renumbered to the mesh's points (and to the face's
        // texture coordinates), the -1 of a triangle among quads dropped.
        int fs = tess.GetFacetSize(), nfacets = tess.GetNumFacets();
        facets.resize((size_t)nfacets * (size_t)fs);
        if (nfacets) tess.GetFacets(facets.data());
        if (uvs) {
            uv_facets = facets;
            if (nfacets) tess.TransformFacetCoordIndices(uv_facets.data(), uv_base);
        }
        if (nfacets) tess.TransformFacetCoordIndices(facets.data(), boundary.data(), first_interior - nb);
        for (int k = 0; k < nfacets; ++k) {
            for (int j = 0; j < fs; ++j) {
                size_t at = (size_t)k * fs + j;
                if (facets[at] < 0) continue;
                if (facets[at] >= num_points)
                    throw ShimError(SDV_ERR_INTERNAL, "face " + str(f) + " has a facet beyond the points");
                m.face_vertices.push_back((uint32_t)facets[at]);
                if (uvs) m.uv_indices.push_back((uint32_t)uv_facets[at]);
            }
            m.face_offsets.push_back((uint32_t)m.face_vertices.size());
            m.facet_faces.push_back((uint32_t)f);
        }
    }
}

const sdv_bfr_mesh &need_mesh(const sdv_bfr_mesh *m) {
    if (!m) fail("null mesh");
    return *m;
}

template <typename T>
void check_out(const std::vector<T> &from, const T *to, size_t cap, const char *what) {
    check_cap(cap, (long long)from.size(), what);
    if (!from.empty() && !to) fail(std::string("null ") + what);
}

template <typename T>
void copy_out(const std::vector<T> &from, T *to) {
    if (!from.empty()) std::copy(from.begin(), from.end(), to);
}

}  // namespace

extern "C" {

int sdv_bfr_mesh_create(const sdv_refiner *r, const sdv_bfr_mesh_input *in, sdv_bfr_mesh **out, char *err,
                        size_t err_len) {
    return guarded(err, err_len, [&] {
        if (!out) fail("null output");
        *out = nullptr;
        const sdv_refiner &rr = need(r);
        if (!in) fail("null input");
        std::unique_ptr<sdv_bfr_mesh> h(new sdv_bfr_mesh());
        tessellate(rr, *in, *h);
        *out = h.release();
    });
}

void sdv_bfr_mesh_destroy(sdv_bfr_mesh *m) { delete m; }

void sdv_bfr_mesh_counts_get(const sdv_bfr_mesh *m, sdv_bfr_mesh_counts *out) {
    if (!out) return;
    *out = sdv_bfr_mesh_counts();
    if (!m) return;
    out->num_points = m->positions.size() / 3;
    out->num_normals = m->normals.size() / 3;
    out->num_facets = m->facet_faces.size();
    out->num_face_vertices = m->face_vertices.size();
    out->num_uvs = m->uvs.size() / 2;
    out->num_uv_indices = m->uv_indices.size();
}

int sdv_bfr_mesh_read(const sdv_bfr_mesh *m, const sdv_bfr_mesh_data *out, char *err, size_t err_len) {
    return guarded(err, err_len, [&] {
        const sdv_bfr_mesh &mm = need_mesh(m);
        if (!out) fail("null output");
        // Every buffer is checked before anything is written.
        check_out(mm.positions, out->positions, out->positions_cap, "positions");
        check_out(mm.normals, out->normals, out->normals_cap, "normals");
        check_out(mm.face_offsets, out->face_offsets, out->face_offsets_cap, "face offsets");
        check_out(mm.face_vertices, out->face_vertices, out->face_vertices_cap, "face vertices");
        check_out(mm.uvs, out->uvs, out->uvs_cap, "texture coordinates");
        check_out(mm.uv_indices, out->uv_indices, out->uv_indices_cap, "texture coordinate indices");
        check_out(mm.facet_faces, out->facet_faces, out->facet_faces_cap, "facet faces");
        copy_out(mm.positions, out->positions);
        copy_out(mm.normals, out->normals);
        copy_out(mm.face_offsets, out->face_offsets);
        copy_out(mm.face_vertices, out->face_vertices);
        copy_out(mm.uvs, out->uvs);
        copy_out(mm.uv_indices, out->uv_indices);
        copy_out(mm.facet_faces, out->facet_faces);
    });
}

}  // extern "C"
