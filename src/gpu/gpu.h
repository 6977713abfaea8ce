/* Internal GPU layer: the context, programs built from the embedded shaders, timers. */
#ifndef OB_GPU_H
#define OB_GPU_H

#include <epoxy/gl.h>

#include "obscura/scene.h"

struct ob_context {
    void *egl_display;  /* EGLDisplay */
    void *egl_context;  /* EGLContext */
    bool adopted;       /* the caller's context (use_current): never made current or destroyed here */
    bool software;
    int max_texture_size;
    char renderer[256];
    char version[256];
    char device[256];
};

/* Whether a GL_RENDERER string names one of Mesa's software rasterisers (llvmpipe, softpipe,
 * SWR): for passes whose fastest variant differs between a CPU and a GPU (crease's tiles). */
bool ob_renderer_is_software(const char *renderer);

/* ---- programs (program.c) ------------------------------------------------------------------ */
/* Build a compute program from an embedded shader (e.g. "ssao.glsl"), or from the file of that
 * name under ob_set_shader_directory's directory when one is set. `defines` is inserted after
 * #version (may be NULL). Errors: OB_ERR_SHADER with "shaders/FILE:LINE: driver message". */
GLuint ob_make_compute_program(const char *name, const char *defines);
/* Build a raster program from a vertex and a fragment shader. */
GLuint ob_make_raster_program(const char *vert_name, const char *frag_name, const char *defines);
/* The resolved (includes expanded) source of an embedded shader, or NULL. */
const char *ob_shader_source(const char *name);
/* Map a driver info log's "SOURCE:LINE(COL)" / "SOURCE(LINE)" locations to "shaders/FILE:LINE";
 * writes one line into out. Exposed for the unit test. */
void ob_format_shader_log(const char *log, const char *fallback_name, char *out, size_t out_len);

/* Dispatch enough groups of size (gx, gy) to cover w x h (pass.c). */
void ob_dispatch_2d(int w, int h, int gx, int gy);

/* ---- a compute pass: program + its std140 constant block (pass.c) ------------------------
 * Every screen-space pass and method holds one; the constants struct comes from the pass's
 * shaders/NAME_params.h. */
typedef struct ob_compute_pass {
    GLuint program;
    GLuint ubo;
    size_t constants_size;
} ob_compute_pass;

ob_error ob_compute_pass_init(ob_compute_pass *p, const char *shader, const char *defines, size_t constants_size);
/* Upload the first `size` bytes of the constants, bind the program and the block at OB_BINDING_PASS. */
void ob_compute_pass_use(ob_compute_pass *p, const void *constants, size_t size);
void ob_compute_pass_destroy(ob_compute_pass *p);

/* ---- textures (pass.c) ------------------------------------------------------------------- */
GLuint ob_make_texture_2d(GLenum internal_format, int w, int h);
/* The 4x4 RG32F rotation texture of shaders/noise.glsl (Puri 2024 §3.3), the same fixed seed for
 * every method, so they all show the same noise tile and the same command gives the same bytes. */
GLuint ob_make_rotation_noise_texture(void);

/* ---- GL state (state.c) ---------------------------------------------------------------------
 * What a pass may change, saved before a call that runs inside a host's frame and put back after
 * it: the current program, the active unit, the GL_TEXTURE_2D and GL_TEXTURE_2D_ARRAY bindings
 * and sampler object of texture units 0..texture_units-1, image units 0..image_units-1, the
 * uniform buffer binding points OB_BINDING_PASS and OB_BINDING_FRAME (indexed, with their ranges,
 * and the generic one), and the unpack buffer, unpack pixel store and query buffer, which
 * ob_gl_state_save also sets to GL's defaults. */
enum { OB_GL_STATE_TEXTURES = 32, OB_GL_STATE_IMAGES = 16 };
typedef struct ob_gl_image_binding {
    GLint name, level, layered, layer, access, format;
} ob_gl_image_binding;
typedef struct ob_gl_state {
    int texture_units, image_units;
    GLint program, active_texture;
    GLint textures[OB_GL_STATE_TEXTURES], arrays[OB_GL_STATE_TEXTURES], samplers[OB_GL_STATE_TEXTURES];
    ob_gl_image_binding images[OB_GL_STATE_IMAGES];
    GLint ubo_generic, ubo[2];
    GLint64 ubo_start[2], ubo_size[2];
    /* Uploads (glTextureSubImage2D) read through the unpack buffer and pixel-store state, and query
     * results (glGetQueryObject*) go into a bound query buffer: both are set to GL's defaults
     * for the call and put back after. */
    GLint unpack_buffer, query_buffer;
    GLint unpack[6]; /* alignment, row length, image height, skip pixels, skip rows, skip images */
    GLboolean unpack_swap, unpack_lsb;
} ob_gl_state;
void ob_gl_state_save(ob_gl_state *s, int texture_units, int image_units);
void ob_gl_state_restore(const ob_gl_state *s);
/* glGetError, except while the calling thread is inside a host-path call (ob_gl_set_quiet(true)):
 * then GL_NO_ERROR, so that an error the host left pending stays for the host. The code that
 * checks for allocation failures calls this, not glGetError. */
GLenum ob_gl_error(void);
void ob_gl_set_quiet(bool on);
/* Reads and drops the GL errors pending when a library call starts that checks its own GL calls
 * with glGetError: they are the caller's, raised before the call, and would read as the call's
 * (a stale error of an engine's failed ob_make_renderer so, "making the HDR targets"). Bounded: a
 * lost context repeats its error. Not inside a host-path call (ob_gl_set_quiet): none is read there. */
void ob_gl_drop_pending(void);

/* ---- timers (timer.c) ----------------------------------------------------------------------- */
#define OB_MAX_TIMED_PASSES 20
/* Frames of queries in flight: results are read 1..OB_TIMER_RING frames late (timer.c says why). */
#define OB_TIMER_RING 4

typedef struct ob_timer_frame {
    GLuint queries[2 * OB_MAX_TIMED_PASSES]; /* a GL_TIMESTAMP before and after each pass */
    const char *names[OB_MAX_TIMED_PASSES];
    double cpu_ms[OB_MAX_TIMED_PASSES];      /* CPU time spent issuing each pass (CLOCK_MONOTONIC) */
    double cpu_start;                        /* when the open pass began issuing, ms */
    int count;          /* passes begun in this frame */
    long long frame;    /* the frame recorded here (ob_timers_frame_begin's count), -1 if none */
    bool pending;       /* recorded, results not read yet */
} ob_timer_frame;

typedef struct ob_timer_set {
    ob_timer_frame ring[OB_TIMER_RING];
    ob_timer_frame *current; /* the slot being recorded, NULL between frames */
    int open;                /* index of the running query in *current, -1 if none */
    long long frames;        /* frames begun */
    /* The newest frame whose queries have all landed: */
    const char *names[OB_MAX_TIMED_PASSES];
    double ms[OB_MAX_TIMED_PASSES];
    double cpu_ms[OB_MAX_TIMED_PASSES]; /* of the same frame, reported with its GPU times */
    int count;
    long long frame;         /* its number (0 = the first frame begun), -1 before any */
    bool finish_stamps;      /* a software rasteriser: glFinish after each stamp (timer.c says why) */
} ob_timer_set;

void ob_timers_init(ob_timer_set *t);
void ob_timers_destroy(ob_timer_set *t);
/* Start recording a frame into the next slot of the ring (waiting for that slot's old results
 * only if the GPU is a whole ring behind). */
void ob_timers_frame_begin(ob_timer_set *t);
void ob_timer_begin(ob_timer_set *t, const char *name); /* name must outlive the ring */
void ob_timer_end(ob_timer_set *t);
/* Close the frame and read every slot whose queries have landed, without waiting: names/ms/count
 * then describe frame `frame`, which may be an earlier one than this. */
void ob_timers_frame_end(ob_timer_set *t);
/* Wait for every recorded frame: names/ms/count then describe the last one (a stall: for one-shot
 * measurements and tests, not for an interactive loop). */
void ob_timers_wait(ob_timer_set *t);

#endif
