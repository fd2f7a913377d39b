// osd_driver: an independent OpenSubdiv reference driver for conformance tests.
//
// Reads an OBJ file (with OpenSubdiv's "t" tag lines), refines it uniformly
// with Far::TopologyRefiner and writes the last level as OBJ, printing every
// coordinate with %.17g so two drivers computing the same doubles produce
// byte-identical files.
//
// Usage:
//   osd_driver INPUT.obj OUTPUT.obj [--level N] [--scheme catmark|loop|bilinear]
//   (OUTPUT "-" refines without writing anything, for whole-process benchmarks,
//   and prints the process's peak memory as "peak_memory_bytes N" on stderr)
//       [--boundary none|edge-only|edge-and-corner]
//       [--fvar none|corners-only|corners-plus1|corners-plus2|boundaries|all]
//       [--creasing uniform|chaikin] [--triangles catmark|smooth]
//   osd_driver INPUT.obj OUTPUT.json --adaptive N [--secondary M]
//       [--single-crease yes|no] [--inf-sharp yes|no] [--faces-first yes|no]
//       (and the options above): refines with RefineAdaptive instead and
//       writes every level as `subdiv refine --levels-json` does:
//       {"levels": [{"vertices": V, "edges": E, "faces": F,
//       "face_vertices": [[...], ...], "positions": [[x, y, z], ...]}, ...]},
//       holes included, positions interpolated level by level in double.
//   osd_driver INPUT.obj OUTPUT.txt --bfr-eval LOCATIONS.txt (and the options
//       above but the refinement's): each base face's limit surface the Bfr
//       way (Bfr::RefinerSurfaceFactory, default options: approximation
//       levels 2 and 6), evaluated at every location `FACE U V` of the file
//       (blank lines and `#` comments skipped): one line per location,
//       `x y z dx/du dy/du dz/du dx/dv dy/dv dz/dv` with %.17g. With
//       --bfr-random N the driver first writes LOCATIONS.txt itself: N
//       pseudo-random locations on every face with a limit surface, in its
//       Bfr parameterization (sub-faces of n-gons through
//       ConvertNormalizedSubFaceToCoord).
//   osd_driver INPUT.obj OUTPUT.obj --bfr-tessellate RATE [--bfr-quads yes|no]:
//       every base face with a limit surface tessellated at the uniform rate
//       (Bfr::Tessellation; triangles, or quads kept). As OpenSubdiv's bfr
//       tutorial 2_2 does, the point at a base vertex and the points inside a
//       base edge are evaluated by the first face that uses them and written
//       once (the boundary coordinates of a uniform pattern: each corner,
//       then the RATE - 1 points of the edge after it); a face's interior
//       points are its own. Then the facet count: `# facets N`.
//
// This file is deliberately self-contained: it shares no code with the crate's
// own C++ bridge, so agreement between the two is evidence, not tautology.

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/sdc/options.h>
#include <opensubdiv/sdc/types.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

// ---------------------------------------------------------------------------
// Errors

struct Failure : std::runtime_error {
    explicit Failure(const std::string &m) : std::runtime_error(m) {}
};

[[noreturn]] void fail(const std::string &msg) { throw Failure(msg); }

std::string where(int lineNo) { return "line " + std::to_string(lineNo) + ": "; }

// ---------------------------------------------------------------------------
// Primvar types for PrimvarRefinerReal<double>

struct Point3 {
    double x, y, z;
    void Clear(void * = 0) { x = y = z = 0.0; }
    void AddWithWeight(Point3 const &src, double w) {
        x += src.x * w;
        y += src.y * w;
        z += src.z * w;
    }
};

struct Point2 {
    double u, v;
    void Clear(void * = 0) { u = v = 0.0; }
    void AddWithWeight(Point2 const &src, double w) {
        u += src.u * w;
        v += src.v * w;
    }
};

// ---------------------------------------------------------------------------
// Parsed input

struct Tag {
    std::string name;
    std::vector<long> ints;
    std::vector<float> floats;
    std::vector<std::string> strings;
    int line;
};

struct ObjMesh {
    std::vector<Point3> positions;
    std::vector<Point2> uvs;
    std::vector<int> faceSizes;
    std::vector<int> faceVerts;
    std::vector<int> faceUvs;  // parallel to faceVerts when the mesh has uvs
    int facesWithUv = 0;
    std::vector<Tag> tags;
};

std::vector<std::string> splitWs(const std::string &s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string tok;
    while (in >> tok) out.push_back(tok);
    return out;
}

double parseDouble(const std::string &tok, int lineNo) {
    const char *b = tok.c_str();
    char *e = nullptr;
    errno = 0;
    double d = std::strtod(b, &e);
    if (e == b || *e != '\0') fail(where(lineNo) + "bad number '" + tok + "'");
    return d;
}

float parseFloat(const std::string &tok, int lineNo) {
    const char *b = tok.c_str();
    char *e = nullptr;
    float f = std::strtof(b, &e);
    if (e == b || *e != '\0') fail(where(lineNo) + "bad number '" + tok + "'");
    return f;
}

long parseLong(const std::string &tok, int lineNo) {
    const char *b = tok.c_str();
    char *e = nullptr;
    errno = 0;
    long l = std::strtol(b, &e, 10);
    if (e == b || *e != '\0' || errno == ERANGE)
        fail(where(lineNo) + "bad integer '" + tok + "'");
    return l;
}

// Resolves a 1-based (or negative, relative) OBJ index against `count`
// elements seen so far; returns a 0-based index.
int resolveIndex(const std::string &tok, size_t count, const char *what, int lineNo) {
    long i = parseLong(tok, lineNo);
    long r;
    if (i > 0)
        r = i - 1;
    else if (i < 0)
        r = (long)count + i;
    else
        fail(where(lineNo) + std::string(what) + " index 0 is invalid");
    if (r < 0 || r >= (long)count)
        fail(where(lineNo) + std::string(what) + " index " + tok + " out of range");
    return (int)r;
}

Tag parseTag(const std::vector<std::string> &tok, int lineNo) {
    // t NAME nI/nF/nS ints... floats... strings...
    if (tok.size() < 3) fail(where(lineNo) + "malformed tag line");
    Tag t;
    t.name = tok[1];
    t.line = lineNo;
    long n[3];
    {
        const std::string &c = tok[2];
        size_t s1 = c.find('/');
        size_t s2 = (s1 == std::string::npos) ? std::string::npos : c.find('/', s1 + 1);
        if (s1 == std::string::npos || s2 == std::string::npos)
            fail(where(lineNo) + "malformed tag counts '" + c + "'");
        n[0] = parseLong(c.substr(0, s1), lineNo);
        n[1] = parseLong(c.substr(s1 + 1, s2 - s1 - 1), lineNo);
        n[2] = parseLong(c.substr(s2 + 1), lineNo);
        if (n[0] < 0 || n[1] < 0 || n[2] < 0) fail(where(lineNo) + "negative tag count");
    }
    if ((long)tok.size() != 3 + n[0] + n[1] + n[2])
        fail(where(lineNo) + "tag '" + t.name + "' argument count does not match its header");
    size_t k = 3;
    for (long i = 0; i < n[0]; ++i) t.ints.push_back(parseLong(tok[k++], lineNo));
    for (long i = 0; i < n[1]; ++i) t.floats.push_back(parseFloat(tok[k++], lineNo));
    for (long i = 0; i < n[2]; ++i) t.strings.push_back(tok[k++]);
    return t;
}

ObjMesh parseObj(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open '" + path + "'");
    ObjMesh m;
    size_t normalCount = 0;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        size_t hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::vector<std::string> tok = splitWs(line);
        if (tok.empty()) continue;
        const std::string &kw = tok[0];
        if (kw == "v") {
            if (tok.size() < 4) fail(where(lineNo) + "vertex needs 3 coordinates");
            Point3 p;
            p.x = parseDouble(tok[1], lineNo);
            p.y = parseDouble(tok[2], lineNo);
            p.z = parseDouble(tok[3], lineNo);
            m.positions.push_back(p);
        } else if (kw == "vt") {
            if (tok.size() < 3) fail(where(lineNo) + "vt needs 2 coordinates");
            Point2 t;
            t.u = parseDouble(tok[1], lineNo);
            t.v = parseDouble(tok[2], lineNo);
            m.uvs.push_back(t);
        } else if (kw == "vn") {
            ++normalCount;
        } else if (kw == "f") {
            if (tok.size() < 4) fail(where(lineNo) + "face needs at least 3 corners");
            int n = (int)tok.size() - 1;
            int withUv = 0;
            for (int c = 0; c < n; ++c) {
                const std::string &corner = tok[c + 1];
                // split on '/'
                std::vector<std::string> parts;
                size_t start = 0;
                for (;;) {
                    size_t s = corner.find('/', start);
                    parts.push_back(corner.substr(start, s == std::string::npos ? std::string::npos : s - start));
                    if (s == std::string::npos) break;
                    start = s + 1;
                }
                if (parts.size() > 3 || parts[0].empty())
                    fail(where(lineNo) + "malformed face corner '" + corner + "'");
                m.faceVerts.push_back(resolveIndex(parts[0], m.positions.size(), "vertex", lineNo));
                if (parts.size() >= 2 && !parts[1].empty()) {
                    m.faceUvs.push_back(resolveIndex(parts[1], m.uvs.size(), "texture", lineNo));
                    ++withUv;
                }
                if (parts.size() == 3) {
                    if (parts[2].empty()) fail(where(lineNo) + "malformed face corner '" + corner + "'");
                    resolveIndex(parts[2], normalCount, "normal", lineNo);
                }
            }
            if (withUv != 0 && withUv != n)
                fail(where(lineNo) + "face mixes corners with and without texture coordinates");
            if (withUv) ++m.facesWithUv;
            m.faceSizes.push_back(n);
        } else if (kw == "t") {
            m.tags.push_back(parseTag(tok, lineNo));
        } else {
            // o, g, s, usemtl, mtllib, l, ...: not topology, ignored.
        }
    }
    if (m.facesWithUv != 0 && m.facesWithUv != (int)m.faceSizes.size())
        fail("some faces have texture coordinates and others do not");
    if (m.faceSizes.empty()) fail("the mesh has no faces");
    return m;
}

// ---------------------------------------------------------------------------
// Options

struct Settings {
    int level = 2;
    int adaptive = -1;  // the isolation level; -1: uniform refinement
    int secondary = 15;
    bool singleCrease = false, infSharp = false, facesFirst = false;
    std::string bfrEval;      // --bfr-eval LOCATIONS.txt
    int bfrRandom = 0;        // --bfr-random N
    int bfrRate = 0;          // --bfr-tessellate RATE
    bool bfrQuads = false;    // --bfr-quads yes|no
    Sdc::SchemeType scheme = Sdc::SCHEME_CATMARK;
    Sdc::Options opts;
};

struct Overrides {
    bool boundary = false, fvar = false, creasing = false, triangles = false;
    Sdc::Options::VtxBoundaryInterpolation boundaryV{};
    Sdc::Options::FVarLinearInterpolation fvarV{};
    Sdc::Options::CreasingMethod creasingV{};
    Sdc::Options::TriangleSubdivision trianglesV{};
};

void applyOptionTags(const ObjMesh &m, Sdc::Options &o) {
    typedef Sdc::Options O;
    for (const Tag &t : m.tags) {
        if (t.name == "interpolateboundary") {
            if (t.ints.size() != 1) fail(where(t.line) + "interpolateboundary expects 1 integer");
            switch (t.ints[0]) {
                case 0: o.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_NONE); break;
                case 1: o.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_EDGE_AND_CORNER); break;
                case 2: o.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_EDGE_ONLY); break;
                default: fail(where(t.line) + "unknown interpolateboundary value");
            }
        } else if (t.name == "facevaryinginterpolateboundary") {
            if (t.ints.size() != 1)
                fail(where(t.line) + "facevaryinginterpolateboundary expects 1 integer");
            switch (t.ints[0]) {
                case 0: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_NONE); break;
                case 1: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_CORNERS_ONLY); break;
                case 2: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_CORNERS_PLUS1); break;
                case 3: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_CORNERS_PLUS2); break;
                case 4: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_BOUNDARIES); break;
                case 5: o.SetFVarLinearInterpolation(O::FVAR_LINEAR_ALL); break;
                default: fail(where(t.line) + "unknown facevaryinginterpolateboundary value");
            }
        } else if (t.name == "creasemethod") {
            if (t.strings.size() != 1) fail(where(t.line) + "creasemethod expects 1 string");
            if (t.strings[0] == "normal")
                o.SetCreasingMethod(O::CREASE_UNIFORM);
            else if (t.strings[0] == "chaikin")
                o.SetCreasingMethod(O::CREASE_CHAIKIN);
            else
                fail(where(t.line) + "creasemethod must be normal or chaikin");
        } else if (t.name == "smoothtriangles") {
            if (t.strings.size() != 1) fail(where(t.line) + "smoothtriangles expects 1 string");
            if (t.strings[0] == "catmark")
                o.SetTriangleSubdivision(O::TRI_SUB_CATMARK);
            else if (t.strings[0] == "smooth")
                o.SetTriangleSubdivision(O::TRI_SUB_SMOOTH);
            else
                fail(where(t.line) + "smoothtriangles must be catmark or smooth");
        }
    }
}

// ---------------------------------------------------------------------------
// Topology

struct Tags {
    std::vector<Far::Index> creasePairs;
    std::vector<float> creaseWeights;
    std::vector<Far::Index> cornerVerts;
    std::vector<float> cornerWeights;
    std::vector<Far::Index> holes;
};

Tags collectTopologyTags(const ObjMesh &m) {
    Tags out;
    const long nv = (long)m.positions.size();
    const long nf = (long)m.faceSizes.size();
    for (const Tag &t : m.tags) {
        if (t.name == "crease") {
            size_t n = t.ints.size();
            if (n < 2) fail(where(t.line) + "crease needs at least 2 vertices");
            size_t edges = n - 1;
            if (t.floats.size() != 1 && t.floats.size() != edges)
                fail(where(t.line) + "crease needs 1 sharpness or one per edge");
            for (size_t i = 0; i < n; ++i)
                if (t.ints[i] < 0 || t.ints[i] >= nv) fail(where(t.line) + "crease vertex out of range");
            for (size_t e = 0; e < edges; ++e) {
                out.creasePairs.push_back((Far::Index)t.ints[e]);
                out.creasePairs.push_back((Far::Index)t.ints[e + 1]);
                out.creaseWeights.push_back(t.floats.size() == 1 ? t.floats[0] : t.floats[e]);
            }
        } else if (t.name == "corner") {
            size_t n = t.ints.size();
            if (n == 0) fail(where(t.line) + "corner needs at least 1 vertex");
            if (t.floats.size() != 1 && t.floats.size() != n)
                fail(where(t.line) + "corner needs 1 sharpness or one per vertex");
            for (size_t i = 0; i < n; ++i) {
                if (t.ints[i] < 0 || t.ints[i] >= nv) fail(where(t.line) + "corner vertex out of range");
                out.cornerVerts.push_back((Far::Index)t.ints[i]);
                out.cornerWeights.push_back(t.floats.size() == 1 ? t.floats[0] : t.floats[i]);
            }
        } else if (t.name == "hole") {
            for (long f : t.ints) {
                if (f < 0 || f >= nf) fail(where(t.line) + "hole face out of range");
                out.holes.push_back((Far::Index)f);
            }
        }
    }
    return out;
}

// ---------------------------------------------------------------------------
// OpenSubdiv messages go to stderr; errors are remembered.

bool g_osdError = false;
std::string g_osdErrorText;

void onOsdError(Far::ErrorType, const char *msg) {
    g_osdError = true;
    if (g_osdErrorText.empty()) g_osdErrorText = msg ? msg : "";
    std::fprintf(stderr, "osd_driver: OpenSubdiv error: %s\n", msg ? msg : "");
}

void onOsdWarning(const char *msg) {
    std::fprintf(stderr, "osd_driver: OpenSubdiv warning: %s\n", msg ? msg : "");
}

// ---------------------------------------------------------------------------
// Command line

void usage() {
    std::fprintf(stderr,
                 "usage: osd_driver INPUT.obj OUTPUT.obj [--level N] [--scheme catmark|loop|bilinear]\n"
                 "       [--boundary none|edge-only|edge-and-corner]\n"
                 "       [--fvar none|corners-only|corners-plus1|corners-plus2|boundaries|all]\n"
                 "       [--creasing uniform|chaikin] [--triangles catmark|smooth]\n"
                 "       [--adaptive N [--secondary M] [--single-crease yes|no] [--inf-sharp yes|no]\n"
                 "        [--faces-first yes|no]]\n"
                 "       [--bfr-eval LOCATIONS.txt [--bfr-random N] |\n"
                 "        --bfr-tessellate RATE [--bfr-quads yes|no]]\n");
}

// The process's peak resident memory (VmHWM), as `subdiv refine --peak-memory`
// reports its own.
void printPeakMemory() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.compare(0, 6, "VmHWM:") == 0) {
            long long kib = std::atoll(line.c_str() + 6);
            std::fprintf(stderr, "peak_memory_bytes %lld\n", kib * 1024);
            return;
        }
    }
}

// Writes `text` to `path` whole, or removes what was written.
void writeFile(const std::string &path, const std::string &text) {
    FILE *fp = std::fopen(path.c_str(), "wb");
    if (!fp) fail("cannot create '" + path + "': " + std::strerror(errno));
    size_t wrote = std::fwrite(text.data(), 1, text.size(), fp);
    int closed = std::fclose(fp);
    if (wrote != text.size() || closed != 0) {
        std::remove(path.c_str());
        fail("cannot write '" + path + "'");
    }
}

// Feature-adaptive refinement: every level's counts, faces and positions as
// JSON.
int writeAdaptive(Far::TopologyRefiner &refiner, const Settings &s, const ObjMesh &mesh,
                  const std::string &path) {
    Far::TopologyRefiner::AdaptiveOptions ao(s.adaptive);
    ao.SetSecondaryLevel(s.secondary);
    ao.useSingleCreasePatch = s.singleCrease;
    ao.useInfSharpPatch = s.infSharp;
    ao.orderVerticesFromFacesFirst = s.facesFirst;
    refiner.RefineAdaptive(ao);
    if (g_osdError) fail("OpenSubdiv reported an error during refinement: " + g_osdErrorText);

    Far::PrimvarRefinerReal<double> primvar(refiner);
    std::vector<Point3> pos(mesh.positions);
    std::string out = "{\"levels\": [";
    char buf[128];
    for (int l = 0; l <= refiner.GetMaxLevel(); ++l) {
        if (l > 0) {
            std::vector<Point3> next((size_t)refiner.GetLevel(l).GetNumVertices());
            Point3 const *src = pos.data();
            Point3 *dst = next.data();
            primvar.Interpolate(l, src, dst);
            pos.swap(next);
        }
        Far::TopologyLevel const &L = refiner.GetLevel(l);
        std::snprintf(buf, sizeof buf, "%s{\"vertices\": %d, \"edges\": %d, \"faces\": %d, ",
                      l ? ", " : "", L.GetNumVertices(), L.GetNumEdges(), L.GetNumFaces());
        out += buf;
        out += "\"face_vertices\": [";
        for (int f = 0; f < L.GetNumFaces(); ++f) {
            Far::ConstIndexArray fv = L.GetFaceVertices(f);
            out += f ? ", [" : "[";
            for (int c = 0; c < fv.size(); ++c) {
                std::snprintf(buf, sizeof buf, "%s%d", c ? ", " : "", fv[c]);
                out += buf;
            }
            out += "]";
        }
        out += "], \"positions\": [";
        for (size_t v = 0; v < pos.size(); ++v) {
            std::snprintf(buf, sizeof buf, "%s[%.17g, %.17g, %.17g]", v ? ", " : "", pos[v].x,
                          pos[v].y, pos[v].z);
            out += buf;
        }
        out += "]}";
    }
    out += "]}\n";
    if (g_osdError) fail("OpenSubdiv reported an error during interpolation: " + g_osdErrorText);
    writeFile(path, out);
    return 0;
}

// Bfr: `count` pseudo-random locations on every face with a limit surface,
// written to `path` as `FACE U V` lines.
void writeBfrLocations(Far::TopologyRefiner &refiner, int count, const std::string &path) {
    Bfr::RefinerSurfaceFactory<> factory(refiner);
    Bfr::Surface<double> surface;
    unsigned long long state = 0x9E3779B97F4A7C15ull;
    auto unit = [&state]() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (double)(state >> 11) / 9007199254740992.0;
    };
    std::string out;
    char buf[128];
    for (int f = 0; f < refiner.GetLevel(0).GetNumFaces(); ++f) {
        if (!factory.InitVertexSurface(f, &surface)) continue;
        Bfr::Parameterization p = surface.GetParameterization();
        for (int k = 0; k < count; ++k) {
            double uv[2] = {unit(), unit()};
            if (p.GetType() == Bfr::Parameterization::TRI && uv[0] + uv[1] > 1.0) {
                uv[0] = 1.0 - uv[0];
                uv[1] = 1.0 - uv[1];
            } else if (p.GetType() == Bfr::Parameterization::QUAD_SUBFACES) {
                int sub = (int)(unit() * p.GetFaceSize()) % p.GetFaceSize();
                double st[2] = {uv[0], uv[1]};
                p.ConvertNormalizedSubFaceToCoord(sub, st, uv);
            }
            std::snprintf(buf, sizeof buf, "%d %.17g %.17g\n", f, uv[0], uv[1]);
            out += buf;
        }
    }
    writeFile(path, out);
}

// Bfr: the limit surface of each base face at the locations of a file.
int writeBfrEval(Far::TopologyRefiner &refiner, const ObjMesh &mesh, const std::string &atPath,
                 const std::string &outPath) {
    std::ifstream in(atPath);
    if (!in) fail("cannot open '" + atPath + "'");
    Bfr::RefinerSurfaceFactory<> factory(refiner);
    Bfr::Surface<double> surface;
    Bfr::Surface<double>::PointDescriptor desc(3);
    std::vector<double> patch;
    double const *points = &mesh.positions[0].x;
    int current = -1;
    std::string line, out;
    char buf[512];
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        std::istringstream fields(line.substr(0, line.find('#')));
        std::string tf, tu, tv, extra;
        if (!(fields >> tf)) continue;
        if (!(fields >> tu >> tv) || (fields >> extra)) fail(where(lineNo) + "expected FACE U V");
        long face = parseLong(tf, lineNo);
        double uv[2] = {parseDouble(tu, lineNo), parseDouble(tv, lineNo)};
        if (face < 0 || face >= refiner.GetLevel(0).GetNumFaces()) {
            fail(where(lineNo) + "no face " + tf);
        }
        if (face != current) {
            if (!factory.InitVertexSurface((int)face, &surface)) {
                fail(where(lineNo) + "face " + tf + " has no limit surface");
            }
            patch.resize((size_t)surface.GetNumPatchPoints() * 3);
            surface.PreparePatchPoints(points, desc, patch.data(), desc);
            current = (int)face;
        }
        double P[3], Du[3], Dv[3];
        surface.Evaluate(uv, patch.data(), desc, P, Du, Dv);
        std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                      P[0], P[1], P[2], Du[0], Du[1], Du[2], Dv[0], Dv[1], Dv[2]);
        out += buf;
    }
    if (g_osdError) fail("OpenSubdiv reported an error: " + g_osdErrorText);
    writeFile(outPath, out);
    return 0;
}

// Bfr: every base face with a limit surface tessellated at a uniform rate,
// the points at base vertices and inside base edges evaluated by the first
// face using them; the points and the facet count.
int writeBfrTessellation(Far::TopologyRefiner &refiner, const ObjMesh &mesh, const Settings &s,
                         const std::string &outPath) {
    Bfr::RefinerSurfaceFactory<> factory(refiner);
    Bfr::Surface<double> surface;
    Bfr::Surface<double>::PointDescriptor desc(3);
    Bfr::Tessellation::Options topts;
    topts.PreserveQuads(s.bfrQuads).SetFacetSize(s.bfrQuads ? 4 : 3);
    Far::TopologyLevel const &base = refiner.GetLevel(0);
    // The face (plus one) that evaluates each base vertex's and edge's points.
    std::vector<int> vertexOwner((size_t)base.GetNumVertices(), 0);
    std::vector<int> edgeOwner((size_t)base.GetNumEdges(), 0);
    std::vector<double> patch, coords;
    double const *points = &mesh.positions[0].x;
    std::string verts;
    char buf[256];
    long long facets = 0;
    const int rate = s.bfrRate;
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        if (!factory.InitVertexSurface(f, &surface)) continue;
        patch.resize((size_t)surface.GetNumPatchPoints() * 3);
        surface.PreparePatchPoints(points, desc, patch.data(), desc);
        Bfr::Tessellation tess(surface.GetParameterization(), rate, topts);
        coords.resize((size_t)tess.GetNumCoords() * 2);
        tess.GetCoords(coords.data());
        Far::ConstIndexArray fv = base.GetFaceVertices(f);
        Far::ConstIndexArray fe = base.GetFaceEdges(f);
        if (tess.GetNumBoundaryCoords() != fv.size() * rate) fail("unexpected boundary coordinates");
        for (int c = 0; c < tess.GetNumCoords(); ++c) {
            if (c < tess.GetNumBoundaryCoords()) {
                int k = c / rate, j = c % rate;
                int &owner = j == 0 ? vertexOwner[(size_t)fv[k]] : edgeOwner[(size_t)fe[k]];
                if (owner == 0) owner = f + 1;
                if (owner != f + 1) continue;
            }
            double P[3];
            surface.Evaluate(&coords[2 * c], patch.data(), desc, P);
            std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", P[0], P[1], P[2]);
            verts += buf;
        }
        facets += tess.GetNumFacets();
    }
    if (g_osdError) fail("OpenSubdiv reported an error: " + g_osdErrorText);
    std::snprintf(buf, sizeof buf, "# facets %lld\n", facets);
    writeFile(outPath, verts + buf);
    return 0;
}

int run(int argc, char **argv) {
    std::vector<std::string> positional;
    Settings s;
    Overrides ov;
    typedef Sdc::Options O;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a.size() > 2 && a[0] == '-' && a[1] == '-') {
            if (i + 1 >= argc) fail("missing value for " + a);
            std::string v = argv[++i];
            if (a == "--level") {
                long l = parseLong(v, 0);
                if (l < 0 || l > 15) fail("level must be in 0..=15");
                s.level = (int)l;
            } else if (a == "--adaptive" || a == "--secondary") {
                long l = parseLong(v, 0);
                if (l < 0 || l > 15) fail(a + " must be in 0..=15");
                (a == "--adaptive" ? s.adaptive : s.secondary) = (int)l;
            } else if (a == "--bfr-eval") {
                s.bfrEval = v;
            } else if (a == "--bfr-random") {
                long n = parseLong(v, 0);
                if (n < 1 || n > 1000) fail("--bfr-random takes a count in 1..=1000");
                s.bfrRandom = (int)n;
            } else if (a == "--bfr-tessellate") {
                long r = parseLong(v, 0);
                if (r < 1 || r > 64) fail("--bfr-tessellate takes a rate in 1..=64");
                s.bfrRate = (int)r;
            } else if (a == "--single-crease" || a == "--inf-sharp" || a == "--faces-first" ||
                       a == "--bfr-quads") {
                if (v != "yes" && v != "no") fail(a + " takes yes or no");
                bool on = v == "yes";
                if (a == "--bfr-quads") s.bfrQuads = on;
                else if (a == "--single-crease") s.singleCrease = on;
                else if (a == "--inf-sharp") s.infSharp = on;
                else s.facesFirst = on;
            } else if (a == "--scheme") {
                if (v == "catmark") s.scheme = Sdc::SCHEME_CATMARK;
                else if (v == "loop") s.scheme = Sdc::SCHEME_LOOP;
                else if (v == "bilinear") s.scheme = Sdc::SCHEME_BILINEAR;
                else fail("unknown scheme '" + v + "'");
            } else if (a == "--boundary") {
                ov.boundary = true;
                if (v == "none") ov.boundaryV = O::VTX_BOUNDARY_NONE;
                else if (v == "edge-only") ov.boundaryV = O::VTX_BOUNDARY_EDGE_ONLY;
                else if (v == "edge-and-corner") ov.boundaryV = O::VTX_BOUNDARY_EDGE_AND_CORNER;
                else fail("unknown boundary '" + v + "'");
            } else if (a == "--fvar") {
                ov.fvar = true;
                if (v == "none") ov.fvarV = O::FVAR_LINEAR_NONE;
                else if (v == "corners-only") ov.fvarV = O::FVAR_LINEAR_CORNERS_ONLY;
                else if (v == "corners-plus1") ov.fvarV = O::FVAR_LINEAR_CORNERS_PLUS1;
                else if (v == "corners-plus2") ov.fvarV = O::FVAR_LINEAR_CORNERS_PLUS2;
                else if (v == "boundaries") ov.fvarV = O::FVAR_LINEAR_BOUNDARIES;
                else if (v == "all") ov.fvarV = O::FVAR_LINEAR_ALL;
                else fail("unknown fvar '" + v + "'");
            } else if (a == "--creasing") {
                ov.creasing = true;
                if (v == "uniform") ov.creasingV = O::CREASE_UNIFORM;
                else if (v == "chaikin") ov.creasingV = O::CREASE_CHAIKIN;
                else fail("unknown creasing '" + v + "'");
            } else if (a == "--triangles") {
                ov.triangles = true;
                if (v == "catmark") ov.trianglesV = O::TRI_SUB_CATMARK;
                else if (v == "smooth") ov.trianglesV = O::TRI_SUB_SMOOTH;
                else fail("unknown triangles '" + v + "'");
            } else {
                usage();
                fail("unknown option " + a);
            }
        } else {
            positional.push_back(a);
        }
    }
    if (positional.size() != 2) {
        usage();
        fail("expected INPUT.obj and OUTPUT.obj");
    }

    ObjMesh mesh = parseObj(positional[0]);

    // Shape-file defaults, then tags, then command-line overrides.
    s.opts.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_EDGE_ONLY);
    s.opts.SetFVarLinearInterpolation(O::FVAR_LINEAR_ALL);
    s.opts.SetCreasingMethod(O::CREASE_UNIFORM);
    s.opts.SetTriangleSubdivision(O::TRI_SUB_CATMARK);
    applyOptionTags(mesh, s.opts);
    if (ov.boundary) s.opts.SetVtxBoundaryInterpolation(ov.boundaryV);
    if (ov.fvar) s.opts.SetFVarLinearInterpolation(ov.fvarV);
    if (ov.creasing) s.opts.SetCreasingMethod(ov.creasingV);
    if (ov.triangles) s.opts.SetTriangleSubdivision(ov.trianglesV);

    Tags tags = collectTopologyTags(mesh);
    const bool hasUv = mesh.facesWithUv > 0;

    Far::TopologyDescriptor desc;
    desc.numVertices = (int)mesh.positions.size();
    desc.numFaces = (int)mesh.faceSizes.size();
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.faceVerts.data();
    desc.numCreases = (int)tags.creaseWeights.size();
    desc.creaseVertexIndexPairs = tags.creasePairs.empty() ? nullptr : tags.creasePairs.data();
    desc.creaseWeights = tags.creaseWeights.empty() ? nullptr : tags.creaseWeights.data();
    desc.numCorners = (int)tags.cornerWeights.size();
    desc.cornerVertexIndices = tags.cornerVerts.empty() ? nullptr : tags.cornerVerts.data();
    desc.cornerWeights = tags.cornerWeights.empty() ? nullptr : tags.cornerWeights.data();
    desc.numHoles = (int)tags.holes.size();
    desc.holeIndices = tags.holes.empty() ? nullptr : tags.holes.data();
    desc.isLeftHanded = false;

    Far::TopologyDescriptor::FVarChannel channel;
    if (hasUv) {
        channel.numValues = (int)mesh.uvs.size();
        channel.valueIndices = mesh.faceUvs.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
    } else {
        desc.numFVarChannels = 0;
        desc.fvarChannels = nullptr;
    }

    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(s.scheme, s.opts)));
    if (!refiner) {
        fail("TopologyRefinerFactory::Create failed" +
             (g_osdErrorText.empty() ? std::string() : ": " + g_osdErrorText));
    }

    if (s.adaptive >= 0) return writeAdaptive(*refiner, s, mesh, positional[1]);
    if (!s.bfrEval.empty()) {
        if (s.bfrRandom > 0) writeBfrLocations(*refiner, s.bfrRandom, s.bfrEval);
        return writeBfrEval(*refiner, mesh, s.bfrEval, positional[1]);
    }
    if (s.bfrRate > 0) return writeBfrTessellation(*refiner, mesh, s, positional[1]);
    if (s.level > 0) {
        Far::TopologyRefiner::UniformOptions uopts(s.level);
        refiner->RefineUniform(uopts);
    }
    if (g_osdError) fail("OpenSubdiv reported an error during refinement: " + g_osdErrorText);
    const int maxLevel = refiner->GetMaxLevel();
    if (maxLevel != s.level) fail("refiner reached level " + std::to_string(maxLevel));

    Far::PrimvarRefinerReal<double> primvar(*refiner);

    std::vector<Point3> pos(mesh.positions);
    for (int l = 1; l <= maxLevel; ++l) {
        std::vector<Point3> next((size_t)refiner->GetLevel(l).GetNumVertices());
        Point3 const *src = pos.data();
        Point3 *dst = next.data();
        primvar.Interpolate(l, src, dst);
        pos.swap(next);
    }

    std::vector<Point2> uv;
    if (hasUv) {
        uv = mesh.uvs;
        for (int l = 1; l <= maxLevel; ++l) {
            std::vector<Point2> next((size_t)refiner->GetLevel(l).GetNumFVarValues(0));
            Point2 const *src = uv.data();
            Point2 *dst = next.data();
            primvar.InterpolateFaceVarying(l, src, dst, 0);
            uv.swap(next);
        }
    }
    if (g_osdError) fail("OpenSubdiv reported an error during interpolation: " + g_osdErrorText);

    Far::TopologyLevel const &last = refiner->GetLevel(maxLevel);
    if ((int)pos.size() != last.GetNumVertices()) fail("vertex count mismatch");

    // OUTPUT "-" skips writing: the refinement alone, for benchmarks.
    if (positional[1] == "-") {
        printPeakMemory();
        return 0;
    }

    std::string out;
    out.reserve(pos.size() * 64 + (size_t)last.GetNumFaces() * 32);
    char buf[128];
    for (const Point3 &p : pos) {
        std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
        out += buf;
    }
    if (hasUv) {
        for (const Point2 &t : uv) {
            std::snprintf(buf, sizeof buf, "vt %.17g %.17g\n", t.u, t.v);
            out += buf;
        }
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        out += 'f';
        if (hasUv) {
            Far::ConstIndexArray ft = last.GetFaceFVarValues(f, 0);
            if (ft.size() != fv.size()) fail("face-varying face size mismatch");
            for (int c = 0; c < fv.size(); ++c) {
                std::snprintf(buf, sizeof buf, " %d/%d", fv[c] + 1, ft[c] + 1);
                out += buf;
            }
        } else {
            for (int c = 0; c < fv.size(); ++c) {
                std::snprintf(buf, sizeof buf, " %d", fv[c] + 1);
                out += buf;
            }
        }
        out += '\n';
    }

    writeFile(positional[1], out);
    return 0;
}

}  // namespace

int main(int argc, char **argv) {
    Far::SetErrorCallback(onOsdError);
    Far::SetWarningCallback(onOsdWarning);
    try {
        return run(argc, argv);
    } catch (const Failure &e) {
        std::fprintf(stderr, "osd_driver: %s\n", e.what());
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "osd_driver: internal error: %s\n", e.what());
        return 1;
    } catch (...) {
        std::fprintf(stderr, "osd_driver: unknown internal error\n");
        return 1;
    }
}
