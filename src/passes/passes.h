/* The fixed passes of the frame (the AO methods live in src/methods/). Each pass is one .c and
 * one shader; each owns its program and constant buffer. */
#ifndef OB_PASSES_H
#define OB_PASSES_H

#include "gpu/gpu.h"
#include "resample_params.h"
#include "scene/scene.h"

/* ---- G-buffer (gbuffer.c, shaders/gbuffer.{vert,frag}.glsl): the one raster pass ------------ */
typedef struct ob_gpu_mesh {
    GLuint vao, buffers[4]; /* positions, normals, uvs, indices */
    GLsizei index_count;
    int material;
} ob_gpu_mesh;

typedef struct ob_gbuffer {
    GLuint program, ubo, fbo;
    GLuint depth;         /* DEPTH_COMPONENT32F: hardware depth */
    GLuint linear_depth;  /* R32F */
    GLuint normal;        /* RGBA16F view space */
    GLuint albedo;        /* RGBA16F linear */
    int width, height;
    ob_gpu_mesh *meshes;
    int mesh_count;
    GLuint *textures;     /* per material, 0 = none */
    float (*diffuse)[3];  /* per material */
    int material_count;
} ob_gbuffer;

ob_error ob_gbuffer_init(ob_gbuffer *g, int width, int height);
ob_error ob_gbuffer_set_scene(ob_gbuffer *g, const ob_scene *scene);
void ob_gbuffer_run(ob_gbuffer *g, const float *view, const float *proj);
void ob_gbuffer_destroy(ob_gbuffer *g);

/* ---- subsampling: downsample.c, upsample.c, edges.c (shaders of the same names) ----------- */
/* The AO resolution: k full pixels per AO pixel (1, 2 or 4); AO pixel i samples full pixel k i + o. */
typedef struct ob_ao_grid {
    int full_width, full_height;
    int width, height; /* AO resolution */
    int k, o;
} ob_ao_grid;

ob_ao_grid ob_ao_grid_make(int full_width, int full_height, int k);
/* The sizes and factors of a grid into the constants the three passes share. */
void ob_resample_fill(ob_resample_constants *c, const ob_ao_grid *g);

/* Depth and normals at the AO resolution: one representative pixel per block, no averaging. */
ob_error ob_downsample_init(ob_compute_pass *p);
void ob_downsample_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal, GLuint low_depth,
                       GLuint low_normal);

/* Joint bilateral upsampling of the AO to full resolution (seed 003 eq. 3.12). */
ob_error ob_upsample_init(ob_compute_pass *p);
void ob_upsample_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal, GLuint low_depth,
                     GLuint low_normal, GLuint low_ao, GLuint ao_out);

/* Adaptive sample counts: a multiplier 1/2/3 per OB_EDGE_BLOCK^2 AO pixels (seed 003 §4.1). */
ob_error ob_edges_init(ob_compute_pass *p);
void ob_edges_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint ao_depth, GLuint ao_normal, GLuint multiplier);

/* ---- lighting + compose (compose.c, shaders/compose.glsl) ----------------------------------- */
typedef struct ob_compose_pass { ob_compute_pass pass; } ob_compose_pass;

typedef struct ob_compose_inputs {
    GLuint linear_depth, normal, albedo, ao;
    int width, height;
    float proj_info[4];
    float light_dir_view[3]; /* unit, toward the light */
    float light_radiance[3]; /* colour x intensity */
    float ambient[3];
    float background[3];
} ob_compose_inputs;

ob_error ob_compose_init(ob_compose_pass *c);
void ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint final_out);
void ob_compose_destroy(ob_compose_pass *c);

#endif
