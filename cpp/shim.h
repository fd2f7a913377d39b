/*
 * subdiv shim: a plain C ABI over OpenSubdiv's Far layer (and Bfr's
 * Tessellation and Parameterization, cpp/bfr.cpp, its limit surfaces,
 * cpp/bfr_surface.cpp, and a whole mesh tessellated with them,
 * cpp/bfr_mesh.cpp).
 *
 * No C++ type crosses this header. Every function returns SDV_OK (0) or a
 * negative status and, on failure, writes a NUL-terminated message into the
 * caller's `err` buffer (at most `err_len` bytes, truncated if needed).
 * Every C++ exception is caught inside the shim, and every index of a
 * descriptor is range-checked before OpenSubdiv sees it.
 *
 * Output arrays are caller-allocated: each getter takes the buffer and its
 * capacity in elements and fails (without writing) when the capacity is
 * smaller than the count reported by the matching counts or size query.
 */
#ifndef SUBDIV_SHIM_H
#define SUBDIV_SHIM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SDV_OK = 0,
    SDV_ERR_INVALID = -1,  /* bad argument or descriptor */
    SDV_ERR_OSD = -2,      /* OpenSubdiv reported an error */
    SDV_ERR_CAPACITY = -3, /* an output buffer is too small */
    SDV_ERR_INTERNAL = -4, /* an exception, out of memory */
    SDV_ERR_UNSAFE = -5    /* OpenSubdiv would read or write out of bounds, or overflow, on this input */
};

/* Opaque refiner: owns a Far::TopologyRefiner. */
typedef struct sdv_refiner sdv_refiner;
/* Opaque stencil table in CSR form. */
typedef struct sdv_stencils sdv_stencils;

typedef struct sdv_fvar_channel {
    int32_t num_values;
    const int32_t *value_indices; /* one per face corner */
} sdv_fvar_channel;

typedef struct sdv_mesh_desc {
    int32_t num_vertices;
    int32_t num_faces;
    const int32_t *face_sizes;    /* num_faces entries */
    const int32_t *face_vertices; /* sum(face_sizes) entries */
    int32_t num_creases;
    const int32_t *crease_vertex_pairs; /* 2 * num_creases */
    const float *crease_sharpness;      /* num_creases */
    int32_t num_corners;
    const int32_t *corner_vertices;
    const float *corner_sharpness;
    int32_t num_holes;
    const int32_t *holes;
    int32_t num_fvar_channels;
    const sdv_fvar_channel *fvar_channels;
    int32_t is_left_handed; /* TopologyDescriptor::isLeftHanded: faces listed clockwise */
} sdv_mesh_desc;

/* Numeric values are those of Sdc::SchemeType and Sdc::Options. */
typedef struct sdv_options {
    int32_t scheme;     /* 0 bilinear, 1 catmark, 2 loop */
    int32_t boundary;   /* 0 none, 1 edge-only, 2 edge-and-corner */
    int32_t fvar;       /* 0 none .. 5 all */
    int32_t creasing;   /* 0 uniform, 1 chaikin */
    int32_t triangles;  /* 0 catmark, 1 smooth */
} sdv_options;

typedef struct sdv_level_counts {
    int32_t vertices;
    int32_t edges;
    int32_t faces;
    int32_t face_vertices;
    /* 0 for a last level refined without full topology: its edge-vertex
       relation is not built, so edge queries fail for it. */
    int32_t full_topology;
} sdv_level_counts;

/* Primvar kinds for sdv_interpolate_*. */
enum { SDV_VERTEX = 0, SDV_VARYING = 1, SDV_FACE_VARYING = 2 };

/* Version as "3.5.0" and as 30500. */
const char *sdv_osd_version(void);
int32_t sdv_osd_version_number(void);

int sdv_refiner_create(const sdv_mesh_desc *desc, const sdv_options *opts,
                       sdv_refiner **out, char *err, size_t err_len);
void sdv_refiner_destroy(sdv_refiner *r);

/* Warnings OpenSubdiv emitted while building the refiner, '\n'-separated. */
int sdv_refiner_warnings(const sdv_refiner *r, char *buf, size_t buf_len, size_t *needed);

int sdv_refiner_refine_uniform(sdv_refiner *r, int32_t level, int32_t faces_first,
                               int32_t full_topology_last_level, char *err, size_t err_len);

/*
 * Far::TopologyRefiner::AdaptiveOptions, field by field (flags 0 or 1).
 * isolation_level 0..10 and secondary_level 0..15 (OpenSubdiv stores both
 * in 4 bits: the shim refuses what would wrap).
 */
typedef struct sdv_adaptive_options {
    int32_t isolation_level;
    int32_t secondary_level;
    int32_t single_crease_patch;
    int32_t inf_sharp_patch;
    int32_t consider_fvar_channels;
    int32_t faces_first;
} sdv_adaptive_options;

/*
 * Far::TopologyRefiner::RefineAdaptive. `faces` lists the base faces to
 * consider (num_faces entries, each in range); none (num_faces 0) means
 * every face. Refused on a refiner already refined. Every adaptive level,
 * the last included, has full topology.
 */
int sdv_refiner_refine_adaptive(sdv_refiner *r, const sdv_adaptive_options *opts,
                                const int32_t *faces, size_t num_faces, char *err,
                                size_t err_len);

int32_t sdv_refiner_max_level(const sdv_refiner *r);
int32_t sdv_refiner_num_fvar_channels(const sdv_refiner *r);

int sdv_level_counts_get(const sdv_refiner *r, int32_t level, sdv_level_counts *out,
                         char *err, size_t err_len);
/* face sizes (faces), face vertices (face_vertices) */
int sdv_level_faces(const sdv_refiner *r, int32_t level, int32_t *sizes, size_t sizes_cap,
                    int32_t *verts, size_t verts_cap, char *err, size_t err_len);
/* 2 * edges */
int sdv_level_edge_vertices(const sdv_refiner *r, int32_t level, int32_t *out, size_t cap,
                            char *err, size_t err_len);
int sdv_level_edge_sharpness(const sdv_refiner *r, int32_t level, float *out, size_t cap,
                             char *err, size_t err_len);
int sdv_level_vertex_sharpness(const sdv_refiner *r, int32_t level, float *out, size_t cap,
                               char *err, size_t err_len);
/* 1 for hole faces, 0 otherwise */
int sdv_level_face_holes(const sdv_refiner *r, int32_t level, uint8_t *out, size_t cap,
                         char *err, size_t err_len);
int sdv_level_fvar_value_count(const sdv_refiner *r, int32_t level, int32_t channel,
                               int32_t *out, char *err, size_t err_len);
/* face_vertices entries: the value index of every face corner */
int sdv_level_fvar_face_values(const sdv_refiner *r, int32_t level, int32_t channel,
                               int32_t *out, size_t cap, char *err, size_t err_len);

/* A caller's output buffer of int32 values and its capacity. */
typedef struct sdv_ibuf {
    int32_t *data;
    size_t cap;
} sdv_ibuf;

/* A caller's output buffer of bytes and its capacity. */
typedef struct sdv_bbuf {
    uint8_t *data;
    size_t cap;
} sdv_bbuf;

/*
 * Sizes of the child maps of `level` (0 <= level < max level): the total
 * number of child faces and of interior child edges over its faces.
 */
int sdv_level_child_sizes(const sdv_refiner *r, int32_t level, int32_t *face_child_faces,
                          int32_t *face_child_edges, char *err, size_t err_len);

/*
 * The child maps of `level` (0 <= level < max level), Far::TopologyLevel's
 * child queries; -1 for a child sparse refinement did not create.
 */
typedef struct sdv_child_maps {
    sdv_ibuf face_child_face_counts; /* faces */
    sdv_ibuf face_child_faces;       /* sdv_level_child_sizes' face_child_faces */
    sdv_ibuf face_child_edge_counts; /* faces */
    sdv_ibuf face_child_edges;       /* sdv_level_child_sizes' face_child_edges */
    sdv_ibuf edge_child_edges;       /* 2 * edges */
    sdv_ibuf face_child_vertex;      /* faces (Loop: all -1) */
    sdv_ibuf edge_child_vertex;      /* edges */
    sdv_ibuf vertex_child_vertex;    /* vertices */
    sdv_ibuf child_face_parent_face; /* faces of level + 1 */
} sdv_child_maps;

int sdv_level_child_maps(const sdv_refiner *r, int32_t level, const sdv_child_maps *out, char *err,
                         size_t err_len);

/*
 * Sizes of the relations of `level` (a level with full topology): the
 * total number of edge-faces, vertex-faces and vertex-edges.
 */
int sdv_level_relation_sizes(const sdv_refiner *r, int32_t level, int32_t *edge_faces,
                             int32_t *vertex_faces, int32_t *vertex_edges, char *err, size_t err_len);

/* Bits of sdv_relations' vertex_flags and edge_flags (Far::TopologyLevel's Is* queries). */
enum {
    SDV_VTX_BOUNDARY = 1,        /* IsVertexBoundary */
    SDV_VTX_CORNER = 2,          /* IsVertexCorner */
    SDV_VTX_VALENCE_REGULAR = 4, /* IsVertexValenceRegular */
    SDV_VTX_NON_MANIFOLD = 8,    /* IsVertexNonManifold */
    SDV_VTX_INF_SHARP = 16,      /* IsVertexInfSharp */
    SDV_VTX_SEMI_SHARP = 32      /* IsVertexSemiSharp */
};
enum {
    SDV_EDGE_NON_MANIFOLD = 1, /* IsEdgeNonManifold */
    SDV_EDGE_BOUNDARY = 2,     /* IsEdgeBoundary */
    SDV_EDGE_INF_SHARP = 4,    /* IsEdgeInfSharp */
    SDV_EDGE_SEMI_SHARP = 8    /* IsEdgeSemiSharp */
};
/* Vertex rules: Sdc::Crease::Rule as 0 smooth, 1 dart, 2 crease, 3 corner, -1 unknown. */
enum { SDV_RULE_UNKNOWN = -1, SDV_RULE_SMOOTH = 0, SDV_RULE_DART = 1, SDV_RULE_CREASE = 2, SDV_RULE_CORNER = 3 };

/* The relations of a level with full topology; local indices as int32. */
typedef struct sdv_relations {
    sdv_ibuf face_edges;         /* face_vertices */
    sdv_ibuf edge_face_counts;   /* edges */
    sdv_ibuf edge_faces;         /* edge_faces total */
    sdv_ibuf edge_face_local;    /* edge_faces total */
    sdv_ibuf vertex_face_counts; /* vertices */
    sdv_ibuf vertex_faces;       /* vertex_faces total */
    sdv_ibuf vertex_face_local;  /* vertex_faces total */
    sdv_ibuf vertex_edge_counts; /* vertices */
    sdv_ibuf vertex_edges;       /* vertex_edges total */
    sdv_ibuf vertex_edge_local;  /* vertex_edges total */
    sdv_ibuf vertex_rule;        /* vertices: SDV_RULE_* */
    sdv_bbuf vertex_flags;       /* vertices: SDV_VTX_* bits */
    sdv_bbuf edge_flags;         /* edges: SDV_EDGE_* bits */
} sdv_relations;

int sdv_level_relations(const sdv_refiner *r, int32_t level, const sdv_relations *out, char *err,
                        size_t err_len);

/*
 * Far::PtexIndices of the base level: `ids` receives the first ptex face of
 * every base face and, last, the number of ptex faces (faces + 1 entries).
 */
int sdv_ptex_face_ids(const sdv_refiner *r, int32_t *ids, size_t cap, char *err, size_t err_len);
/*
 * Far::PtexIndices::GetAdjacency of base face `face`, sub-face `quadrant`
 * (0 for a regular face, 0..n-1 for an n-sided irregular face): 4 ptex
 * faces (-1 where none) and 4 edges of those faces.
 */
int sdv_ptex_adjacency(const sdv_refiner *r, int32_t face, int32_t quadrant, int32_t adj_faces[4],
                       int32_t adj_edges[4], char *err, size_t err_len);

/*
 * Interpolates one level: `src` holds the data of level-1 (width values per
 * element), `dst` receives the data of `level`. kind is SDV_VERTEX,
 * SDV_VARYING or SDV_FACE_VARYING (then `channel` names the channel).
 */
int sdv_interpolate_f32(const sdv_refiner *r, int32_t kind, int32_t channel, int32_t level,
                        int32_t width, const float *src, size_t src_len, float *dst,
                        size_t dst_len, char *err, size_t err_len);
int sdv_interpolate_f64(const sdv_refiner *r, int32_t kind, int32_t channel, int32_t level,
                        int32_t width, const double *src, size_t src_len, double *dst,
                        size_t dst_len, char *err, size_t err_len);

/*
 * Limit positions and tangents at the vertices of the last level, from data
 * at that level (PrimvarRefiner::Limit). tan1/tan2 may be NULL together.
 */
int sdv_limit_f32(const sdv_refiner *r, int32_t width, const float *src, size_t src_len,
                  float *pos, float *tan1, float *tan2, size_t dst_len, char *err,
                  size_t err_len);
int sdv_limit_f64(const sdv_refiner *r, int32_t width, const double *src, size_t src_len,
                  double *pos, double *tan1, double *tan2, size_t dst_len, char *err,
                  size_t err_len);
/* Limit face-varying values of `channel` at the last level. */
int sdv_limit_fvar_f32(const sdv_refiner *r, int32_t channel, int32_t width, const float *src,
                       size_t src_len, float *dst, size_t dst_len, char *err, size_t err_len);
int sdv_limit_fvar_f64(const sdv_refiner *r, int32_t channel, int32_t width, const double *src,
                       size_t src_len, double *dst, size_t dst_len, char *err, size_t err_len);

/*
 * Stencil tables mapping base vertices to the vertices of the last level.
 * SDV_STENCIL_REFINED: Far::StencilTableFactory (interpolation mode vertex).
 * SDV_STENCIL_LIMIT: the stencils of PrimvarRefiner::Limit (needs
 * full topology in the last level); rows are positions, then du, then dv
 * tangents, each with one stencil per last-level vertex.
 */
enum { SDV_STENCIL_REFINED = 0, SDV_STENCIL_LIMIT = 1 };
int sdv_stencils_create(const sdv_refiner *r, int32_t kind, sdv_stencils **out, char *err,
                        size_t err_len);
void sdv_stencils_destroy(sdv_stencils *s);
/*
 * Far::StencilTableFactoryReal<double>::Create(refiner, options) with every
 * field of StencilTableFactory::Options (interpolation: 0 vertex, 1 varying,
 * 2 face-varying; max_level 0..15). Refused first: an unknown mode, a level
 * beyond 15, face-varying without that channel, and control vertices with
 * neither intermediate levels nor factorization on a refined refiner (3.5
 * loops and writes out of bounds on it). Works after uniform and adaptive
 * refinement.
 */
typedef struct sdv_stencil_options {
    int32_t interpolation;
    int32_t fvar_channel;
    int32_t generate_offsets;
    int32_t generate_control_verts;
    int32_t generate_intermediate_levels;
    int32_t factorize_intermediate_levels;
    int32_t max_level;
} sdv_stencil_options;
int sdv_stencils_create_with(const sdv_refiner *r, const sdv_stencil_options *o, sdv_stencils **out,
                             char *err, size_t err_len);

/* rows = number of stencils (all blocks), nnz = total number of weights */
void sdv_stencils_size(const sdv_stencils *s, size_t *rows, size_t *nnz);
/* sizes: rows, offsets: rows, indices/weights: nnz */
int sdv_stencils_export(const sdv_stencils *s, int32_t *sizes, int32_t *offsets,
                        int32_t *indices, double *weights, size_t rows_cap, size_t nnz_cap,
                        char *err, size_t err_len);

/*
 * OpenSubdiv's production stencil path: a float Far::StencilTable for the
 * last level (vertex interpolation, no intermediate levels), applied by
 * Osd::CpuEvaluator::EvalStencils to interleaved float primvars of `width`
 * components per vertex.
 */
typedef struct sdv_evaluator sdv_evaluator;
int sdv_evaluator_create(const sdv_refiner *r, sdv_evaluator **out, char *err, size_t err_len);
void sdv_evaluator_destroy(sdv_evaluator *e);
/* number of control (base) vertices and of stencils (last-level vertices) */
void sdv_evaluator_counts(const sdv_evaluator *e, int32_t *controls, int32_t *stencils);
int sdv_evaluator_eval_f32(const sdv_evaluator *e, int32_t width, const float *src, size_t src_len,
                           float *dst, size_t dst_len, char *err, size_t err_len);

/*
 * Far::PatchTable (cpp/patches.cpp): PatchTableFactory::Create on a refined
 * refiner, with a Far::PatchMap for locating (ptex face, u, v).
 */
typedef struct sdv_patches sdv_patches;

/* Far::PatchTableFactory::Options, field by field (flags 0 or 1). */
typedef struct sdv_patch_options {
    int32_t end_cap_type; /* EndCapType: 0 none, 1 bilinear, 2 B-spline, 3 Gregory basis, 4 legacy Gregory */
    int32_t share_end_cap_patch_points;
    int32_t generate_all_levels;
    int32_t include_base_level_indices;
    int32_t include_fvar_base_level_indices;
    int32_t triangulate_quads;
    int32_t use_single_crease_patch;
    int32_t use_inf_sharp_patch;
    int32_t max_isolation_level; /* 0..10 */
    int32_t generate_varying_tables;
    int32_t generate_varying_local_points;
    int32_t generate_fvar_tables;
    int32_t patch_precision_double;
    int32_t fvar_patch_precision_double;
    int32_t generate_fvar_legacy_linear_patches;
    int32_t generate_legacy_sharp_corner_patches;
} sdv_patch_options;

/*
 * PatchTableFactory::Create(refiner, options, selectedFaces). `fvar_channels`
 * (num_fvar_channels entries) are the channels of face-varying tables;
 * `faces` (num_faces, each in range) the base faces to build patches for,
 * none meaning all. Refused before OpenSubdiv sees them: an unrefined
 * refiner, a channel or face out of range, an option out of its field.
 */
int sdv_patches_create(const sdv_refiner *r, const sdv_patch_options *o, const int32_t *fvar_channels,
                       size_t num_fvar_channels, const int32_t *faces, size_t num_faces,
                       sdv_patches **out, char *err, size_t err_len);
void sdv_patches_destroy(sdv_patches *p);

typedef struct sdv_patch_counts {
    int32_t num_arrays;
    int32_t num_patches;
    int32_t num_control_vertices; /* entries of the control-vertex table, all arrays */
    int32_t num_local_points;
    int32_t num_local_points_varying;
    int32_t max_valence;
    int32_t num_ptex_faces;
    int32_t num_quad_offsets; /* entries of the legacy Gregory quad-offset table */
    int32_t num_valence_entries; /* entries of the legacy Gregory vertex valence table */
    int32_t feature_adaptive;
    int32_t varying_type; /* GetVaryingPatchDescriptor().GetType() */
    int32_t num_varying_vertices; /* entries of the varying-vertex table, all arrays (0 without) */
    int32_t num_fvar_channels; /* GetNumFVarChannels() */
} sdv_patch_counts;
int sdv_patches_counts(const sdv_patches *p, sdv_patch_counts *out, char *err, size_t err_len);

/* Patch array `array`: PatchDescriptor::Type, patch count, control vertices per patch. */
int sdv_patches_array(const sdv_patches *p, int32_t array, int32_t *type, int32_t *num_patches,
                      int32_t *num_cvs, char *err, size_t err_len);

/*
 * The whole tables, arrays one after the other: control vertices
 * (num_control_vertices), PatchParam words (2 per patch: field0, field1),
 * single-crease sharpness (1 per patch, 0 where none), quad offsets and
 * the vertex valence table (legacy Gregory; empty otherwise).
 */
typedef struct sdv_patch_tables {
    sdv_ibuf cvs;
    uint32_t *params;
    size_t params_cap;
    float *sharpness;
    size_t sharpness_cap;
    uint32_t *quad_offsets;
    size_t quad_offsets_cap;
    sdv_ibuf valence;
    sdv_ibuf varying; /* GetVaryingVertices(): each patch's varying vertices, array after array */
} sdv_patch_tables;
int sdv_patches_tables(const sdv_patches *p, const sdv_patch_tables *out, char *err, size_t err_len);

/*
 * Face-varying patch channel `channel` (0..num_fvar_channels): its regular
 * and irregular PatchDescriptor types, the value stride per patch, and its
 * values (stride per patch, patches in table order: GetFVarValues) and
 * PatchParam words (2 per patch: GetFVarPatchParams). With NULL outputs
 * only the sizes are written.
 */
typedef struct sdv_fvar_patches {
    int32_t regular_type;
    int32_t irregular_type;
    int32_t stride;
    int32_t num_values;
    int32_t num_params;
} sdv_fvar_patches;
int sdv_patches_fvar(const sdv_patches *p, int32_t channel, sdv_fvar_patches *info, int32_t *values,
                     size_t values_cap, uint32_t *params, size_t params_cap, char *err, size_t err_len);

/* Local-point stencils (0 vertex, 1 varying, 2 + k face-varying channel k of the
 * table: GetLocalPointFaceVaryingStencilTable(k)), weights as double; empty
 * where the table has none. */
int sdv_patches_local_stencils(const sdv_patches *p, int32_t kind, sdv_stencils **out, char *err,
                               size_t err_len);

/*
 * PatchMap::FindPatch(face, u, v): `found` 0 when no patch covers the
 * location (a hole); else the patch's array and its index in the array.
 * face must be a ptex face, u and v in [0, 1].
 */
int sdv_patches_find(const sdv_patches *p, int32_t face, double u, double v, int32_t *found,
                     int32_t *array, int32_t *patch, char *err, size_t err_len);

/*
 * PatchTable::EvaluateBasis<double> for patch `patch` of array `array` at
 * (u, v) in [0, 1]^2: the weights of its control vertices (cap at least its
 * control-vertex count); derivative outputs may be NULL (second ones only
 * together with the first).
 */
int sdv_patches_evaluate_basis(const sdv_patches *p, int32_t array, int32_t patch, double u, double v,
                               double *w, double *du, double *dv, double *duu, double *duv,
                               double *dvv, size_t cap, char *err, size_t err_len);

/*
 * The limit surface at n locations (faces[i], us[i], vs[i]), as far
 * tutorial 5_1 computes it: for each, PatchMap::FindPatch,
 * PatchTable::EvaluateBasis<double> and the weighted sum of the patch's
 * control points, read from `points` (num_points points of `width` values:
 * every level's vertices, then the local points). Outputs hold n * width
 * values each; du and dv may be NULL (together), duu, duv and dvv too (and
 * need du and dv). Refused before anything is
 * evaluated: a control vertex beyond num_points, a patch type without a
 * basis; while evaluating: a location off the ptex faces or the unit
 * square, or in a hole (the error names the location's index).
 */
int sdv_patches_evaluate_points(const sdv_patches *p, const double *points, size_t num_points, int32_t width,
                                const int32_t *faces, const double *us, const double *vs, size_t n,
                                double *out, double *du, double *dv, double *duu, double *duv, double *dvv,
                                char *err, size_t err_len);

/*
 * Osd::CpuPatchTable::Create(table): the table as OpenSubdiv's CPU evaluator
 * reads it (patch arrays, control-vertex indices, parameters with each
 * patch's sharpness), copied. It keeps a pointer to `p` (for its PatchMap):
 * `p` must outlive it. Refused: tables whose arrays are shorter than their
 * patches (the constructor copies them unchecked).
 */
typedef struct sdv_cpu_patches sdv_cpu_patches;
int sdv_cpu_patches_create(const sdv_patches *p, sdv_cpu_patches **out, char *err, size_t err_len);
void sdv_cpu_patches_destroy(sdv_cpu_patches *c);

/*
 * The limit surface at n locations (faces[i], us[i], vs[i]) the way
 * OpenSubdiv's evaluators compute it, in float: each location's patch
 * found with PatchMap::FindPatch into an Osd::PatchCoord (u and v rounded
 * to float), then one Osd::CpuEvaluator::EvalPatches over `points`
 * (num_points points of `width` floats: every level's vertices, then the
 * local points). Outputs hold n * width floats each; du and dv may be NULL
 * (together), duu, duv and dvv too (and need du and dv). Refused before
 * OpenSubdiv sees them, as sdv_patches_evaluate_points: a control vertex
 * beyond num_points, a patch type without a basis, a location off the ptex
 * faces or the unit square or in a hole (the error names the location's
 * index).
 */
int sdv_cpu_patches_evaluate(const sdv_cpu_patches *c, const float *points, size_t num_points, int32_t width,
                             const int32_t *faces, const double *us, const double *vs, size_t n, float *out,
                             float *du, float *dv, float *duu, float *duv, float *dvv, char *err,
                             size_t err_len);

/*
 * Far::LimitStencilTableFactoryReal<double>::Create(refiner, locations) with
 * its own stencil and patch tables (as OpenSubdiv builds them when given
 * none) and Options (interpolation 0 vertex, 1 varying, 2 face-varying of
 * fvar_channel; first and second derivatives 0 or 1): one stencil for each
 * of the n locations (faces[i] a ptex face, us[i] and vs[i] in [0, 1]) that
 * is not in a hole, in order. `found` (n entries) says which have one.
 * Refused first: a uniform refiner without refined levels (OpenSubdiv's
 * table of level 0 leaves its patches unset), a location off the ptex
 * faces or the unit square, an
 * unknown mode or channel, an adaptive refinement of selected faces (the
 * patches of the others are undefined), faces repeating a vertex after
 * adaptive refinement (the patch builders overrun), face-varying stencils
 * after adaptive refinement that considered the face-varying channels
 * (appendLocalPointStencilTable reads uninitialised weights), and the
 * Catmull-Clark
 * vertex masks that overflow (as for every stencil table). The result's
 * derivative weights are read with sdv_stencils_derivative.
 */
typedef struct sdv_limit_stencil_options {
    int32_t interpolation;
    int32_t fvar_channel;
    int32_t first_derivatives;
    int32_t second_derivatives;
} sdv_limit_stencil_options;
int sdv_limit_stencils_create(const sdv_refiner *r, const sdv_limit_stencil_options *o, const int32_t *faces,
                              const double *us, const double *vs, size_t n, int32_t *found, sdv_stencils **out,
                              char *err, size_t err_len);
/*
 * The control vertices (or face-varying values) a limit stencil table's
 * indices refer to (0 for other tables).
 */
int32_t sdv_stencils_controls(const sdv_stencils *s);
/*
 * Derivative weights of a limit stencil table (kind 0..4: du, dv, duu, duv,
 * dvv): `len` receives their count (0 when not generated); with `out`
 * non-NULL they are copied into it (cap at least len).
 */
int sdv_stencils_derivative(const sdv_stencils *s, int32_t kind, double *out, size_t cap, size_t *len, char *err,
                            size_t err_len);

/*
 * Bfr (cpp/bfr.cpp): Bfr::Tessellation and Bfr::Parameterization of one
 * face, given by its scheme (0 bilinear, 1 catmark, 2 loop) and size.
 *
 * Refused before OpenSubdiv sees them (SDV_ERR_INVALID unless noted): a
 * scheme outside 0..2; a face size outside 3..65535 (OpenSubdiv's
 * Parameterization would be invalid); under bilinear or Catmull-Clark a
 * face size of 65026 or more (SDV_ERR_UNSAFE: the sub-face grid width,
 * 1 + sqrt(N - 1), wraps to 0 in its unsigned char and the sub-face
 * coordinates divide by it). A non-triangle under Loop is not refused: its
 * Parameterization and Tessellation are invalid, and say so.
 */

/* Bounds of a tessellation: coordinates, and facets (a triangulated disc has
   fewer than two per coordinate). OpenSubdiv counts both in int. */
enum { SDV_BFR_MAX_COORDS = 1 << 24, SDV_BFR_MAX_FACETS = 1 << 25 };

/* Opaque tessellation: owns a Bfr::Tessellation. */
typedef struct sdv_tessellation sdv_tessellation;

/*
 * Bfr::Tessellation(Parameterization(scheme, face_size), num_rates, rates,
 * Options().SetFacetSize(facet_size).PreserveQuads(preserve_quads)), with
 * the default strides (2 per coordinate, facet_size per facet). Refused
 * besides the face sizes above: preserve_quads not 0 or 1, facet_size not 3
 * or 4, num_rates outside 1..face_size + 2, a rate below 1 (OpenSubdiv
 * would hold the tessellation invalid), and rates whose pattern has more
 * than SDV_BFR_MAX_COORDS coordinates or SDV_BFR_MAX_FACETS facets (counted
 * in 64 bits first, with OpenSubdiv's clamp of every rate to 32767 and its
 * inference of the rates not given).
 */
int sdv_tessellation_create(int32_t scheme, int32_t face_size, const int32_t *rates, size_t num_rates,
                            int32_t preserve_quads, int32_t facet_size, sdv_tessellation **out, char *err,
                            size_t err_len);
void sdv_tessellation_destroy(sdv_tessellation *t);

/*
 * IsValid and, for a valid tessellation (all 0 otherwise): IsUniform,
 * GetFaceSize, GetRates' count, GetNumBoundaryCoords, GetNumInteriorCoords,
 * GetNumFacets, GetFacetSize, and the sum of GetNumEdgeCoords over the edges.
 */
typedef struct sdv_tess_counts {
    int32_t is_valid;
    int32_t is_uniform;
    int32_t face_size;
    int32_t num_rates;
    int32_t num_boundary_coords;
    int32_t num_interior_coords;
    int32_t num_facets;
    int32_t facet_size;
    int32_t num_edge_coords;
} sdv_tess_counts;
int sdv_tessellation_counts(const sdv_tessellation *t, sdv_tess_counts *out, char *err, size_t err_len);

/*
 * The contents of a valid tessellation (nothing is written for an invalid
 * one): GetRates (num_rates), GetCoords<double> and GetCoords<float>
 * (2 per coordinate, boundary first), GetFacets (facet_size per facet; a
 * triangle among 4-index facets ends with OpenSubdiv's -1), GetNumEdgeCoords
 * of every edge (face_size), GetEdgeCoords<double> and <float> edge after
 * edge (2 * num_edge_coords), GetVertexCoord<double> of every vertex
 * (2 * face_size).
 */
typedef struct sdv_tess_data {
    sdv_ibuf rates;
    double *coords_f64;
    size_t coords_f64_cap;
    float *coords_f32;
    size_t coords_f32_cap;
    sdv_ibuf facets;
    sdv_ibuf edge_coord_counts;
    double *edge_coords_f64;
    size_t edge_coords_f64_cap;
    float *edge_coords_f32;
    size_t edge_coords_f32_cap;
    double *vertex_coords;
    size_t vertex_coords_cap;
} sdv_tess_data;
int sdv_tessellation_data(const sdv_tessellation *t, const sdv_tess_data *out, char *err, size_t err_len);

/* The overloads of Tessellation::TransformFacetCoordIndices. */
enum {
    SDV_FACETS_OFFSET = 0,            /* (facets, commonOffset) */
    SDV_FACETS_BOUNDARY_OFFSET = 1,   /* (facets, boundaryIndices, interiorOffset) */
    SDV_FACETS_BOUNDARY_INTERIOR = 2  /* (facets, boundaryIndices, interiorIndices) */
};
/*
 * GetFacets into `facets` (facets_cap at least num_facets * facet_size),
 * then TransformFacetCoordIndices of overload `kind` with `offset`,
 * `boundary` (num_boundary_coords entries; kinds 1 and 2) and `interior`
 * (num_interior_coords entries; kind 2). Refused: maps of another length,
 * and (SDV_ERR_UNSAFE) an offset that overflows an int when added to the
 * largest coordinate index it applies to. Nothing is written for an invalid
 * tessellation (it has no facets).
 */
int sdv_tessellation_transform_facets(sdv_tessellation *t, int32_t kind, int32_t offset, const int32_t *boundary,
                                      size_t num_boundary, const int32_t *interior, size_t num_interior,
                                      int32_t *facets, size_t facets_cap, char *err, size_t err_len);

/* Parameterization::IsValid, GetType (0 quad, 1 tri, 2 quad sub-faces), HasSubFaces, GetFaceSize. */
typedef struct sdv_param_info {
    int32_t is_valid;
    int32_t type;
    int32_t has_sub_faces;
    int32_t face_size;
} sdv_param_info;
int sdv_parameterization_info(int32_t scheme, int32_t face_size, sdv_param_info *out, char *err,
                              size_t err_len);

/*
 * Batched Parameterization queries: n queries of one kind, query i reading
 * index[i], t[i] and uv_in[2i..2i+2] and writing index_out[i] and
 * uv_out[2i..2i+2], as the kind uses them (the others may be NULL):
 */
enum {
    SDV_PARAM_VERTEX_COORD = 0,                /* index: vertex -> uv_out (GetVertexCoord) */
    SDV_PARAM_EDGE_COORD = 1,                  /* index: edge, t -> uv_out (GetEdgeCoord) */
    SDV_PARAM_CENTER_COORD = 2,                /* -> uv_out (GetCenterCoord) */
    SDV_PARAM_SUB_FACE = 3,                    /* uv_in -> index_out (GetSubFace) */
    SDV_PARAM_COORD_TO_SUB_FACE = 4,           /* uv_in -> index_out, uv_out (ConvertCoordToSubFace) */
    SDV_PARAM_SUB_FACE_TO_COORD = 5,           /* index: sub-face, uv_in -> uv_out (ConvertSubFaceToCoord) */
    SDV_PARAM_COORD_TO_NORMALIZED_SUB_FACE = 6, /* as 4, ConvertCoordToNormalizedSubFace */
    SDV_PARAM_NORMALIZED_SUB_FACE_TO_COORD = 7  /* as 5, ConvertNormalizedSubFaceToCoord */
};
/*
 * Refused before any query runs: an invalid parameterization (it answers
 * none), a vertex, edge or sub-face outside 0..face_size-1, t or a
 * coordinate that is not finite or beyond +-2^20 (the sub-face queries
 * convert coordinates to int), a sub-face conversion of a parameterization
 * without sub-faces (OpenSubdiv asserts, then divides by 0).
 */
int sdv_parameterization_query_f64(int32_t scheme, int32_t face_size, int32_t kind, size_t n, const int32_t *index,
                                   const double *t, const double *uv_in, int32_t *index_out, double *uv_out,
                                   char *err, size_t err_len);
int sdv_parameterization_query_f32(int32_t scheme, int32_t face_size, int32_t kind, size_t n, const int32_t *index,
                                   const float *t, const float *uv_in, int32_t *index_out, float *uv_out,
                                   char *err, size_t err_len);

/*
 * Bfr limit surfaces (cpp/bfr_surface.cpp): a Bfr::RefinerSurfaceFactory<>
 * over the base level of a refiner (which must outlive it, and is only
 * read), with Bfr::Surface<double> built per call for one base face and
 * evaluated there.
 *
 * The factory's topology cache is disabled: it is keyed by a 64-bit hash
 * alone (a collision hands a face another topology's patch, whose stencils
 * are sized for other control points) and is not thread-safe. Refused
 * before OpenSubdiv sees them (SDV_ERR_INVALID unless noted): approximation
 * levels outside 0..10; a face or channel out of range; a face of more
 * than SDV_BFR_MAX_SURFACE_FACE_SIZE vertices or a corner vertex with more
 * than SDV_BFR_MAX_SURFACE_VALENCE faces (SDV_ERR_UNSAFE: Bfr keeps both in
 * a short); under a non-linear surface, a face with an interior vertex of
 * valence 2, a boundary or non-manifold corner and a sharp interior edge
 * at a corner (SDV_ERR_UNSAFE: OpenSubdiv 3.5.0 then reads crease vertex
 * indices from uninitialised memory and looks edges up with them, fixed in
 * 3.5.1); coordinates not finite or off the face's parameter domain;
 * fewer points than the surface's indices reach, or more than an int of
 * reals.
 */
enum { SDV_BFR_MAX_SURFACE_FACE_SIZE = 32767, SDV_BFR_MAX_SURFACE_VALENCE = 16383 };

/* Opaque: owns a Bfr::RefinerSurfaceFactory<> (not the refiner). */
typedef struct sdv_surfaces sdv_surfaces;

/* Kinds of surface: InitVertexSurface, InitVaryingSurface, InitFaceVaryingSurface. */
enum { SDV_SURFACE_VERTEX = 0, SDV_SURFACE_VARYING = 1, SDV_SURFACE_FACE_VARYING = 2 };

/*
 * SurfaceFactory::Options().SetApproxLevelSmooth(smooth)
 * .SetApproxLevelSharp(sharp).SetDefaultFVarID(0).EnableCaching(false).
 */
int sdv_surfaces_create(const sdv_refiner *r, int32_t approx_level_smooth, int32_t approx_level_sharp,
                        sdv_surfaces **out, char *err, size_t err_len);
void sdv_surfaces_destroy(sdv_surfaces *s);
/* RefinerSurfaceFactory::GetNumFaces (0 for NULL). */
int32_t sdv_surfaces_face_count(const sdv_surfaces *s);

/*
 * The surface of one face: IsValid (0 for a hole or a face OpenSubdiv
 * finds no limit surface for; then only param_type and face_size, of the
 * face's GetFaceParameterization, are set), IsRegular, IsLinear,
 * GetNumControlPoints, GetNumPatchPoints, GetParameterization's type
 * (0 quad, 1 tri, 2 quad sub-faces) and face size. `control_points`
 * receives GetControlPointIndices when it is non-NULL and holds
 * num_control_points (else it is left alone).
 */
typedef struct sdv_surface_info {
    int32_t is_valid;
    int32_t is_regular;
    int32_t is_linear;
    int32_t num_control_points;
    int32_t num_patch_points;
    int32_t param_type;
    int32_t face_size;
} sdv_surface_info;
int sdv_surface_info_get(const sdv_surfaces *s, int32_t face, int32_t kind, int32_t channel, sdv_surface_info *out,
                         int32_t *control_points, size_t cap, char *err, size_t err_len);

/*
 * Evaluation of one face's surface at n coordinates (uv, 2 per coordinate,
 * in the face's Parameterization): PreparePatchPoints from `points`
 * (num_points points of `width` reals: the mesh's vertices, or the
 * channel's values) and Evaluate at each coordinate, with derivatives 0
 * (positions), 1 (and du, dv) or 2 (and duu, duv, dvv). out[0..] receive
 * n * width reals each (out[k] beyond the derivatives asked for may be
 * NULL); cap is their capacity. Fails (SDV_ERR_INVALID) for a face
 * without a limit surface.
 */
typedef struct sdv_surface_eval {
    int32_t kind;
    int32_t channel;
    const double *points;
    size_t num_points;
    int32_t width;
    const double *uv;
    size_t n;
    int32_t derivatives;
    double *out[6];
    size_t cap;
} sdv_surface_eval;
int sdv_surface_evaluate(const sdv_surfaces *s, int32_t face, const sdv_surface_eval *e, char *err, size_t err_len);

/*
 * Surface::EvaluateStencil at n coordinates: for coordinate i and column c
 * (0 position, 1 du, 2 dv, 3 duu, 4 duv, 5 dvv; 1, 3 or 6 columns for
 * derivatives 0, 1 or 2), the weights of the num_control_points control
 * points (GetControlPointIndices' order) at
 * out[(i * columns + c) * num_control_points]. `num_control_points` is
 * always written; with out NULL nothing else is (cap is then ignored),
 * else cap must hold n * columns * num_control_points.
 */
int sdv_surface_stencils(const sdv_surfaces *s, int32_t face, int32_t kind, int32_t channel, const double *uv,
                         size_t n, int32_t derivatives, double *out, size_t cap, int32_t *num_control_points,
                         char *err, size_t err_len);

/*
 * Bfr::Surface::PreparePatchPoints of `face`'s surface of e->kind (and
 * e->channel) from e->points (e->num_points of e->width reals; e's
 * coordinates, derivatives and outputs are not read): *count is always
 * written (GetNumPatchPoints); with out NULL nothing else is, else cap
 * must hold *count * e->width.
 */
int sdv_surface_patch_points(const sdv_surfaces *s, int32_t face, const sdv_surface_eval *e, double *out,
                             size_t cap, int32_t *count, char *err, size_t err_len);

/*
 * A whole mesh tessellated with Bfr (cpp/bfr_mesh.cpp), as a C++ program
 * over OpenSubdiv does it (bfr tutorial 2_2's approach), in one call: one
 * Bfr::RefinerSurfaceFactory<> over the refiner's base level (options as
 * sdv_surfaces_create's, caching off), the faces in index order, a face
 * skipped when InitVertexSurface (InitSurfaces with face-varying channel 0
 * when UVs are asked for) finds no limit surface; a Bfr::Tessellation per
 * face with one rate per edge (the uniform rate, or 1 + floor(length / L)
 * of the edge's control points, at most 32767), facet size 4 and
 * PreserveQuads when `quads`, else 3; a point per base vertex and
 * rate - 1 points per base edge (base edges told apart by their unordered
 * pair of vertices), each created and evaluated (Surface<double>::Evaluate)
 * by the first face using it -- an edge's points in that face's direction,
 * walked backwards by faces traversing the edge the other way -- then each
 * face's interior points; facets renumbered with
 * TransformFacetCoordIndices, the -1 of a triangle among quads dropped.
 * With `normals`, normalize(cross(du, dv)) per point (zero where that
 * cross product has no finite inverse length). With UVs (`uvs` non-NULL:
 * channel 0's values, `uv_width` reals each), channel 0 evaluated at every
 * coordinate of every face, its first two components (the second 0 for a
 * width of 1), indexed per face.
 *
 * Refused before OpenSubdiv sees them (SDV_ERR_INVALID unless noted):
 * approximation levels outside 0..10; fewer positions than base vertices,
 * or more reals than an int indexes; with UVs, a mesh without channel 0,
 * fewer values than it has, a width below 1, more reals than an int
 * indexes; a uniform rate outside 1..32767, an edge length that is not
 * positive and finite; every face (holes aside: Bfr never builds their
 * surfaces) that sdv_surface_evaluate would refuse for its vertex surface,
 * and with UVs for its face-varying one (SDV_ERR_UNSAFE: faces of more than
 * SDV_BFR_MAX_SURFACE_FACE_SIZE vertices, corners of more than
 * SDV_BFR_MAX_SURFACE_VALENCE faces, OpenSubdiv 3.5.0's valence-2 fault);
 * a face whose pattern has more than SDV_BFR_MAX_COORDS coordinates or
 * SDV_BFR_MAX_FACETS facets (as sdv_tessellation_create); a mesh whose
 * tessellation (counted in 64 bits before any surface is built, every face
 * but the holes included) has more than SDV_BFR_MESH_MAX_POINTS points,
 * SDV_BFR_MESH_MAX_FACETS facets or, with UVs, SDV_BFR_MESH_MAX_UVS
 * texture coordinates. OpenSubdiv's errors while building a surface fail
 * the call (SDV_ERR_OSD).
 */
enum {
    SDV_BFR_MESH_MAX_POINTS = 1 << 25,
    SDV_BFR_MESH_MAX_FACETS = 1 << 26,
    SDV_BFR_MESH_MAX_UVS = 1 << 26
};

/* Opaque: the tessellated mesh, owned. */
typedef struct sdv_bfr_mesh sdv_bfr_mesh;

typedef struct sdv_bfr_mesh_input {
    const double *positions; /* 3 per base vertex */
    size_t num_vertices;
    const double *uvs;       /* face-varying channel 0's values, or NULL: no UVs */
    size_t num_uv_values;
    int32_t uv_width;
    int32_t approx_level_smooth;
    int32_t approx_level_sharp;
    int32_t rate;            /* every edge's rate, unless use_edge_length */
    int32_t use_edge_length; /* 0 or 1 */
    double edge_length;
    int32_t quads;           /* 0 or 1 */
    int32_t normals;         /* 0 or 1 */
} sdv_bfr_mesh_input;

int sdv_bfr_mesh_create(const sdv_refiner *r, const sdv_bfr_mesh_input *in, sdv_bfr_mesh **out, char *err,
                        size_t err_len);
void sdv_bfr_mesh_destroy(sdv_bfr_mesh *m);

/* The sizes of the tessellated mesh's arrays (0 for NULL). */
typedef struct sdv_bfr_mesh_counts {
    size_t num_points;        /* positions: 3 reals each */
    size_t num_normals;       /* num_points with normals, else 0 */
    size_t num_facets;
    size_t num_face_vertices; /* all facets' corners */
    size_t num_uvs;           /* texture coordinates: 2 reals each */
    size_t num_uv_indices;    /* num_face_vertices with UVs, else 0 */
} sdv_bfr_mesh_counts;
void sdv_bfr_mesh_counts_get(const sdv_bfr_mesh *m, sdv_bfr_mesh_counts *out);

/*
 * Copies the mesh into caller buffers, each with its capacity in elements:
 * positions and normals (3 * count reals), face_offsets (num_facets + 1:
 * 0, then each facet's end in face_vertices), face_vertices, uvs (2 *
 * num_uvs), uv_indices (one per corner, into uvs), facet_faces (the base
 * face of each facet). A buffer may be NULL when its count is 0.
 */
typedef struct sdv_bfr_mesh_data {
    double *positions;
    size_t positions_cap;
    double *normals;
    size_t normals_cap;
    uint32_t *face_offsets;
    size_t face_offsets_cap;
    uint32_t *face_vertices;
    size_t face_vertices_cap;
    double *uvs;
    size_t uvs_cap;
    uint32_t *uv_indices;
    size_t uv_indices_cap;
    uint32_t *facet_faces;
    size_t facet_faces_cap;
} sdv_bfr_mesh_data;
int sdv_bfr_mesh_read(const sdv_bfr_mesh *m, const sdv_bfr_mesh_data *out, char *err, size_t err_len);

#ifdef __cplusplus
}
#endif

#endif
