/* The internal side of the method registry: what one AO/GI method provides. Adding a method is
 * one .c (defining an ob_method_impl), one shader and one line in registry.c. */
#ifndef OB_METHOD_H
#define OB_METHOD_H

#include "gpu/gpu.h"
#include "lighting_params.h"
#include "obscura/obscura.h"

/* What every method gets each frame: textures of the renderer's size and the camera. */
typedef struct ob_ao_inputs {
    GLuint linear_depth;  /* R32F, positive view depth, 0 = no geometry */
    GLuint view_normal;   /* RGBA16F, view-space unit normal */
    int width, height;
    float proj[16];       /* column-major projection */
    float proj_info[4];   /* 1/P00, 1/P11, P20, P21 */
    uint32_t frame;       /* frame counter, for methods that vary noise over time */
    /* Adaptive sample counts (seed 003 §4.1): when set, a method with a sample count takes
     * samples/3 (at least 1) x the multiplier (1, 2 or 3) of its OB_EDGE_BLOCK^2 block of this
     * R32F texture; methods without one ignore it. */
    GLuint sample_multiplier; /* 0 = off */
    /* ---- what directional methods (ob_method_impl.rgb: SSDO) read besides; AO methods ignore it.
     * Filled by ob_render_frame only (ob_compute_ao refuses rgb methods). */
    GLuint direct;        /* full-resolution RGBA16F direct radiance (the lighting pass's output) */
    GLuint albedo;        /* full-resolution albedo (SSDO leaves the receiver's albedo to compose) */
    int grid_k, grid_o;   /* AO pixel i lies at full pixel k i + o (k = 1, o = 0 at full size) */
    const ob_lighting_constants *lights; /* world-space lights (counts.x of them) and inv_view */
    ob_ambient_mode ambient_mode;
    float ambient[3], sky[3], ground[3]; /* as ob_settings */
    float sh[9][3];       /* environment: irradiance / pi SH, as compose */
    GLuint bounce_out;    /* RGBA16F of the inputs' size: the one-bounce indirect light */
} ob_ao_inputs;

/* The base count that the multiplier scales under adaptive sampling. */
static inline int ob_adaptive_base(int samples) { return samples / 3 > 1 ? (samples + 1) / 3 : 1; }

typedef struct ob_method_impl {
    ob_method_info info;
    /* Make programs and static resources; return NULL with ob_set_error on failure.
     * May be NULL for methods that need nothing. */
    void *(*init)(void);
    /* Write visibility to ao_out (R32F, inputs' size; RGBA16F M and bounce_out for rgb methods).
     * params are in table order, validated. */
    ob_error (*run)(void *state, const ob_ao_inputs *in, const float *params, GLuint ao_out);
    void (*destroy)(void *state);
    /* How `samples` per pixel map onto this method's parameters, when that is more than setting
     * a parameter named "samples" (HBAO: directions x steps). Sets the bits of what it changed in
     * *params_set. NULL for the default. */
    ob_error (*set_samples)(float *params, uint32_t *params_set, int samples);
    /* Samples per pixel these params ask for, when not a parameter named "samples" (HBAO:
     * directions x steps). NULL for the default. */
    int (*count_samples)(const float *params);
    /* Honours ob_ao_inputs.sample_multiplier (adaptive sample counts). */
    bool adapts;
    /* Directional: ao_out is RGBA16F and receives a per-channel modulation factor M (1 = open),
     * and bounce_out an RGB indirect light; the renderer filters and upsamples both and compose
     * uses them as direct x M + bounce (SSDO). false: ao_out is R32F visibility. */
    bool rgb;
} ob_method_impl;

/* Samples per pixel of a method with these (resolved) params; 0 for none. */
int ob_method_samples(const ob_method_impl *m, const float *params);

const ob_method_impl *ob_method_impl_at(int index);

/* Option lists shared by methods' enum parameters (registry.c), in the order of the enums in
 * sampling/sampling.h and the OB_NOISE_* modes of shaders/noise.glsl. */
extern const char *const ob_sampling_options[];  /* random, halton */
extern const char *const ob_direction_options[]; /* uniform, cosine */
extern const char *const ob_noise_options[];     /* texture4, ign */

#endif
