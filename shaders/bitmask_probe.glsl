#version 450 core
/* Test probe for shaders/bitmask.glsl (tests/test_bitmask.c): one invocation runs one slice's
 * samples through the bitmask update and writes the mask after each, and the cosine measure of
 * the final mask. Sample i: (rise of the front, rise of the back, n(φ), side: +1 along dir, -1
 * against). */
#include "frame_params.h"
#include "common.glsl"
#include "slice_march.glsl"
#include "bitmask.glsl"

layout(local_size_x = 1) in;

layout(location = 0) uniform int coverage;
layout(location = 1) uniform int samples_per_slice;

layout(std430, binding = 0) readonly buffer probe_samples { vec4 samples[]; };
layout(std430, binding = 1) writeonly buffer probe_masks { uint masks[]; };
layout(std430, binding = 2) writeonly buffer probe_measures { float measures[]; };

void main()
{
    uint slice = gl_GlobalInvocationID.x;
    uint mask = 0u;
    float ang_n = 0.0;
    for (int i = 0; i < samples_per_slice; ++i) {
        vec4 s = samples[slice * uint(samples_per_slice) + uint(i)];
        ang_n = s.z;
        mask |= ob_sample_bits(s.x, s.y, s.z, s.w > 0.0, coverage);
        masks[slice * uint(samples_per_slice) + uint(i)] = mask;
    }
    measures[slice] = ob_bits_measure(mask, ang_n, cos(ang_n), sin(ang_n));
}
