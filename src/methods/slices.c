/* What the slice methods (gtao, vbao, vbgi) share on the CPU: the split of a sample count into
 * slices x steps, the per-frame jitter offsets and the program variants of their optional features.
 * Their shaders share shaders/slice_march.glsl. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "methods/method.h"

/* The R2 sequence's steps (Roberts 2018, the plastic number's powers): the best-spread 2D
 * low-discrepancy offsets for successive frames. */
#define R2_A1 0.7548776662466927f
#define R2_A2 0.5698402909980532f

ob_error ob_slice_set_samples(const char *method, float *params, uint32_t *params_set, int samples, int p_slices,
                              int p_steps, int max_slices, int max_steps, int fixed_steps)
{
    if (!params) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: params is NULL", method);
    const int most = 2 * max_slices * max_steps;
    if (samples < 2 || samples > most)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "%s: samples must be 2..%d (2 x slices x steps), got %d", method, most,
                            samples);
    int slices = 0, steps = 0;
    if (fixed_steps > 0) {
        /* The steps set the mean, the slices only the noise (method.h): every count marches the
         * same steps, 12 = 1 x 6, 24 = 2 x 6, 36 = 3 x 6, 64 -> 5 x 6 (60). */
        steps = fixed_steps < max_steps ? fixed_steps : max_steps;
        if (samples < 2 * steps) steps = samples / 2;
        slices = (int)lroundf((float)samples / (float)(2 * steps));
        slices = slices < 1 ? 1 : slices > max_slices ? max_slices : slices;
    }
    static const struct { int samples, slices, steps; } presets[] = {{12, 2, 3}, {24, 2, 6}, {36, 3, 6}, {64, 4, 8}};
    for (size_t i = 0; fixed_steps <= 0 && i < sizeof presets / sizeof presets[0]; ++i)
        if (presets[i].samples == samples) {
            slices = presets[i].slices;
            steps = presets[i].steps;
        }
    if (slices == 0) {
        int half = samples / 2;
        slices = (int)lroundf(sqrtf((float)half) / 1.4f);
        slices = slices < 1 ? 1 : slices > max_slices ? max_slices : slices;
        steps = (int)lroundf((float)half / (float)slices);
        steps = steps < 1 ? 1 : steps > max_steps ? max_steps : steps;
    }
    params[p_slices] = (float)slices;
    params[p_steps] = (float)steps;
    if (params_set) *params_set |= (1u << p_slices) | (1u << p_steps);
    return OB_OK;
}

ob_slice_frame ob_slice_frame_make(const ob_ao_inputs *in)
{
    ob_slice_frame f = {0};
    uint32_t frame_index = in->frame->frame_index;
    f.slice_offset = fmodf((float)(frame_index % 4096u) * R2_A1, 1.0f);
    f.step_offset = fmodf((float)(frame_index % 4096u) * R2_A2, 1.0f);
    f.mip_scale = exp2f(-(float)OB_DEPTH_MIPS_TAP_OFFSET) /* shaders/ob_shared.h */;
    f.max_mip = in->depth_mips ? in->depth_mip_levels - 1 : 0;
    return f;
}

void ob_slice_adaptive(const ob_ao_inputs *in, int slices, int *adaptive, int *base)
{
    *adaptive = in->sample_multiplier != 0 ? 1 : 0;
    *base = (slices + 1) / 3 > 1 ? (slices + 1) / 3 : 1;
}

/* Each optional feature is compiled in, not branched on: the MIP chain's level is a per-sample
 * choice, and the second layer and the bent normal are uniform tests that llvmpipe runs masked
 * when false, so as runtime branches they cost the default program too (method.h OB_SLICE_*). */
ob_error ob_slice_use(ob_method_kit *kit, GLuint variants[OB_SLICE_VARIANTS], const char *shader, unsigned features,
                      const void *constants, size_t size, const ob_ao_inputs *in, const ob_ao_outputs *out)
{
    features &= OB_SLICE_VARIANTS - 1;
    if (features) {
        char defines[256] = "";
        if (features & OB_SLICE_MIPS) strcat(defines, "#define OB_MARCH_DEPTH_MIPS 1\n");
        if (features & OB_SLICE_LAYERS) strcat(defines, "#define OB_MARCH_LAYERS 1\n");
        if (features & OB_SLICE_BENT) strcat(defines, "#define OB_GTAO_BENT 1\n");
        if (features & OB_SLICE_PACKED) strcat(defines, "#define OB_MARCH_PACKED 1\n");
        if (features & OB_SLICE_FACETS) strcat(defines, "#define OB_MARCH_FACETS 1\n");
        const unsigned coverage = (features >> OB_SLICE_COVERAGE_SHIFT) & 3u,
                       connect = (features >> OB_SLICE_CONNECT_SHIFT) & 3u;
        char line[48];
        if (coverage) {
            snprintf(line, sizeof line, "#define OB_VB_COVERAGE %u\n", coverage);
            strcat(defines, line);
        }
        if (connect) {
            snprintf(line, sizeof line, "#define OB_VB_CONNECT %u\n", connect);
            strcat(defines, line);
        }
        if (!ob_method_variant(&variants[features], shader, defines)) return ob_peek_error(NULL);
    }
    ob_method_kit_use(kit, constants, size, in, out, GL_R32F);
    if (features) glUseProgram(variants[features]);
    glBindTextureUnit(OB_UNIT_SLICE_DEPTH_MIPS, in->depth_mips ? in->depth_mips : in->linear_depth);
    glBindTextureUnit(OB_UNIT_SLICE_MULTIPLIER, in->sample_multiplier ? in->sample_multiplier : kit->noise);
    /* The second depth layer (full resolution); the depth itself keeps the sampler valid when the
     * frame has none, and then no variant reads it. */
    glBindTextureUnit(OB_UNIT_SECOND_DEPTH, in->second_depth ? in->second_depth : in->linear_depth);
    /* The facet normals likewise (only the OB_SLICE_FACETS variants read them). */
    glBindTextureUnit(OB_UNIT_FACET_NORMAL, in->facet_normal ? in->facet_normal : in->linear_depth);
    return OB_OK;
}

void ob_slice_release(GLuint variants[OB_SLICE_VARIANTS])
{
    for (int i = 0; i < OB_SLICE_VARIANTS; ++i) {
        if (variants[i]) glDeleteProgram(variants[i]);
        variants[i] = 0;
    }
}
