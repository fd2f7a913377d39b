// far_tutorials: OpenSubdiv's far tutorials 5_1, 5_2 and 5_3 (3.5), run
// with their default arguments, each printing what the tutorial prints —
// the reference tests/far_tutorials.rs compares the Rust ports in
// examples/ with.
//
// Usage: far_tutorials 5_1|5_2|5_3
//
//   5_1  limit points and derivatives of a creased pyramid at 200
//        pseudo-random locations per ptex face (double precision), as a
//        Maya MEL script;
//   5_2  a 10 x 10 x 10 lattice of cubes split into 10 groups of faces,
//        each group refined adaptively (level 2) into a patch table of its
//        own, each face tessellated as a fan around its midpoint, as OBJ
//        (single precision);
//   5_3  limit stencils at five locations per face of a cube (level 2),
//        applied to the cube's points, as OBJ (single precision).
//
// Self-contained, as cpp/osd_driver.cpp: it shares no code with the crate's
// bridge. The tutorials' options are kept; their command-line arguments,
// OBJ input and timing options are not.

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

using namespace OpenSubdiv;

namespace {

// A point of REAL coordinates, interpolable by Far's primvar refiner and
// stencil tables.
template <typename REAL>
struct Point3 {
    REAL x[3];
    void Clear(void * = 0) { x[0] = x[1] = x[2] = 0; }
    void AddWithWeight(Point3 const & p, REAL w) {
        for (int k = 0; k < 3; ++k) x[k] += w * p.x[k];
    }
};

typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;

std::unique_ptr<Far::TopologyRefiner>
makeRefiner(std::vector<int> const & sizes, std::vector<int> const & verts,
            int nverts, Sdc::Options::VtxBoundaryInterpolation boundary,
            std::vector<int> const & creasePairs = std::vector<int>(),
            std::vector<float> const & creaseWeights = std::vector<float>()) {
    Far::TopologyDescriptor desc;
    desc.numVertices = nverts;
    desc.numFaces = (int)sizes.size();
    desc.numVertsPerFace = sizes.data();
    desc.vertIndicesPerFace = verts.data();
    desc.numCreases = (int)creaseWeights.size();
    desc.creaseVertexIndexPairs = creasePairs.empty() ? 0 : creasePairs.data();
    desc.creaseWeights = creaseWeights.empty() ? 0 : creaseWeights.data();
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(boundary);
    Far::TopologyRefiner * r = Factory::Create(
        desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc));
    if (!r) {
        fprintf(stderr, "far_tutorials: cannot build the refiner\n");
        exit(1);
    }
    return std::unique_ptr<Far::TopologyRefiner>(r);
}

// The unit cube of tutorials 5_2 and 5_3 centred at (ox, oy, oz), appended.
void appendCube(float ox, float oy, float oz, std::vector<int> & sizes,
                std::vector<int> & verts, std::vector<Point3<float> > & points) {
    static float const corners[8][3] = {
        {-0.5f, -0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f}, {-0.5f, 0.5f, 0.5f},
        {-0.5f, -0.5f, 0.5f},  {0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, -0.5f},
        {0.5f, 0.5f, 0.5f},    {0.5f, -0.5f, 0.5f}};
    static int const faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3},
                                    {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    int first = (int)points.size();
    for (int i = 0; i < 8; ++i) {
        Point3<float> p;
        p.x[0] = ox + corners[i][0];
        p.x[1] = oy + corners[i][1];
        p.x[2] = oz + corners[i][2];
        points.push_back(p);
    }
    for (int f = 0; f < 6; ++f) {
        sizes.push_back(4);
        for (int k = 0; k < 4; ++k) verts.push_back(first + faces[f][k]);
    }
}

// ---------------------------------------------------------------------------
// 5_1

int tutorial51() {
    typedef Point3<double> P;
    std::vector<int> sizes = {3, 3, 3, 3, 4};
    std::vector<int> verts = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 4, 3, 2, 1};
    std::vector<int> creases = {4, 3, 3, 2, 2, 1, 1, 4};
    std::vector<float> weights(4, 3.0f);
    auto refiner = makeRefiner(sizes, verts, 5, Sdc::Options::VTX_BOUNDARY_EDGE_ONLY,
                               creases, weights);

    Far::PatchTableFactory::Options po(3);
    po.SetPatchPrecision<double>();
    po.useInfSharpPatch = true;
    po.generateVaryingTables = false;
    po.endCapType = Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS;
    refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    std::unique_ptr<Far::PatchTable const> table(
        Far::PatchTableFactory::Create(*refiner, po));

    int nRefined = refiner->GetNumVerticesTotal();
    std::vector<P> points(nRefined + table->GetNumLocalPoints());
    double const base[5][3] = {{0, 0, 2}, {0, -2, 0}, {2, 0, 0}, {0, 2, 0}, {-2, 0, 0}};
    for (int i = 0; i < 5; ++i) std::memcpy(points[i].x, base[i], sizeof base[i]);
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    P * src = points.data();
    for (int level = 1; level < refiner->GetNumLevels(); ++level) {
        P * dst = src + refiner->GetLevel(level - 1).GetNumVertices();
        primvar.Interpolate(level, src, dst);
        src = dst;
    }
    if (table->GetNumLocalPoints()) {
        table->GetLocalPointStencilTable<double>()->UpdateValues(
            points.data(), points.data() + nRefined);
    }

    Far::PatchMap map(*table);
    Far::PtexIndices ptex(*refiner);
    int perFace = 200, n = perFace * ptex.GetNumFaces();
    std::vector<P> pos(n), du(n), dv(n);
    srand(2147483647);
    double w[20], ws[20], wt[20];
    for (int i = 0; i < n; ++i) {
        double s = (double)rand() / (double)RAND_MAX;
        double t = (double)rand() / (double)RAND_MAX;
        Far::PatchTable::PatchHandle const * h = map.FindPatch(i / perFace, s, t);
        if (!h) return 1;
        table->EvaluateBasis(*h, s, t, w, ws, wt);
        Far::ConstIndexArray cvs = table->GetPatchVertices(*h);
        pos[i].Clear(), du[i].Clear(), dv[i].Clear();
        for (int k = 0; k < cvs.size(); ++k) {
            pos[i].AddWithWeight(points[cvs[k]], w[k]);
            du[i].AddWithWeight(points[cvs[k]], ws[k]);
            dv[i].AddWithWeight(points[cvs[k]], wt[k]);
        }
    }

    printf("file -f -new;\n");
    char const * names[2] = {"deriv1", "deriv2"};
    std::vector<P> const * derivs[2] = {&du, &dv};
    for (int d = 0; d < 2; ++d) {
        printf("particle -n %s ", names[d]);
        for (int i = 0; i < n; ++i)
            printf("-p %f %f %f\n", pos[i].x[0], pos[i].x[1], pos[i].x[2]);
        printf(";\n");
        printf("setAttr \"%s.particleRenderType\" 6;\n", names[d]);
        printf("setAttr \"%s.velocity\" -type \"vectorArray\" %d ", names[d], n);
        for (int i = 0; i < n; ++i) {
            P const & v = (*derivs[d])[i];
            printf("%f %f %f\n", v.x[0], v.x[1], v.x[2]);
        }
        printf(";\n");
    }
    printf("currentTime -edit `currentTime -q`;\n");
    printf("select deriv1Shape deriv2Shape;\n");
    return 0;
}

// ---------------------------------------------------------------------------
// 5_2

int tutorial52() {
    typedef Point3<float> P;
    int const multiplier = 10, groups = 10, depth = 2;
    std::vector<int> sizes, verts;
    std::vector<P> base;
    for (int x = 0; x < multiplier; ++x)
        for (int y = 0; y < multiplier; ++y)
            for (int z = 0; z < multiplier; ++z)
                appendCube(2.0f * x, 2.0f * y, 2.0f * z, sizes, verts, base);
    auto baseRefiner = makeRefiner(sizes, verts, (int)base.size(),
                                   Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    Far::PtexIndices ptex(*baseRefiner);

    Far::PatchTableFactory::Options po(depth);
    po.generateVaryingTables = false;
    po.shareEndCapPatchPoints = false;
    po.endCapType = Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS;

    int nFaces = baseRefiner->GetNumFacesTotal();
    int small = nFaces / groups, larger = nFaces - groups * small;
    int objVerts = 0;
    for (int g = 0; g < groups; ++g) {
        int first = g * small + std::min(g, larger);
        int last = first + small + (g < larger ? 1 : 0);
        std::vector<Far::Index> faces;
        for (int f = first; f < last; ++f) faces.push_back(f);
        Far::ConstIndexArray selected(faces.data(), (int)faces.size());

        // A refiner sharing the base level, refined for the group only.
        std::unique_ptr<Far::TopologyRefiner> local(Factory::Create(*baseRefiner));
        local->RefineAdaptive(po.GetRefineAdaptiveOptions(), selected);
        std::unique_ptr<Far::PatchTable> table(
            Far::PatchTableFactory::Create(*local, po, selected));
        Far::PatchMap map(*table);

        // Refined and local points after the base ones, in one buffer here.
        int nBase = local->GetLevel(0).GetNumVertices();
        int nRefined = local->GetNumVerticesTotal();
        std::vector<P> points(nRefined + table->GetNumLocalPoints());
        std::copy(base.begin(), base.end(), points.begin());
        Far::PrimvarRefiner primvar(*local);
        P * src = points.data();
        for (int level = 1; level < local->GetNumLevels(); ++level) {
            P * dst = src + local->GetLevel(level - 1).GetNumVertices();
            primvar.Interpolate(level, src, dst);
            src = dst;
        }
        if (table->GetNumLocalPoints()) {
            table->GetLocalPointStencilTable()->UpdateValues(
                points.data(), nBase, points.data() + nBase,
                points.data() + nRefined);
        }

        printf("g patchGroup_%d\n", g);
        static float const quad[5][2] = {
            {0.5f, 0.5f}, {0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int f : faces) {
            int ptexFace = ptex.GetFaceId(f);
            for (int i = 0; i < 5; ++i) {
                float s = quad[i][0], t = quad[i][1];
                Far::PatchTable::PatchHandle const * h = map.FindPatch(ptexFace, s, t);
                if (!h) return 1;
                float w[20];
                table->EvaluateBasis(*h, s, t, w);
                Far::ConstIndexArray cvs = table->GetPatchVertices(*h);
                P p;
                p.Clear();
                for (int k = 0; k < cvs.size(); ++k) p.AddWithWeight(points[cvs[k]], w[k]);
                printf("v %f %f %f\n", p.x[0], p.x[1], p.x[2]);
            }
            int c = objVerts + 1;
            for (int k = 0; k < 4; ++k) printf("f %d %d %d\n", c, c + 1 + k, c + 1 + (k + 1) % 4);
            objVerts += 5;
        }
    }
    return 0;
}

// ---------------------------------------------------------------------------
// 5_3

// weights: instead of the OBJ text, each stencil's terms as "index=bits"
// (the float weights' bits in hex: position, du, dv), first derivatives on.
int tutorial53(bool weights) {
    typedef Point3<float> P;
    std::vector<int> sizes, verts;
    std::vector<P> base;
    appendCube(0, 0, 0, sizes, verts, base);
    auto refiner = makeRefiner(sizes, verts, 8, Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);

    Far::PatchTableFactory::Options po(2);
    po.useInfSharpPatch = true;
    po.generateLegacySharpCornerPatches = false;
    po.generateVaryingTables = false;
    po.generateFVarTables = false;
    po.endCapType = Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS;
    refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, po));

    // Five locations per quad: the middle, then near each corner.
    static float const s[5] = {0.5f, 0.05f, 0.95f, 0.95f, 0.05f};
    static float const t[5] = {0.5f, 0.05f, 0.05f, 0.95f, 0.95f};
    Far::PtexIndices ptex(*refiner);
    Far::TopologyLevel const & level0 = refiner->GetLevel(0);
    std::vector<Far::LimitStencilTableFactory::LocationArray> locations;
    int nPoints = 0;
    for (int f = 0; f < level0.GetNumFaces(); ++f) {
        Far::LimitStencilTableFactory::LocationArray a;
        a.ptexIdx = ptex.GetFaceId(f);
        a.numLocations = 5;
        a.s = s;
        a.t = t;
        locations.push_back(a);
        nPoints += 5;
    }
    Far::LimitStencilTableFactory::Options lo;
    lo.generate1stDerivatives = weights;
    std::unique_ptr<Far::LimitStencilTable const> stencils(
        Far::LimitStencilTableFactory::Create(*refiner, locations, 0, table.get(), lo));
    if (weights) {
        for (int i = 0; i < stencils->GetNumStencils(); ++i) {
            Far::LimitStencil st = stencils->GetLimitStencil(Far::Index(i));
            printf("%d:", i);
            for (int k = 0; k < st.GetSize(); ++k) {
                float const w[3] = {st.GetWeights()[k], st.GetDuWeights()[k], st.GetDvWeights()[k]};
                unsigned bits[3];
                std::memcpy(bits, w, sizeof bits);
                printf(" %d=%08x,%08x,%08x", st.GetVertexIndices()[k], bits[0], bits[1], bits[2]);
            }
            printf("\n");
        }
        return 0;
    }
    std::vector<P> limit(nPoints);
    stencils->UpdateValues(base.data(), limit.data());

    printf("g base_mesh\n");
    for (P const & p : limit) printf("v %f %f %f\n", p.x[0], p.x[1], p.x[2]);
    for (int f = 0, c = 1; f < level0.GetNumFaces(); ++f, c += 5) {
        for (int k = 0; k < 4; ++k) printf("f %d %d %d\n", c, c + 1 + k, c + 1 + (k + 1) % 4);
    }
    return 0;
}

} // namespace

int main(int argc, char ** argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: far_tutorials 5_1|5_2|5_3|5_3_weights\n");
        return 2;
    }
    if (!strcmp(argv[1], "5_1")) return tutorial51();
    if (!strcmp(argv[1], "5_2")) return tutorial52();
    if (!strcmp(argv[1], "5_3")) return tutorial53(false);
    if (!strcmp(argv[1], "5_3_weights")) return tutorial53(true);
    fprintf(stderr, "far_tutorials: no tutorial %s\n", argv[1]);
    return 2;
}
