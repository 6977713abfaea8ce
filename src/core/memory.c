/* What a run will allocate, estimated before anything is (README "Untrusted models", --max-memory):
 * the default limit and the renderer's targets for a size and its settings. A software rasteriser
 * (llvmpipe) keeps every texture in host memory, so these bytes are the process's as much as the
 * GPU's. Each figure stands for an allocation elsewhere, named beside it: a new target there
 * belongs here too, or a run that fits the estimate can still take more than --max-memory. */

#include "base/error.h"
#include "core/renderer.h"
#include "methods/method.h"
#include <unistd.h>

#include "bloom_params.h"
#include "lighting_params.h"
#include "ob_shared.h"

uint64_t ob_default_max_memory(void)
{
    const uint64_t four_gib = 4ull << 30;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page <= 0) return four_gib;
    uint64_t half = (uint64_t)pages * (uint64_t)page / 2u;
    return half < four_gib ? half : four_gib;
}


/* What a renderer has made once it has rendered with every one of the settings: its targets are
 * made on first use and kept (renderer.c), so features add up across the settings. */
typedef struct scale_use {
    bool used;
    bool rgb_scratch;  /* ob_renderer_rgb_targets: scratch_rgb */
    bool directional;  /* raw/filtered M and bounce */
    bool bent;         /* raw/filtered bent normal */
    bool temporal;     /* ob_renderer_temporal_targets */
    bool mips;         /* the depth MIP chain (one texture, remade at the scale in use) */
    bool packed;       /* methods/packed.c: RGBA32UI per AO pixel */
    bool deinterleave; /* methods/deinterleave.c: 16 R32F layers of a quarter of the AO grid each */
} scale_use;

static uint64_t pixels(int w, int h) { return (uint64_t)w * (uint64_t)h; }

/* The shadow maps of one frame (passes/shadow.c allocate): a depth layer per directional or spot
 * light, six per point light, VSM's moments per 2D map and one scratch layer. Without lights of
 * its own the frame takes the scene's, unknown here: the key light, which every scene has. */
static uint64_t shadow_bytes(const ob_settings *s)
{
    const ob_shadow_settings *sh = &s->shadow;
    if (sh->method == OB_SHADOW_NONE) return 0;
    const uint64_t size = sh->size > 0 ? (uint64_t)sh->size : 2048u;
    const uint64_t layer = size * size;
    int maps_2d = 0, cubes = 0;
    if (s->light_count <= 0) {
        maps_2d = 1;
    } else {
        for (int i = 0; i < s->light_count && i < OB_MAX_SHADOW_MAPS; ++i) {
            if (s->lights[i].type == OB_LIGHT_POINT) ++cubes;
            else ++maps_2d;
        }
    }
    uint64_t bytes = layer * 4u * (uint64_t)(maps_2d + 6 * cubes); /* GL_DEPTH_COMPONENT32F */
    if (sh->method == OB_SHADOW_VSM && maps_2d > 0) {
        const uint64_t moment = sh->vsm_bits == 16 ? 4u : 8u; /* RG16F or RG32F */
        bytes += layer * moment * (uint64_t)(maps_2d + 1);
    }
    return bytes;
}

static bool role_on(const ob_method_impl *m, const float *params, ob_param_role role, float off)
{
    const int p = ob_method_role(m, role);
    return p >= 0 && params[p] != off;
}

uint64_t ob_estimate_renderer_memory(int width, int height, const ob_settings *settings, int count)
{
    if (width < 1 || height < 1 || !settings || count < 1) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_estimate_renderer_memory: size %dx%d, %d settings%s", width, height,
                     count, settings ? "" : " (NULL)");
        return 0;
    }
    scale_use scales[3] = {{0}};
    int guard = 0;
    bool peel = false, second_back = false, extra = false, full_rgb = false, full_bent = false;
    uint64_t shadows = 0;
    for (int n = 0; n < count; ++n) {
        const ob_settings *s = &settings[n];
        if (s->method < 0 || s->method >= ob_method_count()) {
            ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_estimate_renderer_memory: settings %d: method %d unknown", n,
                         s->method);
            return 0;
        }
        const int k = s->ao_divisor == 2 || s->ao_divisor == 4 ? s->ao_divisor : 1;
        const int index = k == 4 ? 2 : k == 2 ? 1 : 0;
        /* A reshape makes the new targets before it frees the old; the largest band is the peak. */
        const int g = ob_guard_pixels(s->guard < 0 ? 0 : s->guard, k);
        if (g > guard) guard = g;
        const ob_method_impl *impl = ob_method_impl_at(s->method);
        const uint32_t reads = ob_method_active_reads(impl, s->params);
        const uint32_t writes = ob_method_active_writes(impl, s->params);
        const bool rgb = (impl->writes & OB_WRITES_VISIBILITY_RGB) != 0;
        const bool directional = rgb || (impl->writes & OB_WRITES_BOUNCE) != 0; /* frame.c: run_ao */
        const bool bent = (writes & OB_WRITES_BENT_NORMAL) != 0;
        scale_use *u = &scales[index];
        u->used = true;
        u->rgb_scratch = u->rgb_scratch || directional || bent;
        u->directional = u->directional || directional;
        u->bent = u->bent || bent;
        u->temporal = u->temporal || s->temporal;
        u->mips = u->mips || (reads & OB_READS_DEPTH_MIPS) != 0;
        u->packed = u->packed || role_on(impl, s->params, OB_ROLE_PACKED, (float)OB_PACKED_OFF);
        u->deinterleave = u->deinterleave || role_on(impl, s->params, OB_ROLE_DEINTERLEAVE, 0.0f);
        full_rgb = full_rgb || directional;
        full_bent = full_bent || bent;
        peel = peel || (reads & OB_READS_SECOND_LAYER) != 0;
        second_back = second_back || (reads & OB_READS_SECOND_BACK) != 0;
        extra = extra || (reads & OB_READS_EXTRA_VIEW) != 0;
        /* passes/shadow.c remakes the maps for new settings after freeing the old: the largest. */
        uint64_t sh = shadow_bytes(s);
        if (sh > shadows) shadows = sh;
    }
    const int inner_w = width + 2 * guard, inner_h = height + 2 * guard;
    const uint64_t visible = pixels(width, height), inner = pixels(inner_w, inner_h);
    /* passes/gbuffer.c: depth32F, linear depth R32F, normal and albedo RGBA16F, facet RG16F. */
    const uint64_t gbuffer = 28;
    uint64_t bytes = inner * (gbuffer + 4 + 8); /* renderer.c make_full_targets: ao R32F, direct RGBA16F */
    /* final RGBA8, radiance RGBA16F (renderer.c), the debug view's RGBA8 (passes/view.c). */
    bytes += visible * (4 + 8 + 4);
    /* passes/bloom.c: two RGBA16F targets at 1/OB_BLOOM_FACTOR. */
    bytes += pixels((width + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR, (height + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR) * 16u;
    /* The renderer is made at the visible size; the band's reshape makes the enlarged G-buffer
     * and full targets while those still exist. */
    if (guard > 0) bytes += visible * (gbuffer + 4 + 8);
    if (full_rgb) bytes += inner * 16u;  /* ao_rgb, bounce: RGBA16F (ob_renderer_rgb_targets) */
    if (full_bent) bytes += inner * 8u;  /* bent */
    if (peel) bytes += inner * 12u;      /* passes/peel.c: depth32F, linear depth R32F, planes RG16F */
    if (second_back) bytes += inner * 4u; /* passes/second_back.c: R32F */
    if (extra) bytes += inner * (gbuffer + 8); /* frame.c: the extra view's G-buffer and direct light */
    uint64_t mips = 0, packed = 0, split = 0;
    for (int i = 0; i < 3; ++i) {
        const scale_use *u = &scales[i];
        if (!u->used) continue;
        ob_ao_grid grid = ob_ao_grid_make(inner_w, inner_h, 1 << i);
        const uint64_t ao = pixels(grid.width, grid.height);
        uint64_t per = 12; /* ob_renderer_targets: raw, filtered, scratch R32F */
        if (i > 0) per += 4 + 8; /* its own depth R32F and normal RGBA16F */
        if (u->rgb_scratch) per += 8;
        if (u->directional) per += 4 * 8;
        if (u->bent) per += 2 * 8;
        /* ob_renderer_temporal_targets: accum R32F + 2 RGBA16F, two histories of R32F, R16F and 2
         * RGBA16F, two geometries of R32F + R32UI, motion RG16F. */
        if (u->temporal) per += 4 + 16 + 2 * (4 + 2 + 16) + 2 * 8 + 4;
        bytes += ao * per;
        bytes += pixels((grid.width + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK, (grid.height + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK) * 4u;
        /* One texture each, remade at the scale in use: the largest counts. A MIP chain adds a third. */
        if (u->mips && ao * 4u * 4u / 3u > mips) mips = ao * 4u * 4u / 3u;
        if (u->packed && ao * 16u > packed) packed = ao * 16u;
        if (u->deinterleave && ao * 4u > split) split = ao * 4u;
    }
    return bytes + mips + packed + split + shadows;
}
