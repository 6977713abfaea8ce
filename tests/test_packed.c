/* The packed texel's half decode (shaders/packed_samples.glsl, ob_half_to_float): on the GPU, every
 * one of the 65536 halves decodes to the bits unpackHalf2x16 gives (a NaN to a NaN) and to the
 * value a C decode gives, so the packed programs of ssdo and vbgi read the normals and radiance the
 * plain programs read (test_ssdo and test_vbao compare their outputs bit for bit). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"

/* IEEE 754 binary16 to float, from its definition. */
static float half_value(uint32_t h)
{
    const uint32_t e = (h >> 10) & 31u, m = h & 1023u;
    const float sign = (h & 0x8000u) ? -1.0f : 1.0f;
    if (e == 0) return sign * ldexpf((float)m, -24);
    if (e == 31) return m ? NAN : sign * INFINITY;
    return sign * ldexpf(1.0f + (float)m / 1024.0f, (int)e - 15);
}

static float from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    enum { N = 65536 };
    GLuint program = ob_make_compute_program("packed_probe.glsl", NULL);
    CHECK(program != 0, "packed_probe.glsl compiles");
    if (program) {
        GLuint buf;
        glCreateBuffers(1, &buf);
        glNamedBufferStorage(buf, sizeof(uint32_t) * 2 * N, NULL, GL_DYNAMIC_STORAGE_BIT);
        glUseProgram(program);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf);
        glDispatchCompute(N / 64, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        uint32_t *bits = malloc(sizeof(uint32_t) * 2 * N);
        glGetNamedBufferSubData(buf, 0, sizeof(uint32_t) * 2 * N, bits);
        int differ = 0, wrong = 0, subnormal = 0, nan = 0;
        for (uint32_t h = 0; h < N; ++h) {
            const float ours = from_bits(bits[2 * h]), builtin = from_bits(bits[2 * h + 1]), want = half_value(h);
            if (isnan(want)) {
                nan += 1;
                differ += !(isnan(ours) && isnan(builtin));
                continue;
            }
            subnormal += ((h >> 10) & 31u) == 0 && (h & 1023u) != 0;
            differ += bits[2 * h] != bits[2 * h + 1];
            wrong += memcmp(&ours, &want, sizeof ours) != 0;
        }
        printf("  half decode: %d halves (%d subnormal, %d NaN): %d differ from unpackHalf2x16, %d from the C "
               "decode\n",
               N, subnormal, nan, differ, wrong);
        CHECK(differ == 0, "ob_half_to_float is unpackHalf2x16 bit for bit (%d halves differ)", differ);
        CHECK(wrong == 0, "ob_half_to_float is IEEE binary16's value (%d halves differ)", wrong);
        CHECK(subnormal == 2046 && nan == 2046, "the probe covers every half (%d subnormal, %d NaN)", subnormal, nan);
        free(bits);
        glDeleteBuffers(1, &buf);
        glDeleteProgram(program);
    }
    ob_destroy_context(ctx);
    return check_finish("test_packed");
}
