/*
 * subdiv shim: a plain C ABI over OpenSubdiv's Far layer.
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

#ifdef __cplusplus
}
#endif

#endif
