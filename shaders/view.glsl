#version 450 core
/* Debug views for ob_present: the view's texture of the last frame into RGBA8 display bytes, the
 * mappings of the CLI's --view images (app/render.c view_image), except that depth divides by the
 * far plane and samples by the most a pixel could take, where the CLI takes the image's maximum
 * (a reduction this one pass does not need). */
#include "view_params.h"
#include "common.glsl"

layout(local_size_x = OB_VIEW_GROUP_X, local_size_y = OB_VIEW_GROUP_Y) in;

layout(binding = OB_UNIT_VIEW_SOURCE) uniform sampler2D source;     /* the view's texture; samples: linear depth */
layout(binding = OB_UNIT_VIEW_MULTIPLIER) uniform sampler2D multiplier; /* samples under adaptive sampling: per block */
layout(binding = OB_IMAGE_UNIT_OUT, rgba8) uniform writeonly image2D display;

/* The luminance view's ramp (SSDO thesis Fig. 6.16c): t in [0, 1] through dark blue, blue, cyan,
 * green, yellow and red, evenly; tests/test_present.c has the same ramp in C. */
vec3 luminance_ramp(float t)
{
    const vec3 stops[6] = vec3[6](vec3(0.0, 0.0, 0.3), vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 1.0), vec3(0.0, 1.0, 0.0),
                                  vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0));
    float x = clamp(t, 0.0, 1.0) * 5.0;
    int i = min(int(x), 4);
    return mix(stops[i], stops[i + 1], x - float(i));
}

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, vw.size))) return;
    ivec2 src = pix + vw.offset; /* past the guard band, if the source has one */
    vec4 s = texelFetch(source, src, 0);
    bool directional = vw.directional != 0;
    vec3 c = vec3(0.0);
    switch (vw.view_mode) {
    case OB_VIEW_MODE_AO: c = directional ? s.rgb : vec3(s.r); break;
    case OB_VIEW_MODE_NORMALS: c = s.rgb * 0.5 + 0.5; break;
    case OB_VIEW_MODE_DEPTH: c = vec3(s.r > 0.0 ? 1.0 - s.r / vw.far_z : 0.0); break;
    /* directional here: the frame has a second layer (else black, as the bounce without one). */
    /* directional here: the frame has an extra view (else black). */
    case OB_VIEW_MODE_EXTRA: c = directional ? ob_linear_to_srgb(s.rgb) : vec3(0.0); break;
    case OB_VIEW_MODE_SECOND_DEPTH: c = vec3(directional && s.r > 0.0 ? 1.0 - s.r / vw.far_z : 0.0); break;
    case OB_VIEW_MODE_SHADOW: c = vec3(s.a); break; /* the key light's visibility */
    case OB_VIEW_MODE_RADIANCE: c = ob_linear_to_srgb(s.rgb); break;
    case OB_VIEW_MODE_BOUNCE: c = directional ? ob_linear_to_srgb(s.rgb) : vec3(0.0); break;
    /* directional here: the method wrote a bent normal (filtering averaged it: renormalise). */
    case OB_VIEW_MODE_BENT_NORMALS:
        c = directional && dot(s.xyz, s.xyz) > 1e-8 ? normalize(s.xyz) * 0.5 + 0.5 : vec3(0.0);
        break;
    case OB_VIEW_MODE_LUMINANCE: {
        const float lo = float(OB_VIEW_LUMINANCE_LOG2_LO), hi = float(OB_VIEW_LUMINANCE_LOG2_HI);
        /* The legend: the bottom rows (row 0 is the bottom, GL's first) show the ramp across the
         * width, with a tick per stop, the one at luminance 1 twice as tall. */
        int bar = max(6, vw.size.y / 20);
        if (pix.y < bar) {
            float stops = hi - lo;
            float at = (float(pix.x) + 0.5) / float(vw.size.x) * stops; /* stops above lo */
            int nearest = int(floor(at + 0.5));
            bool on_tick = abs(at - float(nearest)) * float(vw.size.x) / stops < 0.5;
            int tall = nearest == int(-lo) ? bar : bar / 2;
            c = on_tick && pix.y < tall ? vec3(0.0) : luminance_ramp(at / stops);
            break;
        }
        float y = dot(s.rgb, vec3(0.2126, 0.7152, 0.0722));
        float l = y > 0.0 ? log2(y) : -1e30;
        c = y <= 0.0 ? vec3(0.0) : l > hi ? vec3(1.0) : luminance_ramp((l - lo) / (hi - lo));
        break;
    }
    case OB_VIEW_MODE_SAMPLES: {
        /* As the renderer's read_sample_counts: the block of AO pixel pix / k. */
        float count = float(vw.sample_count);
        if (vw.use_multiplier != 0) count *= texelFetch(multiplier, (src / vw.ao_k) / OB_EDGE_BLOCK, 0).r;
        c = vec3(s.r > 0.0 ? count * vw.inv_max_samples : 0.0); /* the sky takes no samples */
        break;
    }
    case OB_VIEW_MODE_HISTORY_AGE: {
        /* The AO grid's history (src / ao_k, as the samples view finds a block): the scalar
         * chain's R16F age texture, or .a of the RGBA16F history (directional). */
        vec4 h = texelFetch(source, src / vw.ao_k, 0);
        c = vec3((directional ? h.a : h.r) * vw.inv_history_frames);
        break;
    }
    default: break;
    }
    imageStore(display, pix, vec4(clamp(c, 0.0, 1.0), 1.0));
}
