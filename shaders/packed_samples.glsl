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

/* unpackHalf2x16's value of the half in the low 16 bits of h, to the bit (zero, subnormals,
 * normals, infinities; a NaN stays a NaN), from integer operations and one conversion. The packed
 * programs exist for software rasterisers, where llvmpipe's unpackHalf2x16 took a sixth of vbgi's
 * instructions and this takes half as many (bench/results/2026-11-23-llvmpipe-instructions.md). */
float ob_half_to_float(uint h)
{
    uint magnitude = h & 0x7FFFu;
    /* A normal half: the exponent rebiased from 15 to 127 (+ 112 << 23), the mantissa widened. */
    float v = uintBitsToFloat((magnitude << 13) + 0x38000000u);
    /* Zero and subnormals: the mantissa x 2^-24, exact (below 2^10 every integer is a float). */
    v = magnitude < 0x0400u ? float(magnitude) * 5.9604644775390625e-8 : v;
    /* Infinities and NaNs: exponent 31 becomes 255. */
    v = magnitude >= 0x7C00u ? uintBitsToFloat((magnitude << 13) | 0x7F800000u) : v;
    return uintBitsToFloat(floatBitsToUint(v) | ((h & 0x8000u) << 16));
}

float ob_packed_depth(uvec4 t) { return uintBitsToFloat(t.w); }
vec3 ob_packed_normal(uvec4 t) { return vec3(ob_half_to_float(t.y >> 16), ob_half_to_float(t.z), ob_half_to_float(t.z >> 16)); }
vec3 ob_packed_radiance(uvec4 t) { return vec3(ob_half_to_float(t.x), ob_half_to_float(t.x >> 16), ob_half_to_float(t.y)); }

#endif
