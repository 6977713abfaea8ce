#version 450 core
/* The host path's input pass (src/passes/host.c): an engine's depth and normals as the AO chain
 * reads them, R32F positive view depth (0 = sky) and RGBA16F view-space unit normals, at the input
 * size, in one dispatch. The host's textures are read through a sampler object with GL_NEAREST
 * and no depth comparison, so neither their filter state nor their compare mode matters.
 *   depth: a depth buffer's window depth w is linearised through the projection's z row (header
 *     comment of host_params.h); reversed Z and an infinite far plane need nothing of their own:
 *     the row says it (reversed infinite: P22 = 0, P32 = n, so d = n / ndc, exact in float);
 *   normals: decoded (unorm, octahedral: Cigolle et al. 2014, "A Survey of Efficient
 *     Representations for Independent Unit Vectors", §3.1), turned into view space, renormalised;
 *     or, with none, rebuilt from depth: the cross product of the smaller of the two one-sided
 *     differences along x and y, so a silhouette's far side does not bend the normal (a flat-shaded
 *     normal: no smoothing groups). */
#include "host_params.h"
#include "frame_params.h"
#include "common.glsl"

layout(local_size_x = OB_HOST_GROUP_X, local_size_y = OB_HOST_GROUP_Y) in;

layout(binding = OB_UNIT_HOST_DEPTH) uniform sampler2D host_depth;
layout(binding = OB_UNIT_HOST_NORMAL) uniform sampler2D host_normal;
layout(binding = OB_UNIT_HOST_SECOND_DEPTH) uniform sampler2D host_second_depth;
layout(binding = OB_IMAGE_UNIT_HOST_DEPTH, r32f) uniform writeonly image2D linear_depth;
layout(binding = OB_IMAGE_UNIT_HOST_NORMAL, rgba16f) uniform writeonly image2D view_normal;
layout(binding = OB_IMAGE_UNIT_HOST_SECOND_DEPTH, r32f) uniform writeonly image2D second_linear_depth;

float linearise(float w)
{
#if OB_HOST_DEPTH_KIND == OB_HOST_DEPTH_LINEAR
    return w > 0.0 ? w : 0.0;
#else
    if (hi.reversed != 0 ? w <= 0.0 : w >= 1.0) return 0.0; /* the cleared far plane: sky */
    float ndc = w * hi.ndc_scale + hi.ndc_bias;
    float d = hi.orthographic != 0 ? (hi.p32 - ndc) / hi.p22 : hi.p32 / (ndc + hi.p22);
    return d > 0.0 && !isinf(d) && !isnan(d) ? d : 0.0;
#endif
}

float depth_at(ivec2 q)
{
    return linearise(texelFetch(host_depth, clamp(q, ivec2(0), hi.size - 1), 0).r);
}

/* The view-space point of pixel q at depth d (common.glsl; the frame block holds the jittered
 * projection the host rasterised with, and whether it is orthographic). */
vec3 point_at(ivec2 q, float d)
{
    return ob_view_position(vec2(q) + 0.5, d, 1.0 / vec2(hi.size), frame.proj_info);
}

vec3 octahedral_decode(vec2 e)
{
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return n;
}

vec3 rebuilt_normal(ivec2 pix, float d)
{
    vec3 p = point_at(pix, d);
    float dl = depth_at(pix - ivec2(1, 0)), dr = depth_at(pix + ivec2(1, 0));
    float db = depth_at(pix - ivec2(0, 1)), dt = depth_at(pix + ivec2(0, 1));
    /* The nearer neighbour in depth on each axis (a missing one, sky, never wins). */
    bool use_right = dr > 0.0 && (dl <= 0.0 || abs(dr - d) < abs(dl - d));
    bool use_top = dt > 0.0 && (db <= 0.0 || abs(dt - d) < abs(db - d));
    vec3 ex = use_right ? point_at(pix + ivec2(1, 0), dr) - p : (dl > 0.0 ? p - point_at(pix - ivec2(1, 0), dl) : vec3(0.0));
    vec3 ey = use_top ? point_at(pix + ivec2(0, 1), dt) - p : (db > 0.0 ? p - point_at(pix - ivec2(0, 1), db) : vec3(0.0));
    vec3 n = cross(ex, ey);
    float len = length(n);
    vec3 ray = ob_view_ray(p); /* p itself, or -Z for an orthographic camera */
    if (!(len > 0.0)) return normalize(-ray); /* an isolated pixel: face the camera */
    n /= len;
    return dot(n, ray) > 0.0 ? -n : n; /* towards the camera */
}

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, hi.size))) return;
    float d = depth_at(pix);
    vec3 n = vec3(0.0);
    if (d > 0.0) {
#if OB_HOST_NORMAL_ENCODING == OB_HOST_NORMAL_NONE
        n = rebuilt_normal(pix, d);
#else
        vec4 t = texelFetch(host_normal, pix, 0);
#if OB_HOST_NORMAL_ENCODING == OB_HOST_NORMAL_RAW
        n = t.xyz;
#elif OB_HOST_NORMAL_ENCODING == OB_HOST_NORMAL_UNORM
        n = t.xyz * 2.0 - 1.0;
#elif OB_HOST_NORMAL_ENCODING == OB_HOST_NORMAL_OCT
        n = octahedral_decode(t.xy);
#else
        n = octahedral_decode(t.xy * 2.0 - 1.0);
#endif
        n = mat3(hi.normal_to_view) * n;
        float len = length(n);
        n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
#endif
    }
    imageStore(linear_depth, pix, vec4(d));
    imageStore(view_normal, pix, vec4(n, 1.0));
#if OB_HOST_SECOND
    imageStore(second_linear_depth, pix, vec4(linearise(texelFetch(host_second_depth, pix, 0).r)));
#endif
}
