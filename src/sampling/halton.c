/* Halton sequences and the direction mappings of SSDO thesis §3.4, §5.3. */
#include <math.h>

#include "sampling/sampling.h"

double ob_radical_inverse(uint32_t i, uint32_t base)
{
    /* eq. 3.6: Phi_b(i) = sum_j a_j(i) b^(-j-1), accumulated from the least significant digit. */
    double inv_base = 1.0 / (double)base;
    double scale = inv_base;
    double result = 0.0;
    while (i > 0) {
        result += (double)(i % base) * scale;
        i /= base;
        scale *= inv_base;
    }
    return result;
}

void ob_direction_cosine(double r1, double r2, float out[3])
{
    /* eq. 5.2: x = cos(2 pi r1) sqrt(1 - r2), y = sin(2 pi r1) sqrt(1 - r2), z = sqrt(r2). */
    double phi = 2.0 * M_PI * r1;
    double s = sqrt(1.0 - r2);
    out[0] = (float)(cos(phi) * s);
    out[1] = (float)(sin(phi) * s);
    out[2] = (float)sqrt(r2);
}

void ob_direction_uniform(double r1, double r2, float out[3])
{
    /* eq. 5.3: x = cos(2 pi r1) sqrt(1 - r2^2), y = sin(2 pi r1) sqrt(1 - r2^2), z = r2. */
    double phi = 2.0 * M_PI * r1;
    double s = sqrt(1.0 - r2 * r2);
    out[0] = (float)(cos(phi) * s);
    out[1] = (float)(sin(phi) * s);
    out[2] = (float)r2;
}
