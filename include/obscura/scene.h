/*
 * obscura/scene.h — libobscura's own frame: scenes (the CPU-side container), their cameras,
 * camera paths and lights, stereo eyes, and the renderer drawing a scene itself: shadow maps ->
 * G-buffer -> direct light -> the AO chain -> compose -> HDR, each pass timed, presented or read
 * back. Part of the core library (libobscura, no further dependencies); scenes come from the
 * built-in set (ob_builtin_scene_*) through ob_load_scene in obscura/eval.h, or from
 * ob_tessellate_scene. Conventions, errors, lifetimes and threading: obscura/obscura.h.
 */
#ifndef OBSCURA_SCENE_H
#define OBSCURA_SCENE_H

#include "obscura/obscura.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- scenes: the container and its queries (materials, lights, camera presets) ---------------- */
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

/* Scenes are CPU memory only: the queries below are pure CPU, need no GL context, and may run on
 * any thread while nothing destroys the scene. */

/* Free the scene and everything it owns, which ends the strings its queries returned. A renderer
 * it was uploaded to keeps its own copy. NULL is a no-op. Never fails. */
void ob_destroy_scene(ob_scene *scene);
/* Counts and bounds. NULL gives zeros, with OB_ERR_INVALID_ARGUMENT recorded. */
ob_scene_stats ob_query_scene_stats(const ob_scene *scene);
/* Owned by the scene: valid until ob_destroy_scene. "" for NULL. Never fails. */
const char *ob_query_scene_name(const ob_scene *scene);
/* 0 for NULL. Never fails. */
int ob_query_scene_material_count(const ob_scene *scene);
/* A copy (the name copied in). Zeros, with OB_ERR_OUT_OF_RANGE recorded, for NULL or an index out
 * of range. */
ob_material_info ob_query_scene_material(const ob_scene *scene, int index);
/* Suggested AO radius in world units (sidecar, else 5% of the bounds' diagonal); 0 for NULL.
 * Never fails. */
float ob_query_scene_ao_radius(const ob_scene *scene);
/* The scene's lights (sidecar or glTF KHR_lights_punctual, else one default directional light
 * from above-front-left); index 0 is the key light. The count is 0 for NULL; a light is a copy,
 * all zero for NULL or an index out of range (no error recorded). Never fail. */
int ob_query_scene_light_count(const ob_scene *scene);
ob_light ob_query_scene_light(const ob_scene *scene, int index);

/* Camera presets: index 0 is always "default", which frames the scene's bounds. The count is 0
 * for NULL (never fails); a camera is a copy, zeros with OB_ERR_OUT_OF_RANGE recorded for NULL or
 * an index out of range. */
int ob_query_camera_count(const ob_scene *scene);
ob_camera ob_query_camera(const ob_scene *scene, int index);
/* By name or decimal index, copied into *out (out may be NULL: a check only). Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL scene or name), OB_ERR_UNKNOWN_CAMERA (the message lists the
 * scene's cameras). */
ob_error ob_find_camera(const ob_scene *scene, const char *name_or_index, ob_camera *out);

/* ---- camera paths: a scene's named paths (sidecar "paths", docs/temporal.md) and orbits ------
 * A path is 2..OB_MAX_PATH_KEYS keyframes (time, eye, target, fov) with increasing times. */
#define OB_MAX_PATHS 8
#define OB_MAX_PATH_KEYS 32
/* 0 for NULL. Never fails. */
int ob_query_path_count(const ob_scene *scene);
/* The name of path `index`, or "" when out of range (or scene NULL). Owned by the scene: valid
 * until ob_destroy_scene. Never fails. */
const char *ob_query_path_name(const ob_scene *scene, int index);
/* The camera at fraction u (clamped to [0, 1]) of path `name`'s time span: eye and target on
 * Catmull-Rom splines through the keys, parametrised by time (C1, through every key; the end
 * tangents mirror their neighbours), the fov linear between keys, up +Y, near and far 0 (the
 * renderer fits them to the scene). Errors: OB_ERR_INVALID_ARGUMENT (NULL, or `name` is none of
 * the scene's paths; the message lists them); *out is untouched on error. */
ob_error ob_camera_on_path(const ob_scene *scene, const char *name, float u, ob_camera *out);
/* `camera` turned by `degrees` about the vertical (+Y) axis through its target: the orbit of the
 * CLI's --orbit DEG (frame i of N at degrees x i / (N - 1)). Everything else is kept. camera must
 * not be NULL. Pure CPU; never fails. */
ob_camera ob_camera_orbit(const ob_camera *camera, float degrees);

/* ---- scene sources: tessellated copies, the data directory, built-in scenes ------------------ */
/* A deep copy of `scene` with every triangle split `levels` times by midpoint subdivision (each
 * triangle becomes 4: levels 1 = 4x, 2 = 16x the triangles; 0 = a plain copy). New vertices lie on
 * the original triangles, so the surfaces, cameras, lights, bounds and suggested radius are
 * unchanged: for the benchmark's triangle-count scaling (`obscura bench --scaling`). The result is
 * the caller's and shares nothing with `scene` (which may be destroyed first): destroy it with
 * ob_destroy_scene. NULL on failure. Errors: OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_OUT_OF_RANGE
 * (levels outside [0, 4]), OB_ERR_OUT_OF_MEMORY (also when a mesh would pass 2^32 indices). */
ob_scene *ob_tessellate_scene(const ob_scene *scene, int levels);

/* The data directory: scenes/ (named scene sidecars), data/ (files they name, e.g. the repacked
 * oa_dm1.pk3) and shaders/ (what the viewer reloads). No path is compiled in; the first of these
 * wins:
 *   1. the OBSCURA_DATA_DIR environment variable when set and not empty (read on every call);
 *   2. beside the loaded libobscura (dladdr; in a static link, the executable): where the install
 *      puts it, <libdir>/../share/obscura = <prefix>/share/obscura, then a build tree's
 *      share/obscura in the library's directory or its parent (the build links that to the
 *      source tree's scenes/, data/ and shaders/);
 *   3. the same beside the executable (/proc/self/exe): <bindir>/../share/obscura, then a build
 *      tree's;
 *   4. "." (the working directory).
 * Steps 2-4 count a directory only when it holds scenes/, and run once per process. Never NULL,
 * never fails; thread-safe. The string is the environment's (step 1: valid until the environment
 * changes) or static storage (valid for the process). */
const char *ob_data_dir(void);

/* Built-in scenes that need no file (ob_load_scene in obscura/eval.h makes them). Name and
 * description are static strings, valid for the process; NULL when index is out of range. Never
 * fail. */
int ob_builtin_scene_count(void);
const char *ob_builtin_scene_name(int index);
const char *ob_builtin_scene_description(int index);

/* ---- stereo: the two eyes of a headset (Belonogov 2018 §5.2) -------------------------------------- */
typedef struct ob_headset {
    const char *name;        /* "vive" */
    const char *description;
    int width, height;       /* pixels per eye */
    float ipd;               /* default eye separation, metres */
    float fov_y_deg;         /* each eye's vertical field of view (its frustum's window height) */
    float shift[2];          /* the left eye's lens shift (ob_camera.shift); the right eye's is
                                mirrored in x (-shift[0], shift[1]) */
} ob_headset;

/* The presets are a static table: these are thread-safe; the count never fails. */
int ob_headset_count(void);
/* NULL when index is out of range. The entry and its strings are static, valid for the process. */
const ob_headset *ob_headset_at(int index);
/* By name, copied into *out (its strings static). Errors: OB_ERR_INVALID_ARGUMENT (NULL, or an
 * unknown name: the message lists the presets); *out is untouched on error. */
ob_error ob_find_headset(const char *name, ob_headset *out);

/* Zero means default. */
typedef struct ob_stereo_desc {
    float ipd;          /* eye separation in world units; zero = the headset's, else 0.064 */
    float convergence;  /* parallel-axis stereo: distance of the zero-parallax plane along the view;
                           zero = |target - eye| of the centre camera */
    float aspect;       /* width / height of each eye's image: the shift is in units of the window's
                           half-width; zero = the headset's, else 1 */
    const char *headset;/* NULL or "": parallel-axis asymmetric frusta from the centre camera's fov;
                           a preset name: the preset's fov and per-eye frustum (convergence unused) */
} ob_stereo_desc;

/* The left (eyes_out[0]) and right eye of a centre camera: each moved by -+ipd/2 along the right
 * vector (forward x up), eye and target alike, so the view directions stay parallel; each frustum
 * off axis (ob_camera.shift) so that the two windows coincide on the convergence plane (Bourke's
 * parallel-axis asymmetric-frustum stereo: the left eye's window moves right by
 * (ipd/2) / (convergence tan(fov_x/2)) of its half-width, the right eye's left by as much; a point
 * on that plane lands at the same NDC in both eyes), or with the headset's per-eye frustum. The
 * centre camera's own shift is added to each eye's; near, far and name are kept ("NAME-left",
 * "NAME-right"). desc NULL = all defaults. Pure CPU, thread-safe.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL centre or eyes_out, an unknown headset, ipd, convergence or
 * aspect negative or not finite, eye = target, forward parallel to up, fov not below 179);
 * eyes_out is untouched on error. */
ob_error ob_stereo_cameras(const ob_camera *centre, const ob_stereo_desc *desc, ob_camera eyes_out[2]);


/* ---- lights: checking and parsing (the type is in obscura/obscura.h) ------------------------- */
/* Checks a light as every source must have it (--light, sidecars, models, a host's own): colour,
 * intensity, position, range and cone finite; a directional or spot light's direction finite and
 * not zero (it need not be unit: the renderer uses it as given, so callers normalise it, as
 * ob_parse_light and the sidecar do); colour >= 0, intensity >= 0; position within
 * +-OB_MAX_COORDINATE; the brightest channel's colour x intensity at most OB_MAX_DIRECTIONAL for a
 * directional light and OB_MAX_POINT for a point or spot light (falling off as 1/d^2, 1e12 gives
 * 1 at 10^6 units). Why a ceiling: the frame's radiance targets are 16-bit floats (largest 65504),
 * so a sun above about 6e4 overflows to infinity at the first lit pixel and the tone mapper makes
 * the whole image white; the point light's ceiling leaves six orders of magnitude of scene scale
 * (shipped sidecars use up to 2.25e6). Pure CPU, thread-safe. Errors: OB_ERR_INVALID_ARGUMENT
 * naming the field (or NULL, or a type that is none of the three). */
#define OB_MAX_DIRECTIONAL 1e4f
#define OB_MAX_POINT 1e12f
ob_error ob_check_light(const ob_light *light);

/* A light from text, as the CLI's --light takes it: a type, then key=value pairs separated by
 * spaces, e.g. "directional dir=0.3,1,0.2 color=1,0.9,0.8 intensity=2",
 * "point pos=0,2,0 intensity=8 range=10", "spot pos=0,3,0 dir=0,-1,0 cone=20,30 intensity=20".
 * Unset fields: colour 1,1,1, intensity 1, cone 20,30; the result passes ob_check_light. Pure CPU.
 * Errors: OB_ERR_INVALID_ARGUMENT with what is wrong (NULL, text over 511 bytes, an unknown type
 * or key, a bad value, what ob_check_light refuses); *out is untouched on error. */
ob_error ob_parse_light(const char *text, ob_light *out);

/* ---- HDR on the CPU (SSDO thesis §2.2, §5.5, §6.5; the settings are in obscura/obscura.h) --------- */
/* The HDR math on the CPU, the same formulas the shaders use (for tests and tools):
 * log-average luminance (eq. 2.1) of n values, Reinhard with L_white (eq. 2.4, eq. 2.3 when
 * l_white <= 0) and the automatic key for a log-average. Pure CPU, thread-safe; never fail
 * (ob_hdr_log_average gives 0 for NULL or n = 0; NaN, negative and above 65504 are clamped as on
 * the GPU). */
double ob_hdr_log_average(const float *luminance, size_t n);
float ob_hdr_reinhard(float scaled_luminance, float l_white);
float ob_hdr_auto_key(float log_average);

/* ---- the frame: a scene rendered by libobscura itself ------------------------------------------ */
/* Upload a scene's meshes and textures. The renderer keeps no pointer to the ob_scene: it may be
 * destroyed after the call. Errors: OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_MODEL (a texture
 * larger than the GL takes; the renderer keeps its old scene), OB_ERR_OUT_OF_MEMORY (the old
 * scene is released by then: the renderer has no scene, and ob_render_frame refuses until one is
 * set). The upload's own GL errors are not
 * checked here (no OB_ERR_GL). */
ob_error ob_renderer_set_scene(ob_renderer *r, const ob_scene *scene);
/* The environment map for OB_AMBIENT_ENVIRONMENT and SSDO: width x height equirectangular linear
 * RGB radiance (3 floats a pixel, top row = +Y first), copied: the renderer keeps no pointer.
 * `name` is what error messages call the map (NULL: "(the host's pixels)"); obscura/eval.h's
 * ob_renderer_set_environment reads a Radiance .hdr file into it; name is used for the messages
 * of this call only. Errors: OB_ERR_INVALID_ARGUMENT (NULL r or rgb), OB_ERR_IO (smaller than
 * 2x1, larger than GL_MAX_TEXTURE_SIZE, negative or non-finite radiance, or the upload failed); the
 * renderer keeps its old map then, except after a failed upload (none). */
ob_error ob_renderer_set_environment_rgb(ob_renderer *r, int width, int height, const float *rgb, const char *name);

/* shadow maps -> G-buffer -> direct light -> [downsample] -> [edges] -> AO -> filter -> [upsample]
 * -> compose -> HDR (luminance, bloom, tone map), each pass timed. Errors: OB_ERR_INVALID_ARGUMENT
 * (NULL, settings not initialised, no scene yet, environment ambient without an environment map,
 * a camera that is not finite or whose fov is not in (0, 179)), OB_ERR_OUT_OF_RANGE (a settings
 * field outside its range), OB_ERR_BAD_SIZE (a guard band beyond GL_MAX_TEXTURE_SIZE),
 * OB_ERR_SHADER (a pass compiled on first use), OB_ERR_OUT_OF_MEMORY, OB_ERR_GL (an error during
 * the frame). After an error no frame can be read back or presented until the next one renders. */
ob_error ob_render_frame(ob_renderer *r, const ob_camera *camera, const ob_settings *settings);

/* ---- the floor: the least any AO method must cost on this machine -------------------------- */
/* The floor of this machine for a method (obscura bench --floor, bench/README.md): a bare compute
 * kernel (shaders/floor.glsl) over the last frame's AO-grid depth (R32F) and normals (RGBA16F)
 * that takes the N taps the settings' method would take (its sample count; HBAO directions x
 * steps, GTAO and VBAO 2 x slices x steps) spread over its radius in pixels, in the same pattern
 * (a disk, or rays for the horizon marchers), sums them and writes one R32F value per pixel: what
 * any AO method at those settings must at least do. It runs as a frame of the timers of its own
 * with one pass, "floor": ob_wait_timings then ob_query_timings gives its time (and
 * ob_query_timings_frame counts it as a frame). The last ob_render_frame must have used the same
 * AO scale, and the frame's outputs stay as they were. info (may be NULL) gets what the kernel
 * took. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL r or settings, settings not initialised, no frame yet or one at
 * another AO scale, a method without a sample count or a radius, more than 2048 taps),
 * OB_ERR_OUT_OF_RANGE (a settings field), OB_ERR_SHADER, OB_ERR_OUT_OF_MEMORY, OB_ERR_GL. */
typedef struct ob_floor_info {
    int taps;        /* N */
    int rays;        /* 0: spread over the disk of the radius; else the rays the taps lie on */
    float radius;    /* the method's radius, world units */
} ob_floor_info;
ob_error ob_render_floor(ob_renderer *r, const ob_settings *settings, ob_floor_info *info);


/* ---- presenting: the last frame or a debug view into a framebuffer, on the GPU --------------
 * The views are the CLI's --view images (app/render.c), made by one compute pass (shaders/view.glsl)
 * instead of a read-back:
 *   final     the tone-mapped sRGB frame (OB_IMAGE_FINAL_RGBA8)
 *   ao        the AO after filter and upsampling: grey for AO methods, M's RGB for directional ones
 *   normals   view-space normal n * 0.5 + 0.5
 *   depth     grey 1 - d / far, far = the last frame's far plane (the CLI divides by the image's
 *             largest depth instead, so its picture is darker); 0 for sky
 *   shadow    the key light's visibility, grey
 *   radiance  the direct light, clamped to [0, 1] and sRGB-encoded
 *   samples   samples each pixel took / the most any pixel could take that frame (the method's
 *             count, under adaptive sampling its base x 3; the CLI divides by the image's largest
 *             count instead), grey; 0 for sky
 *   bounce    the one-bounce light of methods that write one (SSDO, vbgi), clamped and sRGB-encoded; black otherwise
 *   bent_normals  the method's bent normal (renormalised) as b * 0.5 + 0.5; black when it wrote none
 *   luminance the composed HDR radiance's luminance before tone mapping in false colour (SSDO thesis
 *             Fig. 6.16c): log2 over [OB_LUMINANCE_LOG2_LO, OB_LUMINANCE_LOG2_HI] through dark blue,
 *             blue, cyan, green, yellow and red, white above the top, black at 0; the scale itself
 *             along the bottom edge with a tick per stop (taller at 1) */
typedef enum ob_view {
    OB_VIEW_FINAL = 0,
    OB_VIEW_AO,
    OB_VIEW_NORMALS,
    OB_VIEW_DEPTH,
    OB_VIEW_SHADOW,
    OB_VIEW_RADIANCE,
    OB_VIEW_SAMPLES,
    OB_VIEW_BOUNCE,
    OB_VIEW_BENT_NORMALS,
    OB_VIEW_LUMINANCE,
    OB_VIEW_SECOND_DEPTH, /* the second depth layer as the depth view shows the first (black where
                             none or not the first layer's back, or when the frame's method did not
                             read it: layers=2) */
    OB_VIEW_EXTRA,        /* the extra view's direct light as radiance shows the main one's (ssdo with
                             extra_view=on; black otherwise): the camera turned 90 degrees around the
                             target (Belonogov 2018 §4.4) */
    OB_VIEW_HISTORY_AGE,  /* temporal accumulation: frames in each pixel's history / temporal_frames,
                             grey (black at a disocclusion, on the sky, or with temporal off) */
    OB_VIEW_COUNT
} ob_view;

/* The luminance view's range in stops: 1/256 to 16 (radiance 1 is the display's white before
 * tone mapping), shaders/view.glsl. */
#define OB_LUMINANCE_LOG2_LO (-8)
#define OB_LUMINANCE_LOG2_HI 4

/* "final", "ao", "normals", "depth", "shadow", "radiance", "samples", "bounce", "bent_normals",
 * "luminance", "second_depth", "extra", "history_age" (the CLI's --view names); "" if out of range.
 * Static storage, valid for the process. Never fails. */
const char *ob_view_name(ob_view view);

/* Draw the last frame (OB_VIEW_FINAL) or one of its debug views into `framebuffer` (0 = the
 * default framebuffer, e.g. a window's), over x, y, width, height (GL convention, y from the
 * bottom), nearest-neighbour scaled, with glBlitNamedFramebuffer. The bytes are display-ready
 * sRGB: GL_FRAMEBUFFER_SRGB and the scissor test are switched off for the blit. Needs the
 * renderer's context current. Leaves GL state as it found it (bindings of programs, textures,
 * images, uniform buffers and framebuffers, enables); GL errors raised before the call are
 * cleared. Not timed (it is no part of the frame). Errors: OB_ERR_INVALID_ARGUMENT (NULL, no frame
 * rendered yet or since a resize, a view out of range, a non-positive width or height),
 * OB_ERR_SHADER (the view pass, compiled on the first debug view), OB_ERR_GL (e.g. `framebuffer`
 * is not a complete framebuffer). */
ob_error ob_present(ob_renderer *r, ob_view view, uint32_t framebuffer, int x, int y, int width, int height);

/* The same view as ob_present draws, read back: width x height x 4 sRGB bytes (alpha 255), top
 * row first, as image files want them (the CLI's --view). dst_size at least ob_image_size(r,
 * OB_IMAGE_FINAL_RGBA8); dst is the caller's, nothing is kept. Errors: as ob_present,
 * OB_ERR_INVALID_ARGUMENT for a NULL or small dst, OB_ERR_OUT_OF_MEMORY (a scratch row for the
 * final view's flip). */
ob_error ob_read_view(ob_renderer *r, ob_view view, uint8_t *dst, size_t dst_size);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif
#endif /* OBSCURA_SCENE_H */
