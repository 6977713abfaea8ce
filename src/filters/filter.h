/* The internal side of the filter registry: denoising passes that run after any AO method, at
 * the AO's resolution (Belonogov 2018 §4.3; SSDO thesis §3.5, §4.3). Adding a filter is one .c (defining
 * an ob_filter_impl), one shader and one line in registry.c. */
#ifndef OB_FILTER_H
#define OB_FILTER_H

#include "filter_params.h"
#include "gpu/gpu.h"
#include "obscura/scene.h"

/* What a filter gets: textures of one size (the AO resolution). */
typedef struct ob_filter_inputs {
    GLuint src;           /* R32F AO to filter (visibility, sky pixels hold 1) */
    GLuint dst;           /* R32F result */
    GLuint scratch;       /* R32F, free for the first pass of a separable filter */
    GLuint linear_depth;  /* R32F, positive view depth, 0 = no geometry */
    GLuint view_normal;   /* RGBA16F view-space unit normal */
    int width, height;
    /* The RGB variant (SSDO's modulation factor and bounce): src, dst and scratch are RGBA16F,
     * run with the state from init_rgb; sky pixels get `sky` in every channel (1 for M, 0 for
     * the bounce). false: R32F, sky pixels 1. */
    bool rgb;
    float sky;
    /* The frame's camera is orthographic (frame_params.h's `orthographic`, which the shaders read
     * themselves): for a filter that compiles a program of its own for it (crease's block). */
    bool orthographic;
} ob_filter_inputs;

/* The image format of a filter's targets. */
static inline GLenum ob_filter_format(const ob_filter_inputs *in) { return in->rgb ? GL_RGBA16F : GL_R32F; }

typedef struct ob_filter_impl {
    ob_filter_info info;
    /* Programs and static resources; NULL + ob_set_error on failure. May be NULL. */
    void *(*init)(void);
    /* src -> dst (may use scratch). params in table order, validated. Images written with
     * imageStore; the caller puts the memory barrier after. Between the passes of a separable
     * filter the filter itself calls glMemoryBarrier. */
    ob_error (*run)(void *state, const ob_filter_inputs *in, const float *params);
    void (*destroy)(void *state);
    /* The same for RGBA16F targets (the shader compiled with OB_FILTER_RGB); NULL when init is
     * NULL or the filter is format-blind (none). */
    void *(*init_rgb)(void);
} ob_filter_impl;

const ob_filter_impl *ob_filter_impl_at(int index);

/* ---- shared by the Gaussian-family filters (kernel.c) ------------------------------------- */
/* Fill size, radius (clamped to 0..OB_FILTER_MAX_RADIUS), the range falloffs, sky_value and the
 * spatial weights: Belonogov 2018 eq. 4.4 sampled at the integer taps 0..radius and normalised so that
 * the 1D kernel (w0 + 2 sum w_i) sums to 1. sigma_depth / sigma_normal (radians) <= 0 leave that
 * range term off. axis is left (0,0): ob_filter_run_separable sets it per pass. Pure: no GL. */
void ob_filter_constants_init(ob_filter_constants *c, const ob_filter_inputs *in, int radius, float sigma_px,
                              float sigma_depth, float sigma_normal);
/* `crease` (crease.c, shaders/crease.glsl): the constants above with the spatial weights of its
 * eq. 1 (1 for taps 0..radius-1, 1/2 at the rim, unnormalised: the shader divides by the sum) and
 * depth_falloff taken by the plane distance |n_p . (P_q - P_p)| / d_p. Pure: no GL. */
void ob_crease_constants_init(ob_filter_constants *c, const ob_filter_inputs *in, int radius, float sigma_plane,
                              float sigma_normal);
/* The two dispatches of a separable filter (Belonogov 2018 eq. 4.6-4.7): along x from in->src into
 * in->scratch, a barrier, then along y into in->dst. Binds AO at OB_UNIT_FILTER_IN, linear depth
 * at OB_UNIT_FILTER_DEPTH, view normals at OB_UNIT_FILTER_NORMAL and the output at OB_IMAGE_UNIT_OUT. */
void ob_filter_run_separable(ob_compute_pass *pass, ob_filter_constants *c, const ob_filter_inputs *in);
/* The one dispatch of a single-pass filter: the first `used` bytes of c uploaded, AO, linear depth and view
 * normals at OB_UNIT_FILTER_IN, _DEPTH and _NORMAL, in->dst at OB_IMAGE_UNIT_OUT. */
void ob_filter_run_single(ob_compute_pass *pass, const ob_filter_constants *c, size_t used, const ob_filter_inputs *in);
/* The same for a shader whose invocations each write a block x block square of pixels: one
 * invocation per square (crease's block program). */
void ob_filter_run_blocks(ob_compute_pass *pass, const ob_filter_constants *c, size_t used, const ob_filter_inputs *in,
                          int block);
/* A filter's compute pass from its shader, R32F or (rgb) RGBA16F; NULL + ob_set_error. */
void *ob_filter_make_pass(const char *shader, bool rgb);
/* Frees what ob_filter_make_pass made (NULL is a no-op): every filter's destroy. */
void ob_filter_destroy_pass(void *state);
/* Bytes of c worth uploading: the block up to the last weight in use. */
size_t ob_filter_constants_used(const ob_filter_constants *c);

#endif
