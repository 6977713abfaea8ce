/* The table of AO/GI methods: one line per method in OB_METHODS, in the order `obscura list`
 * shows them (none first: the reference frame and the cost baseline). */
#include <pthread.h>
#include <string.h>

#include "base/error.h"
#include "methods/method.h"

#define OB_METHODS(X) \
    X(none)           \
    X(ssao)           \
    X(hbao)           \
    X(crytek)         \
    X(alchemy)        \
    X(ssdo)           \
    X(ssdo_merged)    \
    X(gtao)           \
    X(vbao)           \
    X(vbgi)

#define OB_X_EXTERN(name) extern const ob_method_impl ob_method_##name;
OB_METHODS(OB_X_EXTERN)
#undef OB_X_EXTERN

#define OB_X_ENTRY(name) &ob_method_##name,
static const ob_method_impl *const methods[] = {OB_METHODS(OB_X_ENTRY)};
#undef OB_X_ENTRY

enum { METHOD_COUNT = sizeof methods / sizeof methods[0] };

const char *const ob_sampling_options[] = {"random", "halton"};
const char *const ob_direction_options[] = {"uniform", "cosine"};
const char *const ob_noise_options[] = {"texture4", "ign"};

/* The public descriptions: each entry's info with `directional` derived from what it writes and
 * `adapts` copied, so a method declares each once. Filled on first use. */
static ob_method_info infos[METHOD_COUNT];
static pthread_once_t infos_once = PTHREAD_ONCE_INIT;

static void fill_infos(void)
{
    for (int i = 0; i < METHOD_COUNT; ++i) {
        infos[i] = methods[i]->info;
        infos[i].directional = (methods[i]->writes & (OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE)) != 0;
        infos[i].adapts = methods[i]->adapts;
    }
}

int ob_method_count(void) { return METHOD_COUNT; }

const ob_method_impl *ob_method_impl_at(int index)
{
    return index >= 0 && index < METHOD_COUNT ? methods[index] : NULL;
}

const ob_method_info *ob_method_at(int index)
{
    if (index < 0 || index >= METHOD_COUNT) return NULL;
    pthread_once(&infos_once, fill_infos);
    return &infos[index];
}

int ob_find_method(const char *name)
{
    if (!name) return -1;
    for (int i = 0; i < METHOD_COUNT; ++i)
        if (strcmp(methods[i]->info.name, name) == 0) return i;
    return -1;
}

int ob_method_role(const ob_method_impl *m, ob_param_role role)
{
    if (!m || (int)role < 0 || role >= OB_ROLE_COUNT) return -1;
    const int index = m->roles[role] - 1;
    return index >= 0 && index < m->info.param_count ? index : -1;
}

int ob_method_samples(const ob_method_impl *m, const float *params)
{
    if (m->count_samples) return m->count_samples(params);
    const int p = ob_method_role(m, OB_ROLE_SAMPLES);
    return p >= 0 ? (int)params[p] : 0;
}

uint32_t ob_method_active_reads(const ob_method_impl *m, const float *params)
{
    return m->active_reads ? m->active_reads(params) & m->reads : m->reads;
}

uint32_t ob_method_active_writes(const ob_method_impl *m, const float *params)
{
    return m->active_writes ? m->active_writes(params) & m->writes : m->writes;
}

int ob_method_kernel(const ob_settings *s, float *xyzw, int max)
{
    if (!s || !xyzw || max < 0) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_method_kernel: NULL settings or output, or max < 0");
        return -1;
    }
    const ob_method_impl *m = ob_method_impl_at(s->method);
    if (!m) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_method_kernel: settings are not initialised");
        return -1;
    }
    return m->kernel && max > 0 ? m->kernel(s->params, xyzw, max) : 0;
}
