/*
 * obscura.h — public API of libobscura: screen-space ambient occlusion and indirect light.
 *
 * The frame flows one way (see ../shared/DESIGN.md): scene -> G-buffer -> AO method -> filter ->
 * [upsample] -> compose -> sRGB. Every screen-space pass is a GLSL compute shader with its own GPU timer.
 *
 * Conventions
 *   - AO value = visibility in [0,1]; 1 = open sky.
 *   - View space is OpenGL's: the camera looks down -Z; linear depth is the positive distance
 *     along -Z. Radii are in world units.
 *   - Desc structs: zero means "default" (sokol style), resolved in one place per object.
 *
 * Errors
 *   Functions that can fail return an ob_error (or NULL) and record a one-line message that
 *   ob_get_error() returns (glfwGetError style). Library code never aborts or prints.
 *
 * Threading
 *   An ob_context and everything made from it belong to the thread that made the context (its
 *   GL context is current there). Scenes (ob_load_scene) are CPU-only and may be loaded on any
 *   thread. The last-error slot is thread-local.
 */
#ifndef OBSCURA_H
#define OBSCURA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define OB_VERSION_STRING "0.1.0"

/* ---- errors ---------------------------------------------------------------------------------
 * One X-macro list yields the enum, the names and the default messages. The CLI maps classes of
 * errors to exit codes (see app/main.c). */
#define OB_ERRORS(X)                                                                   \
    X(OB_OK, "no error")                                                               \
    X(OB_ERR_INVALID_ARGUMENT, "invalid argument")                                     \
    X(OB_ERR_OUT_OF_RANGE, "value out of range")                                       \
    X(OB_ERR_UNKNOWN_SCENE, "unknown scene")                                           \
    X(OB_ERR_UNKNOWN_METHOD, "unknown method")                                         \
    X(OB_ERR_UNKNOWN_PARAM, "unknown parameter")                                       \
    X(OB_ERR_UNKNOWN_CAMERA, "unknown camera")                                         \
    X(OB_ERR_BAD_SIZE, "bad image size")                                               \
    X(OB_ERR_IO, "file could not be read or written")                                  \
    X(OB_ERR_MODEL, "model could not be imported")                                     \
    X(OB_ERR_SIDECAR, "malformed scene sidecar")                                       \
    X(OB_ERR_NO_CONTEXT, "no OpenGL 4.5 context could be created")                     \
    X(OB_ERR_SHADER, "shader failed to compile or link")                               \
    X(OB_ERR_GL, "OpenGL error")                                                       \
    X(OB_ERR_OUT_OF_MEMORY, "out of memory")

typedef enum ob_error {
#define OB_X_ENUM(code, msg) code,
    OB_ERRORS(OB_X_ENUM)
#undef OB_X_ENUM
        OB_ERROR_COUNT
} ob_error;

/* The last error on this thread and its one-line message (never NULL; "" when none). */
ob_error ob_get_error(const char **message);
/* The enum's name, e.g. "OB_ERR_UNKNOWN_METHOD". */
const char *ob_error_name(ob_error err);
/* Forget the last error. */
void ob_clear_error(void);

/* ---- GPU context ----------------------------------------------------------------------------
 * A headless OpenGL 4.5 core context from EGL's device platform (EGL_EXT_platform_device), no X
 * server. OB_GPU_AUTO prefers a hardware device and falls back to Mesa's software device
 * (llvmpipe). */
typedef enum ob_gpu_kind { OB_GPU_AUTO = 0, OB_GPU_HW, OB_GPU_SW } ob_gpu_kind;

typedef struct ob_context_desc {
    ob_gpu_kind gpu;
    bool debug; /* GL debug output into the error log (slow) */
} ob_context_desc;

typedef struct ob_context ob_context;

/* Errors: OB_ERR_NO_CONTEXT (message names every device and step that was tried). */
ob_context *ob_make_context(const ob_context_desc *desc);
void ob_destroy_context(ob_context *ctx);
const char *ob_query_renderer(const ob_context *ctx); /* GL_RENDERER */
const char *ob_query_gl_version(const ob_context *ctx); /* GL_VERSION */
const char *ob_query_device(const ob_context *ctx);   /* which EGL device was used */
bool ob_query_is_software(const ob_context *ctx);
int ob_query_max_texture_size(const ob_context *ctx);

/* ---- scenes (CPU side) ---------------------------------------------------------------------- */
typedef enum ob_up_axis { OB_UP_DEFAULT = 0, OB_UP_Y, OB_UP_Z } ob_up_axis;

typedef struct ob_scene_desc {
    /* A built-in scene ("cornell", "corner", "sphere-on-plane"), a named scene from the data
     * directory's scenes/NAME.obscura.json (e.g. "bunny", "fzk-haus"), or a model path. */
    const char *name;
    const char *sidecar; /* explicit sidecar JSON; default: MODEL.obscura.json beside the model */
    ob_up_axis up;       /* overrides the sidecar's up axis */
} ob_scene_desc;

typedef struct ob_camera {
    float eye[3];
    float target[3];
    float up[3];      /* zero = world up (+Y) */
    float fov_y_deg;  /* zero = 60 */
    float near_z;     /* zero = derived from the scene bounds */
    float far_z;      /* zero = derived from the scene bounds */
    char name[64];
} ob_camera;

#define OB_MAX_LIGHTS 8

typedef enum ob_light_type { OB_LIGHT_DIRECTIONAL = 0, OB_LIGHT_POINT, OB_LIGHT_SPOT } ob_light_type;

typedef struct ob_light {
    float direction[3];  /* directional: world, FROM the surface TOWARD the light; spot: the axis
                            the cone points along, away from the light */
    float color[3];      /* linear RGB */
    float intensity;     /* directional: irradiance scale; point/spot: falls off as 1/d^2 */
    ob_light_type type;
    float position[3];   /* point, spot: world position */
    float range;         /* point, spot: smooth cut-off distance; 0 = pure 1/d^2 */
    float spot_inner_deg, spot_outer_deg; /* spot: half-angles, full inside inner, 0 outside outer */
} ob_light;

/* A light from text, as the CLI's --light takes it: a type, then key=value pairs separated by
 * spaces, e.g. "directional dir=0.3,1,0.2 color=1,0.9,0.8 intensity=2",
 * "point pos=0,2,0 intensity=8 range=10", "spot pos=0,3,0 dir=0,-1,0 cone=20,30 intensity=20".
 * Errors: OB_ERR_INVALID_ARGUMENT with what is wrong. */
ob_error ob_parse_light(const char *text, ob_light *out);

typedef enum ob_shadow_method { OB_SHADOW_NONE = 0, OB_SHADOW_HARD, OB_SHADOW_PCF, OB_SHADOW_VSM } ob_shadow_method;

/* Shadow maps (seed 003 §2.1, §5.1, §6.1) for every light up to 4: directional and spot lights
 * through one 2D map each, point lights through a cube map. */
typedef struct ob_shadow_settings {
    ob_shadow_method method;
    int size;             /* map resolution (square, per face for cube maps); default 2048 */
    float bias;           /* constant depth bias, in map texels' world size */
    float slope_bias;     /* slope-scaled bias, x tan(angle to the light) */
    int pcf_radius;       /* PCF: taps each side of the kernel (1 = 3x3 bilinear comparisons) */
    float vsm_blur;       /* VSM: Gaussian sigma of the moment blur, in map texels */
    float vsm_bleed;      /* VSM: light-bleeding reduction threshold in [0, 1) */
} ob_shadow_settings;

typedef struct ob_material_info {
    char name[64];
    float diffuse[3];
    bool has_texture;
} ob_material_info;

typedef struct ob_scene_stats {
    uint32_t triangles;
    uint32_t vertices;
    uint32_t meshes;
    uint32_t materials;
    float bounds_min[3];
    float bounds_max[3];
} ob_scene_stats;

typedef struct ob_scene ob_scene;

/* Errors: OB_ERR_UNKNOWN_SCENE, OB_ERR_IO, OB_ERR_MODEL, OB_ERR_SIDECAR. */
ob_scene *ob_load_scene(const ob_scene_desc *desc);
void ob_destroy_scene(ob_scene *scene);
ob_scene_stats ob_query_scene_stats(const ob_scene *scene);
const char *ob_query_scene_name(const ob_scene *scene);
int ob_query_scene_material_count(const ob_scene *scene);
ob_material_info ob_query_scene_material(const ob_scene *scene, int index);
/* Suggested AO radius in world units (sidecar, else 5% of the bounds' diagonal). */
float ob_query_scene_ao_radius(const ob_scene *scene);
/* The scene's lights (sidecar or glTF KHR_lights_punctual, else one default directional light
 * from above-front-left); index 0 is the key light. */
int ob_query_scene_light_count(const ob_scene *scene);
ob_light ob_query_scene_light(const ob_scene *scene, int index);

/* Camera presets: index 0 is always "default", which frames the scene's bounds. */
int ob_query_camera_count(const ob_scene *scene);
ob_camera ob_query_camera(const ob_scene *scene, int index);
/* By name or decimal index. Errors: OB_ERR_UNKNOWN_CAMERA. */
ob_error ob_find_camera(const ob_scene *scene, const char *name_or_index, ob_camera *out);

/* Directory holding scenes/ (named scene sidecars): the source tree by default, overridden by the
 * OBSCURA_DATA_DIR environment variable. */
const char *ob_data_dir(void);

/* Built-in scenes that need no file. */
int ob_builtin_scene_count(void);
const char *ob_builtin_scene_name(int index);
const char *ob_builtin_scene_description(int index);

/* ---- AO methods: the registry --------------------------------------------------------------- */
#define OB_MAX_PARAMS 16

/* ENUM values are stored as the option's index (0, 1, ...) and set by name or index. */
typedef enum ob_param_type { OB_PARAM_FLOAT = 0, OB_PARAM_INT, OB_PARAM_BOOL, OB_PARAM_ENUM } ob_param_type;

typedef struct ob_param_info {
    const char *name;
    ob_param_type type;
    float min, max, def;
    const char *unit;
    const char *help;
    /* When not set explicitly, the renderer uses the scene's suggested AO radius instead of def
     * (radii are world units, and scenes come in metres, millimetres or anything else). */
    bool follows_scene_radius;
    const char *const *options; /* OB_PARAM_ENUM: option names, max+1 of them */
} ob_param_info;

typedef struct ob_method_info {
    const char *name;
    const char *description;
    const char *reference; /* seed / paper section */
    int param_count;
    const ob_param_info *params;
} ob_method_info;

int ob_method_count(void);
const ob_method_info *ob_method_at(int index);
/* Index of the method, or -1. */
int ob_find_method(const char *name);

/* ---- filters: the denoising registry (same table shape as the methods) --------------------- */
typedef ob_method_info ob_filter_info;

int ob_filter_count(void);
const ob_filter_info *ob_filter_at(int index);
/* Index of the filter, or -1. */
int ob_find_filter(const char *name);

/* ---- HDR (seed 003 §2.2, §5.5, §6.5) -------------------------------------------------------- */
typedef struct ob_hdr_settings {
    bool enabled;          /* false (--hdr off): radiance clamped to [0,1] before sRGB */
    float exposure;        /* linear scale applied to the radiance first (default 1) */
    float key;             /* Reinhard's key alpha (eq. 2.2); 0 = automatic from the log-average (§6.5) */
    float l_white;         /* eq. 2.4: the smallest scaled luminance mapped to white; 0 = eq. 2.3 */
    float bloom_threshold; /* scaled luminance above which the bright pass keeps the excess */
    float bloom_strength;  /* how much of the blurred excess is added back; 0 = no bloom */
} ob_hdr_settings;

/* The HDR math on the CPU, the same formulas the shaders use (for tests and tools):
 * log-average luminance (eq. 2.1) of n values, Reinhard with L_white (eq. 2.4, eq. 2.3 when
 * l_white <= 0) and the automatic key for a log-average. */
double ob_hdr_log_average(const float *luminance, size_t n);
float ob_hdr_reinhard(float scaled_luminance, float l_white);
float ob_hdr_auto_key(float log_average);

/* ---- per-frame settings --------------------------------------------------------------------- */
/* Ambient light: a constant, a sky/ground hemisphere, or the environment map given to
 * ob_renderer_set_environment (its diffuse irradiance through 9 spherical-harmonic terms). */
typedef enum ob_ambient_mode { OB_AMBIENT_CONSTANT = 0, OB_AMBIENT_HEMISPHERE, OB_AMBIENT_ENVIRONMENT } ob_ambient_mode;

typedef struct ob_settings {
    int method;                   /* registry index */
    float params[OB_MAX_PARAMS];  /* in the method's parameter-table order */
    uint32_t params_set;          /* bit i: params[i] was set explicitly */
    int filter;                   /* filter registry index (default "geometry") */
    float filter_params[OB_MAX_PARAMS];
    uint32_t filter_params_set;   /* bit i: filter_params[i] was set explicitly */
    float ao_scale;               /* 1, 0.5 or 0.25: the AO runs at this fraction of the size */
    bool adaptive;                /* per-pixel sample counts from an edge pre-pass (seed 003 §4.1) */
    ob_hdr_settings hdr;
    ob_light lights[OB_MAX_LIGHTS];
    int light_count;              /* 0 = the scene's lights */
    ob_shadow_settings shadow;
    ob_ambient_mode ambient_mode;
    float ambient[3];             /* constant ambient radiance (multiplied by AO) */
    float sky[3], ground[3];      /* hemisphere ambient: radiance from above and from below */
    bool ao_all_light;            /* AO darkens all light, not only the ambient term */
    float background[3];          /* linear RGB of pixels with no geometry */
} ob_settings;

/* Defaults for a method (by name; NULL = "ssao"). Errors: OB_ERR_UNKNOWN_METHOD. */
ob_error ob_settings_init(ob_settings *settings, const char *method);
/* Set "method.param=value", "filter.param=value" (the current filter) or "param=value" (the
 * current method) from text, validated against the table. Errors: OB_ERR_UNKNOWN_METHOD (an
 * unknown prefix), OB_ERR_UNKNOWN_PARAM, OB_ERR_OUT_OF_RANGE, OB_ERR_INVALID_ARGUMENT
 * (malformed, NaN, not an integer, a parameter of a method or filter not in use). */
ob_error ob_settings_set(ob_settings *settings, const char *assignment);
/* The value of a parameter of the current method by name, or NaN if unknown. */
float ob_settings_get(const ob_settings *settings, const char *param);
/* Pick the filter (its parameters reset to their defaults). Errors: OB_ERR_UNKNOWN_METHOD. */
ob_error ob_settings_set_filter(ob_settings *settings, const char *filter);
/* The value of a parameter of the current filter, or NaN. */
float ob_settings_get_filter(const ob_settings *settings, const char *param);
/* 1, 0.5 or 0.25 (seed 000 §4.7.1, seed 003 §4.4). Errors: OB_ERR_OUT_OF_RANGE. */
ob_error ob_settings_set_ao_scale(ob_settings *settings, float scale);

/* Quality presets (seed 000 §3.2.3, §5.1): "low" 12, "medium" 24, "high" 36, "ultra" 64 samples
 * per pixel. Returns the count, or -1 for an unknown name. */
int ob_quality_samples(const char *name);
/* Give the current method `samples` samples per pixel: the `samples` parameter, or what the
 * method makes of the count (HBAO: directions x steps). Marks what it sets as explicit.
 * Errors: OB_ERR_OUT_OF_RANGE (beyond the method's table), OB_ERR_INVALID_ARGUMENT (the method
 * takes no sample count, e.g. none — then nothing changes). */
ob_error ob_settings_set_samples(ob_settings *settings, int samples);

/* ---- renderer ------------------------------------------------------------------------------- */
typedef struct ob_renderer_desc {
    int width, height; /* zero = 640x480 */
} ob_renderer_desc;

typedef struct ob_renderer ob_renderer;

/* Errors: OB_ERR_BAD_SIZE (zero, negative or above GL_MAX_TEXTURE_SIZE), OB_ERR_SHADER. */
ob_renderer *ob_make_renderer(ob_context *ctx, const ob_renderer_desc *desc);
void ob_destroy_renderer(ob_renderer *r);
/* Upload a scene's meshes and textures. The renderer keeps no pointer to the ob_scene. */
ob_error ob_renderer_set_scene(ob_renderer *r, const ob_scene *scene);
/* The environment map (equirectangular Radiance .hdr) for OB_AMBIENT_ENVIRONMENT and SSDO.
 * Errors: OB_ERR_IO. */
ob_error ob_renderer_set_environment(ob_renderer *r, const char *hdr_path);

/* shadow maps -> G-buffer -> direct light -> [downsample] -> [edges] -> AO -> filter -> [upsample]
 * -> compose -> HDR (luminance, bloom, tone map), each pass timed. */
ob_error ob_render_frame(ob_renderer *r, const ob_camera *camera, const ob_settings *settings);

typedef enum ob_image_kind {
    OB_IMAGE_FINAL_RGBA8 = 0, /* sRGB, rows top to bottom, 4 bytes per pixel */
    OB_IMAGE_AO_F32,          /* visibility after filter and upsampling, 1 float per pixel, bottom row first */
    OB_IMAGE_AO_RAW_F32,      /* visibility before the filter, at the AO resolution (ao_scale) */
    OB_IMAGE_DEPTH_F32,       /* linear view depth (0 where no geometry), bottom row first */
    OB_IMAGE_NORMAL_F32,      /* view-space normal xyz, 3 floats per pixel, bottom row first */
    OB_IMAGE_SAMPLES_F32,     /* samples each pixel took (adaptive sampling varies it), bottom row first */
    OB_IMAGE_RADIANCE_F32,    /* direct light (all lights, shadowed), linear RGB, 3 floats, bottom row first */
    OB_IMAGE_SHADOW_F32,      /* the key light's visibility (0 where it faces away), bottom row first */
    OB_IMAGE_HDR_F32,         /* the composed linear radiance before tone mapping, 3 floats */
    /* Directional methods (ssdo, ssdo_merged) write an RGB modulation factor M instead of one
     * visibility: OB_IMAGE_AO_F32 and OB_IMAGE_AO_RAW_F32 then hold the average of M's three
     * channels, and these two the full picture (AO methods: AO in all three, and a zero bounce). */
    OB_IMAGE_AO_RGB_F32,      /* M after filter and upsampling, 3 floats per pixel, bottom row first */
    OB_IMAGE_BOUNCE_F32,      /* the one-bounce indirect light off a white receiver (compose multiplies
                                 it by the albedo), after filter and upsampling, 3 floats, bottom row first */
} ob_image_kind;

/* Bytes needed for an image of the renderer's size. */
size_t ob_image_size(const ob_renderer *r, ob_image_kind kind);
ob_error ob_read_image(ob_renderer *r, ob_image_kind kind, void *dst, size_t dst_size);

typedef struct ob_pass_timing {
    const char *name; /* "shadow", "gbuffer", "lighting", "downsample", "edges", "ao", "filter",
                         "upsample", "compose", "luminance", "bloom", "tonemap" */
    double ms;        /* GPU time between GL_TIMESTAMP queries around the pass */
} ob_pass_timing;

/* Timings of the last frame; returns the count written (at most max). */
int ob_query_timings(ob_renderer *r, ob_pass_timing *out, int max);

/* Run the current method on an engine's own textures (ob_renderer still owns the scratch
 * targets). Not for directional methods (ssdo*: they need the frame's direct light; errors
 * OB_ERR_INVALID_ARGUMENT). linear_depth is R32F positive view depth, normal is RGBA16F/RGBA32F view-space
 * normal, both of the renderer's size; ao_out is an R8/R16F/R32F texture of that size. proj is the
 * column-major projection matrix used to rasterise them. */
ob_error ob_compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex,
                       const float proj[16], const ob_settings *settings, uint32_t ao_out_tex);

/* ---- image files (written atomically: temporary file, then rename) -------------------------- */
/* Top-row-first RGBA8 or grey (channels 1, 3 or 4). */
ob_error ob_write_png(const char *path, int width, int height, int channels, const uint8_t *px);
/* PFM: bottom-row-first floats, channels 1 (Pf) or 3 (PF), little-endian. */
ob_error ob_write_pfm(const char *path, int width, int height, int channels, const float *px);
/* Reads a PFM; *px is malloc'd (free it). */
ob_error ob_read_pfm(const char *path, int *width, int *height, int *channels, float **px);

#ifdef __cplusplus
}
#endif
#endif /* OBSCURA_H */
