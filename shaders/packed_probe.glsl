#version 450 core
/* Test probe for shaders/packed_samples.glsl (tests/test_packed.c): invocation h decodes the half
 * with bits h (0 ... 65535) by ob_half_to_float and by unpackHalf2x16 and writes both as bits; the
 * upper 16 bits of the word are set too, which the decode must ignore. */
#include "packed_samples.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) writeonly buffer probe_bits { uvec2 bits[]; };

void main()
{
    uint h = gl_GlobalInvocationID.x;
    bits[h] = uvec2(floatBitsToUint(ob_half_to_float(h | 0xABCD0000u)), floatBitsToUint(unpackHalf2x16(h).x));
}
