/* Log-average luminance (SSDO thesis eq. 2.1, §5.5 step 5) and the key (eq. 2.2, §6.5), computed and
 * kept on the GPU: shaders/luminance.glsl sums ln(delta + L) per 64x64 block, then one work group
 * reduces the blocks and writes (L_avg, key, scale) to a buffer the bloom and tone-map passes
 * read, so a frame never waits on a read-back. */
#include <string.h>

#include "base/error.h"
#include "luminance_params.h"
#include "passes/passes.h"

/* The result vec4, then one partial sum per gx x gy block. */
static GLuint make_result(int gx, int gy)
{
    size_t bytes = OB_HDR_RESULT_BYTES + (size_t)gx * (size_t)gy * sizeof(float);
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    /* Zero-filled, so a query before the first frame reads 0s rather than garbage. */
    glNamedBufferData(buf, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_COPY);
    glClearNamedBufferData(buf, GL_R32F, GL_RED, GL_FLOAT, NULL);
    return buf;
}

ob_error ob_luminance_init(ob_luminance_pass *p, int width, int height)
{
    memset(p, 0, sizeof *p);
    p->width = width;
    p->height = height;
    p->groups_x = (width + OB_LUMINANCE_SPAN - 1) / OB_LUMINANCE_SPAN;
    p->groups_y = (height + OB_LUMINANCE_SPAN - 1) / OB_LUMINANCE_SPAN;
    if (ob_compute_pass_init(&p->partial, "luminance.glsl", NULL, sizeof(ob_luminance_constants)) != OB_OK ||
        ob_compute_pass_init(&p->final, "luminance.glsl", "#define OB_LUMINANCE_FINAL 1\n",
                             sizeof(ob_luminance_constants)) != OB_OK) {
        ob_error err = ob_peek_error(NULL);
        ob_luminance_destroy(p);
        return err;
    }
    p->result = make_result(p->groups_x, p->groups_y);
    return OB_OK;
}

ob_error ob_luminance_resize(ob_luminance_pass *p, int width, int height)
{
    int gx = (width + OB_LUMINANCE_SPAN - 1) / OB_LUMINANCE_SPAN;
    int gy = (height + OB_LUMINANCE_SPAN - 1) / OB_LUMINANCE_SPAN;
    GLuint made = make_result(gx, gy);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        glDeleteBuffers(1, &made);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d luminance buffer", e, width, height);
    }
    glDeleteBuffers(1, &p->result);
    p->result = made;
    p->width = width;
    p->height = height;
    p->groups_x = gx;
    p->groups_y = gy;
    return OB_OK;
}

void ob_luminance_run(ob_luminance_pass *p, GLuint radiance, float exposure, float key)
{
    ob_luminance_constants k;
    memset(&k, 0, sizeof k);
    k.exposure = exposure;
    k.key = key > 0.0f ? key : 0.0f;
    k.delta = (float)OB_HDR_DELTA;
    k.inv_pixel_count = 1.0f / ((float)p->width * (float)p->height);
    k.width = p->width;
    k.height = p->height;
    k.partial_count = p->groups_x * p->groups_y;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OB_BINDING_HDR_RESULT, p->result);

    ob_compute_pass_use(&p->partial, &k, sizeof k);
    glBindTextureUnit(OB_UNIT_SOURCE, radiance);
    glDispatchCompute((GLuint)p->groups_x, (GLuint)p->groups_y, 1);
    /* The final reduction reads the partial sums the first dispatch stored. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    ob_compute_pass_use(&p->final, &k, sizeof k);
    glDispatchCompute(1, 1, 1);
}

void ob_luminance_destroy(ob_luminance_pass *p)
{
    ob_compute_pass_destroy(&p->partial);
    ob_compute_pass_destroy(&p->final);
    if (p->result) glDeleteBuffers(1, &p->result);
    memset(p, 0, sizeof *p);
}
