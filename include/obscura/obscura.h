/*
 * obscura.h — libobscura's engine API: screen-space ambient occlusion and indirect light on an
 * engine's own depth and normals (the host path, docs/embedding.md), and what it is configured
 * with (methods, filters, settings, the renderer that holds the targets).
 *
 * libobscura is the core library: it needs OpenGL 4.5 (through libepoxy) and nothing else. Two
 * more headers go with it:
 *   obscura/scene.h  also libobscura: scenes, lights, stereo cameras and the frame renderer that
 *                    draws a scene itself (G-buffer, lighting, shadows, HDR), as the CLI does;
 *   obscura/eval.h   libobscura-eval, the laboratory above the core: scenes loaded from files
 *                    (Assimp), the ray-traced ground truth (Embree), metrics, masks, image files.
 * CMake: find_package(obscura) gives obscura::obscura; find_package(obscura COMPONENTS eval) adds
 * obscura::eval. pkg-config: obscura, obscura-eval.
 *
 * The frame flows one way (README.md, docs/methods.md): scene -> G-buffer -> AO method -> filter ->
 * [upsample] -> compose -> sRGB. Every screen-space pass is a GLSL compute shader with its own GPU timer.
 *
 * Conventions
 *   - AO value = visibility in [0,1]; 1 = open sky.
 *   - View space is OpenGL's: the camera looks down -Z; linear depth is the positive distance
 *     along -Z. Radii are in world units.
 *   - Desc structs: zero means "default" (sokol style), resolved in one place per object.
 *   - "seed N §x" cites one of the three theses the methods come from (Belonogov 2018, SSDO thesis, Puri 2024), as
 *     the top of README.md lists them; docs/methods.md gives each method's sources.
 *
 * Errors
 *   Functions that can fail return an ob_error (or NULL, or a value documented as the failure)
 *   and record a one-line message that ob_get_error() returns (glfwGetError style); each
 *   function's comment names the errors it returns, or says "Never fails" (it records no error)
 *   or what it returns for NULL or out-of-range arguments. Library code never aborts or prints.
 *
 * Lifetimes
 *   Strings and table entries the library returns (names, ob_method_info, ob_query_renderer...)
 *   are static or owned by the object they came from, valid as long as it lives; the caller
 *   frees nothing the library returns unless the comment says so (ob_read_pfm's pixels, and the
 *   objects made by ob_make_* / ob_load_scene / ob_tessellate_scene, destroyed by ob_destroy_*).
 *   What a call is given (strings, arrays, desc structs) is read during the call: the library
 *   copies what it keeps and holds no pointer into the caller's memory, except the objects it is
 *   handed (a renderer keeps its context) and the error callback's user pointer.
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

/* libobscura.so exports what this header and obscura/scene.h declare (and libobscura-eval.so what
 * obscura/eval.h declares): the libraries are compiled with -fvisibility=hidden, and this pragma
 * (popped at the end) gives these declarations default visibility. */
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- version ---------------------------------------------------------------------------------
 * The version of this header; ob_version gives the library's, so a host can check at run time that
 * the library it loaded is the one it was built against. The shared library's soname follows the
 * ABI: libobscura.so.MAJOR from 1.0 on, libobscura.so.0.MINOR before (every 0.x minor release may
 * break the ABI). `make test` compares the library's ABI with the committed abi/libobscura.abi
 * (abidiff): any change fails until the baseline is remade (scripts/abi-baseline.sh), which refuses
 * an incompatible change unless the version, and with it the soname, moved. docs/changelog.md says
 * what changed for hosts in each version. CMake's project version is read from these lines. */
#define OB_VERSION_MAJOR 0
#define OB_VERSION_MINOR 4
#define OB_VERSION_PATCH 0
#define OB_VERSION_STRING "0.4.0"

/* The library's version: its numbers (each pointer may be NULL) and "MAJOR.MINOR.PATCH". A host
 * built against this header works with a library of the same MAJOR (and, before 1.0, the same
 * MINOR). The string is static (valid for the process). Never fails. */
const char *ob_version(int *major, int *minor, int *patch);

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

/* The last error on this thread, then forgets it, as glfwGetError does: a second call returns
 * OB_OK. message may be NULL; *message (never NULL) is the one-line message of the last error
 * recorded on this thread, kept after the read so that a log line can still quote it ("" before
 * any). It points into this thread's own buffer, valid on this thread until the next error
 * recorded here or ob_clear_error overwrites it: copy it to keep it. Never fails. */
ob_error ob_get_error(const char **message);
/* Called on the failing thread with each error as it is recorded (before the failing call
 * returns), e.g. to log it; the message is valid during the call only. NULL removes it. The
 * error is still there for ob_get_error afterwards. `user` is kept and passed back until the
 * callback is replaced. Process-wide and unsynchronised: set it before other threads use the
 * library. Never fails. */
typedef void (*ob_error_callback)(ob_error err, const char *message, void *user);
void ob_set_error_callback(ob_error_callback callback, void *user);
/* The enum's name, e.g. "OB_ERR_UNKNOWN_METHOD"; "OB_ERR_?" for a value outside the enum. Static
 * storage, valid for the process. Never fails. */
const char *ob_error_name(ob_error err);
/* Forget this thread's last error and its message ("" after). Never fails. */
void ob_clear_error(void);

/* ---- GPU context ----------------------------------------------------------------------------
 * A headless OpenGL 4.5 core context from EGL's device platform (EGL_EXT_platform_device), no X
 * server. OB_GPU_AUTO prefers a hardware device and falls back to Mesa's software device
 * (llvmpipe). Or, with use_current, the context the caller already has current (a window's). */
typedef enum ob_gpu_kind { OB_GPU_AUTO = 0, OB_GPU_HW, OB_GPU_SW } ob_gpu_kind;

typedef struct ob_context_desc {
    ob_gpu_kind gpu;
    bool debug; /* GL debug output into the error log (slow) */
    /* Adopt the OpenGL 4.5 core context current on this thread (a GLFW window's, an engine's)
     * instead of making a headless EGL one; ob_destroy_context then leaves it alone (current and
     * alive). gpu is ignored. The context must stay current on this thread, and alive, for as long
     * as anything made from the ob_context is used or destroyed. Whether a context is current is
     * asked of EGL and GLX first, so calling this with none is an error, not a crash. */
    bool use_current;
} ob_context_desc;

typedef struct ob_context ob_context;

/* desc NULL = all defaults. A headless context is left current on the calling thread. The
 * context is the caller's: ob_destroy_context, after every renderer made from it. NULL on
 * failure. Errors: OB_ERR_NO_CONTEXT (message names every device and step that was tried;
 * use_current: no current context, or one below desktop OpenGL 4.5, named by renderer and
 * version), OB_ERR_OUT_OF_MEMORY. */
ob_context *ob_make_context(const ob_context_desc *desc);
/* Destroy the context (its EGL context and display; an adopted one is left alone, current and
 * alive). Destroy the renderers made from it first: they keep a pointer to it and need its GL
 * context to free their objects. NULL is a no-op. Never fails. */
void ob_destroy_context(ob_context *ctx);
/* What the context is, read once when it was made. The strings are owned by the context, valid
 * until ob_destroy_context; NULL gives "" (false, 0). Never fail. */
const char *ob_query_renderer(const ob_context *ctx); /* GL_RENDERER */
const char *ob_query_gl_version(const ob_context *ctx); /* GL_VERSION */
const char *ob_query_device(const ob_context *ctx);   /* which EGL device was used, or "the caller's context" */
bool ob_query_is_software(const ob_context *ctx);     /* a software rasteriser (llvmpipe) */
int ob_query_max_texture_size(const ob_context *ctx); /* GL_MAX_TEXTURE_SIZE */

/* ---- cameras, lights and shadow maps: what a frame is seen with and lit by -------------------- */
typedef struct ob_camera {
    float eye[3];
    float target[3];
    float up[3];      /* zero = world up (+Y) */
    float fov_y_deg;  /* zero = 60 */
    float near_z;     /* zero = derived from the scene bounds */
    float far_z;      /* zero = derived from the scene bounds */
    /* Lens shift: an off-axis frustum, e.g. one eye of a stereo pair (ob_stereo_cameras). The
     * frustum's window moves by shift[0] (shift[1]) of its half-width (half-height) to the right
     * (up) without turning the view: the projection's P20 = shift[0], P21 = shift[1]. The window
     * keeps its size, so fov_y_deg is still its vertical extent. Zero = symmetric. */
    float shift[2];
    char name[64];
} ob_camera;


/* Checks a camera as every source must have it (the CLI's options, sidecars, built-in presets, a
 * host's own), so that no frame renders nothing or NaN from a camera: eye, target, up and shift
 * finite, each coordinate within +-OB_MAX_COORDINATE (its squares still fit a float); eye !=
 * target; up (zero = +Y) not parallel to the view direction (the roll would be undefined:
 * lookAt's cross product vanishes); fov_y_deg 0 (= 60) or in [OB_MIN_FOV_DEG, 179); near_z and
 * far_z both 0 (fitted to the scene) or 0 < near_z < far_z, finite. Pure CPU, thread-safe.
 * Errors: OB_ERR_INVALID_ARGUMENT with what is wrong ("up is parallel to the view direction"); the
 * caller names where the camera came from. */
#define OB_MAX_COORDINATE 1e18f
#define OB_MIN_FOV_DEG 0.01f
ob_error ob_check_camera(const ob_camera *cam);
/* The matrices ob_render_frame draws a camera with, for a frame of width x height: *cam's
 * defaults filled in (fov 0 = 60 degrees, up 0 = +Y, near_z and far_z both 0 = fitted to
 * bounds_min..bounds_max, the scene's ob_query_scene_stats bounds; NULL bounds = keep them, then
 * they must be set), view = lookAt(eye, target, up) and an OpenGL perspective projection with the
 * lens shift in P20, P21, column-major. A host that draws a project scene itself uses them to
 * match `obscura render` (and *cam then holds the planes used). Pure CPU. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL, a size below 1x1, what ob_check_camera refuses, no planes and no
 * bounds). */
ob_error ob_camera_matrices(ob_camera *cam, const float bounds_min[3], const float bounds_max[3], int width, int height,
                            float view[16], float proj[16]);

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

typedef enum ob_shadow_method { OB_SHADOW_NONE = 0, OB_SHADOW_HARD, OB_SHADOW_PCF, OB_SHADOW_VSM } ob_shadow_method;

/* Shadow maps (SSDO thesis §2.1, §5.1, §6.1) for every light up to 4: directional and spot lights
 * through one 2D map each, point lights through a cube map. */
typedef struct ob_shadow_settings {
    ob_shadow_method method;
    int size;             /* map resolution (square, per face for cube maps); default 2048 */
    float bias;           /* constant depth bias, in map texels' world size */
    float slope_bias;     /* slope-scaled bias, x tan(angle to the light) */
    int pcf_radius;       /* PCF: taps each side of the kernel (1 = 3x3 bilinear comparisons) */
    float vsm_blur;       /* VSM: Gaussian sigma of the moment blur, in map texels */
    float vsm_bleed;      /* VSM: light-bleeding reduction threshold in [0, 1) */
    int vsm_bits;         /* VSM: bits per stored moment, 16 (RG16F) or 32 (RG32F; 0 = 32): SSDO thesis
                             §6.1 / Fig. 6.5's precision comparison, docs/lighting.md */
    /* Keep the maps from the last frame while the lights, these settings and the scene are
     * unchanged: the scene is static, so the maps do not depend on the camera (the viewer sets
     * this; a frame that reuses them has no "shadow" timing). false: render them every frame, as
     * the benchmarks time them. */
    bool reuse;
} ob_shadow_settings;

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
    bool directional;      /* writes RGB modulation (SSDO) or a bounce (vbgi): compare its radiance too */
    bool adapts;           /* takes per-pixel sample counts (ob_settings.adaptive); for the others the
                              renderer skips the edge pass and the setting does nothing */
    int param_count;
    const ob_param_info *params;
} ob_method_info;

/* The registry is fixed at build time and read-only: these are thread-safe and never fail. */
int ob_method_count(void);
/* NULL when index is out of range. The entry and everything it points to (names, parameter
 * table, option names) are static: valid for the process, never freed. */
const ob_method_info *ob_method_at(int index);
/* Index of the method, or -1 for an unknown name or NULL (no error recorded). */
int ob_find_method(const char *name);

/* ---- filters: the denoising registry (same table shape as the methods) --------------------- */
typedef ob_method_info ob_filter_info;

/* As the methods': thread-safe, never fail. */
int ob_filter_count(void);
/* NULL when index is out of range; the entry is static, valid for the process. */
const ob_filter_info *ob_filter_at(int index);
/* Index of the filter, or -1 for an unknown name or NULL (no error recorded). */
int ob_find_filter(const char *name);

/* ---- HDR settings: exposure, tone mapping, bloom (SSDO thesis §2.2, §5.5, §6.5) ------------------ */
typedef struct ob_hdr_settings {
    bool enabled;          /* false (--hdr off): radiance clamped to [0,1] before sRGB */
    float exposure;        /* linear scale applied to the radiance first (default 1) */
    float key;             /* Reinhard's key alpha (eq. 2.2); 0 = automatic from the log-average (§6.5) */
    float l_white;         /* eq. 2.4: the smallest scaled luminance mapped to white; 0 = eq. 2.3 */
    float bloom_threshold; /* scaled luminance above which the bright pass keeps the excess */
    float bloom_strength;  /* how much of the blurred excess is added back; 0 = no bloom */
} ob_hdr_settings;

/* ---- per-frame settings --------------------------------------------------------------------- */
/* Ambient light: a constant, a sky/ground hemisphere, or the environment map given to
 * ob_renderer_set_environment (its diffuse irradiance through 9 spherical-harmonic terms). */
typedef enum ob_ambient_mode { OB_AMBIENT_CONSTANT = 0, OB_AMBIENT_HEMISPHERE, OB_AMBIENT_ENVIRONMENT } ob_ambient_mode;

typedef struct ob_settings {
    int method;                   /* registry index */
    float params[OB_MAX_PARAMS];  /* in the method's parameter-table order */
    uint32_t params_set;          /* bit i: params[i] was set explicitly */
    /* Every method's "radius_scale" (OB_RADIUS_SCALE_MIN..MAX; 0 = 1): its radius parameters (those
     * that follow the scene's radius R) are scale x R, or scale x the value set, so a method whose
     * own definition wants a wider search can have one while the frame is still graded at R. */
    float radius_scale;
    int filter;                   /* filter registry index (default "crease") */
    float filter_params[OB_MAX_PARAMS];
    uint32_t filter_params_set;   /* bit i: filter_params[i] was set explicitly */
    int ao_divisor;               /* 1, 2 or 4 (0 = 1): the AO runs at 1/ao_divisor of the size on the
                                     grid of full pixels k i + o (Belonogov 2018 §4.7.1, SSDO thesis §4.4) */
    bool adaptive;                /* per-pixel sample counts from an edge pre-pass (SSDO thesis §4.1) */
    ob_hdr_settings hdr;
    ob_light lights[OB_MAX_LIGHTS];
    int light_count;              /* 0 = the scene's lights */
    ob_shadow_settings shadow;
    ob_ambient_mode ambient_mode;
    float ambient[3];             /* constant ambient radiance (multiplied by AO) */
    float sky[3], ground[3];      /* hemisphere ambient: radiance from above and from below */
    bool ao_all_light;            /* AO darkens all light, not only the ambient term */
    /* Jimenez et al. 2016's multi-bounce fit (§5, "Approximated multiple bounces"): the AO the
     * ambient term is multiplied by becomes max(v, ((a v + b) v + c) v) per colour channel, with
     * a, b, c linear in the albedo, so light bouncing between nearby bright surfaces lifts the
     * occlusion (white walls lose about half of their darkening, black ones none). */
    bool multibounce;
    /* Draw every material in its diffuse colour alone, its texture ignored (Puri 2024 §3.6, §4.1:
     * the AO is easier to judge on untextured surfaces). false = textures on. */
    bool textures_off;
    float background[3];          /* linear RGB of pixels with no geometry */
    /* Guard band (Belonogov 2018 §3.2.2), px per side, 0 = off: the G-buffer, the direct light, the AO
     * method, its filter and the upsampler run on (W + 2g) x (H + 2g) with the projection widened
     * so that the visible W x H frame is exactly its centre, and compose crops; occluders up to g
     * pixels beyond the frame's edge then darken its border. Rounded up to a multiple of 4 x
     * ao_divisor (the AO grid and its 4x4 rotation tile fall on the same visible pixels as without
     * the band). Everything read back or presented is the visible frame. A change reallocates the
     * targets at the next ob_render_frame; W + 2g above GL_MAX_TEXTURE_SIZE is OB_ERR_BAD_SIZE
     * there. Not for ob_compute_ao (see there). "guard=PX" in ob_settings_set. */
    int guard;
    /* Temporal accumulation (docs/temporal.md): a pass at the AO resolution that
     * reprojects last frame's accumulated AO (and M, bounce) through this frame's depth and last
     * frame's camera (static scenes), drops it where depth or normal say the surface is new
     * (disocclusion), clamps it to this frame's 4x4 neighbourhood and blends with a history of
     * temporal_frames frames. It also turns every stochastic method's noise with the frame index:
     * gtao/vbao/vbgi's "temporal" parameter (R2 jitters) unless set explicitly, and a per-frame
     * rotation of the random-kernel methods' noise. A new method, AO scale or size starts the
     * history again. "temporal=on|off", "temporal_at=before|after", "temporal_frames=N",
     * "temporal_detail=A" in ob_settings_set. Not for ob_compute_ao. */
    bool temporal;
    int temporal_at;              /* ob_temporal_at: before (default) or after the spatial filter */
    int temporal_frames;          /* history length N, 1..OB_TEMPORAL_FRAMES_MAX (0 = OB_TEMPORAL_FRAMES_DEFAULT) */
    /* The least share A in [0, 1) of one-pixel detail (a crease line, a window frame) that the
     * history keeps while the camera moves: every moving frame resamples the history between
     * pixels, which fades such detail toward its neighbours' average; A > 0 weighs the current
     * frame more where this frame's resampling fades most (docs/temporal.md, "Thin detail under
     * motion"). A sharper image against the reference for more flicker; 0 (default) = no bound, a
     * still camera is the same either way. "temporal_detail=A" in ob_settings_set. */
    float temporal_detail;
    /* How the upsampler reads the AO grid at ao_divisor 2 or 4 (ob_upsample_program; the same
     * bits either way): "upsample=auto|plain|block" in ob_settings_set. */
    int upsample;
    /* Sub-pixel jitter of ob_render_frame's G-buffer, as a TAA host jitters its raster: 0 = off
     * (every pass samples the pixel centres), else the number of positions J
     * (1..OB_JITTER_POSITIONS_MAX) it cycles through with the frame index, the Halton (2, 3)
     * points ob_jitter_offset gives. Every pass reads the jittered G-buffer, and the temporal
     * accumulation reprojects without the jitter (the history stays at the pixel centres), so a
     * still camera's history averages the AO over J points of each pixel's footprint instead of
     * its centre alone (docs/temporal.md, "Jitter"). The lit image moves by the jitter too: meant
     * with temporal on. "jitter=J|on|off" in ob_settings_set (on = OB_JITTER_POSITIONS_DEFAULT).
     * Not for ob_host_ao: the host jitters its own raster (ob_host_frame.jitter). */
    int jitter;
} ob_settings;

#define OB_JITTER_POSITIONS_DEFAULT 8
#define OB_JITTER_POSITIONS_MAX 64
/* The sub-pixel offset of jitter position `index` (taken modulo `positions`), in pixels, each
 * coordinate in (-0.5, 0.5): the Halton points of bases 2 and 3 from index 1, minus one half. The
 * pixel's sample moves by +offset (its projection's P20 grows by 2 offset[0] / width, P21 by
 * 2 offset[1] / height). ob_render_frame with ob_settings.jitter = J uses position
 * (frame number mod J). positions < 1 or offset NULL: OB_ERR_INVALID_ARGUMENT. */
ob_error ob_jitter_offset(int index, int positions, float offset[2]);

/* The upsampler's program (ob_settings.upsample; docs/filters.md, "Subsampling"). */
typedef enum ob_upsample_program {
    OB_UPSAMPLE_AUTO = 0, /* block on a software rasteriser, plain on a GPU */
    OB_UPSAMPLE_PLAIN,    /* one invocation per pixel, 27 fetches each: the baseline */
    OB_UPSAMPLE_BLOCK,    /* one invocation per k x k pixels, the 4x4 AO samples around them read once */
    OB_UPSAMPLE_PROGRAM_COUNT
} ob_upsample_program;
/* "auto", "plain", "block" (--upsample and "upsample=" take these names); "" if out of range.
 * Static storage, valid for the process. Never fails. */
const char *ob_upsample_program_name(ob_upsample_program program);

/* Where the accumulation runs in the AO chain (ob_settings.temporal_at). */
typedef enum ob_temporal_at {
    OB_TEMPORAL_BEFORE_FILTER = 0, /* method -> accumulate -> filter: the filter smooths the history too */
    OB_TEMPORAL_AFTER_FILTER,      /* method -> filter -> accumulate: the history holds filtered AO */
} ob_temporal_at;
#define OB_TEMPORAL_FRAMES_DEFAULT 16
#define OB_TEMPORAL_FRAMES_MAX 256

/* The largest ob_settings.guard ob_settings_set takes (the GL's texture size limits it further). */
#define OB_GUARD_MAX 4096

/* The range of ob_settings.radius_scale ("METHOD.radius_scale=V" in ob_settings_set). */
#define OB_RADIUS_SCALE_MIN 0.25f
#define OB_RADIUS_SCALE_MAX 4.0f

/* The default method: the one closest to the ray-traced AO_R over the graded views (vbao: mean
 * RMSE 0.0355 against gtao's 0.0469 over the 16 choose views its defaults were chosen on, 0.0398
 * against 0.0517 over 17 check views never chosen on; docs/methods.md, "Choose and check views"). */
#define OB_DEFAULT_METHOD "vbao"

/* Defaults for a method (by name; NULL = OB_DEFAULT_METHOD): every field of *settings is
 * overwritten. Errors: OB_ERR_INVALID_ARGUMENT (NULL settings), OB_ERR_UNKNOWN_METHOD (the
 * message lists the methods); *settings is untouched on error. */
ob_error ob_settings_init(ob_settings *settings, const char *method);
/* Set "method.param=value", "filter.param=value" (the current filter) or "param=value" (the
 * current method) from text, validated against the table; "method.radius_scale=value" for every
 * method (ob_settings.radius_scale); "guard=PX" the guard band (ob_settings.guard, 0..OB_GUARD_MAX
 * pixels per side); "temporal=on|off", "temporal_at=before|after", "temporal_frames=N" and "temporal_detail=A"
 * the temporal accumulation (ob_settings.temporal*); "jitter=J|on|off" the sub-pixel jitter
 * (ob_settings.jitter, 0..OB_JITTER_POSITIONS_MAX positions). Errors: OB_ERR_UNKNOWN_METHOD (an
 * unknown prefix), OB_ERR_UNKNOWN_PARAM, OB_ERR_OUT_OF_RANGE, OB_ERR_INVALID_ARGUMENT
 * (NULL, settings not initialised, malformed, NaN, not an integer, a parameter of a method or
 * filter not in use); *settings is unchanged on error. */
ob_error ob_settings_set(ob_settings *settings, const char *assignment);
/* The value of a parameter of the current method by name ("radius_scale", "guard", "jitter", "temporal" (0/1),
 * "temporal_at" (ob_temporal_at), "temporal_frames" and "temporal_detail" too), or NaN if unknown,
 * for NULL arguments or settings not initialised (no error recorded). */
float ob_settings_get(const ob_settings *settings, const char *param);
/* Pick the filter (its parameters reset to their defaults). Errors: OB_ERR_INVALID_ARGUMENT (NULL),
 * OB_ERR_UNKNOWN_METHOD (an unknown filter; the message lists them); *settings is unchanged on
 * error. */
ob_error ob_settings_set_filter(ob_settings *settings, const char *filter);
/* The value of a parameter of the current filter, or NaN if unknown or for NULL arguments (no
 * error recorded). */
float ob_settings_get_filter(const ob_settings *settings, const char *param);
/* The AO resolution as a divisor of the size: 1, 2 or 4 (Belonogov 2018 §4.7.1, SSDO thesis §4.4).
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_OUT_OF_RANGE. */
ob_error ob_settings_set_ao_divisor(ob_settings *settings, int divisor);
/* The same as a fraction, as the CLI's --ao-scale takes it: exactly 1, 0.5 or 0.25 (divisor 1, 2,
 * 4). Errors: OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_OUT_OF_RANGE. */
ob_error ob_settings_set_ao_scale(ob_settings *settings, float scale);

/* Quality presets (Belonogov 2018 §3.2.3, §5.1): "low" 12, "medium" 24, "high" 36, "ultra" 64 samples
 * per pixel (vbao and vbgi take 64 as 5 slices x 6 steps x 2 sides = 60: they keep 6 steps at
 * every count). Returns the count, or -1 for an unknown name or NULL (no error recorded). */
int ob_quality_samples(const char *name);
/* Give the current method `samples` samples per pixel: the `samples` parameter, or what the
 * method makes of the count (HBAO: directions x steps). Marks what it sets as explicit.
 * Errors: OB_ERR_OUT_OF_RANGE (beyond the method's table), OB_ERR_INVALID_ARGUMENT (NULL or
 * settings not initialised, or the method takes no sample count, e.g. none); nothing changes on
 * error. */
ob_error ob_settings_set_samples(ob_settings *settings, int samples);
/* The sample kernel of the settings' method at their (fixed) sample count, as the shader gets it:
 * xyz per entry in the kernel's frame (+Z = the surface normal for hemisphere kernels; crytek's
 * fills the sphere), w 0, at most max entries (4 floats each, into the caller's xyzw). Returns the
 * entries written: 0 for a method without a kernel (the slice and horizon methods march instead)
 * or max 0, -1 with OB_ERR_INVALID_ARGUMENT recorded for NULL arguments, max < 0 or settings not
 * initialised. Halton kernels repeat their pattern every 10 entries (bases 2 x 5; 30 with
 * the length's base 3): the viewer's kernel view shows it (SSDO thesis Fig. 4.1/4.2). */
int ob_method_kernel(const ob_settings *settings, float *xyzw, int max);

/* ---- renderer ------------------------------------------------------------------------------- */
typedef struct ob_renderer_desc {
    int width, height; /* zero = 640x480 */
} ob_renderer_desc;

typedef struct ob_renderer ob_renderer;

/* A renderer on ctx's GL context, which must be current on this thread (desc NULL = 640x480).
 * It keeps a pointer to ctx: destroy it (ob_destroy_renderer) before the context. NULL on
 * failure. It checks its own GL calls with glGetError, so a GL error the caller left pending is
 * read and dropped first: read yours before calling it (ob_render_frame, ob_render_floor,
 * ob_read_image, ob_read_view and ob_wait_timings do the same; the host path reads none). Errors: OB_ERR_INVALID_ARGUMENT (NULL ctx), OB_ERR_BAD_SIZE (one side zero, negative
 * or above GL_MAX_TEXTURE_SIZE), OB_ERR_SHADER (the passes compiled up front),
 * OB_ERR_OUT_OF_MEMORY, OB_ERR_GL (the GL could not make the targets). */
ob_renderer *ob_make_renderer(ob_context *ctx, const ob_renderer_desc *desc);
/* About the bytes the targets of a renderer of width x height take once it has rendered with each
 * of settings[0..count-1] (targets are made on first use and kept): the G-buffer and full-size
 * targets enlarged by the guard band, each AO scale's chain with the directional, bent-normal and
 * temporal targets its methods use, the second depth layer, the extra view, the depth MIP chain,
 * the bloom chain and the shadow maps of the settings' lights (with none of their own: the key
 * light, one map). A software rasteriser keeps all of it in host memory. Needs no context: for a
 * check before anything is allocated. The scene's meshes and textures are not included (the
 * import counts them: ob_scene_desc). 0 with OB_ERR_INVALID_ARGUMENT for a size below 1x1, NULL
 * settings, count < 1 or an unknown method. Pure CPU. */
uint64_t ob_estimate_renderer_memory(int width, int height, const ob_settings *settings, int count);
/* The default memory limit of a run: 4 GiB or half the physical memory, whichever is less
 * (ob_scene_desc.max_memory's default in obscura/eval.h, the CLI's --max-memory). Never fails. */
uint64_t ob_default_max_memory(void);
/* Free the renderer's GL objects and memory: its context must be current on this thread. The
 * host's textures are not touched. NULL is a no-op. Never fails. */
void ob_destroy_renderer(ob_renderer *r);
/* A new size for every size-dependent target (a window was resized); the uploaded scene, the
 * environment map, the shadow maps and the compiled programs are kept. The same size is a no-op.
 * The last frame is dropped (ob_present refuses until the next ob_render_frame). Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_BAD_SIZE (zero, negative or above GL_MAX_TEXTURE_SIZE,
 * also with the last frame's guard band added; unlike ob_make_renderer, 0x0 is not "default"),
 * OB_ERR_GL (the GL could not make the targets); on any error the renderer keeps its old size and
 * still works. */
ob_error ob_renderer_resize(ob_renderer *r, int width, int height);
/* The renderer's size (0 x 0 for NULL), the visible frame's: a guard band (ob_settings.guard)
 * does not change it; either pointer may be NULL. Never fails. */
void ob_query_renderer_size(const ob_renderer *r, int *width, int *height);

/* Forget the temporal history (ob_settings.temporal): the next frame starts every pixel's history
 * again, as after a camera cut, and the frame index that moves the methods' noise starts again at
 * 0. NULL is a no-op. Never fails. */
void ob_renderer_reset_history(ob_renderer *r);

/* ---- read-back: the last frame's images into the caller's memory ---------------------------- */

typedef enum ob_image_kind {
    OB_IMAGE_FINAL_RGBA8 = 0, /* sRGB, rows top to bottom, 4 bytes per pixel */
    OB_IMAGE_AO_F32,          /* visibility after filter and upsampling, 1 float per pixel, bottom row first */
    OB_IMAGE_AO_RAW_F32,      /* visibility before the filter, at the AO resolution (ao_scale); vbao's
                               * and vbgi's leave [0, 1] by their noise (an unbiased estimate; the
                               * filter, `none` included, clamps) */
    OB_IMAGE_DEPTH_F32,       /* linear view depth (0 where no geometry), bottom row first */
    OB_IMAGE_NORMAL_F32,      /* view-space normal xyz, 3 floats per pixel, bottom row first */
    OB_IMAGE_SAMPLES_F32,     /* samples each pixel took (adaptive sampling varies it), bottom row first */
    OB_IMAGE_RADIANCE_F32,    /* direct light (all lights, shadowed), linear RGB, 3 floats, bottom row first */
    OB_IMAGE_SHADOW_F32,      /* the key light's visibility (0 where it faces away), bottom row first */
    OB_IMAGE_HDR_F32,         /* the composed linear radiance before tone mapping, 3 floats */
    OB_IMAGE_ALBEDO_F32,      /* the G-buffer's linear albedo, 3 floats per pixel, bottom row first */
    /* Directional methods (ssdo, ssdo_merged) write an RGB modulation factor M instead of one
     * visibility: OB_IMAGE_AO_F32 and OB_IMAGE_AO_RAW_F32 then hold the average of M's three
     * channels, and these two the full picture (AO methods: AO in all three, and a zero bounce). */
    OB_IMAGE_AO_RGB_F32,      /* M after filter and upsampling, 3 floats per pixel, bottom row first */
    OB_IMAGE_BOUNCE_F32,      /* the one-bounce indirect light off a white receiver (compose multiplies
                                 it by the albedo), after filter and upsampling, 3 floats, bottom row first */
    OB_IMAGE_BENT_NORMAL_F32, /* the method's view-space bent normal (gtao with bent_normals on), after
                                 filter and upsampling (not renormalised), 3 floats; zeros otherwise */
    OB_IMAGE_SECOND_DEPTH_F32, /* the second depth layer's linear depth: where the view ray leaves the
                                 solid whose front the first layer shows (depth peeling: the nearest
                                 surface behind the first, where it is that solid's back: the same
                                 connected part wound the other way; docs/methods.md), 0 = none or not
                                 that, when the last frame's method read it (layers = 2, vbao's and
                                 vbgi's default); zeros otherwise. 1 float per pixel, bottom row first */
    OB_IMAGE_EXTRA_RADIANCE_F32, /* the extra view's direct light (ssdo with extra_view=on; zeros otherwise),
                                 linear RGB, 3 floats per pixel, bottom row first */
    OB_IMAGE_HISTORY_AGE_F32, /* temporal accumulation: frames in each pixel's history (1 = just reset by a
                                 disocclusion, temporal_frames at most, 0 = sky), at the AO resolution as
                                 OB_IMAGE_AO_RAW_F32; zeros with temporal off. 1 float, bottom row first */
    OB_IMAGE_MOTION_F32,      /* temporal accumulation: where each AO pixel's point was in the previous
                                 frame, minus where it is, in AO pixels (x, y; y up), at the AO resolution,
                                 without the jitter's change (a still camera: 0 whatever the jitter);
                                 zeros with temporal off. 2 floats per pixel, bottom row first */
} ob_image_kind;

/* Bytes needed for an image of the renderer's size (the AO-grid kinds: at the last frame's AO
 * scale). 0 for NULL r or an unknown kind (no error recorded). */
size_t ob_image_size(const ob_renderer *r, ob_image_kind kind);
/* One of the last ob_render_frame's images into dst (dst_size at least ob_image_size). After an
 * ob_host_ao call (whose results are in the host's own textures) only OB_IMAGE_AO_RAW_F32,
 * OB_IMAGE_HISTORY_AGE_F32 and, when the depth went through the input pass, OB_IMAGE_MOTION_F32
 * are the call's, at the AO grid of its input size. dst is the caller's; nothing is kept. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL, an unknown kind, a small dst, or no such image: none rendered
 * yet, or not since a resize or a failed frame), OB_ERR_OUT_OF_MEMORY (scratch rows for the flip or
 * the conversion), OB_ERR_GL. */
ob_error ob_read_image(ob_renderer *r, ob_image_kind kind, void *dst, size_t dst_size);

/* ---- GPU timings: per-pass times of the frames ---------------------------------------------- */
typedef struct ob_pass_timing {
    const char *name; /* "shadow", "gbuffer", "lighting", "downsample", "edges", "depth_mips", "ao", "temporal", "filter",
                         "upsample", "compose", "luminance", "bloom", "tonemap" */
    double ms;        /* GPU time between GL_TIMESTAMP queries around the pass */
    double cpu_ms;    /* CPU time the calling thread spent issuing the pass (CLOCK_MONOTONIC around
                         its calls), of the same frame; on a GPU mostly the driver's, on a software
                         rasteriser, which runs compute work in the call, close to ms */
} ob_pass_timing;

/* Per-pass GPU (and CPU) times of the newest frame whose timer queries the GPU has finished, read without
 * waiting: the queries of the last 4 frames are kept in a ring, so this is usually a frame one to
 * three behind the last ob_render_frame (ob_query_timings_frame says which). Only the passes that
 * ran in that frame are listed, in the order they ran: a frame that reused its shadow maps
 * (ob_shadow_settings.reuse) has no "shadow". Returns the count written into out (at most max);
 * 0 before any frame has finished, or for NULL r or out or max <= 0: never fails. The names are static strings, valid for the process. Call ob_wait_timings first for
 * the last frame's own timings. */
int ob_query_timings(ob_renderer *r, ob_pass_timing *out, int max);

/* Which frame ob_query_timings describes: *timed gets its number, counting ob_render_frame calls
 * on this renderer from 0 (-1 when none has finished yet), *rendered the number of the last frame
 * rendered (-1 before the first). A host that averages timings adds them when *timed changes.
 * Either pointer may be NULL; NULL r gives -1 for both. Never fails. */
void ob_query_timings_frame(const ob_renderer *r, long long *timed, long long *rendered);

/* Wait until the GPU has finished every frame rendered so far, so that ob_query_timings returns
 * the last one's timings: for one-shot measurements (the CLI's render --timings and bench). It
 * stalls the CPU until the GPU is idle: an interactive loop reads ob_query_timings alone.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_GL. */
ob_error ob_wait_timings(ob_renderer *r);

/* ---- development ---------------------------------------------------------------------------- */
/* Compile shaders from the .glsl/.h files under `dir` (the source tree's shaders/), with #include
 * resolved and #line encoded exactly as at build time, instead of the embedded copies, for every
 * program made from now on (existing programs are untouched: make a new renderer to pick them
 * up). Only files this build embeds can be used (their list numbers the lines); errors in the
 * files surface as OB_ERR_SHADER "shaders/FILE:LINE: ..." when a program is made. NULL = back to
 * the embedded copies. dir is copied. Errors: OB_ERR_IO (dir not a readable directory, or longer
 * than 4095 bytes; the setting is then unchanged). Process-wide and not thread-safe: call it
 * between frames on the GL thread. */
ob_error ob_set_shader_directory(const char *dir);

/* ---- ob_compute_ao: the host path of the first releases --------------------------------------- */
/* The host path of the first releases (ob_host_ao is the whole of it): the settings' method, at
 * the renderer's size, on an engine's linear depth (R32F or R16F positive view depth, or a depth
 * buffer) and view-space normals (any format ob_host_frame takes), written to ao_out (any format
 * ob_host_outputs.ao takes) as the raw AO, OB_IMAGE_AO_RAW_F32 of a frame clamped to [0, 1]; proj is the
 * column-major projection used to rasterise them (perspective or orthographic, as
 * ob_host_frame.projection), view space is taken as world space. AO scale,
 * adaptive sampling, temporal accumulation and the guard band are ignored here, and a radius that
 * was not set stays its default (0.5 world units). Only methods that read depth and normals
 * alone and write plain visibility (not ssdo*, vbgi: OB_ERR_INVALID_ARGUMENT). It runs through
 * ob_host_ao: its textures are checked and the GL state is kept as described there. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL r, proj or settings, settings not initialised, a method above, a
 * texture refused), OB_ERR_OUT_OF_RANGE (a settings field outside its range, even one ignored
 * here), OB_ERR_SHADER, OB_ERR_OUT_OF_MEMORY. Not OB_ERR_GL, as ob_host_ao. */
ob_error ob_compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex,
                       const float proj[16], const ob_settings *settings, uint32_t ao_out_tex);
/* The same, followed by the settings' filter (ob_settings_set_filter) on the same depth and
 * normals: the denoised AO an engine composes with, as OB_IMAGE_AO_F32 of a full-size frame.
 * Errors: as ob_compute_ao. */
ob_error ob_compute_ao_filtered(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex,
                                const float proj[16], const ob_settings *settings, uint32_t ao_out_tex);

/* ---- the host path: libobscura inside an engine (docs/embedding.md) --------------------------
 * An engine hands the library its own depth (a hardware depth buffer or linear depth), its own
 * normals (or none) and, for the indirect-light methods, its direct light and albedo, and gets
 * back AO (and bent normals, indirect light) in textures of its own format. The call runs the
 * same AO chain as ob_render_frame: [input pass] -> [downsample] -> [edges] -> [depth MIPs] ->
 * method -> [temporal accumulation] -> filter -> [joint bilateral upsample] -> [output pass], so
 * every method, filter, AO scale, temporal accumulation, the guard band and a second depth layer
 * work here as they do in the CLI, under a perspective or an orthographic projection (the CLI's
 * own cameras are perspective). Zero (or NULL) in every field means its default.
 *
 * GL state: the call binds its programs, the GL_TEXTURE_2D and GL_TEXTURE_2D_ARRAY targets and
 * the sampler object of texture units 0..OB_HOST_TEXTURE_UNITS-1 (never texture 0, which would
 * unbind the other targets), image units 0..OB_HOST_IMAGE_UNITS-1, uniform buffer binding points
 * 0 and 1 and the generic GL_UNIFORM_BUFFER binding, and the active texture unit; it sets the
 * GL_PIXEL_UNPACK_BUFFER and GL_QUERY_BUFFER bindings and the unpack pixel store to GL's defaults
 * for its uploads and timer reads; and a depth-stencil input read as stencil
 * (GL_DEPTH_STENCIL_TEXTURE_MODE) is read as depth. It puts every one of these back before
 * returning, on success and on failure. It binds no framebuffer, VAO, program pipeline or buffer
 * of any other target and changes no enable, viewport, clip control or pack state. It issues
 * glMemoryBarrier(GL_ALL_BARRIER_BITS) before returning, so the host may read the outputs by any
 * means. It calls no glGetError: a GL error the host left pending stays for the host to read, and
 * every argument is checked before anything is dispatched (OB_ERR_INVALID_ARGUMENT naming the
 * argument, what it is and what is accepted). In a debug context (GL_CONTEXT_FLAG_DEBUG_BIT) the
 * call's commands sit inside a KHR_debug group "obscura" so that the host's debug callback can
 * tell them apart.
 * Threads: the renderer's context must be current on the calling thread. */

/* The texture units and image units the host path (and every pass) may bind. */
#define OB_HOST_TEXTURE_UNITS 16
#define OB_HOST_IMAGE_UNITS 8

/* The space the host's normals are in. */
typedef enum ob_normal_space {
    OB_NORMALS_VIEW = 0, /* view space: +Z towards the camera, as OpenGL's eye space */
    OB_NORMALS_WORLD,    /* world space: turned into view space by ob_host_frame.view */
} ob_normal_space;

typedef struct ob_host_frame {
    /* The depth, GL_TEXTURE_2D of the input size (ob_host_input_size), read at level 0:
     *   hardware depth: GL_DEPTH_COMPONENT16, _24, _32F, GL_DEPTH24_STENCIL8, GL_DEPTH32F_STENCIL8,
     *     linearised by the input pass through `projection` and `depth_zero_to_one`; standard or
     *     reversed Z and a finite or infinite far plane are read from the matrix itself; a pixel
     *     whose depth is the far plane's (1, or 0 reversed) is sky;
     *   linear depth: GL_R16F or GL_R32F, positive view-space depth in world units, 0 = sky.
     * Required. */
    uint32_t depth;
    /* An optional second depth layer in the same format: where each pixel's view ray leaves the
     * solid whose front depth shows (depth peeling's nearest surface behind the first, where that
     * surface is the same object's back; sky = none or unknown: a single sheet, or another
     * object's front). Read by methods with layers = 2 (vbao's and vbgi's default); 0 = none, and
     * they fall back to one layer (their constant thickness). */
    uint32_t second_depth;
    /* Normals, GL_TEXTURE_2D of the input size, unit length, in normal_space:
     *   GL_RGBA16F, GL_RGBA32F: xyz as is;
     *   GL_RGB10_A2, GL_RGBA8: xyz encoded as n * 0.5 + 0.5;
     *   GL_RG16F, GL_RG16_SNORM: octahedral (Cigolle et al. 2014) in [-1, 1];
     *   GL_RG8: octahedral encoded as e * 0.5 + 0.5.
     * 0 = none: reconstructed from depth by the input pass (flat-shaded: no smoothing groups;
     * docs/embedding.md gives its cost in accuracy). */
    uint32_t normal;
    ob_normal_space normal_space;
    /* The projection the host rasterised with, before any TAA jitter: column-major, OpenGL clip
     * space, perspective (P23 = -1, P33 = 0; an off-axis P20, P21 taken) or orthographic (P23 = 0,
     * P33 = 1, P20 = P21 = 0; an off-centre P30, P31 taken), with P00, P11 and the z row's P22
     * (orthographic) or P32 (perspective) non-zero. Every method, filter and pass of the chain
     * follows the camera's kind: view positions, projected radii and view rays. */
    float projection[16];
    /* World -> view, column-major; all zeros = identity. Needed for world-space normals and for
     * temporal accumulation (the history follows the camera through it). */
    float view[16];
    /* The TAA jitter of this frame, in pixels of the input size: the host rasterised with
     * `projection` plus 2 jitter[0] / width in P20 (element 8) and 2 jitter[1] / height in P21
     * (element 9), which moves the image by -jitter pixels; an orthographic one with `projection`
     * minus 2 jitter[0] / width in P30 (element 12) and 2 jitter[1] / height in P31 (element 13),
     * the same move. The library does the same, so the AO lines up with the jittered depth; the
     * temporal accumulation reprojects through the last frame's camera with this frame's jitter,
     * so the history stays at the pixel centres (a still camera reads it where it was written)
     * and averages the jittered samples over each pixel's footprint, as TAA does. */
    float jitter[2];
    /* The depth buffer was written under glClipControl(..., GL_ZERO_TO_ONE): window depth = NDC z.
     * false: GL's default, window depth = NDC z * 0.5 + 0.5. */
    bool depth_zero_to_one;
    /* Optional motion vectors for temporal accumulation of moving objects: GL_RG16F or GL_RG32F of
     * the input size, where each pixel's surface was in the previous frame minus where it is now,
     * in pixels (+y up), multiplied by motion_scale (zeros = 1; e.g. {width, height} for UV
     * units, negative for current minus previous). 0 = the camera's motion alone (static scenes). */
    uint32_t motion;
    float motion_scale[2];
    /* The indirect-light methods (vbgi, ssdo, ssdo_merged) read the host's direct light:
     * GL_RGBA16F, GL_RGBA32F or GL_R11F_G11F_B10F linear radiance (no AO, no ambient), of the
     * input size. 0 for AO methods. albedo (GL_RGBA8, GL_SRGB8_ALPHA8, GL_RGBA16F) is for methods
     * that declare it; none does today (their bounce leaves a white receiver: multiply `indirect`
     * by your albedo), but one given is checked all the same. */
    uint32_t radiance;
    uint32_t albedo;
} ob_host_frame;

typedef struct ob_host_outputs {
    /* GL_TEXTURE_2D of the renderer's size (the guard band cropped), level 0 written:
     * GL_R8, GL_R16F, GL_R32F visibility in [0, 1] (a directional method's: the mean of its M), or
     * GL_RGBA8, GL_RGBA16F, GL_RGBA32F: an RGB modulation M of directional methods (ssdo*), grey
     * for AO methods. Required. */
    uint32_t ao;
    /* Bent normals of methods that write them (gtao with bent_normals = on): GL_RGBA16F or
     * GL_RGBA32F, unit length, in the space of the input normals (view space when normal was 0);
     * zeros where none. 0 = not wanted. */
    uint32_t bent_normal;
    /* The one-bounce indirect light of vbgi, ssdo and ssdo_merged, off a white receiver (multiply
     * by your albedo): GL_RGBA16F, GL_RGBA32F or GL_R11F_G11F_B10F. 0 = not wanted. */
    uint32_t indirect;
} ob_host_outputs;

/* Quality presets (ob_quality_samples): 12, 24, 36, 64 samples per pixel. */
typedef enum ob_quality {
    OB_QUALITY_DEFAULT = 0, /* the method's own default */
    OB_QUALITY_LOW,
    OB_QUALITY_MEDIUM,
    OB_QUALITY_HIGH,
    OB_QUALITY_ULTRA,
} ob_quality;

/* Typed settings for a host, turned into ob_settings by ob_settings_from_host; what is not here
 * goes through ob_settings_set afterwards. Zero means the default, except radius. */
typedef struct ob_host_settings {
    const char *method;   /* NULL = OB_DEFAULT_METHOD */
    ob_quality quality;
    /* R, the distance within which geometry occludes, in the host's world units (the units of its
     * view matrix and linear depth): required, > 0. docs/embedding.md, "Choosing R". */
    float radius;
    float intensity;      /* the method's intensity or contrast parameter; 0 = its default */
    float thickness;      /* assumed thickness of what the depth buffer shows, x R; 0 = default */
    float falloff;        /* the share of R over which occlusion fades out; 0 = default */
    int ao_divisor;       /* 1, 2 or 4: AO at 1/divisor of the size, joint-bilateral upsampled */
    const char *filter;   /* NULL = the default ("crease"); "none" for the raw AO */
    bool temporal;        /* temporal accumulation (call every frame; ob_renderer_reset_history on cuts) */
    int temporal_frames;  /* 0 = OB_TEMPORAL_FRAMES_DEFAULT */
    int guard;            /* guard band, px per side of the visible frame (ob_host_input_size) */
} ob_host_settings;

/* Fill `settings` from `host`. A field the method has no parameter for (intensity for vbao, say)
 * is an error, not ignored. Errors: OB_ERR_INVALID_ARGUMENT (NULL, radius not > 0, a field the
 * method lacks), OB_ERR_UNKNOWN_METHOD (method or filter), OB_ERR_OUT_OF_RANGE. On error
 * `settings` is unchanged. `host` and its strings are read during the call only. Pure CPU. */
ob_error ob_settings_from_host(ob_settings *settings, const ob_host_settings *host);

/* The size the host's input textures must have for these settings: the renderer's size plus the
 * guard band, ob_settings.guard rounded up to a multiple of 4 x ao_divisor, on each side. Either
 * pointer may be NULL; *guard (may be NULL) gets the band's pixels per side. The host renders that
 * size with its projection widened as ob_guard_projection does (identity without a band). NULL r
 * gives 0 x 0 (and no band), NULL settings no band. Never fails. */
void ob_host_input_size(const ob_renderer *r, const ob_settings *settings, int *width, int *height, int *guard);
/* Widen a projection for a guard band of `guard` px per side around width x height (in place,
 * column-major): P00, P20, P30 scaled by width / (width + 2 guard), P11, P21, P31 by height /
 * (height + 2 guard), so that the enlarged image's centre is the visible frame, pixel for pixel
 * (perspective or orthographic). guard <= 0 leaves proj as it is. Pure CPU; never fails. */
void ob_guard_projection(float proj[16], int width, int height, int guard);

/* Compile and allocate everything these settings will use (method, filter, input and output
 * passes, upsampler, temporal targets) ahead of the first frame, so that the first ob_host_ao
 * does not stall on shader compiles (seconds on a software rasteriser without a warm shader
 * cache): it runs the settings' chain on scratch textures of the formats hosts use most (linear
 * R32F depth with RGBA16F normals, and a D32F depth buffer with RG16F octahedral normals; AO
 * output in R8, R16F, R32F, RGBA8, RGBA16F), then forgets the temporal history and the frame
 * count. A driver that specialises programs per texture format may still compile at the first
 * call with other formats. GL state as ob_host_ao. Errors: OB_ERR_INVALID_ARGUMENT (NULL r,
 * settings not initialised, what ob_host_ao refuses), OB_ERR_OUT_OF_RANGE (a settings field),
 * OB_ERR_BAD_SIZE (the guard band beyond GL_MAX_TEXTURE_SIZE), OB_ERR_SHADER, OB_ERR_OUT_OF_MEMORY. */
ob_error ob_host_prepare(ob_renderer *r, const ob_settings *settings);

/* Run the settings' AO chain on the host's textures into its outputs (above). The method's
 * radius must have been set (ob_settings_from_host, or "radius=R"): with no scene there is no
 * default R. ssdo and ssdo_merged spread ob_settings.lights (light_count of them; none by
 * default) into their lobes, and take the ambient light from ob_settings as ob_render_frame does.
 * A method with extra_view = on needs the scene: refused. frame, settings and outputs are read
 * during the call; the textures stay the host's. Errors: OB_ERR_INVALID_ARGUMENT (NULL, settings
 * not initialised, no radius set, every texture argument checked first: "normal texture 7 is
 * 160x120 GL_RGBA8; expected 320x240 and one of ..."), OB_ERR_OUT_OF_RANGE (a settings field
 * outside its range), OB_ERR_BAD_SIZE (the guard band makes the input larger than
 * GL_MAX_TEXTURE_SIZE), OB_ERR_SHADER, OB_ERR_OUT_OF_MEMORY. Not OB_ERR_GL: see "GL state" above. */
ob_error ob_host_ao(ob_renderer *r, const ob_host_frame *frame, const ob_settings *settings,
                    const ob_host_outputs *outputs);


#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif
#endif /* OBSCURA_H */
