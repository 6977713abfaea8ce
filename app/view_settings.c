/* obscura view's render settings: the ob_settings built from the options at start, and the
 * switches that keep per-method state (each method's own parameter values, the quality preset)
 * and reset what depends on them. */
#include <stdio.h>
#include <string.h>

#include "view.h"

/* Switching methods keeps each method's own parameter values; a quality preset other than the
 * methods' defaults is applied to every method picked, as --quality is. */
void select_method(viewer *v, int index)
{
    int n = ob_method_count();
    index = ((index % n) + n) % n;
    memcpy(v->method_params[v->s.method], v->s.params, sizeof v->s.params);
    v->method_set[v->s.method] = v->s.params_set;
    v->s.method = index;
    memcpy(v->s.params, v->method_params[index], sizeof v->s.params);
    v->s.params_set = v->method_set[index];
    static const char *const presets[] = {"", "low", "medium", "high", "ultra"};
    if (v->quality > 0) {
        ob_settings_set_samples(&v->s, ob_quality_samples(presets[v->quality]));
        ob_clear_error(); /* none takes no sample count: nothing to set */
    }
    profiler_reset(&v->prof);
    update_title(v);
}

bool select_method_by_name(viewer *v, const char *name)
{
    int index = ob_find_method(name);
    if (index < 0) {
        say(v, true, "unknown method '%s'", name);
        return false;
    }
    select_method(v, index);
    return true;
}

void set_view(viewer *v, int index)
{
    v->view = (ob_view)(((index % OB_VIEW_COUNT) + OB_VIEW_COUNT) % OB_VIEW_COUNT);
    update_title(v);
}

int setup_settings(viewer *v)
{
    const view_opts *o = &v->o;
    if (ob_settings_init(&v->s, o->method) != OB_OK) return cli_fail_from_library();
    for (int m = 0; m < ob_method_count() && m < MAX_METHODS; ++m) {
        ob_settings tmp;
        ob_settings_init(&tmp, ob_method_at(m)->name);
        memcpy(v->method_params[m], tmp.params, sizeof tmp.params);
    }
    if (ob_settings_set_filter(&v->s, o->filter) != OB_OK || ob_settings_set_ao_scale(&v->s, o->ao_scale) != OB_OK)
        return cli_fail_from_library();
    v->s.adaptive = o->adaptive;
    if (o->shadow_method >= 0) v->s.shadow.method = (ob_shadow_method)o->shadow_method;
    if (o->shadow_size > 0) v->s.shadow.size = o->shadow_size;
    /* Scenes are static: the maps only change with the lights or the shadow settings, not with
     * the camera (on llvmpipe FZK-Haus's sun + 2 cube maps cost 500+ ms a frame otherwise). */
    v->s.shadow.reuse = true;
    v->s.hdr.enabled = !o->hdr_off;
    if (o->quality_samples > 0) {
        static const int counts[] = {12, 24, 36, 64};
        for (int q = 0; q < 4; ++q)
            if (counts[q] == o->quality_samples) v->quality = q + 1;
        ob_error err = ob_settings_set_samples(&v->s, o->quality_samples);
        if (err != OB_OK && err != OB_ERR_INVALID_ARGUMENT) return cli_fail_from_library();
    }
    /* --set may name any method (ssao.radius=...): it goes to that method's stored values. */
    for (int i = 0; i < o->set_count; ++i) {
        const char *dot = strchr(o->sets[i], '.'), *eq = strchr(o->sets[i], '=');
        int m = v->s.method;
        if (dot && eq && dot < eq) {
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)(dot - o->sets[i]), o->sets[i]);
            if (ob_find_method(name) >= 0) m = ob_find_method(name);
        }
        int current = v->s.method;
        if (m != current) select_method(v, m);
        /* Report before switching back: select_method clears the library's error (with a
         * quality preset), and a failure ends the viewer anyway. */
        if (ob_settings_set(&v->s, o->sets[i]) != OB_OK) return cli_fail_from_library();
        if (m != current) select_method(v, current);
    }
    /* The scene's lights as explicit ones, so the panel can edit them. */
    v->s.light_count = ob_query_scene_light_count(v->scene);
    if (v->s.light_count > OB_MAX_LIGHTS) v->s.light_count = OB_MAX_LIGHTS;
    for (int i = 0; i < v->s.light_count; ++i) v->s.lights[i] = ob_query_scene_light(v->scene, i);
    if (o->env) v->s.ambient_mode = OB_AMBIENT_ENVIRONMENT;
    return 0;
}
