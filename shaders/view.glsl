#version 450 core
/* Debug views for ob_present: the view's texture of the last frame into RGBA8 display bytes, the
 * mappings of the CLI's --view images (app/render.c view_image), except that depth divides by the
 * far plane and samples by the most a pixel could take, where the CLI takes the image's maximum
 * (a reduction this one pass does not need). */
#include "view_params.h"
#include "common.glsl"

layout(local_size_x = OB_VIEW_GROUP_X, local_size_y = OB_VIEW_GROUP_Y) in;

layout(binding = 0) uniform sampler2D source;     /* the view's texture; samples: linear depth */
layout(binding = 1) uniform sampler2D multiplier; /* samples under adaptive sampling: per block */
layout(binding = 0, rgba8) uniform writeonly image2D display;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, vw.size))) return;
    vec4 s = texelFetch(source, pix, 0);
    bool directional = vw.directional != 0;
    vec3 c = vec3(0.0);
    switch (vw.view_mode) {
    case OB_VIEW_MODE_AO: c = directional ? s.rgb : vec3(s.r); break;
    case OB_VIEW_MODE_NORMALS: c = s.rgb * 0.5 + 0.5; break;
    case OB_VIEW_MODE_DEPTH: c = vec3(s.r > 0.0 ? 1.0 - s.r / vw.far_z : 0.0); break;
    case OB_VIEW_MODE_SHADOW: c = vec3(s.a); break; /* the key light's visibility */
    case OB_VIEW_MODE_RADIANCE: c = ob_linear_to_srgb(s.rgb); break;
    case OB_VIEW_MODE_BOUNCE: c = directional ? ob_linear_to_srgb(s.rgb) : vec3(0.0); break;
    /* directional here: the method wrote a bent normal (filtering averaged it: renormalise). */
    case OB_VIEW_MODE_BENT_NORMALS:
        c = directional && dot(s.xyz, s.xyz) > 1e-8 ? normalize(s.xyz) * 0.5 + 0.5 : vec3(0.0);
        break;
    case OB_VIEW_MODE_SAMPLES: {
        /* As the renderer's read_sample_counts: the block of AO pixel pix / k. */
        float count = float(vw.sample_count);
        if (vw.use_multiplier != 0) count *= texelFetch(multiplier, (pix / vw.ao_k) / OB_EDGE_BLOCK, 0).r;
        c = vec3(s.r > 0.0 ? count * vw.inv_max_samples : 0.0); /* the sky takes no samples */
        break;
    }
    default: break;
    }
    imageStore(display, pix, vec4(clamp(c, 0.0, 1.0), 1.0));
}
