/* The method kit: what every method needs made, bound and freed, done once here from the
 * registry entry's declaration (shader, constant size, state size), so a method file holds only
 * its parameter table, its settings -> constants function and its dispatch. */
#include <stdlib.h>

#include "base/error.h"
#include "methods/method.h"

void *ob_method_make_state(const ob_method_impl *m)
{
    size_t size = m->state_size > sizeof(ob_method_kit) ? m->state_size : sizeof(ob_method_kit);
    ob_method_kit *kit = calloc(1, size);
    if (!kit) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory (%s)", m->info.name);
        return NULL;
    }
    if (m->shader) {
        if (ob_compute_pass_init(&kit->pass, m->shader, NULL, m->constants_size) != OB_OK) {
            free(kit);
            return NULL;
        }
        kit->noise = ob_make_rotation_noise_texture();
    }
    if (m->init && m->init(kit) != OB_OK) {
        ob_compute_pass_destroy(&kit->pass);
        glDeleteTextures(1, &kit->noise);
        free(kit);
        return NULL;
    }
    return kit;
}

void ob_method_destroy_state(const ob_method_impl *m, void *state)
{
    if (!state) return;
    if (m->destroy) m->destroy(state);
    ob_method_kit *kit = state;
    ob_compute_pass_destroy(&kit->pass);
    if (kit->noise) glDeleteTextures(1, &kit->noise);
    free(state);
}

ob_sample_plan ob_method_sample_plan(const ob_ao_inputs *in, int samples, int sampling, int max)
{
    ob_sample_plan p = {samples, ob_adaptive_base(samples), sampling, in->sample_multiplier != 0};
    if (p.adaptive) {
        p.count = 3 * p.base > max ? max / 3 * 3 : 3 * p.base;
        p.base = p.count / 3;
        p.sampling = OB_SAMPLING_MODE_HALTON;
    }
    return p;
}

void ob_method_kit_bind_multiplier(const ob_method_kit *kit, const ob_ao_inputs *in)
{
    glBindTextureUnit(OB_UNIT_SAMPLE_MULTIPLIER, in->sample_multiplier ? in->sample_multiplier : kit->noise);
}

GLuint ob_method_variant(GLuint *slot, const char *shader, const char *defines)
{
    if (!*slot) *slot = ob_make_compute_program(shader, defines);
    return *slot;
}

void ob_method_kit_use(ob_method_kit *kit, const void *constants, size_t size, const ob_ao_inputs *in,
                       const ob_ao_outputs *out, GLenum format)
{
    ob_compute_pass_use(&kit->pass, constants, size);
    glBindTextureUnit(OB_UNIT_DEPTH, in->linear_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, in->view_normal);
    glBindTextureUnit(OB_UNIT_NOISE, kit->noise);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, out->visibility, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
}
