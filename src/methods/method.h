/* The internal side of the method registry: what one AO/GI method provides, and the kit that
 * makes and frees what every method shares. Adding a method is one .c (defining an
 * ob_method_impl), one shader, one params header (its constant block) and one line in
 * registry.c's OB_METHODS list; the renderer knows no method by name, only what each entry
 * declares it reads and writes, and which of its parameters plays each role (ob_param_role):
 * declare in .roles every parameter that has one, or the renderer will not find it. */
#ifndef OB_METHOD_H
#define OB_METHOD_H

#include "frame_params.h"
#include "gpu/gpu.h"
#include "obscura/scene.h"

/* What a method reads (ob_method_impl.reads): the renderer provides these in ob_ao_inputs. */
enum {
    OB_READS_DEPTH = 1u << 0,        /* linear depth at the AO resolution (always available) */
    OB_READS_NORMALS = 1u << 1,      /* view normals at the AO resolution (always available) */
    OB_READS_ALBEDO = 1u << 2,       /* the full-resolution albedo */
    OB_READS_RADIANCE = 1u << 3,     /* the full-resolution direct radiance (the lighting pass's output):
                                        only inside ob_render_frame, so ob_compute_ao refuses such methods */
    OB_READS_DEPTH_MIPS = 1u << 4,   /* reserved: a prefiltered depth MIP chain */
    OB_READS_SECOND_LAYER = 1u << 5, /* a second depth layer (depth peeling, passes/peel.c) */
    OB_READS_HISTORY = 1u << 6,      /* reserved: the previous frame's output, reprojected */
    OB_READS_EXTRA_VIEW = 1u << 7,   /* an extra view's G-buffer and direct light (Belonogov 2018 §4.4) */
    /* With OB_READS_SECOND_LAYER: the second layer over each pixel's footprint (passes/second_back.c)
     * in place of the peel pass's own, as ob_ao_inputs.second_depth: the back of a sample's solid
     * (vbao, vbgi). gtao and ssdo read the layer as it is (docs/methods.md, "The back over a
     * pixel's footprint"). */
    OB_READS_SECOND_BACK = 1u << 8,
    /* With OB_READS_SECOND_BACK: that pass follows the two layers' own planes (the G-buffer's facet
     * normals and the peel pass's) across a footprint edge where the front steps; a host's frame
     * has none (docs/methods.md, "Where part of the footprint has no known back"). */
    OB_READS_SECOND_PLANES = 1u << 9,
};

/* What a method writes (ob_method_impl.writes); the renderer makes, filters and upsamples each. */
enum {
    OB_WRITES_VISIBILITY = 1u << 0,     /* R32F visibility in [0, 1] */
    OB_WRITES_VISIBILITY_RGB = 1u << 1, /* RGBA16F per-channel modulation factor M (a directional method,
                                           ob_method_info.directional) instead of R32F visibility */
    OB_WRITES_BOUNCE = 1u << 2,         /* RGBA16F one-bounce indirect light off a white receiver */
    OB_WRITES_BENT_NORMAL = 1u << 3,    /* RGBA16F bent normal: the visible cone's cosine-weighted mean direction */
};

/* What a parameter means to the renderer beyond its own method: the renderer, the settings and
 * the memory estimate find a method's radius, sample count or temporal switch through the role
 * its entry declares (ob_method_impl.roles, ob_method_role), never by the parameter's name, so a
 * method may name its parameters as its paper does. tests/test_cpu.c checks each role's type and
 * that every parameter named as a role's usual name (radius, samples, temporal, ...) declares it. */
typedef enum ob_param_role {
    OB_ROLE_RADIUS,        /* FLOAT, follows_scene_radius: R, world units (AO_R's radius) */
    OB_ROLE_MAX_RADIUS_PX, /* FLOAT: a cap on the projected radius, px */
    OB_ROLE_SAMPLES,       /* INT: samples per pixel, what --samples and --quality set (a method whose
                              count is a product of parameters has set_samples/count_samples instead) */
    OB_ROLE_TEMPORAL,      /* BOOL: noise that moves with the frame index (temporal accumulation
                              switches it on unless the user set it) */
    OB_ROLE_INTENSITY,     /* FLOAT: an intensity or contrast exponent or scale on the result */
    OB_ROLE_THICKNESS,     /* FLOAT: the thickness assumed behind a surface, x radius */
    OB_ROLE_FALLOFF,       /* FLOAT: the share of R over which occlusion fades out */
    OB_ROLE_BENT_NORMALS,  /* BOOL: also writes bent normals (OB_WRITES_BENT_NORMAL) */
    OB_ROLE_LAYERS,        /* INT or ENUM: depth layers read (2 = OB_READS_SECOND_LAYER too) */
    OB_ROLE_PACKED,        /* ENUM OB_PACKED_*: samples read the packed texels (methods/packed.c) */
    OB_ROLE_DEINTERLEAVE,  /* ENUM off/on: deinterleaved taps (methods/deinterleave.c) */
    OB_ROLE_COUNT
} ob_param_role;

/* An entry of ob_method_impl.roles: parameter P_X (its index in the table) plays the role. */
#define OB_ROLE_PARAM(p) ((signed char)((p) + 1))

/* What a method gets each frame. The camera, the AO grid, the lights and the ambient light are in
 * the per-frame block (frame_params.h), bound at OB_BINDING_FRAME for every dispatch; `frame` is
 * the same data on the CPU, for constants derived from it (e.g. pixels per world unit). */
typedef struct ob_ao_inputs {
    const ob_frame_constants *frame;
    GLuint linear_depth;      /* R32F, positive view depth at the AO resolution, 0 = no geometry */
    GLuint view_normal;       /* RGBA16F, view-space unit normal at the AO resolution */
    int width, height;        /* the AO resolution (frame->ao_size) */
    /* Adaptive sample counts (SSDO thesis §4.1): when set, a method with a sample count takes
     * samples/3 (at least 1) x the multiplier (1, 2 or 3) of its OB_EDGE_BLOCK^2 block of this
     * R32F texture; methods without one ignore it. */
    GLuint sample_multiplier; /* 0 = off */
    GLuint radiance;          /* OB_READS_RADIANCE: full-resolution RGBA16F direct radiance */
    GLuint albedo;            /* OB_READS_ALBEDO: full-resolution albedo */
    /* OB_READS_DEPTH_MIPS: the prefiltered MIP chain of linear_depth (R32F, level 0 = the AO
     * grid's depth), or 0 where the frame has none (ob_compute_ao); a method then reads level 0. */
    GLuint depth_mips;
    int depth_mip_levels;
    /* OB_READS_SECOND_LAYER: the full-resolution R32F linear depth of the nearest surface behind
     * the first (0 where none), or 0 where the frame has no second layer (ob_compute_ao): a method
     * then falls back to its single-layer assumption. AO pixel i reads full pixel k i + o, the
     * pixel the AO grid's depth came from. */
    GLuint second_depth;
    /* The full-resolution RG16F octahedral normal of each pixel's own triangle (the G-buffer's
     * `facet`), or 0 where the frame has none (a host's frame, ob_compute_ao). AO pixel i reads
     * full pixel k i + o, as second_depth. */
    GLuint facet_normal;
    /* OB_READS_EXTRA_VIEW: a second camera's G-buffer, turned 90 degrees about the up axis around
     * the main camera's target (Belonogov 2018 §4.4), at the G-buffer's size: its linear depth, view
     * normal (in ITS view space) and direct radiance; 0 where the frame has none (ob_compute_ao).
     * extra_from_view takes this frame's view space to the extra camera's, extra_to_view back,
     * extra_proj is its projection (column-major 4x4 each). */
    GLuint extra_depth, extra_normal, extra_radiance;
    const float *extra_from_view, *extra_to_view, *extra_proj;
} ob_ao_inputs;

/* Where a method writes: textures of the inputs' size. */
typedef struct ob_ao_outputs {
    GLuint visibility;        /* R32F, or RGBA16F for OB_WRITES_VISIBILITY_RGB */
    GLuint bounce;            /* RGBA16F, when the method writes OB_WRITES_BOUNCE (else 0) */
    GLuint bent_normal;       /* RGBA16F view-space unit bent normal (xyz; 0 for sky), when the active
                                 outputs include OB_WRITES_BENT_NORMAL (else 0) */
} ob_ao_outputs;

/* The base count that the multiplier scales under adaptive sampling. */
static inline int ob_adaptive_base(int samples) { return samples / 3 > 1 ? (samples + 1) / 3 : 1; }

/* What the kit makes for every method from its entry (shader, constants_size): every method
 * state begins with one, so a method's state struct is `{ ob_method_kit kit; ...its own... }`. */
typedef struct ob_method_kit {
    ob_compute_pass pass;     /* the entry's shader, with a constants_size-byte block at OB_BINDING_PASS */
    GLuint noise;             /* the 4x4 RG32F rotation tile of noise.glsl (OB_UNIT_NOISE) */
} ob_method_kit;

typedef struct ob_method_impl {
    ob_method_info info;      /* info.directional is derived from writes (registry.c) */
    const char *shader;       /* compute shader; NULL for a method that dispatches nothing (none) */
    size_t constants_size;    /* bytes of its constant block (sizeof the *_params.h struct) */
    size_t state_size;        /* bytes of its state, beginning with an ob_method_kit; zero-filled */
    uint32_t reads;           /* OB_READS_* */
    uint32_t writes;          /* OB_WRITES_* it can produce */
    /* Set-up beyond the kit (kernel caches, a flag); NULL for none. Fails with ob_set_error. */
    ob_error (*init)(void *state);
    /* Write the outputs; params are in table order, validated, radii resolved. */
    ob_error (*run)(void *state, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out);
    /* Frees what init made beyond the kit; NULL for nothing. */
    void (*destroy)(void *state);
    /* The inputs these params read, when a parameter turns one off (gtao's depth MIPs); NULL =
     * every input in reads. */
    uint32_t (*active_reads)(const float *params);
    /* The outputs these params produce, when a parameter turns one off (SSDO's bounce); NULL =
     * every output in writes. */
    uint32_t (*active_writes)(const float *params);
    /* How `samples` per pixel map onto this method's parameters, when that is more than setting
     * its OB_ROLE_SAMPLES parameter (HBAO: directions x steps). Sets the bits of what it changed
     * in *params_set. NULL for the default. */
    ob_error (*set_samples)(float *params, uint32_t *params_set, int samples);
    /* Samples per pixel these params ask for, when not its OB_ROLE_SAMPLES parameter (HBAO:
     * directions x steps). NULL for the default. */
    int (*count_samples)(const float *params);
    /* Rays these params march from the pixel, when the samples lie on rays (HBAO: directions;
     * GTAO and VBAO: 2 x slices, a slice searched on both sides); NULL: the samples scatter over
     * the disk of the radius. The floor kernel takes its taps in the same pattern (bench --floor). */
    int (*count_rays)(const float *params);
    /* Honours ob_ao_inputs.sample_multiplier (adaptive sample counts). */
    bool adapts;
    /* Which parameter plays each role: OB_ROLE_PARAM(P_X), indexed by ob_param_role; 0 = the
     * method has no such parameter. Read through ob_method_role. */
    signed char roles[OB_ROLE_COUNT];
    /* The sample kernel these params give the shader at a fixed count: xyz per entry in the
     * kernel's own frame (+Z = the normal for hemisphere kernels), w 0; at most max entries; the
     * count written. NULL for a method without a kernel (ob_method_kernel). */
    int (*kernel)(const float *params, float *xyzw, int max);
} ob_method_impl;

/* The index in m's parameter table of the parameter that plays `role`, or -1 where none does. */
int ob_method_role(const ob_method_impl *m, ob_param_role role);
/* Samples per pixel of a method with these (resolved) params; 0 for none. */
int ob_method_samples(const ob_method_impl *m, const float *params);
/* The inputs a method reads with these params (reads, less what a parameter turned off). */
uint32_t ob_method_active_reads(const ob_method_impl *m, const float *params);
/* The outputs a method produces with these params (writes, less what a parameter turned off). */
uint32_t ob_method_active_writes(const ob_method_impl *m, const float *params);

const ob_method_impl *ob_method_impl_at(int index);

/* The kit: a zero-filled state of m->state_size bytes with its ob_method_kit made (the pass from
 * m->shader, the noise tile), then m->init. NULL with the error set on failure. */
void *ob_method_make_state(const ob_method_impl *m);
/* m->destroy, then the kit's pass and noise, then the state itself. NULL is a no-op. */
void ob_method_destroy_state(const ob_method_impl *m, void *state);
/* Upload `size` bytes of constants (a prefix: methods with kernels send only the entries in use),
 * bind the program, the depth (OB_UNIT_DEPTH), normals (OB_UNIT_NORMAL) and noise tile
 * (OB_UNIT_NOISE), and the visibility output as image OB_IMAGE_UNIT_OUT in `format`. */
void ob_method_kit_use(ob_method_kit *kit, const void *constants, size_t size, const ob_ao_inputs *in,
                       const ob_ao_outputs *out, GLenum format);

/* Adaptive sample counts (SSDO thesis §4.1) for a method with a kernel of `samples` entries: how many
 * entries to build and the base count the edge pass's multiplier (1..3) scales. Under adaptive
 * sampling (in->sample_multiplier) the kernel holds 3 x base entries (at most `max`, a multiple of
 * 3) from Halton numbers, whose prefixes are evenly spread where random ones are not; otherwise
 * it is `samples` entries from `sampling`. */
typedef struct ob_sample_plan {
    int count;      /* kernel entries to build and upload */
    int base;       /* the count at multiplier 1 */
    int sampling;   /* OB_SAMPLING_MODE_* of the kernel */
    bool adaptive;
} ob_sample_plan;
ob_sample_plan ob_method_sample_plan(const ob_ao_inputs *in, int samples, int sampling, int max);
/* A program variant of a method's shader: the shader compiled with `defines` (a per-sample choice
 * made at compile time, as gtao's depth MIPs and ssdo's second layer: llvmpipe runs both sides of a
 * branch its lanes disagree on, and a variant keeps the code out of the default program), made into
 * *slot the first time it is asked for. The program, or 0 with the error set. */
GLuint ob_method_variant(GLuint *slot, const char *shader, const char *defines);

/* Bind the multiplier of adaptive sampling to OB_UNIT_SAMPLE_MULTIPLIER (the noise tile when off,
 * so the sampler is always valid). */
void ob_method_kit_bind_multiplier(const ob_method_kit *kit, const ob_ao_inputs *in);

/* Option lists shared by methods' enum parameters (registry.c), in the order of the
 * OB_SAMPLING_MODE_*, OB_DIRECTIONS_MODE_* and OB_NOISE_* values of shaders/ob_enums.h. */
extern const char *const ob_sampling_options[];  /* random, halton */
extern const char *const ob_direction_options[]; /* uniform, cosine */
extern const char *const ob_noise_options[];     /* texture4, ign */

/* The `layers` parameter of every method that can read the second depth layer (gtao, vbao, vbgi,
 * ssdo, ssdo_merged): 1 = the depth buffer alone, 2 = OB_READS_SECOND_LAYER too. What each makes of
 * the layer is its own (docs/methods.md, "A second depth layer"). */
#define OB_LAYERS_PARAM                                                                                       \
    {"layers", OB_PARAM_INT, 1.0f, 2.0f, 1.0f, "count",                                                     \
     "depth layers: 1 = the depth buffer alone (every occluder as the method assumes), 2 = also the second " \
     "layer (depth peeling) behind it",                                                                      \
     false}

/* ---- the slice methods (slices.c): gtao, vbao and vbgi march the same slices ----------------
 * (shaders/slice_march.glsl); what their C sides share. */
/* N taps per pixel -> slices x steps x 2 sides, written to params[p_slices] and params[p_steps]
 * (the bits of both set in *params_set). A sparse march misses small occluders between its steps,
 * so the step count moves the mean AO, while the slices, averaged, only move the noise.
 * fixed_steps > 0 (vbao, vbgi): every count marches that many steps, N / (2 x fixed_steps) slices
 * rounded, at least one (12 = 1 x 6, 24 = 2 x 6, 36 = 3 x 6, 64 -> 5 x 6 = 60 taps with 6): the
 * presets then agree in their mean (docs/methods.md, "Presets that keep their mean"); counts below
 * 2 x fixed_steps march N / 2 steps on one slice. fixed_steps = 0 (gtao): Belonogov 2018's quality
 * levels (§3.2.3) get fixed splits, 12 = 2 x 3, 24 = 2 x 6, 36 = 3 x 6, 64 = 4 x 8 (too few steps
 * bias the horizon toward open: 24 taps on cornell:front, 2 x 6 bias +0.014, 3 x 4 +0.019), and
 * other counts split N / 2 near slices = sqrt(N / 2) / 1.4. OB_ERR_OUT_OF_RANGE (naming `method`)
 * outside 2..2 x max x max. */
ob_error ob_slice_set_samples(const char *method, float *params, uint32_t *params_set, int samples, int p_slices,
                              int p_steps, int max_slices, int max_steps, int fixed_steps);
/* What a slice method's constants take from the frame: the jitter offsets (an R2 sequence over
 * the frame index, for temporal noise), the MIP level scale of the depth march, and the
 * coarsest MIP level there is (0 without the chain). */
typedef struct ob_slice_frame {
    float slice_offset, step_offset;
    float mip_scale;
    int max_mip;
} ob_slice_frame;
ob_slice_frame ob_slice_frame_make(const ob_ao_inputs *in);
/* Adaptive slices (SSDO thesis §4.1): *adaptive and the slices at multiplier 1, (slices + 1) / 3 as
 * ob_adaptive_base rounds taps, at least 1. Fill them into the constants before ob_slice_use. */
void ob_slice_adaptive(const ob_ao_inputs *in, int slices, int *adaptive, int *base);
/* A slice method's optional features, each compiled into its own program variant rather than
 * tested at run time: llvmpipe runs an if block whose (uniform) condition is false as it runs every
 * other, so the default-off second-layer block, one more fetch and its arithmetic per sample, cost
 * gtao 43 % of its AO pass at its default settings (fzk-haus:stair 640x480, 36 taps: 135 -> 77 ms
 * with the block compiled out). */
enum {
    OB_SLICE_MIPS = 1,   /* OB_MARCH_DEPTH_MIPS: far steps read the depth MIP chain */
    OB_SLICE_LAYERS = 2, /* OB_MARCH_LAYERS: the second depth layer bounds each sample's thickness */
    OB_SLICE_BENT = 4,   /* OB_GTAO_BENT: gtao also writes the bent normal */
    OB_SLICE_PACKED = 8, /* OB_MARCH_PACKED: samples read OB_UNIT_PACKED_SAMPLES (vbgi; no MIPs) */
    /* vbao and vbgi: OB_SECTOR_COVERAGE_* in the two bits from here (OB_VB_COVERAGE; 0, `touch`, is
     * the kit's own program). Each sample worked out all three rules and selected one: 6 % of vbao's
     * instructions at 16 taps. */
    OB_SLICE_COVERAGE_SHIFT = 4,
    /* vbao and vbgi: OB_CONNECT_* in the two bits from here (OB_VB_CONNECT; 0, `off`, is the kit's
     * own program). A uniform mode kept every mode's code in one program: on an H200 `chord` ran
     * slower so than a program doing more than chord without the curve's code (docs/methods.md,
     * "What the curve costs on a GPU"). */
    OB_SLICE_CONNECT_SHIFT = 6,
    /* OB_MARCH_FACETS: the facet wedge (gtao, vbao, vbgi `facets`: the G-buffer's facet normals). */
    OB_SLICE_FACETS = 256,
    OB_SLICE_VARIANTS = 512
};
/* The run of a slice method after its constants are filled: the kit's uploads and bindings, the
 * program for `features` (OB_SLICE_*: the kit's own for none, else a variant of `shader` made on
 * first use into variants[features]), the depth chain on OB_UNIT_SLICE_DEPTH_MIPS (the depth
 * itself without one), the adaptive multiplier on OB_UNIT_SLICE_MULTIPLIER (the noise tile when
 * off) and the second layer on OB_UNIT_SECOND_DEPTH (the depth when there is none), so every
 * sampler is valid. Dispatch after. Fails with the error set. */
ob_error ob_slice_use(ob_method_kit *kit, GLuint variants[OB_SLICE_VARIANTS], const char *shader, unsigned features,
                      const void *constants, size_t size, const ob_ao_inputs *in, const ob_ao_outputs *out);
/* Frees the variants ob_slice_use made. */
void ob_slice_release(GLuint variants[OB_SLICE_VARIANTS]);

/* Each AO texel's depth, normal and direct radiance in one RGBA32UI texel (methods/packed.c,
 * shaders/sample_pack.glsl, the layout in shaders/packed_samples.glsl), for methods whose samples
 * read all three (ssdo, ssdo_merged, vbgi): one fetch a sample. */
typedef struct ob_packed_samples {
    GLuint program; /* made on first use */
    GLuint texture; /* at the AO grid's size */
    int width, height;
    int software;   /* 0 = not asked yet, 1 = a software rasteriser, -1 = not */
} ob_packed_samples;
/* The methods' `packed` parameter: off, on, or auto (on for a software rasteriser, off on a GPU). */
enum { OB_PACKED_OFF, OB_PACKED_ON, OB_PACKED_AUTO };
extern const char *const ob_packed_options[];
#define OB_PACKED_PARAM(extra)                                                                                \
    {"packed", OB_PARAM_ENUM, 0.0f, 2.0f, (float)OB_PACKED_AUTO, "",                                          \
     "read each sample's depth, normal and direct light from one packed texel: on, off, or auto (on for a "   \
     "software rasteriser)" extra,                                                                             \
     false, ob_packed_options}
/* Whether the parameter's value `mode` packs on this context (auto asks GL_RENDERER once). */
bool ob_packed_samples_wanted(ob_packed_samples *p, float mode);
/* Packs this frame's in->linear_depth, in->view_normal and in->radiance (AO texel q's pixel
 * q ao_k + ao_o) and binds the result to texture unit `unit` after a barrier. Uses OB_IMAGE_UNIT_PACKED
 * and OB_UNIT_DEPTH, OB_UNIT_NORMAL, OB_UNIT_RADIANCE: run it before the method binds its own.
 * Fails with the error set. */
ob_error ob_packed_samples_run(ob_packed_samples *p, const ob_ao_inputs *in, int unit);
void ob_packed_samples_release(ob_packed_samples *p);

/* Deinterleaved sampling (methods/deinterleave.c; Bavoil 2014) for the random-kernel methods'
 * `deinterleave` parameter (ssao, crytek, hbao, alchemy, ssdo, ssdo_merged): the depth split into the 16 classes of
 * the 4x4 noise tile (shaders/deinterleave.glsl), and the method's OB_DEINTERLEAVED program, whose
 * taps read the nearest pixel of their own class from one compact layer
 * (shaders/taps.glsl). A selectable baseline beside the plain program, for a GPU's
 * texture cache; off by default (docs/methods.md, "Deinterleaved sampling"). */
typedef struct ob_deinterleaved {
    GLuint split;   /* deinterleave.glsl, made on first use */
    GLuint program; /* the method's OB_DEINTERLEAVED variant, made on first use (0: the method's own) */
    GLuint layers;  /* R32F 2D array: 16 layers of ceil(w / 4) x ceil(h / 4) */
    int width, height;
} ob_deinterleaved;
extern const char *const ob_deinterleave_options[]; /* off, on */
#define OB_DEINTERLEAVE_PARAM                                                                                 \
    {"deinterleave", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "",                                                     \
     "deinterleaved sampling (Bavoil 2014): taps read the nearest pixel of their own 4x4 noise class from "   \
     "the depth split into 16 compact layers, for a GPU's texture cache at large radii; off = the plain "     \
     "program",                                                                                                \
     false, ob_deinterleave_options}
#define OB_DEINTERLEAVED_DEFINE "#define OB_DEINTERLEAVED 1\n"
/* Splits in->linear_depth into d->layers and binds them to OB_UNIT_DEPTH_LAYERS after a barrier;
 * makes `shader`'s OB_DEINTERLEAVED program into d->program on first use (NULL: the method makes
 * its own, with OB_DEINTERLEAVED_DEFINE among its variants' defines: ssdo). Uses OB_IMAGE_UNIT_OUT and
 * OB_UNIT_DEPTH: run it before the method's kit_use. Fails with the error set. */
ob_error ob_deinterleaved_prepare(ob_deinterleaved *d, const char *shader, const ob_ao_inputs *in);
/* A method's dispatch after its own bindings: `program` (0 = the one bound) over the AO grid in
 * groups of gx x gy pixels, or, `deinterleaved`, over the 16 classes' texels in groups of gx x gy
 * texels of one class each (then `program` is a deinterleaved one). */
void ob_method_dispatch(GLuint program, bool deinterleaved, const ob_ao_inputs *in, int gx, int gy);
void ob_deinterleaved_release(ob_deinterleaved *d);

/* Depth MIP taps (shaders/taps.glsl, OB_TAPS_DEPTH_MIPS; SAO §2.2) for the `depth_mips` parameter
 * of ssao, crytek, hbao, alchemy (through ob_taps) and ssdo, ssdo_merged (their own variants): a
 * tap d px from the pixel reads level floor(log2 d - 3.3) of the frame's depth MIP chain
 * (passes/depth_mips.c), the same chain and levels as the slice methods' march. A selectable baseline beside the plain program, off by default
 * (docs/methods.md, "Depth MIP prefilter"). */
#define OB_TAPS_DEPTH_MIPS_PARAM                                                                              \
    {"depth_mips", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",                                                 \
     "taps 20 px or more from the pixel read the prefiltered depth MIP chain (SAO's trick) instead of full "  \
     "resolution; not with deinterleave",                                                                     \
     false}
/* A random-kernel method's program for where its taps read depth: plain, deinterleaved or from the
 * MIP chain (each made on first use). */
typedef struct ob_taps {
    ob_deinterleaved split; /* `deinterleave` */
    GLuint mips;            /* the OB_TAPS_DEPTH_MIPS variant */
    GLuint program;         /* this frame's choice: 0 = the kit's plain program */
    bool deinterleaved;     /* this frame dispatches by class */
} ob_taps;
/* Chooses and prepares this frame's program for `method`'s shader: the deinterleaved split (see
 * ob_deinterleaved_prepare: run before the kit's bindings) or the MIP chain bound at
 * OB_UNIT_TAPS_DEPTH_MIPS (in->depth_mips; the depth itself, one level, where the frame has no
 * chain: every tap reads level 0). Both on is OB_ERR_INVALID_ARGUMENT, naming the method: two
 * ways to read one tap. */
ob_error ob_taps_prepare(ob_taps *t, const char *method, const char *shader, const ob_ao_inputs *in, bool deinterleave,
                         bool depth_mips);
/* ob_method_dispatch with the chosen program. */
void ob_taps_dispatch(const ob_taps *t, const ob_ao_inputs *in, int gx, int gy);
/* For a method that makes its own variants (ssdo): ob_taps_prepare's error for both programs on,
 * and its binding of the MIP chain (or the depth, one level) at OB_UNIT_TAPS_DEPTH_MIPS. */
ob_error ob_taps_exclusive(const char *method, bool deinterleave, bool depth_mips);
void ob_taps_bind_mips(const ob_ao_inputs *in);
/* A random-kernel method's active_reads from its `depth_mips` value: everything but the MIP chain
 * when off (ob_method_active_reads masks the method's own reads with it). */
uint32_t ob_taps_reads(float depth_mips);
void ob_taps_release(ob_taps *t);

#endif
