/* The table of AO/GI methods. One line per method. */
#include <string.h>

#include "methods/method.h"

extern const ob_method_impl ob_method_none;
extern const ob_method_impl ob_method_ssao;
extern const ob_method_impl ob_method_hbao;
extern const ob_method_impl ob_method_crytek;
extern const ob_method_impl ob_method_alchemy;
extern const ob_method_impl ob_method_ssdo;
extern const ob_method_impl ob_method_ssdo_merged;

static const ob_method_impl *const methods[] = {
    &ob_method_none,
    &ob_method_ssao,
    &ob_method_hbao,
    &ob_method_crytek,
    &ob_method_alchemy,
    &ob_method_ssdo,
    &ob_method_ssdo_merged,
};

const char *const ob_sampling_options[] = {"random", "halton"};
const char *const ob_direction_options[] = {"uniform", "cosine"};
const char *const ob_noise_options[] = {"texture4", "ign"};

int ob_method_count(void) { return (int)(sizeof methods / sizeof methods[0]); }

const ob_method_impl *ob_method_impl_at(int index)
{
    return index >= 0 && index < ob_method_count() ? methods[index] : NULL;
}

const ob_method_info *ob_method_at(int index)
{
    const ob_method_impl *m = ob_method_impl_at(index);
    return m ? &m->info : NULL;
}

int ob_find_method(const char *name)
{
    if (!name) return -1;
    for (int i = 0; i < ob_method_count(); ++i)
        if (strcmp(methods[i]->info.name, name) == 0) return i;
    return -1;
}

int ob_method_samples(const ob_method_impl *m, const float *params)
{
    if (m->count_samples) return m->count_samples(params);
    for (int i = 0; i < m->info.param_count; ++i)
        if (!strcmp(m->info.params[i].name, "samples")) return (int)params[i];
    return 0;
}
