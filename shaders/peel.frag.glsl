#version 450 core
/* The second depth layer (depth peeling, Everitt 2001; Belonogov 2018 §4.4, SSDO thesis §6.4): the same
 * scene drawn again with the G-buffer's vertex shader, keeping per pixel the nearest surface that
 * lies behind the first layer by more than a small separation. Back faces count (culling is off,
 * as in the G-buffer). The layer is meant as the back of the solid whose front the first layer
 * shows, so that the two bound it along the view ray: a method reads "a sample between the two
 * layers is inside an object, a sample behind the second is free".
 *
 * That holds only where the surface behind belongs to the same connected part of the mesh as the
 * first layer (scene/parts.c) and shows the other side of its triangles (by winding: a closed
 * part's front faces one way, its back the other). Anything else and the two do not bound one
 * solid: the front of another object behind a single sheet (a drilled brake disc, a wall of one
 * polygon), the ground behind a part. Taking that for the sheet's back made the whole gap between
 * them solid: the holes of the motorbike's brake disc read black, with the ground 0.9 m behind
 * the disc taken as its back (docs/methods.md). The winding alone, without the part, still took
 * the ground for the back of the parts wound the other way (that motorbike is wound either way,
 * part by part); comparing the two sides, not requiring a front face first, keeps a part wound
 * clockwise throughout right. Another part's back face behind a front face is not taken either:
 * in a Quake map, whose brushes' faces are not joined into parts, it is as often the far side of
 * a room as the back of a wall, and oa_shouse's beams and furniture read black bands so
 * (docs/methods.md, "Which surface is the back"). Where the two do not bound one solid the layer
 * is 0, as where nothing lies behind: the method's own thickness, the single-layer answer.
 *
 * A sheet with holes in it (scene/parts.c: a part whose open edges form two loops or more, a
 * drilled plate or a grille) has no thickness at all: where nothing of its own part closes it,
 * the layer is the sheet itself, which the methods read as their thinnest occluder (one step's
 * spacing, ob_layer_thickness). With the constant instead, the floor seen through the holes and
 * around the sheet read a slab between them, and the holes black (docs/methods.md, "Thin holes").
 */
#include "gbuffer_params.h"
#include "octahedral.glsl"

in vec3 v_view_pos;
in vec3 v_view_normal;
in vec2 v_uv;
flat in float v_part;
flat in float v_sheet;

layout(binding = OB_UNIT_FIRST_LAYER) uniform sampler2D first_layer; /* the G-buffer's R32F linear depth, 0 = sky */
layout(binding = OB_UNIT_FIRST_FACING) uniform sampler2D first_normal; /* the G-buffer's normal: w = ±part, + front face */

layout(location = 0) out float out_linear_depth;   /* R32F: the second layer's linear depth, 0 = none or unknown */
layout(location = 1) out vec2 out_plane;           /* RG16F: that surface's own triangle's view normal, octahedral
                                                      (second_back.glsl reads the back's plane over the pixel) */

/* The separation, relative to the first layer's depth: it drops the first surface itself where a
 * second triangle coincides with it (duplicated or z-fighting faces), and nothing an occluder test
 * could tell apart (1e-3 of the depth is 100x the R32F resolution at any depth). */
const float SEPARATION = 1e-3;

void main()
{
    /* The triangle's own plane, as the G-buffer's facet normal (gbuffer.frag.glsl): before any
     * discard, where the quad's derivatives are defined. */
    out_plane = ob_oct_encode(normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos))));
    float z = -v_view_pos.z;
    float first = texelFetch(first_layer, ivec2(gl_FragCoord.xy), 0).r;
    /* Behind the sky there is nothing (first = 0 only where no triangle covers the pixel). */
    if (first <= 0.0) discard;
    float first_part = texelFetch(first_normal, ivec2(gl_FragCoord.xy), 0).w;
    bool first_front = first_part > 0.0;
    bool same_part = abs(first_part) == v_part;
    bool closes = same_part && gl_FrontFacing != first_front;
    /* A triangle of the same part on the first layer's plane, wound the other way, is that
     * surface's back: a sheet drawn twice, once each way (the motorbike's brake discs), is a
     * solid of no thickness, and behind it lies the other disc. Any other triangle there is
     * the first layer itself or a copy of it. */
    bool coincident = z <= first * (1.0 + SEPARATION);
    /* The first layer's own fragment, on a sheet: the sheet is its own back. It lies nearer than
     * anything behind, so the depth test keeps it over the surfaces beyond. */
    if (coincident && !closes && v_sheet > 0.5 && same_part && gl_FrontFacing == first_front) {
        out_linear_depth = first;
        return;
    }
    if (coincident && !closes) discard;
    out_linear_depth = closes ? max(z, first) : 0.0;
}
