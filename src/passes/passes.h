/* The fixed passes of the frame (the AO methods live in src/methods/). Each pass is one .c and
 * one shader; each owns its program and constant buffer. */
#ifndef OB_PASSES_H
#define OB_PASSES_H

#include "gpu/gpu.h"
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

/* ---- 4x4 box blur (blur.c, shaders/blur_box4.glsl) ------------------------------------------ */
typedef struct ob_blur_pass { ob_compute_pass pass; } ob_blur_pass;
ob_error ob_blur_init(ob_blur_pass *b);
void ob_blur_run(ob_blur_pass *b, GLuint ao_in, GLuint linear_depth, GLuint ao_out, int width, int height);
void ob_blur_destroy(ob_blur_pass *b);

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
