/* The packed-sample texel's layout (src/methods/packed.c): written by sample_pack.glsl, read by
 * ssdo.glsl and visibility_bitmask.glsl (vbgi) with their `packed` on.
 *   x = half2(L.r, L.g), y = half2(L.b, n.x), z = half2(n.y, n.z), w = the float bits of d
 * for an AO texel's linear depth d (R32F), view normal n and direct radiance L (both RGBA16F),
 * so packing is lossless and a packed program's output is the plain one's bit for bit. */
#ifndef OB_PACKED_SAMPLES_GLSL
#define OB_PACKED_SAMPLES_GLSL

uvec4 ob_pack_sample(float d, vec3 n, vec3 l)
{
    return uvec4(packHalf2x16(l.rg), packHalf2x16(vec2(l.b, n.x)), packHalf2x16(n.yz), floatBitsToUint(d));
}

float ob_packed_depth(uvec4 t) { return uintBitsToFloat(t.w); }
vec3 ob_packed_normal(uvec4 t) { return vec3(unpackHalf2x16(t.y).y, unpackHalf2x16(t.z)); }
vec3 ob_packed_radiance(uvec4 t) { return vec3(unpackHalf2x16(t.x), unpackHalf2x16(t.y).x); }

#endif
