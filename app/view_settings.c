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
    v->method_radius_scale[v->s.method] = v->s.radius_scale;
    v->s.method = index;
    memcpy(v->s.params, v->method_params[index], sizeof v->s.params);
    v->s.params_set = v->method_set[index];
    v->s.radius_scale = v->method_radius_scale[index];
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
    const cli_common *c = &v->o.common;
    /* The settings the command line asks for, built as every rendering command builds them
     * (method, filter, AO scale, quality, lights, shadows, ambient, HDR, and the --set that name
     * the starting method or filter). */
    cli_config cfg = {.method = c->methods[0], .filter = c->filters[0], .ao_divisor = c->ao_divisors[0],
                      .samples = c->sample_count > 0 ? c->samples[0] : (cli_samples){0, NULL},
                      .tuned = cli_common_tuned(c, c->methods[0])};
    int code = cli_common_apply(c, &cfg);
    if (code != 0) return code;
    v->s = cfg.settings;
    for (int m = 0; m < ob_method_count() && m < MAX_METHODS; ++m) {
        ob_settings tmp;
        ob_settings_init(&tmp, ob_method_at(m)->name);
        /* --settings: a tuned method starts from its tuned values when picked. */
        const cli_tuned *t = cli_common_tuned(c, m);
        if (t && (code = cli_tuned_apply(t, &tmp)) != 0) return code;
        memcpy(v->method_params[m], tmp.params, sizeof tmp.params);
        v->method_radius_scale[m] = tmp.radius_scale;
    }
    /* Scenes are static: the maps only change with the lights or the shadow settings, not with
     * the camera (on llvmpipe FZK-Haus's sun + 2 cube maps cost 500+ ms a frame otherwise). */
    v->s.shadow.reuse = true;
    if (c->sample_count > 0) {
        static const int counts[] = {12, 24, 36, 64};
        for (int q = 0; q < 4; ++q)
            if (counts[q] == c->samples[0].count) v->quality = q + 1;
    }
    /* A --set naming another method goes to that method's stored values, for when it is picked. */
    for (int i = 0; i < c->set_count; ++i) {
        const char *dot = strchr(c->sets[i], '.'), *eq = strchr(c->sets[i], '=');
        if (!dot || !eq || dot > eq) continue;
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)(dot - c->sets[i]), c->sets[i]);
        int m = ob_find_method(name), current = v->s.method;
        if (m == current) continue; /* cli_common_apply set it */
        if (m < 0) {
            /* The current filter's (set already, harmless twice) or a name the library refuses. */
            if (ob_settings_set(&v->s, c->sets[i]) != OB_OK) return cli_fail_from_library();
            continue;
        }
        select_method(v, m);
        /* Report before switching back: select_method clears the library's error (with a
         * quality preset), and a failure ends the viewer anyway. */
        if (ob_settings_set(&v->s, c->sets[i]) != OB_OK) return cli_fail_from_library();
        select_method(v, current);
    }
    /* The scene's lights as explicit ones (unless --light gave some), so the panel can edit them. */
    if (v->s.light_count == 0) {
        v->s.light_count = ob_query_scene_light_count(v->scene);
        if (v->s.light_count > OB_MAX_LIGHTS) v->s.light_count = OB_MAX_LIGHTS;
        for (int i = 0; i < v->s.light_count; ++i) v->s.lights[i] = ob_query_scene_light(v->scene, i);
    }
    /* --env alone lights the scene with it, as the viewer always has (--ambient picks otherwise). */
    if (c->env && c->ambient_mode == OB_AMBIENT_CONSTANT) v->s.ambient_mode = OB_AMBIENT_ENVIRONMENT;
    return 0;
}
