/* Lights from text (the CLI's --light), and the check every light passes (ob_check_light). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h"
#include "obscura/scene.h"

static bool parse_floats(const char *v, float *out, int n)
{
    const char *p = v;
    for (int i = 0; i < n; ++i) {
        char *end = NULL;
        double d = strtod(p, &end);
        /* Finite as a float too: 1e39 is a finite double and an infinite float. */
        if (end == p || !isfinite(d) || !isfinite((float)d)) return false;
        out[i] = (float)d;
        if (i < n - 1) {
            if (*end != ',') return false;
            p = end + 1;
        } else if (*end != '\0') {
            return false;
        }
    }
    return true;
}

ob_error ob_parse_light(const char *text, ob_light *out)
{
    if (!text || !out) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_parse_light: NULL argument");
    char buf[512];
    if (snprintf(buf, sizeof buf, "%s", text) >= (int)sizeof buf)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%.40s...' is too long", text);
    ob_light l = {.color = {1.0f, 1.0f, 1.0f}, .intensity = 1.0f, .spot_inner_deg = 20.0f, .spot_outer_deg = 30.0f};
    bool has_dir = false, has_pos = false;
    char *save = NULL;
    char *tok = strtok_r(buf, " ", &save);
    if (!tok) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': expected directional, point or spot", text);
    if (!strcmp(tok, "directional") || !strcmp(tok, "dir")) l.type = OB_LIGHT_DIRECTIONAL;
    else if (!strcmp(tok, "point")) l.type = OB_LIGHT_POINT;
    else if (!strcmp(tok, "spot")) l.type = OB_LIGHT_SPOT;
    else return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': unknown type '%s' (directional, point, spot)", text, tok);
    while ((tok = strtok_r(NULL, " ", &save)) != NULL) {
        char *eq = strchr(tok, '=');
        if (!eq) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': expected key=value, got '%s'", text, tok);
        *eq = '\0';
        const char *k = tok, *v = eq + 1;
        bool ok = true;
        if (!strcmp(k, "dir")) ok = parse_floats(v, l.direction, 3), has_dir = true;
        else if (!strcmp(k, "pos")) ok = parse_floats(v, l.position, 3), has_pos = true;
        else if (!strcmp(k, "color")) ok = parse_floats(v, l.color, 3) && l.color[0] >= 0.0f && l.color[1] >= 0.0f && l.color[2] >= 0.0f;
        else if (!strcmp(k, "intensity")) ok = parse_floats(v, &l.intensity, 1) && l.intensity >= 0.0f;
        else if (!strcmp(k, "range")) ok = parse_floats(v, &l.range, 1) && l.range > 0.0f;
        else if (!strcmp(k, "cone")) {
            float c[2] = {0.0f, 0.0f};
            ok = parse_floats(v, c, 2) && c[0] >= 0.0f && c[0] <= c[1] && c[1] < 90.0f;
            l.spot_inner_deg = c[0];
            l.spot_outer_deg = c[1];
        } else {
            return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                                "light '%s': unknown key '%s' (dir, pos, color, intensity, range, cone)", text, k);
        }
        if (!ok) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': bad value for %s: '%s'", text, k, v);
    }
    if (l.type != OB_LIGHT_POINT) {
        if (!has_dir) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': needs dir=x,y,z", text);
        if (!ob_normalize_direction(l.direction)) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': dir is zero", text);
    }
    if (l.type != OB_LIGHT_DIRECTIONAL && !has_pos)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': needs pos=x,y,z", text);
    if (ob_check_light(&l) != OB_OK) {
        /* Copied: the message lives in the buffer the next ob_set_error writes. */
        const char *why = NULL;
        ob_get_error(&why);
        char msg[400];
        snprintf(msg, sizeof msg, "%s", why ? why : "invalid");
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': %s", text, msg);
    }
    *out = l;
    return OB_OK;
}

bool ob_normalize_direction(float v[3])
{
    /* Scaled by the largest component first: the squares of 1e30 overflow a float, and the
     * direction would become 0 or NaN (a light that silently gives nothing). */
    float m = fmaxf(fabsf(v[0]), fmaxf(fabsf(v[1]), fabsf(v[2])));
    if (!(m > 0.0f) || !isfinite(m)) return false;
    float u[3] = {v[0] / m, v[1] / m, v[2] / m};
    float len = sqrtf(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int i = 0; i < 3; ++i) v[i] = u[i] / len;
    return true;
}

static bool all_finite(const float *v, int n, float limit)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i]) || fabsf(v[i]) > limit) return false;
    return true;
}

ob_error ob_check_light(const ob_light *l)
{
    if (!l) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_check_light: NULL light");
    if (l->type != OB_LIGHT_DIRECTIONAL && l->type != OB_LIGHT_POINT && l->type != OB_LIGHT_SPOT)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "type %d is not directional, point or spot", (int)l->type);
    if (!all_finite(l->color, 3, 3.0e38f) || l->color[0] < 0.0f || l->color[1] < 0.0f || l->color[2] < 0.0f)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "color (%g, %g, %g): expected finite components >= 0",
                            (double)l->color[0], (double)l->color[1], (double)l->color[2]);
    if (!isfinite(l->intensity) || l->intensity < 0.0f)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "intensity %g: expected a finite number >= 0", (double)l->intensity);
    const bool directional = l->type == OB_LIGHT_DIRECTIONAL;
    const float most = directional ? OB_MAX_DIRECTIONAL : OB_MAX_POINT;
    const double peak = (double)fmaxf(l->color[0], fmaxf(l->color[1], l->color[2])) * (double)l->intensity;
    if (peak > (double)most)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "intensity %g x color %g is above %g for a %s light (the 16-bit float radiance would "
                            "overflow: see ob_check_light)",
                            (double)l->intensity, peak / fmax((double)l->intensity, 1e-30), (double)most,
                            directional ? "directional" : "point or spot");
    if (l->type != OB_LIGHT_POINT) {
        const float *d = l->direction;
        if (!all_finite(d, 3, 3.0e38f) || (d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f))
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "direction (%g, %g, %g): expected finite and not zero",
                                (double)d[0], (double)d[1], (double)d[2]);
    }
    if (l->type != OB_LIGHT_DIRECTIONAL) {
        if (!all_finite(l->position, 3, OB_MAX_COORDINATE))
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "position (%g, %g, %g) is not finite or beyond +-%g",
                                (double)l->position[0], (double)l->position[1], (double)l->position[2],
                                (double)OB_MAX_COORDINATE);
        if (!isfinite(l->range) || l->range < 0.0f)
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "range %g: expected finite and >= 0 (0 = none)", (double)l->range);
    }
    if (l->type == OB_LIGHT_SPOT &&
        !(l->spot_inner_deg >= 0.0f && l->spot_inner_deg <= l->spot_outer_deg && l->spot_outer_deg < 90.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "cone %g, %g: need 0 <= inner <= outer < 90 degrees",
                            (double)l->spot_inner_deg, (double)l->spot_outer_deg);
    return OB_OK;
}
