/* Depth MIP prefilter (issue 13): a MIP chain of linear view depth in one dispatch, for the
 * horizon-based methods' far taps (McGuire, Mara & Luebke 2012, "Scalable Ambient Obscurance",
 * §2.2). Shader and the reasons for its reduction: shaders/depth_mips.glsl. */
#include <string.h>

#include "base/error.h"
#include "depth_mips_params.h"
#include "passes/passes.h"

int ob_depth_mips_level_count(int width, int height)
{
    /* glTextureStorage2D allows 1 + floor(log2(max(w, h))) levels: a 1x1 input has level 0 only. */
    int longest = width > height ? width : height, levels = 1;
    while (levels < OB_DEPTH_MIPS_LEVELS && (longest >> levels) > 0) ++levels;
    return levels;
}

void ob_depth_mips_level_size(int width, int height, int level, int *level_width, int *level_height)
{
    int w = width >> level, h = height >> level;
    *level_width = w > 1 ? w : 1;
    *level_height = h > 1 ? h : 1;
}

void ob_depth_mips_fill(ob_depth_mips_constants *c, int width, int height)
{
    memset(c, 0, sizeof *c);
    c->size[0] = width;
    c->size[1] = height;
    c->levels = ob_depth_mips_level_count(width, height);
}

/* The shader's reduce(): SAO's rotated-grid child, sky included. */
static float reduce(const float d[4], int x, int y)
{
    return d[2 * (x & 1) + (y & 1)]; /* child (y & 1, x & 1); d is (0,0), (1,0), (0,1), (1,1) */
}

int ob_depth_mips_reference(const float *depth, int width, int height, float *const levels[OB_DEPTH_MIPS_LEVELS])
{
    int count = ob_depth_mips_level_count(width, height);
    memcpy(levels[0], depth, (size_t)width * (size_t)height * sizeof(float));
    for (int level = 1; level < count; ++level) {
        int bw = 0, bh = 0, w = 0, h = 0;
        ob_depth_mips_level_size(width, height, level - 1, &bw, &bh);
        ob_depth_mips_level_size(width, height, level, &w, &h);
        const float *below = levels[level - 1];
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
                for (int k = 0; k < 4; ++k) {
                    int cx = 2 * x + (k & 1), cy = 2 * y + (k >> 1);
                    cx = cx < bw ? cx : bw - 1;
                    cy = cy < bh ? cy : bh - 1;
                    d[k] = below[(size_t)cy * (size_t)bw + (size_t)cx];
                }
                levels[level][(size_t)y * (size_t)w + (size_t)x] = reduce(d, x, y);
            }
    }
    return count;
}

ob_error ob_depth_mips_init(ob_depth_mips *m)
{
    if (!m) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_depth_mips_init: NULL");
    memset(m, 0, sizeof *m);
    return ob_compute_pass_init(&m->pass, "depth_mips.glsl", NULL, sizeof(ob_depth_mips_constants));
}

/* A new texture for width x height, swapped in only when the GL made it (on an error m keeps its
 * old one). */
static ob_error remake(ob_depth_mips *m, int width, int height)
{
    int levels = ob_depth_mips_level_count(width, height);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, levels, GL_R32F, width, height);
    /* Readers pick the level themselves (textureLod / texelFetch); NEAREST keeps every value a
     * real depth (filtering would blend foreground and background again). */
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    GLenum e = ob_gl_error();
    if (e != GL_NO_ERROR) {
        glDeleteTextures(1, &tex);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d depth MIP texture (%d levels)", e, width,
                            height, levels);
    }
    if (m->texture) glDeleteTextures(1, &m->texture);
    m->texture = tex;
    m->width = width;
    m->height = height;
    m->levels = levels;
    return OB_OK;
}

ob_error ob_depth_mips_run(ob_depth_mips *m, GLuint linear_depth, int width, int height)
{
    if (!m) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_depth_mips_run: NULL pass");
    if (!m->pass.program) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_depth_mips_run: pass not initialised");
    if (!linear_depth) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_depth_mips_run: no input texture");
    if (width <= 0 || height <= 0)
        return ob_set_error(OB_ERR_BAD_SIZE, "ob_depth_mips_run: size %dx%d", width, height);
    if (!m->texture || width != m->width || height != m->height) {
        ob_error err = remake(m, width, height);
        if (err != OB_OK) return err;
    }
    ob_depth_mips_constants c;
    ob_depth_mips_fill(&c, width, height);
    ob_compute_pass_use(&m->pass, &c, sizeof c);
    glBindTextureUnit(OB_UNIT_DEPTH, linear_depth);
    for (int level = 0; level < OB_DEPTH_MIPS_LEVELS; ++level) {
        /* Units past the texture's last level get that level, never written (see the shader). */
        int bound = level < m->levels ? level : m->levels - 1;
        glBindImageTexture((GLuint)(OB_IMAGE_UNIT_DEPTH_MIPS + level), m->texture, bound, GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_R32F);
    }
    ob_dispatch_2d(width, height, OB_DEPTH_MIPS_TILE, OB_DEPTH_MIPS_TILE);
    /* The methods sample the levels next (texture fetches or image loads). */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return OB_OK;
}

void ob_depth_mips_destroy(ob_depth_mips *m)
{
    if (!m) return;
    ob_compute_pass_destroy(&m->pass);
    if (m->texture) glDeleteTextures(1, &m->texture);
    memset(m, 0, sizeof *m);
}
