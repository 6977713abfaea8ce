/* Per-frame settings: method parameters validated against the registry's tables. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/error.h"
#include "base/suggest.h"
#include "filters/filter.h"
#include "methods/method.h"
#include "obscura/scene.h"

/* "unknown WHAT 'NAME'; did you mean 'NEAR'? (known: a, b, c)", OB_ERR_UNKNOWN_METHOD (a method or
 * a filter). */
static ob_error unknown_name(const char *what, const char *name, const char *const *names, int n)
{
    char list[512] = "", hint[96];
    for (int i = 0; i < n; ++i) snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", names[i]);
    return ob_set_error(OB_ERR_UNKNOWN_METHOD, "unknown %s '%s'%s (known: %s)", what, name,
                        ob_suggest_text(name, strlen(name), names, n, hint, sizeof hint), list);
}

ob_error ob_settings_init(ob_settings *s, const char *method)
{
    if (!s) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_init: settings is NULL");
    const char *name = method ? method : OB_DEFAULT_METHOD;
    int index = ob_find_method(name);
    if (index < 0) {
        const char *names[64] = {0};
        int n = 0;
        for (; n < ob_method_count() && n < 64; ++n) names[n] = ob_method_at(n)->name;
        return unknown_name("method", name, names, n);
    }
    memset(s, 0, sizeof *s);
    s->method = index;
    const ob_method_info *m = ob_method_at(index);
    for (int i = 0; i < m->param_count && i < OB_MAX_PARAMS; ++i) s->params[i] = m->params[i].def;
    /* `crease`: the edge-aware 5x5 that cancels the 4x4 rotation noise without averaging a crease
     * with the open floor beside it (docs/filters.md: on the four graded views it lowers every
     * method's error against unfiltered; SSDO thesis's `geometry` brightened the corner crease by up
     * to 0.25 and raised most methods' error). */
    s->filter = -1;
    s->ao_divisor = 1;
    s->radius_scale = 1.0f;
    ob_error err = ob_settings_set_filter(s, "crease");
    if (err != OB_OK) return err;
    /* light_count 0 = the scene's lights (sidecar, glTF or default). */
    s->ambient_mode = OB_AMBIENT_CONSTANT;
    s->ambient[0] = s->ambient[1] = s->ambient[2] = 0.3f;
    /* A pale blue sky over a dim warm ground: a hemisphere ambient that still reads as daylight. */
    s->sky[0] = 0.35f;
    s->sky[1] = 0.40f;
    s->sky[2] = 0.50f;
    s->ground[0] = 0.12f;
    s->ground[1] = 0.10f;
    s->ground[2] = 0.08f;
    /* Biases from the shadow pass's sweep of light elevations (no acne for hard and PCF at 10-85
     * degrees); 2048 texels is about 1 cm on a 20 m scene. */
    s->shadow = (ob_shadow_settings){.method = OB_SHADOW_PCF, .size = 2048, .bias = 1.0f, .slope_bias = 0.75f,
                                     .pcf_radius = 1, .vsm_blur = 2.0f, .vsm_bleed = 0.25f};
    /* L_white 3 keeps brightly lit faces apart (none burn at 4x the default light); a bloom
     * threshold of half of it halos only what is over-bright (tools' HDR helper measurements,
     * see docs/lighting.md). */
    s->hdr = (ob_hdr_settings){.enabled = true, .exposure = 1.0f, .key = 0.0f, .l_white = 3.0f,
                               .bloom_threshold = 1.5f, .bloom_strength = 0.3f};
    /* A pale sky grey: AO halos around silhouettes stay visible against it. */
    s->background[0] = 0.60f;
    s->background[1] = 0.66f;
    s->background[2] = 0.74f;
    return OB_OK;
}

static int find_param(const ob_method_info *m, const char *name, size_t len)
{
    for (int i = 0; i < m->param_count; ++i)
        if (strlen(m->params[i].name) == len && strncmp(m->params[i].name, name, len) == 0) return i;
    return -1;
}

static ob_error parse_value(const ob_method_info *m, const ob_param_info *p, const char *text, float *out)
{
    const char *v = text;
    while (isspace((unsigned char)*v)) ++v;
    if (p->type == OB_PARAM_ENUM) {
        for (int i = 0; p->options && i <= (int)p->max; ++i) {
            char index[16];
            snprintf(index, sizeof index, "%d", i);
            if (!strcmp(v, p->options[i]) || !strcmp(v, index)) {
                *out = (float)i;
                return OB_OK;
            }
        }
        char list[256] = "";
        for (int i = 0; p->options && i <= (int)p->max; ++i) {
            size_t n = strlen(list);
            snprintf(list + n, sizeof list - n, "%s%s", i ? "|" : "", p->options[i]);
        }
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s.%s expects %s, got '%s'", m->name, p->name, list, text);
    }
    if (p->type == OB_PARAM_BOOL) {
        if (!strcasecmp(v, "1") || !strcasecmp(v, "true") || !strcasecmp(v, "on")) { *out = 1.0f; return OB_OK; }
        if (!strcasecmp(v, "0") || !strcasecmp(v, "false") || !strcasecmp(v, "off")) { *out = 0.0f; return OB_OK; }
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s.%s expects on/off, got '%s'", m->name, p->name, text);
    }
    char *end = NULL;
    errno = 0;
    double d = strtod(v, &end);
    if (end == v || *end != '\0' || errno == ERANGE)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s.%s expects a number, got '%s'", m->name, p->name, text);
    if (!isfinite(d))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s.%s must be finite, got '%s'", m->name, p->name, text);
    if (p->type == OB_PARAM_INT && d != floor(d))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s.%s expects an integer, got '%s'", m->name, p->name, text);
    if (d < (double)p->min || d > (double)p->max)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "%s.%s = %s is out of range [%g, %g] (%s)", m->name, p->name,
                            text, (double)p->min, (double)p->max, p->unit);
    *out = (float)d;
    return OB_OK;
}

/* A frame setting's whole number: `v` (leading blanks skipped) of the assignment's value `raw`,
 * within [lo, hi]; the errors name the key, what it expects and the unit of its range. */
static ob_error whole_number(const char *key, const char *raw, const char *expects, long lo, long hi, const char *unit,
                             int *out)
{
    const char *v = raw;
    while (isspace((unsigned char)*v)) ++v;
    char *end = NULL;
    errno = 0;
    long n = strtol(v, &end, 10);
    if (end == v || *end != '\0' || errno == ERANGE)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s expects %s, got '%s'", key, expects, raw);
    if (n < lo || n > hi)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "%s = %s is out of range [%ld, %ld] (%s)", key, raw, lo, hi, unit);
    *out = (int)n;
    return OB_OK;
}

ob_error ob_settings_set(ob_settings *s, const char *assignment)
{
    if (!s || !assignment) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_set: NULL argument");
    const ob_method_info *m = ob_method_at(s->method);
    if (!m) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "settings are not initialised");
    /* The table the assignment is for: the method's, unless the prefix names the filter. */
    float *values = s->params;
    uint32_t *set_bits = &s->params_set;
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment || eq[1] == '\0')
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "expected METHOD.PARAM=VALUE, got '%s'", assignment);
    const char *key = assignment;
    size_t key_len = (size_t)(eq - assignment);
    if (key_len == strlen("guard") && !strncmp(key, "guard", key_len))
        /* The frame's, not a method's: no prefix. Whole pixels per side. */
        return whole_number("guard", eq + 1, "whole pixels per side", 0, OB_GUARD_MAX, "px per side", &s->guard);
    if (key_len == strlen("jitter") && !strncmp(key, "jitter", key_len)) {
        /* The frame's sub-pixel jitter, no prefix: J positions, on (the default count) or off. */
        const char *v = eq + 1;
        while (isspace((unsigned char)*v)) ++v;
        if (!strcmp(v, "on")) s->jitter = OB_JITTER_POSITIONS_DEFAULT;
        else if (!strcmp(v, "off")) s->jitter = 0;
        else return whole_number("jitter", eq + 1, "on, off or a number of positions", 0, OB_JITTER_POSITIONS_MAX, "positions",
                                 &s->jitter);
        return OB_OK;
    }
    if (key_len == strlen("upsample") && !strncmp(key, "upsample", key_len)) {
        /* The frame's upsampler program, no prefix: auto, plain or block (ob_upsample_program). */
        const char *v = eq + 1;
        while (isspace((unsigned char)*v)) ++v;
        for (int i = 0; i < OB_UPSAMPLE_PROGRAM_COUNT; ++i)
            if (!strcmp(v, ob_upsample_program_name((ob_upsample_program)i))) {
                s->upsample = i;
                return OB_OK;
            }
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "upsample expects auto, plain or block, got '%s'", eq + 1);
    }
    if (key_len > 8 && !strncmp(key, "temporal", 8) && !memchr(key, '.', key_len)) {
        /* The frame's temporal accumulation, no prefix: temporal=on|off, temporal_at=before|after,
         * temporal_frames=N, temporal_detail=A. */
        const char *v = eq + 1;
        while (isspace((unsigned char)*v)) ++v;
        if (key_len == strlen("temporal_at") && !strncmp(key, "temporal_at", key_len)) {
            if (!strcmp(v, "before")) s->temporal_at = OB_TEMPORAL_BEFORE_FILTER;
            else if (!strcmp(v, "after")) s->temporal_at = OB_TEMPORAL_AFTER_FILTER;
            else return ob_set_error(OB_ERR_INVALID_ARGUMENT, "temporal_at expects before or after, got '%s'", eq + 1);
            return OB_OK;
        }
        if (key_len == strlen("temporal_frames") && !strncmp(key, "temporal_frames", key_len))
            return whole_number("temporal_frames", eq + 1, "a whole number of frames", 1, OB_TEMPORAL_FRAMES_MAX, "frames",
                                &s->temporal_frames);
        if (key_len == strlen("temporal_detail") && !strncmp(key, "temporal_detail", key_len)) {
            char *end = NULL;
            errno = 0;
            float a = strtof(v, &end);
            if (end == v || *end != '\0' || errno == ERANGE)
                return ob_set_error(OB_ERR_INVALID_ARGUMENT, "temporal_detail expects a number in [0, 1), got '%s'",
                                    eq + 1);
            if (!(a >= 0.0f && a < 1.0f))
                return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_detail = %s is out of range [0, 1)", eq + 1);
            s->temporal_detail = a;
            return OB_OK;
        }
    }
    if (key_len == strlen("temporal") && !strncmp(key, "temporal", key_len)) {
        const char *v = eq + 1;
        while (isspace((unsigned char)*v)) ++v;
        if (!strcmp(v, "on") || !strcmp(v, "1")) s->temporal = true;
        else if (!strcmp(v, "off") || !strcmp(v, "0")) s->temporal = false;
        else return ob_set_error(OB_ERR_INVALID_ARGUMENT, "temporal expects on or off, got '%s'", eq + 1);
        return OB_OK;
    }
    const char *dot = memchr(key, '.', key_len);
    if (dot) {
        size_t mlen = (size_t)(dot - key);
        int mi = -1, fi = -1;
        for (int i = 0; i < ob_method_count(); ++i)
            if (strlen(ob_method_at(i)->name) == mlen && strncmp(ob_method_at(i)->name, key, mlen) == 0) mi = i;
        for (int i = 0; i < ob_filter_count(); ++i)
            if (strlen(ob_filter_at(i)->name) == mlen && strncmp(ob_filter_at(i)->name, key, mlen) == 0) fi = i;
        if (mi < 0 && fi < 0)
            return ob_set_error(OB_ERR_UNKNOWN_METHOD, "unknown method or filter '%.*s' in '%s'", (int)mlen, key,
                                assignment);
        if (mi >= 0 && mi == s->method) {
            /* the method's own parameter */
        } else if (fi >= 0 && fi == s->filter) {
            m = ob_filter_at(fi);
            values = s->filter_params;
            set_bits = &s->filter_params_set;
        } else if (mi >= 0) {
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "'%s' sets a parameter of %s, but the method is %s",
                                assignment, ob_method_at(mi)->name, m->name);
        } else {
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "'%s' sets a parameter of filter %s, but the filter is %s",
                                assignment, ob_filter_at(fi)->name, ob_filter_at(s->filter)->name);
        }
        key = dot + 1;
        key_len -= mlen + 1;
    }
    if (values == s->params && key_len == strlen("radius_scale") && !strncmp(key, "radius_scale", key_len)) {
        /* Every method's: validated like a table entry of its own. */
        static const ob_param_info scale = {"radius_scale", OB_PARAM_FLOAT, OB_RADIUS_SCALE_MIN, OB_RADIUS_SCALE_MAX,
                                            1.0f, "x radius", "occluder radius = scale x R", false, NULL};
        float value = 0.0f;
        ob_error err = parse_value(m, &scale, eq + 1, &value);
        if (err != OB_OK) return err;
        s->radius_scale = value;
        return OB_OK;
    }
    int pi = find_param(m, key, key_len);
    if (pi < 0) {
        char list[512] = "";
        for (int i = 0; i < m->param_count; ++i) {
            size_t n = strlen(list);
            snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "", m->params[i].name);
        }
        const char *names[OB_MAX_PARAMS] = {0};
        for (int i = 0; i < m->param_count && i < OB_MAX_PARAMS; ++i) names[i] = m->params[i].name;
        char hint[96];
        return ob_set_error(OB_ERR_UNKNOWN_PARAM, "%s has no parameter '%.*s'%s (it has: %s)", m->name, (int)key_len,
                            key, ob_suggest_text(key, key_len, names, m->param_count, hint, sizeof hint),
                            m->param_count ? list : "none");
    }
    float value = 0.0f;
    ob_error err = parse_value(m, &m->params[pi], eq + 1, &value);
    if (err != OB_OK) return err;
    values[pi] = value;
    *set_bits |= 1u << pi;
    return OB_OK;
}

float ob_settings_get(const ob_settings *s, const char *param)
{
    const ob_method_info *m = s ? ob_method_at(s->method) : NULL;
    if (!m || !param) return NAN;
    if (!strcmp(param, "radius_scale")) return s->radius_scale > 0.0f ? s->radius_scale : 1.0f;
    if (!strcmp(param, "guard")) return (float)s->guard;
    if (!strcmp(param, "jitter")) return (float)s->jitter;
    if (!strcmp(param, "temporal")) return s->temporal ? 1.0f : 0.0f;
    if (!strcmp(param, "temporal_at")) return (float)s->temporal_at;
    if (!strcmp(param, "upsample")) return (float)s->upsample;
    if (!strcmp(param, "temporal_frames"))
        return (float)(s->temporal_frames > 0 ? s->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT);
    if (!strcmp(param, "temporal_detail")) return s->temporal_detail;
    int pi = find_param(m, param, strlen(param));
    return pi < 0 ? NAN : s->params[pi];
}

int ob_quality_samples(const char *name)
{
    static const struct { const char *name; int samples; } presets[] = {
        {"low", 12}, {"medium", 24}, {"high", 36}, {"ultra", 64}};
    for (size_t i = 0; name && i < sizeof presets / sizeof presets[0]; ++i)
        if (!strcmp(name, presets[i].name)) return presets[i].samples;
    return -1;
}

ob_error ob_settings_set_samples(ob_settings *s, int samples)
{
    const ob_method_impl *m = s ? ob_method_impl_at(s->method) : NULL;
    if (!m) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "settings are not initialised");
    if (m->set_samples) return m->set_samples(s->params, &s->params_set, samples);
    const int p = ob_method_role(m, OB_ROLE_SAMPLES);
    if (p < 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "method %s takes no sample count", m->info.name);
    /* Through ob_settings_set, so the count is checked against the parameter's range as typed;
     * qualified by the method, so that no name of the settings' own (temporal...) can take it. */
    char assignment[160];
    snprintf(assignment, sizeof assignment, "%s.%s=%d", m->info.name, m->info.params[p].name, samples);
    return ob_settings_set(s, assignment);
}

ob_error ob_settings_set_filter(ob_settings *s, const char *name)
{
    if (!s || !name) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_set_filter: NULL argument");
    int index = ob_find_filter(name);
    if (index < 0) {
        const char *names[64] = {0};
        int n = 0;
        for (; n < ob_filter_count() && n < 64; ++n) names[n] = ob_filter_at(n)->name;
        return unknown_name("filter", name, names, n);
    }
    const ob_filter_info *f = ob_filter_at(index);
    s->filter = index;
    s->filter_params_set = 0;
    for (int i = 0; i < OB_MAX_PARAMS; ++i) s->filter_params[i] = i < f->param_count ? f->params[i].def : 0.0f;
    return OB_OK;
}

float ob_settings_get_filter(const ob_settings *s, const char *param)
{
    const ob_filter_info *f = s ? ob_filter_at(s->filter) : NULL;
    if (!f || !param) return NAN;
    int pi = find_param(f, param, strlen(param));
    return pi < 0 ? NAN : s->filter_params[pi];
}

ob_error ob_settings_set_ao_divisor(ob_settings *s, int divisor)
{
    if (!s) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_set_ao_divisor: NULL settings");
    if (divisor != 1 && divisor != 2 && divisor != 4)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ao divisor %d is not 1, 2 or 4", divisor);
    s->ao_divisor = divisor;
    return OB_OK;
}

ob_error ob_settings_set_ao_scale(ob_settings *s, float scale)
{
    if (!s) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_set_ao_scale: NULL settings");
    if (scale != 1.0f && scale != 0.5f && scale != 0.25f)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ao scale %g is not 1, 0.5 or 0.25", (double)scale);
    s->ao_divisor = scale == 1.0f ? 1 : scale == 0.5f ? 2 : 4;
    return OB_OK;
}
