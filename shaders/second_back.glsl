#version 450 core
/* The second layer over each pixel's footprint (src/passes/second_back.c): the back a method
 * gives a sample (slice_march.glsl ob_layer_thickness). The peel pass (peel.frag.glsl) finds the
 * back of the solid on the ray through the pixel's centre, but a sample stands for the whole pixel
 * it was taken from: on a thin part seen near its edge, a fin or a chain's link, the solid behind
 * the rest of the footprint reaches deeper, and a back read at the centre alone let light through
 * that the part blocks (docs/methods.md, "The back over a pixel's footprint"). Along each axis the
 * footprint ends half way to the neighbour, where the back is the mean of the two (linear between
 * the centres); the pixel's back is the deepest of those four edges and its own centre.
 *
 * A neighbour counts only where it shows the same solid: its front lies in front of this pixel's
 * back (the solids overlap along the view). A neighbour in a hole (the floor behind a sheet) or
 * beside a silhouette (a wall far behind) is left out, and a pixel whose back is unknown (0:
 * peel.frag.glsl found no closing surface) stays unknown.
 *
 * A neighbour of the same solid whose own back is unknown says that part of the footprint's solid
 * reaches back further than anything known: the peel found no closing surface on its ray, and a
 * method's answer there is its own constant thickness. The pixel's back is then written negated,
 * -deepest: at least the deepest known, and at least the method's constant (visibility_bitmask.glsl
 * takes the thicker). On a Quake stair whose risers are one pixel tall, the ray through a riser's
 * centre clips the step's nose and leaves through the tread, while the riser's lower half, on the
 * neighbour's ray, runs into the solid below: read at the centre alone, two layers read that stair
 * more open than one (docs/methods.md, "The back over a pixel's footprint").
 *
 * Where the footprint's front is not one surface the neighbours cannot say what the back does
 * inside it: their backs belong to other solids, or to other steps of the same one. The flag above
 * does not cover the topmost visible steps of such a stair, whose neighbours all have known
 * backs. There the back's own plane does (the peel pass keeps each second-layer pixel's triangle
 * normal, as the G-buffer its facet normal): at each edge of the footprint across which the front
 * is not the same surface, the back is where the ray through that edge meets the back's plane. On
 * a riser one pixel tall the ray through its lower edge runs under the tread about twice as far as
 * the ray through its centre. That edge's back is at most the centre's thickness deeper than the
 * centre's: a back that deepens faster along a plane would meet the front before the opposite
 * edge (with a linear thickness the centre's is the two opposite edges' mean). The front counts
 * as the same surface across an edge where the neighbour's depth lies nearer the depth this
 * pixel's front plane gives its centre than half its depth step from this pixel (0.5 is the
 * midpoint between the plane explaining the step and the step being a jump). There the
 * neighbours' backs, linear between the centres as above, already say it, and a plane would only
 * add its curvature error: on a smooth convex object the back's tangent plane runs deeper than the
 * back itself, and Debian's convex models read darker with the planes at every edge. A host frame
 * has no planes (`ob_host_ao` takes a depth for the second layer): the neighbours alone.
 *
 * A sheet is its own back (back = front), so no neighbour's front lies in front of it but one
 * nearer on the same sheet, whose back is nearer too, or a nearer object's: a sheet stays a sheet,
 * never flagged, and its planes are not read. */
#include "ob_shared.h"
#include "octahedral.glsl"

#define OB_SECOND_BACK_GROUP 8
layout(local_size_x = OB_SECOND_BACK_GROUP, local_size_y = OB_SECOND_BACK_GROUP) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D front_depth;   /* the first layer's linear depth, full resolution */
layout(binding = OB_UNIT_SECOND_DEPTH) uniform sampler2D second; /* the peel pass's linear depth, same size */
layout(binding = OB_UNIT_FACET_NORMAL) uniform sampler2D front_plane;  /* the G-buffer's facet normals */
layout(binding = OB_UNIT_SECOND_PLANE) uniform sampler2D back_plane;   /* the peel pass's */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D back;
/* size: the size of all of them, then 1 where the planes are bound, 1 for an orthographic camera;
 * proj_info and inv_size as frame_params.h's (common.glsl ob_view_position). */
layout(std140, binding = OB_BINDING_PASS) uniform second_back_block { ivec4 size; vec4 proj_info; vec4 inv_size; } sb;

/* View position at linear depth d on the view ray through screen point `pixel`. */
vec3 view_position(vec2 pixel, float d)
{
    vec2 ndc = pixel * sb.inv_size.xy * 2.0 - 1.0;
    float s = sb.size.w != 0 ? 1.0 : d;
    return vec3((ndc.x + sb.proj_info.z) * s * sb.proj_info.x, (ndc.y + sb.proj_info.w) * s * sb.proj_info.y, -d);
}

/* The linear depth at which the view ray through `pixel` meets the plane through q of normal m;
 * -1 where the ray runs along it. The ray is o + t d at depth t: from the eye through the point at
 * depth 1, or an orthographic ray's origin on the image plane along -Z. */
float plane_depth(vec2 pixel, vec3 q, vec3 m)
{
    vec3 at_one = view_position(pixel, 1.0);
    bool ortho = sb.size.w != 0;
    vec3 o = ortho ? vec3(at_one.xy, 0.0) : vec3(0.0), d = ortho ? vec3(0.0, 0.0, -1.0) : at_one;
    float den = dot(d, m);
    return abs(den) > 1e-4 * length(d) ? dot(q - o, m) / den : -1.0;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = sb.size.xy;
    if (any(greaterThanEqual(p, size))) return;
    float z1 = texelFetch(front_depth, p, 0).r, z2 = texelFetch(second, p, 0).r, deepest = z2;
    bool sheet = z2 <= z1, open_behind = false;
    if (z2 > 0.0) {
        bool planes = sb.size.z != 0 && !sheet;
        vec2 c = vec2(p) + 0.5;
        vec3 f = view_position(c, z1), b = view_position(c, z2), n = vec3(0.0, 0.0, 1.0), m = n;
        if (planes) {
            n = ob_oct_decode(texelFetch(front_plane, p, 0).xy);
            m = ob_oct_decode(texelFetch(back_plane, p, 0).xy);
        }
        const ivec2 step[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int k = 0; k < 4; ++k) {
            ivec2 q = p + step[k];
            bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
            ivec2 qc = clamp(q, ivec2(0), size - 1);
            float q1 = inside ? texelFetch(front_depth, qc, 0).r : 0.0, q2 = texelFetch(second, qc, 0).r;
            if (q1 > 0.0 && q1 < z2) {
                if (q2 > 0.0) deepest = max(deepest, 0.5 * (z2 + q2));
                else open_behind = true;
            }
            /* The back's plane only where the front steps across this edge: most edges lie inside
             * one surface, and there the second ray is not cast. */
            float seen = planes && q1 > 0.0 ? plane_depth(vec2(q) + 0.5, f, n) : -1.0;
            bool same_front = seen > 0.0 && abs(q1 - seen) <= 0.5 * abs(q1 - z1);
            if (planes && !same_front) {
                float edge = plane_depth(c + 0.5 * vec2(step[k]), b, m);
                if (edge > 0.0) deepest = max(deepest, min(edge, 2.0 * z2 - z1));
            }
        }
    }
    imageStore(back, p, vec4(open_behind && !sheet ? -deepest : deepest));
}
