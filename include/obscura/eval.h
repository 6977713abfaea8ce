/*
 * obscura/eval.h — libobscura-eval, the evaluation library above the core: scenes loaded from
 * files and named scenes (Assimp, sidecars), environment maps from Radiance .hdr files, image
 * files, the ray-traced ground truth (Embree), metrics, metric masks and stereo consistency. The
 * CLI's compare, report and tune stand on it; an engine that wants AO alone needs none of it.
 * Link obscura::eval (CMake) or obscura-eval (pkg-config). Conventions, errors, lifetimes and
 * threading: obscura/obscura.h.
 */
#ifndef OBSCURA_EVAL_H
#define OBSCURA_EVAL_H

#include "obscura/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- loading scenes: built-in, named (scenes/NAME.obscura.json) or a model file -------------- */
typedef enum ob_up_axis { OB_UP_DEFAULT = 0, OB_UP_Y, OB_UP_Z } ob_up_axis;

typedef struct ob_scene_desc {
    /* A built-in scene ("cornell", "corner", "sphere-on-plane"), a named scene from the data
     * directory's scenes/NAME.obscura.json (e.g. "bunny", "fzk-haus"), or a model path. */
    const char *name;
    const char *sidecar; /* explicit sidecar JSON; default: MODEL.obscura.json beside the model */
    ob_up_axis up;       /* overrides the sidecar's up axis */
    /* Untrusted models (README "Untrusted models"): every file a model refers to (glTF buffers
     * and images, OBJ's MTL and textures, ...) must resolve into the model's directory tree and
     * not be an absolute path, else OB_ERR_MODEL naming the reference; true lifts that. Device
     * files, FIFOs and directories are refused either way. */
    bool allow_external_files;
    /* The most memory, in bytes, the run may take (ob_default_max_memory() when 0). The import is
     * estimated from the counts the file declares before Assimp allocates and again from the raw
     * scene before post-processing; then, before any texture is decoded, the geometry, every
     * texture the materials name (sized from its image header: decoded RGBA8 and its mipmapped
     * copy on the GPU, each file or embedded image once however many materials name it, and the
     * largest one's decoding) and reserved_memory together. A model over it is OB_ERR_MODEL, the
     * message naming the largest items. */
    uint64_t max_memory;
    /* What the caller's run takes besides the scene (render targets: ob_estimate_renderer_memory,
     * its own image buffers) and a few words on it for that message, e.g. "render targets 21 MiB
     * (--size 640x480)" (NULL: "the rest of the run"). 0 = nothing besides the scene. */
    uint64_t reserved_memory;
    const char *reserved_what;
    /* A model path with no sidecar (none given, none beside it, none in scenes/) gets a ground
     * under it, as a sidecar's "ground": {} would add (docs/scenes.md): a lone object has nothing
     * else to be occluded by. Its material is named OB_AUTOMATIC_GROUND_MATERIAL, so that a caller
     * can say so. The suggested AO radius and the default camera still follow the model alone. */
    bool automatic_ground;
} ob_scene_desc;

#define OB_AUTOMATIC_GROUND_MATERIAL "automatic ground"

/* The scene `desc->name` names: a built-in, else the data directory's scenes/NAME.obscura.json
 * (ob_data_dir), else a model path. desc and its strings are read during the call only. The scene
 * is the caller's: ob_destroy_scene. CPU-only: any thread, no GL context. NULL on failure.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL desc, a NULL or empty name, an up axis outside the enum,
 * a path too long), OB_ERR_UNKNOWN_SCENE (a bare name that is no built-in, named scene or file),
 * OB_ERR_IO (a missing or unreadable file, or one that is no regular file), OB_ERR_MODEL (the
 * import failed, a reference outside the model's tree, over max_memory), OB_ERR_SIDECAR,
 * OB_ERR_OUT_OF_MEMORY. */
ob_scene *ob_load_scene(const ob_scene_desc *desc);
/* The named scenes of the data directory (ob_data_dir): NAME of every scenes/NAME.obscura.json,
 * sorted, at most `max` (names shorter than 64 bytes; longer ones are skipped). Returns how many
 * were written; 0 without the directory. CPU-only, any thread. Never fails. */
int ob_named_scenes(char names[][64], int max);

/* ---- environment maps from files --------------------------------------------------------------- */
/* The environment map (equirectangular Radiance .hdr) for OB_AMBIENT_ENVIRONMENT and SSDO, read
 * with stb_image and handed to ob_renderer_set_environment_rgb. Errors: OB_ERR_INVALID_ARGUMENT
 * (NULL), OB_ERR_IO (naming the path: unreadable, not a Radiance file, truncated, a declared size
 * the file cannot hold, and ob_renderer_set_environment_rgb's); the renderer keeps its old map,
 * except after a failed GL upload, which leaves it none. The file is closed and the pixels freed
 * before the call returns (the GL texture is the renderer's copy). */
ob_error ob_renderer_set_environment(ob_renderer *r, const char *hdr_path);

/* ---- image and text files: written atomically (temporary file, then rename); PFM read back -- */
/* The writers read the caller's pixels during the call and keep nothing; a NULL or empty path is
 * OB_ERR_INVALID_ARGUMENT. CPU-only, any thread. */
/* Top-row-first RGBA8 or grey (channels 1, 3 or 4). Errors: OB_ERR_INVALID_ARGUMENT (NULL, a
 * size below 1x1, another channel count), OB_ERR_IO (naming the path; an existing file is kept). */
ob_error ob_write_png(const char *path, int width, int height, int channels, const uint8_t *px);
/* Baseline JPEG of the same top-row-first pixels (channels 1, 3 or 4; a fourth is dropped: JPEG
 * has no alpha), quality 1..100. Errors: OB_ERR_INVALID_ARGUMENT, OB_ERR_OUT_OF_RANGE, OB_ERR_IO. */
ob_error ob_write_jpg(const char *path, int width, int height, int channels, const uint8_t *px, int quality);
/* PFM: bottom-row-first floats, channels 1 (Pf) or 3 (PF), little-endian. Errors: as
 * ob_write_png (another channel count than 1 or 3). */
ob_error ob_write_pfm(const char *path, int width, int height, int channels, const float *px);
/* A text file (JSON, HTML), written atomically like the images. Errors: OB_ERR_INVALID_ARGUMENT
 * (NULL), OB_ERR_IO (naming the path; an existing file is kept). */
ob_error ob_write_text(const char *path, const char *text);
/* Reads a little-endian PFM; *px is malloc'd and the caller's (free it with free()); nothing is
 * allocated on an error, *px is then NULL and *width, *height, *channels are untouched. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL), OB_ERR_IO (unreadable, not a little-endian PFM, a side above
 * 65536, truncated), OB_ERR_OUT_OF_MEMORY. */
ob_error ob_read_pfm(const char *path, int *width, int *height, int *channels, float **px);

/* ---- ground truth: ray-traced AO and one bounce (Embree on the CPU) at G-buffer points -------
 * AO_R(x) = 1/pi * integral over the hemisphere of V_R(x, w) cos(theta) dw (Belonogov 2018 eq. 2.6-2.7,
 * t = 1), with V_R = 0 when a ray from x hits geometry within R, estimated from cosine-weighted
 * rays (pdf cos(theta)/pi, so the estimate is the plain mean of the visibility) cast from the very
 * G-buffer points the screen-space methods see. Every point's random numbers come from the seed
 * and the point's index, so results are bit-identical for a seed whatever the thread count.
 * Threading: the calls are CPU-only and may run on any thread; they use `threads` worker threads
 * of their own and keep nothing between calls. */
typedef struct ob_reference_desc {
    int spp;         /* rays per point; 0 = 512 (mean standard error under 0.01 on the demo scenes) */
    float radius;    /* R in world units; ob_reference_ao needs R > 0, ob_reference_bounce takes
                        <= 0 as unbounded */
    int threads;     /* worker threads; 0 = all cores */
    bool progress;   /* a progress bar on stderr */
    uint64_t seed;
} ob_reference_desc;

/* AO_R at `count` points: world positions and unit normals, xyz each. A point whose normal is all
 * zero (sky) is skipped and gets ao 1 and standard error 0. ao_out gets count values; stderr_out
 * (may be NULL) the standard error of each estimate, sqrt(p (1 - p) / (n - 1)) of the Bernoulli
 * mean p over n rays. Rays start a little off the surface along the normal (1e-4 of the scene's
 * bounds diagonal) and end at R.
 * count 0 returns at once. Errors: OB_ERR_INVALID_ARGUMENT (NULL scene or desc, points or output
 * NULL with count > 0, R <= 0 or not finite, spp < 0 or 1, threads < 0), OB_ERR_OUT_OF_MEMORY,
 * OB_ERR_MODEL (Embree failed; the message names rtcGetDeviceError's code). */
ob_error ob_reference_ao(const ob_scene *scene, const float *positions, const float *normals, size_t count,
                         const ob_reference_desc *desc, float *ao_out, float *stderr_out);

/* One-bounce diffuse reference for SSDO, in the renderer's convention (shaders/lighting.glsl:
 * radiance = albedo x sum over lights of colour x intensity x falloff x max(0, n.l) x visibility,
 * no 1/pi; directional lights point toward the light, point and spot lights fall off as 1/d^2 with
 * the range window (1 - (d/range)^4)^2 and the spot's smoothstep between the cones). At each
 * point x with albedo a(x):
 *   rgb(x) = a(x) * direct(x)                                     shadow rays instead of maps
 *          + a(x) * mean over cosine rays of  hit within R ? a(h) * direct(h) : ambient
 * i.e. one diffuse bounce of the direct light plus the ambient radiance times AO_R. With the
 * cosine pdf the 1/pi of a Lambertian receiver cancels, so the mean is the outgoing radiance in
 * the same units as the direct term. direct(h) uses the hit triangle's interpolated normal (turned
 * toward the ray) and its material's diffuse colour (textures are ignored); specular is left out
 * on both ends. lights == NULL or light_count == 0 takes the scene's lights; ambient NULL = black;
 * radius <= 0 = unbounded rays. rgb_out gets 3 floats per point; points with a zero normal get 0.
 * Errors: as ob_reference_ao, and OB_ERR_INVALID_ARGUMENT for light_count outside
 * [0, OB_MAX_LIGHTS] or albedo_rgb NULL. */
ob_error ob_reference_bounce(const ob_scene *scene, const ob_light *lights, int light_count, const float ambient[3],
                             const float *positions, const float *normals, const float *albedo_rgb, size_t count,
                             const ob_reference_desc *desc, float *rgb_out);

/* The renderer's read-back G-buffer as world points, with the shaders' reconstruction
 * (shaders/common.glsl ob_view_position at pixel centres): linear_depth (1 float per pixel,
 * bottom row first, 0 = sky) and view_normals (3 floats per pixel) of width x height pixels,
 * proj_info = {1/P00, 1/P11, P20, P21} of the column-major projection, inv_view the column-major
 * camera-to-world matrix. positions_out and normals_out get 3 floats per pixel; sky pixels get
 * zeros (so ob_reference_ao skips them). Pure CPU, no Embree. Errors: OB_ERR_INVALID_ARGUMENT (a
 * NULL argument), OB_ERR_BAD_SIZE (width or height below 1). */
ob_error ob_reference_points(const float *linear_depth, const float *view_normals, int width, int height,
                             const float proj_info[4], const float inv_view[16], float *positions_out,
                             float *normals_out);

/* ---- metrics: image comparison against the reference (src/eval/metrics.c) -------------------- */
typedef struct ob_metrics {
    double rmse;  /* sqrt(mean((test - reference)^2)) over every channel value compared */
    double mae;   /* mean(|test - reference|) */
    double bias;  /* mean(test - reference): > 0 when the test is brighter / less occluded */
    double psnr;  /* 10 log10(1 / MSE) in dB with peak 1 (visibility's range); INFINITY when identical */
    double psnr_srgb; /* the same after encoding both images with the sRGB transfer (IEC 61966-2-1),
                       * values clamped to [0, 1] first: XeGTAO's measure, about 21.4 dB for its
                       * High preset against 512-spp ray tracing */
    double ssim;  /* mean SSIM (Wang et al. 2004) over the masked-in windows, averaged over channels */
    size_t count; /* pixels compared (not channel values) */
} ob_metrics;

/* Compare `test` against `reference`: width x height pixels of `channels` interleaved floats each,
 * both in the same layout (either row order, as long as mask uses it too). mask: one byte per
 * pixel in the same layout, non-zero = compared; NULL = every pixel.
 * RMSE, MAE, bias, PSNR and sRGB PSNR are taken over every channel value of the masked-in pixels.
 * SSIM follows Wang et al. 2004 (eq. 13 with the 11x11 Gaussian window of sigma 1.5 normalised to
 * unit sum, eqs. 14-16, C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1) on each channel of the full image;
 * the local SSIM is averaged (eq. 17) over the windows whose centre pixel is masked in, then over
 * the channels. The statistics use every pixel under the window, masked in or not (the mask picks
 * which windows count, it does not cut holes in them). At the image border the window is cut to
 * the pixels inside the image and its weights renormalised to unit sum, so every pixel has a
 * window (Wang's MATLAB code instead drops the 5-pixel border; values there differ slightly).
 * A NaN in either image makes the metrics NaN. Thread-safe; no GL context needed.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL test, reference or out, width/height/channels < 1 or too
 * large, no pixel in the mask), OB_ERR_OUT_OF_MEMORY (a few rows of doubles); *out is zeroed first. */
ob_error ob_compare_images(const float *test, const float *reference, const uint8_t *mask, int width,
                           int height, int channels, ob_metrics *out);

/* Signed error heatmap of two 1-channel images: rgb_out (width x height x 3 bytes, top row first)
 * shows test - reference through a diverging map (ColorBrewer RdBu with a white centre): white at
 * 0, towards blue where the test is lower (darker / more occluded), towards red where it is higher,
 * saturating at +-range. Masked-out pixels (mask in the inputs' layout, NULL = all in) are grey
 * (128,128,128); a non-finite difference is black. bottom_first: the inputs' rows run bottom to
 * top (the renderer's *_F32 images), so they are flipped into rgb_out.
 * Thread-safe; no GL context needed.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL test, reference or rgb_out, width/height < 1 or too large,
 * range not finite and > 0). */
ob_error ob_error_heatmap(const float *test, const float *reference, const uint8_t *mask, int width, int height,
                          bool bottom_first, float range, uint8_t *rgb_out);

/* ---- metric masks: where the error matters (src/eval/masks.c) ------------------------------- */
typedef enum ob_metric_mask {
    OB_MASK_OCCLUDED = 0, /* the reference AO is below occluded_below: creases, contacts, corners */
    OB_MASK_SILHOUETTE,   /* within edge_band pixels of a depth discontinuity: where halos sit */
    OB_MASK_THIN,         /* background farther than R on both sides within thin_reach pixels */
    OB_MASK_BORDER,       /* the outer border_fraction of each side of the image */
    OB_MASK_COUNT
} ob_metric_mask;

/* "occluded", "silhouette", "thin", "border"; "" if out of range. Static storage, valid for the
 * process. Never fails. */
const char *ob_metric_mask_name(ob_metric_mask mask);

/* Zero means default; ob_metric_mask_defaults says what each zero becomes. */
typedef struct ob_metric_mask_desc {
    float occluded_below;  /* occluded: reference < this (default 0.75) */
    float edge_relative;   /* silhouette: a 4-neighbour is sky or its depth differs by more than this
                            * fraction of the nearer of the two depths (default 0.1) */
    int edge_band;         /* silhouette: pixels within this Euclidean distance of such an edge
                            * pixel (default max(1, round(width / 160)): 2 at 320 wide) */
    int thin_reach;        /* thin: how far to look for background on each side, in pixels
                            * (default max(1, round(3 width / 320)): 3 at 320 wide) */
    float border_fraction; /* border: this fraction of the width (height) on the left and right (bottom
                            * and top) sides, at least 1 pixel (default 0.05) */
} ob_metric_mask_desc;

/* *desc (NULL = all zero) with every zero replaced by its default for an image `width` wide.
 * Returned by value; non-zero fields are kept as given (ob_metric_masks checks them). Never fails. */
ob_metric_mask_desc ob_metric_mask_defaults(const ob_metric_mask_desc *desc, int width);

/* The OB_MASK_COUNT masks of a width x height view, for measuring the error where it matters (e.g.
 * ob_compare_images with each mask). linear_depth: 1 float per pixel, 0 = sky (the renderer's
 * OB_IMAGE_DEPTH_F32); reference: the reference AO, 1 float per pixel in the same layout (either row
 * order: every definition is symmetric under a vertical flip); radius: the AO radius R in world
 * units. masks_out gets OB_MASK_COUNT planes of width x height bytes, plane m at m x width x height,
 * 1 = in the mask, 0 = out; sky (depth <= 0 or not finite) is in none. A pixel is:
 *   occluded    reference < occluded_below;
 *   silhouette  within edge_band pixels of an edge pixel: a geometry pixel with a 4-neighbour that
 *               is sky or whose depth differs by more than edge_relative x the nearer depth;
 *   thin        sky or a depth more than R farther than its own within thin_reach pixels on both
 *               sides, left and right or below and above (a part at most 2 thin_reach - 1 pixels
 *               across, in front of something far; pixels off the image do not count);
 *   border      within border_fraction x width of the left or right side, or border_fraction x
 *               height of the bottom or top.
 * desc: NULL = defaults. Thread-safe; no GL context needed.
 * Errors: OB_ERR_INVALID_ARGUMENT (NULL linear_depth, reference or masks_out, width/height < 1 or too
 * large, radius not finite and > 0, occluded_below or edge_relative not finite and > 0, edge_band or
 * thin_reach outside 1..1024, border_fraction outside (0, 0.5]), OB_ERR_OUT_OF_MEMORY (one byte per
 * pixel of scratch). */
ob_error ob_metric_masks(const float *linear_depth, const float *reference, int width, int height, float radius,
                         const ob_metric_mask_desc *desc, uint8_t *masks_out);

/* ---- stereo consistency (src/eval/stereo.c) ------------------------------------------------- */
/* One eye's rendered view. */
typedef struct ob_stereo_view {
    const float *ao;           /* 1 float per pixel, bottom row first (OB_IMAGE_AO_F32) */
    const float *linear_depth; /* 1 float per pixel, bottom row first, 0 = sky (OB_IMAGE_DEPTH_F32) */
    int width, height;
    ob_camera camera;          /* as rendered: eye, target, up (zero = +Y), fov (zero = 60), shift;
                                  near and far are not used */
} ob_stereo_view;

typedef struct ob_stereo_consistency {
    double mean_abs;  /* mean |AO_right - AO_left reprojected| over the pixels seen by both eyes */
    double fraction;  /* those pixels / the right eye's geometry pixels */
    size_t count;     /* those pixels */
} ob_stereo_consistency;

/* How well the AO of two views of the same scene agree (AO_R is a property of the surface point,
 * not of the view: Belonogov 2018 eq. 2.6-2.7). Every right-eye geometry pixel is taken to the world by
 * its depth, into the left eye, and the left eye's AO is read there (bilinear); the pixel counts
 * only when it is seen by both eyes: the left position lies inside the left image, its four taps
 * are geometry, and the left depth there (bilinear) matches the point's left-eye depth within
 * depth_tolerance x that depth (else something else is in front: occluded in the left eye).
 * depth_tolerance: zero = 0.02. Thread-safe; no GL context needed. *out (when not NULL) is zeroed
 * first. Errors: OB_ERR_INVALID_ARGUMENT (NULL argument or image, size < 1, a camera with eye =
 * target or fov outside (0, 179), depth_tolerance negative or not finite, no pixel seen by both
 * eyes: *out then has count 0). */
ob_error ob_metric_stereo_consistency(const ob_stereo_view *left, const ob_stereo_view *right,
                                      float depth_tolerance, ob_stereo_consistency *out);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif
#endif /* OBSCURA_EVAL_H */
