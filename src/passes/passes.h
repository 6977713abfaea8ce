/* The fixed passes of the frame (the AO methods live in src/methods/). Each pass is one .c and
 * one shader; each owns its program and constant buffer. */
#ifndef OB_PASSES_H
#define OB_PASSES_H

#include "depth_mips_params.h"
#include "floor_params.h"
#include "gpu/gpu.h"
#include "lighting_params.h"
#include "resample_params.h"
#include "scene/scene.h"
#include "temporal_params.h"

/* ---- G-buffer (gbuffer.c, shaders/gbuffer.{vert,frag}.glsl): the one raster pass ------------ */
typedef struct ob_gpu_mesh {
    GLuint vao, buffers[5]; /* positions, normals, uvs, indices, part labels (scene/parts.c) */
    GLsizei index_count;
    int material;
} ob_gpu_mesh;

typedef struct ob_gbuffer {
    GLuint program, ubo, fbo;
    GLuint depth;         /* DEPTH_COMPONENT32F: hardware depth */
    GLuint linear_depth;  /* R32F */
    GLuint normal;        /* RGBA16F view space */
    GLuint albedo;        /* RGBA16F linear */
    GLuint facet;         /* RG16F: the view-space unit normal of the pixel's own triangle, octahedral
                             (shaders/common.glsl ob_oct_decode); (0, 0) where no triangle */
    int width, height;
    ob_gpu_mesh *meshes;
    int mesh_count;
    GLuint *textures;     /* per material, 0 = none */
    float (*diffuse)[3];  /* per material */
    int material_count;
    unsigned scene_generation; /* counts ob_gbuffer_set_scene calls: cached shadow maps go stale */
} ob_gbuffer;

ob_error ob_gbuffer_init(ob_gbuffer *g, int width, int height);
/* New targets at width x height, swapped into the framebuffer only when all were made (on an
 * error g is unchanged). The program and the scene stay. Errors: OB_ERR_GL. */
ob_error ob_gbuffer_resize(ob_gbuffer *g, int width, int height);
ob_error ob_gbuffer_set_scene(ob_gbuffer *g, const ob_scene *scene);
/* textures false: every material's diffuse colour alone (ob_settings.textures_off). */
void ob_gbuffer_run(ob_gbuffer *g, const float *view, const float *proj, bool textures);
/* The same into g's targets, drawing the meshes and materials of `scene` (another G-buffer, e.g.
 * the main one for an extra view; g itself for ob_gbuffer_run). */
void ob_gbuffer_run_from(ob_gbuffer *g, const ob_gbuffer *scene, const float *view, const float *proj, bool textures);
void ob_gbuffer_destroy(ob_gbuffer *g);

/* ---- the second depth layer: peel.c, peel.frag.glsl ----------------------------------------- */
/* Per pixel the nearest surface behind the G-buffer's by more than a small separation, back faces
 * included (depth peeling): R32F linear depth at the G-buffer's size, 0 = none. */
typedef struct ob_peel {
    GLuint program, ubo, fbo;
    GLuint depth;         /* DEPTH_COMPONENT32F */
    GLuint linear_depth;  /* R32F, the second layer */
    GLuint plane;         /* RG16F: the second layer's own triangle's view normal, octahedral */
    int width, height;    /* of the targets; 0 until the first run */
} ob_peel;

ob_error ob_peel_init(ob_peel *p);
/* Draw the G-buffer's meshes behind its linear depth (which must be current), with the frame's
 * view and projection; (re)makes the targets at g's size. Errors: OB_ERR_GL. */
ob_error ob_peel_run(ob_peel *p, const ob_gbuffer *g, const float *view, const float *proj);
void ob_peel_destroy(ob_peel *p);

/* ---- fill.c, shaders/fill.glsl: one value into a whole R32F (or, rgb, RGBA16F) target -------- */
ob_error ob_fill_init(ob_compute_pass *p, bool rgb);
/* The texture's whole level 0 (its own size, guard band included); rgb as at init. */
void ob_fill_run(ob_compute_pass *p, bool rgb, GLuint target, const float value[4]);

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

/* Joint bilateral upsampling of the AO to full resolution (SSDO thesis eq. 3.12): R32F, or RGBA16F
 * for SSDO's M (`rgb`). Programs (shaders/upsample.glsl), [pair][plain, block k = 2, block k = 4],
 * made on first use but the plain single one: `pair` also upsamples a second RGBA16F value (the
 * bounce or the bent normals) with the same weights in the same dispatch. */
typedef struct ob_upsample {
    ob_compute_pass programs[2][3];
    bool rgb;
    bool software; /* the context is a software rasteriser: what OB_UPSAMPLE_AUTO follows */
} ob_upsample;
ob_error ob_upsample_init(ob_upsample *u, bool rgb);
/* Upsamples low_ao (the grid's AO resolution) to ao_out with `program` (ob_upsample_program); sky
 * pixels get `sky` in the RGB pass (1 for M), 1 in the R32F one. With low_second (RGBA16F, 0 = none)
 * also upsamples it to second_out, 0 on the sky: in the same dispatch, but for an RGB main value
 * in the block program (two dispatches). The block program needs k = 2 or 4; another k takes the
 * plain one. */
ob_error ob_upsample_run(ob_upsample *u, int program, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal,
                         GLuint low_depth, GLuint low_normal, GLuint low_ao, GLuint ao_out, float sky, GLuint low_second,
                         GLuint second_out);
void ob_upsample_destroy(ob_upsample *u);

/* Adaptive sample counts: a multiplier 1/2/3 per OB_EDGE_BLOCK^2 AO pixels (SSDO thesis §4.1). */
ob_error ob_edges_init(ob_compute_pass *p);
void ob_edges_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint ao_depth, GLuint ao_normal, GLuint multiplier);

/* ---- temporal accumulation: temporal.c, shaders/temporal.glsl (issue 17) --------------------
 * At the AO resolution, one dispatch for the main chain (visibility or M) and a method's bounce
 * together: reprojected history, disocclusion by depth and normal, a 4x4 clamp, a blend of history
 * length N. The history's age: an R16F texture beside the R32F value, or RGBA16F (rgb, age). A
 * program per shape of the chains (made on first use): scalar with or without a result, RGB;
 * each with or without the bounce. */
enum { OB_TEMPORAL_PROGRAMS = 24 }; /* 3 shapes x bounce or not x a host's motion vectors or not x jittered or not */
typedef struct ob_temporal_pass {
    ob_compute_pass programs[OB_TEMPORAL_PROGRAMS]; /* a slot whose .program is 0 is not made yet */
    ob_compute_pass motion_program;                 /* ob_temporal_motion's, made on first use */
    ob_temporal_constants last;                     /* the last run's, for ob_temporal_motion */
} ob_temporal_pass;
/* The camera of the previous frame and the history rules (pure; no GL): prev_view (world -> the
 * previous view), inv_view (this frame's view -> world) and prev_ao_proj column-major,
 * history_frames N >= 1, detail the share of one-pixel detail kept under motion in [0, 1)
 * (ob_settings.temporal_detail; 0 = no bound). */
void ob_temporal_fill(ob_temporal_constants *c, const float prev_view[16], const float inv_view[16],
                      const float prev_ao_proj[16], bool history_valid, int history_frames, float detail);
ob_error ob_temporal_init(ob_temporal_pass *p);
/* The main chain: `current` (R32F or RGBA16F) and `history` (R32F, its age R16F in `age`; or
 * RGBA16F with the age in .a) in, `result`, `next_history` and `next_age` out (the same formats);
 * the bounce (bounce_current != 0): RGBA16F throughout, with a result always. depth/normal are
 * this frame's at the AO resolution; `prev` the previous frame's depth and packed normal, `next`
 * where this frame's go for the next (other textures). */
typedef struct ob_temporal_chain {
    GLuint current, history, next_history;
    GLuint age, next_age; /* visibility only */
    GLuint result;        /* 0: none, the next history is the output (visibility only) */
    bool rgb;
    GLuint bounce_current, bounce_history, bounce_next_history, bounce_result;
    GLuint host_motion;   /* a host's motion vectors (RG16F/RG32F, full resolution), or 0: the camera's */
    /* The G-buffer is jittered (this frame's or the last): the previous frame sampled each pixel at
     * another point of its footprint, so a tap also counts where the previous frame saw this
     * point's surface around it (temporal.glsl 2, OB_TEMPORAL_JITTER). */
    bool jittered;
} ob_temporal_chain;
/* The host's motion vectors in the constants: on (motion != 0) with their scale to full-resolution
 * pixels (zeros = 1). */
void ob_temporal_set_motion(ob_temporal_constants *c, GLuint motion, const float scale[2]);
typedef struct ob_temporal_geometry {
    GLuint depth;  /* R32F linear depth */
    GLuint normal; /* R32UI view normal, octahedral snorm16 x 2 (temporal.glsl's pack_normal) */
} ob_temporal_geometry;
ob_error ob_temporal_run(ob_temporal_pass *p, const ob_temporal_constants *c, const ob_ao_grid *g, GLuint depth,
                         GLuint normal, const ob_temporal_geometry *prev, const ob_temporal_geometry *next,
                         const ob_temporal_chain *chain);
/* The last run's reprojection offset, in AO pixels (where each pixel's point was in the previous
 * frame's AO grid - its centre; 0 on the sky), into `motion` (RG16F): the accumulation itself
 * writes none. `depth` is the last run's, and the frame block still the last frame's. */
ob_error ob_temporal_motion(ob_temporal_pass *p, const ob_ao_grid *g, GLuint depth, GLuint motion);
void ob_temporal_destroy(ob_temporal_pass *p);

/* ---- the second layer over each pixel's footprint: second_back.c, shaders/second_back.glsl -----
 * What the methods read as their samples' backs: per pixel the deepest of the peel pass's back at
 * its centre and at the four edges of its footprint (half way to each neighbour that shows the
 * same solid); 0 where the peel pass found none. The shader says why. */
typedef struct ob_second_back {
    ob_compute_pass pass;
    GLuint texture;    /* R32F, the second layer's size; 0 before the first run */
    int width, height;
} ob_second_back;
/* Builds the program; the texture is made by the first run. Errors: OB_ERR_INVALID_ARGUMENT (NULL),
 * OB_ERR_SHADER. */
ob_error ob_second_back_init(ob_second_back *b);
/* b->texture from front_depth (the first layer's linear depth) and second_depth (the peel pass's),
 * both R32F-readable and of one size, their writes visible to texture fetches; with planes (both
 * textures non-zero, of that size) the back over the footprint's edges where the front steps
 * (shaders/second_back.glsl). A pixel written negated is flagged: part of its footprint's solid has
 * no known back. Remakes the texture
 * when the size differs from the last run's. Issues a texture-fetch barrier after its dispatch.
 * Not timed here. Errors: OB_ERR_INVALID_ARGUMENT (not initialised, an input 0), OB_ERR_BAD_SIZE,
 * OB_ERR_GL (the texture could not be made; b keeps its old one and nothing runs). */
/* The two layers' own planes, for the back over the footprint's edges: the first layer's facet
 * normals (the G-buffer's) and the second's (the peel pass's), RG16F octahedral, with the camera that
 * maps a pixel to its view ray (frame_params.h's proj_info, and 1 for an orthographic camera). */
typedef struct ob_second_back_planes {
    GLuint front, back;
    float proj_info[4];
    int orthographic;
} ob_second_back_planes;
/* planes may be NULL (a host's frame: no planes), and then only the neighbours' backs count. */
ob_error ob_second_back_run(ob_second_back *b, GLuint front_depth, GLuint second_depth,
                            const ob_second_back_planes *planes);
/* Safe on a zeroed or already destroyed b. */
void ob_second_back_destroy(ob_second_back *b);
/* The CPU twin of the shader, for the tests: back (width x height floats, row-major) from front
 * and second; planes as ob_second_back_planes with the normals' octahedral pairs in memory (two
 * floats a pixel, as the textures hold them), or NULL. */
typedef struct ob_second_back_planes_data {
    const float *front, *back;
    float proj_info[4];
    int orthographic;
} ob_second_back_planes_data;
void ob_second_back_reference(const float *front, const float *second, int width, int height,
                              const ob_second_back_planes_data *planes, float *back);

/* ---- depth MIP prefilter: depth_mips.c, shaders/depth_mips.glsl (issue 13) -------------------
 * A MIP chain of linear view depth (R32F, positive along -Z, 0 = sky) built in one dispatch, for
 * the horizon-based methods to read far taps from coarser levels (McGuire et al. 2012, SAO §2.2).
 * Level 0 is a copy of the input; level L (GL's size rule: max(1, size >> L)) holds, per texel, the
 * depth of ONE level-0 pixel under it: SAO's rotated-grid child of each 2x2, or the farthest
 * geometry of the 2x2 when that child is sky; 0 only where all four are sky. No value is ever a
 * blend, so no level has a surface between a foreground and a background (the shader says why).
 * Reading: level-L texel p stands for level-0 pixels [p 2^L, (p+1) 2^L); fetch pixel x's texel at
 * min(x >> L, size_L - 1). The depth is that of one pixel inside the footprint, not of its centre. */
typedef struct ob_depth_mips {
    ob_compute_pass pass;
    GLuint texture;    /* R32F, `levels` levels, GL_NEAREST_MIPMAP_NEAREST, clamp to edge; 0 before the first run */
    int width, height; /* level 0, px */
    int levels;        /* ob_depth_mips_level_count(width, height): 5 from 16 px up, fewer below */
} ob_depth_mips;

/* min(OB_DEPTH_MIPS_LEVELS, 1 + floor(log2(max(width, height)))): a texture cannot have more. */
int ob_depth_mips_level_count(int width, int height);
/* Level `level`'s size: max(1, width >> level) x max(1, height >> level). */
void ob_depth_mips_level_size(int width, int height, int level, int *level_width, int *level_height);
/* The pass's constants for an input of width x height (pure; no GL). */
void ob_depth_mips_fill(ob_depth_mips_constants *c, int width, int height);
/* Builds the program; the texture is made by the first run. Errors: OB_ERR_INVALID_ARGUMENT (NULL),
 * OB_ERR_SHADER. */
ob_error ob_depth_mips_init(ob_depth_mips *m);
/* Build every level from linear_depth (R32F, width x height, complete; the caller makes its writes
 * visible to texture fetches first). Remakes m->texture (a new name) when the size differs from the
 * last run's; readers must take m->texture after each run. Issues a texture-fetch and image-access
 * barrier after its dispatch. Not timed here: the caller brackets it with ob_timer_begin. Errors:
 * OB_ERR_INVALID_ARGUMENT (NULL m, m not initialised, linear_depth 0), OB_ERR_BAD_SIZE (width or
 * height <= 0), OB_ERR_GL (the texture could not be made; m keeps its old one and nothing runs). */
ob_error ob_depth_mips_run(ob_depth_mips *m, GLuint linear_depth, int width, int height);
/* Safe on a zeroed or already destroyed m. */
void ob_depth_mips_destroy(ob_depth_mips *m);
/* The CPU twin of the shader, for the tests: levels[L] (max(1, width >> L) x max(1, height >> L)
 * floats, row-major, for L below the returned count) from depth (width x height). Returns
 * ob_depth_mips_level_count(width, height). */
int ob_depth_mips_reference(const float *depth, int width, int height, float *const levels[OB_DEPTH_MIPS_LEVELS]);

/* ---- the floor: floor.c, shaders/floor.glsl (obscura bench --floor; issue 18) ---------------
 * A bare N-tap kernel over the AO grid's depth and normals: what any AO method at N taps and radius
 * R must at least do (the shader says exactly what it does and leaves out). */
/* core/frame.c: a column-major OpenGL projection is orthographic when P23 = 0 and P33 = 1 (clip
 * w = 1), else perspective; ob_proj_info fills what common.glsl's ob_view_position takes of it:
 * 1/P00, 1/P11, P20, P21 (perspective) or 1/P00, 1/P11, -P30, -P31 (orthographic). The frame's
 * camera kind is frame_params.h's `orthographic`. */
bool ob_projection_is_orthographic(const float *proj);
void ob_proj_info(const float *proj, float out[4]);

typedef struct ob_floor_desc {
    int taps;            /* N, 1..OB_FLOOR_MAX_TAPS */
    int rays;            /* 0: a spiral over the disk of R_px; D: D rays of N / D steps (N a multiple of D) */
    float radius;        /* R, world units, > 0 */
    float px_per_unit;   /* R_px = R x px_per_unit / d: 0.5 x AO-grid height x P11, as the methods */
    float max_radius_px; /* the method's clamp of R_px; 0 = none */
} ob_floor_desc;

typedef struct ob_floor {
    ob_compute_pass pass;
    GLuint taps_buffer;  /* the tap table, OB_FLOOR_MAX_TAPS vec4 */
    GLuint texture;      /* R32F output, made by the first run at its size */
    int width, height;
} ob_floor;

/* The constants and the tap table (taps x 4 floats: unit direction xy, distance a + b R_px) for a
 * width x height grid; pure, for the test's CPU twin. Errors: OB_ERR_INVALID_ARGUMENT (NULL, taps
 * out of range or not a multiple of rays, radius or scale <= 0), OB_ERR_BAD_SIZE. */
ob_error ob_floor_fill(const ob_floor_desc *d, int width, int height, ob_floor_constants *c, float *table);
ob_error ob_floor_init(ob_floor *f);
/* One dispatch into f->texture (remade when the size changes), then a fetch/image barrier. Not
 * timed here: the caller brackets it. Errors: those of ob_floor_fill, OB_ERR_GL. */
ob_error ob_floor_run(ob_floor *f, const ob_floor_desc *d, GLuint linear_depth, GLuint view_normal, int width,
                      int height);
/* Safe on a zeroed or destroyed f. */
void ob_floor_destroy(ob_floor *f);

/* ---- direct light: lighting.c, shaders/lighting.glsl ---------------------------------------- */
/* The lighting pass: `pass` uploads the constants; the program that runs is one of `variants`,
 * by the shadow method and whether any light reads a cube or a 2D map (shaders/shadow.glsl), each
 * made on first use. */
#define OB_LIGHTING_VARIANTS 16
typedef struct ob_lighting_pass {
    ob_compute_pass pass;
    ob_lighting_constants constants;
    GLuint variants[OB_LIGHTING_VARIANTS];
} ob_lighting_pass;

/* The lights, the camera and the size come from the frame block (frame_params.h, bound at
 * OB_BINDING_FRAME); the pass's own constants are the specular lobe and the shadow maps. */
ob_error ob_lighting_init(ob_lighting_pass *l);
/* The specular lobe; the shadow members are ob_shadows_fill's. */
void ob_lighting_setup(ob_lighting_pass *l);
/* `frame` is the block the dispatch reads (its lights' types and shadow maps pick the variant).
 * Fails (error set) only when a variant does not compile. */
ob_error ob_lighting_run(ob_lighting_pass *l, const ob_frame_constants *frame, int width, int height, GLuint linear_depth,
                         GLuint normal, GLuint albedo, GLuint radiance_out);
void ob_lighting_destroy(ob_lighting_pass *l);

/* ---- the environment map: environment.c (upload, spherical harmonics) ---------------------- */
typedef struct ob_environment {
    GLuint texture;   /* RGBA16F equirectangular radiance with mipmaps; 0 = none */
    float sh[9][3];   /* diffuse irradiance / pi, convolved (Ramamoorthi & Hanrahan 2001) */
} ob_environment;

/* Upload w x h RGB floats (top row first), replacing e's map; `what` names it in messages (the
 * file's path from the evaluation library's reader, src/eval/environment.c). Errors:
 * OB_ERR_IO (too small, larger than GL_MAX_TEXTURE_SIZE, negative or non-finite radiance, the
 * upload failed); e keeps its old map then, except after a failed upload (none). */
ob_error ob_environment_upload(ob_environment *e, const float *rgb, int w, int h, const char *what);
/* Project equirectangular radiance (w x h RGB floats, top row first) onto 9 SH and convolve with
 * the clamped cosine: out = E_lm / pi. Exposed for the unit test. */
void ob_environment_sh(const float *rgb, int w, int h, float out[9][3]);
void ob_environment_destroy(ob_environment *e);

/* ---- compose: compose.c, shaders/compose.glsl ----------------------------------------------- */
/* A program per combination of the frame's choices (compose.glsl's OB_COMPOSE_* defines): the
 * ambient mode (3) x directional, bounce, bent normal, multi-bounce and AO on all light (bits), made
 * on first use but [0] (constant ambient, one AO value, nothing else). */
#define OB_COMPOSE_VARIANTS (3 << 5)
typedef struct ob_compose_pass { ob_compute_pass variants[OB_COMPOSE_VARIANTS]; } ob_compose_pass;

/* The camera, the size and the ambient light are the frame block's (frame_params.h). */
typedef struct ob_compose_inputs {
    GLuint linear_depth, normal, albedo, ao, direct, environment;
    /* Directional (SSDO): ao is RGBA16F M, multiplying direct and ambient light; bounce (RGBA16F,
     * radiance off a white receiver) is added times the albedo. */
    bool directional;
    GLuint bounce;        /* 0 = none */
    int width, height;      /* the visible frame: hdr_out's size */
    int guard;              /* the guard band: the inputs are (width + 2 guard) x (height + 2 guard) and
                               visible pixel (x, y) reads their (x + guard, y + guard) */
    bool ao_all_light;      /* AO multiplies the direct light too */
    bool multibounce;       /* the visibility goes through the multi-bounce fit (compose.glsl) */
    GLuint bent_normal;     /* RGBA16F view-space bent normal for the ambient lookup; 0 = the normal */
    int ambient_mode;       /* OB_AMBIENT_MODE_*: the frame block's ambient_mode, compiled in */
} ob_compose_inputs;

ob_error ob_compose_init(ob_compose_pass *c);
/* Writes linear HDR radiance (RGBA16F). */
ob_error ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint hdr_out);
void ob_compose_destroy(ob_compose_pass *c);

/* ---- HDR (SSDO thesis §2.2, §5.5, §6.5): luminance.c, bloom.c, tonemap.c, driven by hdr.c ------
 * radiance (RGBA16F, linear) -> luminance: log-average (eq. 2.1) + key -> a small GPU buffer
 *                            -> bloom: bright pass at 1/4 resolution + separable Gaussian
 *                            -> tonemap: scale (eq. 2.2) + bloom, Reinhard (eq. 2.4), sRGB RGBA8 */
typedef struct ob_luminance_pass {
    ob_compute_pass partial, final; /* shaders/luminance.glsl without / with OB_LUMINANCE_FINAL */
    GLuint result;                  /* SSBO: vec4 (L_avg, key, exposure key / L_avg, 0), partial sums */
    int width, height, groups_x, groups_y;
} ob_luminance_pass;

ob_error ob_luminance_init(ob_luminance_pass *p, int width, int height);
/* A new partial-sum buffer for this size; on an error p is unchanged. Errors: OB_ERR_GL. */
ob_error ob_luminance_resize(ob_luminance_pass *p, int width, int height);
/* key <= 0: the automatic key of §6.5, chosen on the GPU. */
void ob_luminance_run(ob_luminance_pass *p, GLuint radiance, float exposure, float key);
void ob_luminance_destroy(ob_luminance_pass *p);

typedef struct ob_bloom_pass {
    ob_compute_pass bright, blur;   /* shaders/bloom.glsl with / without OB_BLOOM_BRIGHT */
    GLuint bloom, scratch;          /* RGBA16F at 1/OB_BLOOM_FACTOR; bloom is sampled bilinearly */
    int width, height, bloom_width, bloom_height;
} ob_bloom_pass;

ob_error ob_bloom_init(ob_bloom_pass *b, int width, int height);
/* New targets for this size; on an error b is unchanged. Errors: OB_ERR_GL. */
ob_error ob_bloom_resize(ob_bloom_pass *b, int width, int height);
/* result: the luminance pass's buffer (its scale); threshold in scaled luminance (eq. 2.2). */
void ob_bloom_run(ob_bloom_pass *b, GLuint radiance, GLuint result, float threshold);
void ob_bloom_destroy(ob_bloom_pass *b);

typedef struct ob_tonemap_pass { ob_compute_pass pass; } ob_tonemap_pass;

typedef struct ob_tonemap_inputs {
    GLuint radiance, result;        /* result: the luminance pass's buffer (unused with HDR off) */
    GLuint bloom;                   /* 0 = no bloom */
    int width, height, bloom_width, bloom_height;
} ob_tonemap_inputs;

ob_error ob_tonemap_init(ob_tonemap_pass *t);
void ob_tonemap_run(ob_tonemap_pass *t, const ob_tonemap_inputs *in, const ob_hdr_settings *s, GLuint final_out);
void ob_tonemap_destroy(ob_tonemap_pass *t);

typedef struct ob_hdr_pass {
    ob_luminance_pass luminance;
    ob_bloom_pass bloom;
    ob_tonemap_pass tonemap;
    int width, height;
} ob_hdr_pass;

/* Errors: OB_ERR_BAD_SIZE, OB_ERR_SHADER. On failure h is left destroyed (safe to destroy again). */
ob_error ob_hdr_init(ob_hdr_pass *h, int width, int height);
/* The luminance and bloom targets at a new size, programs kept; on an error h keeps its old size.
 * Errors: OB_ERR_BAD_SIZE, OB_ERR_GL. */
ob_error ob_hdr_resize(ob_hdr_pass *h, int width, int height);
/* radiance: RGBA16F full-resolution linear radiance; final: RGBA8 of the same size. Times its passes
 * with ob_timer_begin(timers, "luminance" / "bloom" / "tonemap") (timers may be NULL). With
 * s->enabled false only "tonemap" runs (exposure x radiance clamped, sRGB); bloom runs only when
 * s->bloom_strength > 0. Issues the barriers its passes need, and one after the last so `final`
 * can be read, sampled or copied. */
void ob_hdr_run(ob_hdr_pass *h, GLuint radiance, const ob_hdr_settings *s, GLuint final, ob_timer_set *timers);
/* After a frame: the log-average luminance and the key used (reads a few bytes back; for tests and
 * -v). Both 0 after a frame with HDR off or before the first frame. Either pointer may be NULL. */
void ob_hdr_query(ob_hdr_pass *h, float *log_average, float *key);
void ob_hdr_destroy(ob_hdr_pass *h);

/* ---- shadow maps (SSDO thesis §2.1, §5.1, §6.1): shadow.c, shaders/shadow_depth.{vert,frag}.glsl,
 * shaders/shadow_vsm.glsl; looked up by shaders/shadow.glsl (OB_UNIT_SHADOW_*, ob_units.h) ----
 * Directional lights: an orthographic map along the light, fitted to the scene bounds. Spot lights:
 * a perspective map (fov = 2 x outer half-angle + 2 degrees, at most 160), storing distance/far.
 * Point lights: a cube map storing distance/far. The first OB_MAX_SHADOW_MAPS lights get a map. */
typedef struct ob_shadow_maps {
    GLuint depth_program;    /* orthographic maps: hardware depth */
    GLuint distance_program; /* spot and point maps: distance to the light / far */
    GLuint ubo, fbo;
    ob_compute_pass vsm_x, vsm_y; /* VSM: depth -> moments blurred along x; then along y (RG32F) */
    ob_compute_pass vsm_x16, vsm_y16; /* the same writing RG16F (vsm_bits 16), made on first use */
    GLuint maps_2d;   /* DEPTH_COMPONENT32F 2D array: a layer per directional or spot map */
    GLuint maps_cube; /* DEPTH_COMPONENT32F cube-map array: a cube per point-light map */
    GLuint moments;   /* RG32F or RG16F 2D array (VSM only): blurred (z, z^2) per directional or spot map */
    GLuint scratch;   /* the same format, 2D (VSM only): the blur's intermediate */
    int size, layers_2d, cubes, moment_layers, moment_bits; /* what is allocated */
    ob_shadow_method method; /* of the last ob_shadows_render; NONE = no maps this frame */
    int light_map[OB_MAX_LIGHTS]; /* map index of each light, -1 = unshadowed */
    float matrix[OB_MAX_SHADOW_MAPS][16]; /* -> ob_lighting_constants.shadow_matrix */
    float params[OB_MAX_SHADOW_MAPS][4];  /* -> shadow_params */
    float options[4];                     /* -> shadow_method, pcf_radius, vsm_min_variance, vsm_bleed */
    /* What the maps were rendered from, for ob_shadow_settings.reuse. */
    bool key_valid;
    ob_light key_lights[OB_MAX_SHADOW_MAPS];
    int key_count;
    ob_shadow_settings key_settings;
    float key_bounds[6];
    unsigned key_scene;
} ob_shadow_maps;

/* Builds the programs; allocates no maps yet. Errors: OB_ERR_SHADER. */
ob_error ob_shadows_init(ob_shadow_maps *s);
/* Maps for the first OB_MAX_SHADOW_MAPS lights (any type) when settings->method != NONE, from
 * the G-buffer's uploaded meshes; (re)allocates when the size or the number of maps of a kind
 * changes; timed as "shadow" (timers may be NULL; nothing is timed with method NONE). Leaves
 * framebuffer 0 bound and restores the viewport and depth-test state. Errors: OB_ERR_OUT_OF_RANGE
 * (size, bias, slope_bias, pcf_radius, vsm_blur or vsm_bleed outside its range; only the fields
 * the method uses are checked), OB_ERR_OUT_OF_MEMORY (the GL could not allocate the maps). */
ob_error ob_shadows_render(ob_shadow_maps *s, const ob_gbuffer *g, const ob_light *lights, int light_count,
                           const float bounds_min[3], const float bounds_max[3], const ob_shadow_settings *settings,
                           ob_timer_set *timers);
/* Fill the lighting constants' shadow members and each light's frame->light_direction[i].w (map
 * index or -1; call after the frame's lights are filled), and bind the textures to the units
 * shadow.glsl declares (0 where a kind has no map). Call after ob_shadows_render, before the frame
 * block is uploaded and the lighting pass runs. */
void ob_shadows_fill(const ob_shadow_maps *s, ob_lighting_constants *c, ob_frame_constants *frame);
void ob_shadows_destroy(ob_shadow_maps *s);

/* ---- presenting: view.c, shaders/view.glsl (ob_present) -------------------------------------
 * OB_VIEW_FINAL blits the frame's RGBA8 as it is; the debug views first map their texture into
 * an RGBA8 display texture with one compute pass, then blit that. */
typedef struct ob_view_pass {
    ob_compute_pass pass; /* made on the first debug view */
    bool ready;
    GLuint display;       /* RGBA8 display bytes of the views, (re)made at the inputs' size */
    int width, height;    /* of display */
    GLuint read_fbo;      /* the blit's source: final or display attached */
} ob_view_pass;

typedef struct ob_view_inputs {
    ob_view view;
    GLuint source;        /* the view's texture (see shaders/view.glsl); final for OB_VIEW_FINAL */
    GLuint multiplier;    /* samples under adaptive sampling: the edge pass's per-block multiplier */
    bool directional;     /* the last frame's method wrote RGB M and a bounce */
    int width, height;    /* of the display: the visible frame */
    int offset;           /* source pixel of display pixel (0, 0), on both axes: the guard band for
                             sources that carry it, 0 for final and the composed radiance */
    float far_z;          /* depth: the last frame's far plane */
    int samples;          /* samples: the method's count, or the adaptive base with multiplier */
    int grid_k;           /* samples: full pixels per AO pixel */
    int max_samples;      /* samples: the most a pixel could take */
    int history_frames;   /* history_age: the history length (white); 0 = no history, black */
} ob_view_inputs;

/* Draw the view into framebuffer's x, y, w, h (ob_present's contract: state restored). Errors:
 * OB_ERR_SHADER, OB_ERR_GL. */
ob_error ob_view_present(ob_view_pass *v, const ob_view_inputs *in, GLuint framebuffer, int x, int y, int w, int h);
/* Run the view pass only (not OB_VIEW_FINAL): *out is the RGBA8 texture it wrote, owned by v.
 * GL state is restored as for ob_view_present. Errors: OB_ERR_SHADER. */
ob_error ob_view_render(ob_view_pass *v, const ob_view_inputs *in, GLuint *out);
void ob_view_destroy(ob_view_pass *v);


/* ---- the host path's own passes: host.c, shaders/host_input.glsl, host_output.glsl ----------
 * The input pass turns an engine's depth and normals into the AO chain's R32F linear depth and
 * RGBA16F view normals (and a second layer's linear depth); the output pass crops one of the
 * chain's results to the visible frame in the host's texture format. A sampler object (GL_NEAREST,
 * no comparison) reads the host's textures whatever their own filter and compare state. */
#include "host_params.h"
enum { OB_HOST_OUTPUT_FORMATS = 7 };
/* The input pass's variant (host_params.h): the depth's kind, the normals' encoding, a second layer. */
typedef struct ob_host_input_variant {
    int depth_kind;       /* OB_HOST_DEPTH_* */
    int normal_encoding;  /* OB_HOST_NORMAL_* */
    bool second;
} ob_host_input_variant;
typedef struct ob_host_passes {
    ob_compute_pass input[2][OB_HOST_NORMAL_ENCODINGS][2]; /* by variant; .program 0 until made */
    ob_compute_pass output[OB_HOST_OUTPUT_FORMATS];  /* one per image format, made on first use */
    GLuint sampler;
    GLuint second;                                   /* R32F: the host's second layer, linearised */
    int second_width, second_height;
} ob_host_passes;
/* The output formats, in the order of ob_host_passes.output; -1 for one it does not write. */
int ob_host_output_format_index(GLenum internal_format);
ob_error ob_host_input_prepare(ob_host_passes *h, const ob_host_input_variant *v);
ob_error ob_host_output_prepare(ob_host_passes *h, GLenum format);
/* The input pass over c->size; second (and out_second) 0 when there is no second layer. */
ob_error ob_host_input_run(ob_host_passes *h, const ob_host_input_variant *v, const ob_host_input_constants *c,
                           GLuint depth, GLuint normal, GLuint second, GLuint out_depth, GLuint out_normal,
                           GLuint out_second);
/* The output pass: source (at the enlarged size) cropped at c->offset to c->size into target. */
ob_error ob_host_output_run(ob_host_passes *h, const ob_host_output_constants *c, GLuint source, GLuint target,
                            GLenum format);
/* The R32F target of the host's second layer at this size, made or remade as needed (0 on failure). */
GLuint ob_host_second_target(ob_host_passes *h, int width, int height);
void ob_host_passes_destroy(ob_host_passes *h);

#endif
