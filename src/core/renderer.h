/* The renderer's insides, shared by its four files:
 *   renderer.c  lifecycle: make, resize, destroy, scene, environment, lazily made method and
 *               filter states and AO-resolution targets;
 *   frame.c     the frame (ob_render_frame, ob_compute_ao) and the per-frame block;
 *   readback.c  images back to the CPU (ob_read_image) and the timings;
 *   present.c   the debug views on the GPU (ob_present, ob_read_view). */
#ifndef OB_CORE_RENDERER_H
#define OB_CORE_RENDERER_H

#include "filters/filter.h"
#include "frame_params.h"
#include "methods/method.h"
#include "passes/passes.h"

/* Targets at one AO resolution (k = 1, 2 or 4), made when a frame first asks for it. */
typedef struct ao_targets {
    ob_ao_grid grid;
    GLuint depth, normal;      /* k > 1: downsampled (owned); k = 1: the G-buffer's (not owned) */
    GLuint raw, filtered, scratch;
    GLuint multiplier;         /* adaptive sample counts, one per OB_EDGE_BLOCK^2 pixels */
    /* Directional methods (OB_WRITES_VISIBILITY_RGB, OB_WRITES_BOUNCE): RGBA16F M and bounce
     * chains, made when one first runs. */
    GLuint raw_rgb, filtered_rgb, scratch_rgb, bounce_raw, bounce_filtered;
    /* Methods that write a bent normal (OB_WRITES_BENT_NORMAL): RGBA16F, made with the above. */
    GLuint bent_raw, bent_filtered;
    /* Temporal accumulation (ob_settings.temporal), made when a frame first asks for it: per chain
     * the stage between accumulation and filter (the accumulation's output before the filter, the
     * filter's before the accumulation) and two histories with the age, read and written in turn
     * (history_index holds the last frame's); the last frame's depth and normals; the motion. */
    GLuint accum, history[2], history_age[2]; /* visibility: R32F; R32F value, R16F age */
    GLuint accum_rgb, history_rgb[2];         /* M: RGBA16F; RGBA16F (rgb, age) */
    GLuint bounce_accum, bounce_history[2];   /* the bounce: the same */
    ob_temporal_geometry geometry[2];         /* depth, packed normal: [history_index] the last frame's */
    GLuint motion;                            /* RG16F (offset in AO pixels) */
    int history_index;
    bool temporal_ready;
    bool ready;
} ao_targets;

/* What a history was accumulated under: the next frame reuses it only under the same (temporal.c). */
typedef struct ob_history_key {
    int method, scale, at;
    int width, height;          /* the inner size */
    int orthographic;           /* the camera's kind: the previous frame's matrices are read as this one's */
    bool rgb, bounce;
} ob_history_key;

/* What the last frame ran (ob_render_frame or ob_host_ao), for read-back, the debug views and the
 * floor kernel: one record written where the frame is planned and run, instead of a flag each. */
typedef struct ob_frame_record {
    int scale;                 /* index into scales */
    int method;
    float params[OB_MAX_PARAMS];
    bool adaptive;
    bool rgb;                  /* the method wrote RGB M */
    bool bounce;               /* it wrote a bounce (SSDO's beside M, vbgi's beside visibility) */
    bool bent;                 /* it wrote a bent normal */
    bool second_layer;         /* it read a second depth layer (peeled, or the host's) */
    bool extra_view;           /* the extra view was rendered */
    bool temporal;             /* the chain accumulated (the history_age view and read-backs) */
    int temporal_frames;
    float far;                 /* the far plane (the depth view's scale) */
} ob_frame_record;

enum { OB_AO_SCALES = 3 }; /* k = 1, 2, 4 */

struct ob_renderer {
    ob_context *ctx;
    int width, height;         /* the visible frame: radiance, final, the HDR passes, every read-back */
    /* The guard band (Belonogov 2018 §3.2.2), px per side, and the size every pass before compose works
     * on, width + 2 guard by height + 2 guard: the G-buffer, ao, direct, the AO chains and their
     * scales. Visible pixel (x, y) is internal pixel (x + guard, y + guard); compose crops. */
    int guard;
    int inner_width, inner_height;
    ob_gbuffer gbuffer;
    ob_compute_pass downsample, edges;
    ob_upsample upsample;
    ob_compute_pass fill, fill_rgb; /* fill.c: none's visibility 1, the bounce's 0 */
    ob_upsample upsample_rgb;      /* made with the first directional frame */
    ob_compose_pass compose;
    ob_lighting_pass lighting;
    ob_shadow_maps shadows;
    ob_hdr_pass hdr;
    ob_environment environment;
    ao_targets scales[OB_AO_SCALES];
    GLuint ao, final;          /* full resolution */
    GLuint direct;             /* RGBA16F direct radiance; alpha = the key light's visibility */
    GLuint radiance;           /* RGBA16F composed HDR radiance, before tone mapping */
    GLuint ao_rgb, bounce;     /* RGBA16F full-resolution M and bounce (made on first use) */
    GLuint bent;               /* RGBA16F full-resolution bent normal (made with them) */
    GLuint frame_ubo;          /* the per-frame block at OB_BINDING_FRAME */
    ob_frame_constants frame_constants;
    void **method_states;      /* lazily made by the method kit, one per registry entry */
    void **filter_states;      /* the same for filters */
    bool *filter_ready;
    void **filter_states_rgb;  /* and their RGBA16F variants (init_rgb) */
    bool *filter_ready_rgb;
    ob_timer_set timers;
    bool has_scene;
    float bounds_min[3], bounds_max[3];
    float scene_radius;
    ob_light scene_lights[OB_MAX_LIGHTS];
    int scene_light_count;
    uint32_t frame;
    ob_frame_record last;
    ob_host_passes host;       /* ob_host_ao's input and output passes, made on first use */
    bool has_frame;            /* the targets hold a whole frame (ob_present) */
    /* The AO grid's targets (raw AO, history age, motion) hold the last ob_host_ao call's, and the
     * motion read-back can find its depth (the input pass wrote it into the G-buffer's). */
    bool has_host_chain, host_depth_in_gbuffer;
    ob_view_pass view;         /* ob_present */
    ob_depth_mips depth_mips;  /* for methods that read OB_READS_DEPTH_MIPS, made on first use */
    ob_floor floor;            /* ob_render_floor, made on first use */
    ob_peel peel;              /* the second depth layer, for methods that read OB_READS_SECOND_LAYER */
    ob_second_back second_back; /* that layer over each pixel's footprint, what they read; made on first use */
    /* The extra view (Belonogov 2018 §4.4), for methods that read OB_READS_EXTRA_VIEW, made on first use
     * at the G-buffer's size: its own G-buffer (drawing the main one's meshes), direct light and
     * per-frame block; the matrices between the two views of the current frame. */
    ob_gbuffer extra_gbuffer;
    GLuint extra_direct, extra_ubo;
    ob_frame_constants extra_constants;
    float extra_view[16], extra_proj[16], extra_from_view[16], extra_to_view[16];
    /* Temporal accumulation: the pass (made on first use), the last frame's camera as the AO grid
     * saw it and what its history was accumulated under (valid: the last frame accumulated). */
    ob_temporal_pass temporal;
    bool history_valid;
    /* r->ao holds 1 everywhere, left by a `none` frame: the next `none` frame need not clear it. */
    bool ao_is_one;
    ob_history_key history_key;
    /* The AO grid's projection without this frame's sub-pixel jitter (ob_settings.jitter, the
     * host's ob_host_frame.jitter), and the last frame's: the accumulation reprojects through the
     * last frame's camera with this frame's jitter, so a still camera reads its history where it
     * was written (chain.c, run_temporal). */
    float ao_proj_unjittered[16];
    float prev_view[16], prev_ao_proj[16];
    bool prev_jittered; /* the last accumulated frame was jittered */
};

/* renderer.c: the targets for a visible size and a guard band (px per side, a multiple of 4), made
 * anew when either changed; on an error the renderer keeps its old targets and still works. guard
 * must be a multiple of every AO divisor in use (ob_guard_pixels). */
ob_error ob_renderer_reshape(ob_renderer *r, int width, int height, int guard);
/* ob_settings.guard as the renderer uses it for AO divisor k: rounded up to a multiple of 4 k. */
int ob_guard_pixels(int guard, int k);

/* renderer.c: the lazily made states and targets. NULL / an error when making them failed. */
void *ob_renderer_method_state(ob_renderer *r, int index, ob_error *err);
void *ob_renderer_filter_state(ob_renderer *r, int index, bool rgb, ob_error *err);
ao_targets *ob_renderer_targets(ob_renderer *r, int scale_index);
/* The last frame's second depth layer and the extra view's direct light, each at the G-buffer's
 * (enlarged) size, or 0 where that frame made none (read-back and the debug views). */
GLuint ob_renderer_second_layer(const ob_renderer *r);
GLuint ob_renderer_extra_direct(const ob_renderer *r);
/* The RGBA16F chains, each made on first use: a directional method's M and bounce, a bent normal. */
ob_error ob_renderer_rgb_targets(ob_renderer *r, ao_targets *t, bool directional, bool bent);
/* The temporal accumulation's targets at this scale (ao_targets), made on first use. */
ob_error ob_renderer_temporal_targets(ob_renderer *r, ao_targets *t);

/* frame.c: the per-frame block from the camera, the AO grid, the lights and the settings, as a
 * pure function (no GL): lights as lighting.glsl reads them (colour x intensity, unit directions,
 * cosines of the spot cones, no shadow map yet: ob_shadows_fill adds those). */
typedef struct ob_frame_desc {
    const float *view, *proj;  /* column-major 4x4 */
    const ob_ao_grid *grid;
    float near_z, far_z;
    uint32_t frame_index;
    const ob_light *lights;
    int light_count;
    const ob_settings *settings; /* ambient and background; NULL = none */
    const float (*sh)[3];        /* 9 environment SH coefficients; NULL = zeros */
} ob_frame_desc;
void ob_frame_constants_fill(ob_frame_constants *f, const ob_frame_desc *d);
/* The projection as the AO grid g sees it (P00, P20, P11, P21 or P30, P31 folded; frame.c). */
void ob_ao_grid_projection(const ob_ao_grid *g, const float *proj, float out[16]);
/* The extra view's camera (Belonogov 2018 §4.4): c's eye turned 90 degrees about its up axis (world +Y
 * when zero) around its target, the same target, up, fov and planes. */
void ob_extra_view_camera(const ob_camera *c, ob_camera *out);

/* chain.c: the AO chain both front doors run (ob_render_frame, ob_host_ao). */
/* The method of a frame, resolved once: its entry, state, parameters as it sees them (explicit
 * values, else defaults, with radii that were not set following the scene) and what it writes. */
typedef struct ob_method_plan {
    int index;
    const ob_method_impl *impl;
    void *state;
    float params[OB_MAX_PARAMS];
    uint32_t reads;   /* ob_method_active_reads */
    uint32_t writes;  /* ob_method_active_writes */
    bool rgb;         /* OB_WRITES_VISIBILITY_RGB: M instead of visibility */
    bool bounce;      /* OB_WRITES_BOUNCE among the active outputs */
    bool bent;        /* OB_WRITES_BENT_NORMAL among the active outputs */
} ob_method_plan;
/* scene_radius > 0: radii not set explicitly follow it (ob_render_frame); 0: as set (hosts). */
ob_error ob_plan_method(ob_renderer *r, const ob_settings *s, float scene_radius, ob_method_plan *p);
/* What the chain reads and writes, at the enlarged (inner) size. The RGB results go to the
 * renderer's ao_rgb, bounce and bent (ob_renderer_rgb_targets). */
typedef struct ob_chain_io {
    GLuint depth, normal;      /* R32F-compatible positive linear depth (0 = sky), view-space normals */
    GLuint radiance, albedo;   /* for methods that read them; 0 otherwise */
    GLuint second_depth;       /* linear depth of the second layer, or 0 */
    GLuint facet;              /* the G-buffer's facet normals (RG16F octahedral), or 0 (a host's frame) */
    GLuint second_plane;       /* the peel pass's own planes (RG16F octahedral), or 0 (a host's frame) */
    bool extra_view;           /* the extra view was rendered this frame (ob_render_frame) */
    GLuint ao;                 /* R32F: the visibility (r->ao, or a host's R32F texture) */
    GLuint motion;             /* a host's motion vectors for the temporal accumulation, or 0 */
    float motion_scale[2];     /* their units -> pixels (zeros = 1) */
} ob_chain_io;
ob_error ob_run_ao_chain(ob_renderer *r, const ob_settings *s, const ob_method_plan *plan, ao_targets *t,
                         const ob_chain_io *io);
ob_error ob_check_settings(const ob_settings *s);
int ob_scale_index(int divisor);
/* The per-frame block into its buffer, bound at OB_BINDING_FRAME. */
void ob_upload_frame(ob_renderer *r);

#endif
