/* Scene sidecar: a small JSON file that gives a model what its file format cannot carry
 * (camera presets, the key light, a sensible AO radius, the up axis). docs/scenes.md is its
 * user's documentation (test docs_standalone holds it to the keys parsed here).
 *
 * Format (every key optional unless noted; coordinates are in the scene's final Y-up frame,
 * in the model's units):
 *
 *   {
 *     "_comment": "keys starting with an underscore are ignored, anywhere",
 *     "model": "/usr/share/glmark2/models/bunny.obj",   model file; absolute or relative to
 *                                                       this file. Required for a named scene
 *                                                       (scenes/NAME.obscura.json), else ignored.
 *     "up": "y" | "z",           the model's up axis; "z" is rotated to Y-up on import. Read by
 *                                the loader before importing (ob_sidecar_peek).
 *     "ao_radius": 0.05,         suggested AO radius, > 0 and at most the diagonal of the
 *                                scene's bounds (the ground included)
 *     "cameras": [               presets, added after "default" in this order; a preset with the
 *       {                        name of an existing one (e.g. from glTF) replaces it, and one
 *                                named "default" replaces the framing camera (for a model whose
 *                                open side does not face +Z, like the Cornell box)
 *         "name": "front",       required, 1-63 characters, unique
 *         "eye": [x, y, z],      required
 *         "target": [x, y, z],   required, != eye
 *         "up": [0, 1, 0],       default +Y; must not be parallel to target - eye
 *         "fov": 50              vertical field of view in degrees, in (1, 179); default 60
 *       }
 *     ],
 *     "paths": [                 named camera paths (issue 17; render/compare/bench --path NAME),
 *       {                        up to 8, each 2..32 keyframes
 *         "name": "walk",        required, 1-63 characters, unique
 *         "keys": [              required; eye and target follow Catmull-Rom splines in time
 *           {"time": 0, "eye": [x, y, z], "target": [x, y, z], "fov": 60},
 *           ...                  time: required, strictly increasing, within +-1e9; eye, target: required,
 *         ]                      != each other; fov: (1, 179), default 60 (linear between keys)
 *       }
 *     ],
 *     "lights": [                up to 8; the first one is the scene's key light
 *       {
 *         "type": "directional", "directional" (default), "point" or "spot"
 *         "direction": [x, y, z],directional: required, FROM the surface TOWARD the light;
 *                                spot: required, the cone's axis, away from the light
 *         "position": [x, y, z], point and spot: required
 *         "color": [r, g, b],    linear RGB, >= 0, default [1, 1, 1]
 *         "intensity": 1.0,      >= 0, default 1 (point/spot: falls off as 1/d^2)
 *         "range": 10,           point and spot: > 0, smooth cut-off distance; default none
 *         "cone": [20, 30]       spot: inner and outer half-angles in degrees, 0 <= inner <= outer < 90
 *       }
 *     ],
 *     "ground": {                a square floor added under the model (a scanned object has none,
 *                                and without one there is no contact occlusion to grade); the
 *                                default camera keeps framing the model alone
 *       "y": 0,                  height of the plane; default the model's lowest point, so the
 *                                model stands on it
 *       "size": 10,              side of the square, > 0, centred under the model's bounds;
 *                                default 4 x the model's larger horizontal extent
 *       "color": [r, g, b],      linear RGB albedo in [0, 1], default [0.8, 0.8, 0.8]
 *       "walls": [               at most 4 walls standing on the ground, as wide as it, in its
 *         {"x": 1.0,             colour, facing the model: the plane x = 1 (or "z": z = ...);
 *          "height": 2}          > 0, default 1.5 x the model's height
 *       ]
 *     }
 *   }
 *
 * Validation is strict because a silently ignored typo ("camera" for "cameras") would render the
 * wrong view without any hint: unknown or duplicate keys, wrong types, wrong array lengths and
 * out-of-range numbers are all OB_ERR_SIDECAR with "path: where: what is wrong". Nothing is
 * applied unless the whole file is valid. */
#include "eval/sidecar.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "base/error.h"
#include "base/suggest.h"
#include "io/file.h"
#include "eval/import.h"

/* Sidecars are hand-written and tiny; anything bigger is the wrong file. */
#define SIDECAR_MAX_BYTES (4u << 20)
#define SIDECAR_MODEL_MAX 4096

enum { MAX_WALLS = 4 }; /* a box open at the top and the front needs three; four close it */

typedef struct sidecar {
    char model[SIDECAR_MODEL_MAX];
    ob_up_axis up;
    float ao_radius; /* 0 = not given */
    ob_camera cameras[OB_MAX_CAMERAS];
    int camera_count;
    ob_camera_path paths[OB_MAX_PATHS];
    int path_count;
    ob_light lights[OB_MAX_LIGHTS];
    int light_count;
    bool ground;          /* "ground" given */
    bool ground_has_y;    /* else the model's lowest point */
    float ground_y;
    float ground_size;    /* 0 = 4 x the larger horizontal extent */
    float ground_color[3];
    /* "ground.walls": vertical quads standing on the ground along x = at (axis 0) or z = at
     * (axis 2), facing the model; height 0 = 1.5 x the model's height. */
    struct {
        int axis;
        float at, height;
    } walls[MAX_WALLS];
    int wall_count;
} sidecar;

/* Record "path: message" as OB_ERR_SIDECAR. */
static ob_error fail(const char *path, const char *fmt, ...) OB_PRINTF(2, 3);
static ob_error fail(const char *path, const char *fmt, ...)
{
    char msg[512] = "";
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return ob_set_error(OB_ERR_SIDECAR, "%s: %s", path, msg);
}

/* "path: field: unknown key; did you mean 'NEAR'? (expected a, b, c)": keys[] are the valid ones. */
static ob_error unknown_key(const char *path, const char *field, const char *key, const char *const *keys, int n,
                            const char *also)
{
    char list[256] = "", hint[96];
    for (int i = 0; i < n; ++i) snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", keys[i]);
    return fail(path, "%s: unknown key%s (expected %s%s)", field, ob_suggest_text(key, strlen(key), keys, n, hint, sizeof hint),
                list, also);
}

/* The failed ob_check_camera/ob_check_light's message, named by the sidecar and the entry. Copied
 * first: it lives in the buffer the next ob_set_error writes. */
static ob_error fail_check(const char *path, const char *where)
{
    const char *why = NULL;
    ob_get_error(&why);
    char msg[400];
    snprintf(msg, sizeof msg, "%s", why ? why : "invalid");
    return fail(path, "%s: %s", where, msg);
}

static const char *json_type_name(const cJSON *item)
{
    if (cJSON_IsNumber(item)) return "a number";
    if (cJSON_IsString(item)) return "a string";
    if (cJSON_IsBool(item)) return "a boolean";
    if (cJSON_IsNull(item)) return "null";
    if (cJSON_IsArray(item)) return "an array";
    if (cJSON_IsObject(item)) return "an object";
    return "an invalid value";
}

/* A top-level list (cameras, paths, lights): an array of at most `most` entries, counted in *n. */
static ob_error array_entries(const char *path, const char *key, const cJSON *item, int most, const char *what, int *n)
{
    if (!cJSON_IsArray(item)) return fail(path, "%s: expected an array, got %s", key, json_type_name(item));
    *n = cJSON_GetArraySize(item);
    if (*n > most) return fail(path, "%s: %d %s, at most %d", key, *n, what, most);
    return OB_OK;
}

static ob_error read_number(const char *path, const char *where, const cJSON *item, float *out)
{
    if (!cJSON_IsNumber(item)) {
        return fail(path, "%s: expected a number, got %s", where, json_type_name(item));
    }
    /* cJSON turns 1e999 into inf; a float overflow would do the same. */
    double v = item->valuedouble;
    if (!isfinite(v) || fabs(v) > 3.0e38) return fail(path, "%s: number is not finite", where);
    *out = (float)v;
    return OB_OK;
}

static ob_error read_vec3(const char *path, const char *where, const cJSON *item, float out[3])
{
    if (!cJSON_IsArray(item)) {
        return fail(path, "%s: expected an array of 3 numbers, got %s", where,
                    json_type_name(item));
    }
    int n = cJSON_GetArraySize(item);
    if (n != 3) {
        return fail(path, "%s: expected an array of 3 numbers, got %d element%s", where, n,
                    n == 1 ? "" : "s");
    }
    for (int i = 0; i < 3; ++i) {
        char elem[160] = "";
        snprintf(elem, sizeof elem, "%s[%d]", where, i);
        ob_error err = read_number(path, elem, cJSON_GetArrayItem(item, i), &out[i]);
        if (err != OB_OK) return err;
    }
    return OB_OK;
}

static float len3(const float v[3])
{
    return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* True when key was already seen in this object (cJSON keeps duplicates; the first would win
 * silently). */
static bool seen_before(const cJSON *obj, const cJSON *item)
{
    for (const cJSON *c = obj->child; c && c != item; c = c->next) {
        if (c->string && strcmp(c->string, item->string) == 0) return true;
    }
    return false;
}

static bool is_comment_key(const char *key)
{
    return key && key[0] == '_';
}

static ob_error parse_camera(const char *path, int index, const cJSON *obj, ob_camera *cam)
{
    char where[96] = "";
    snprintf(where, sizeof where, "cameras[%d]", index);
    if (!cJSON_IsObject(obj)) {
        return fail(path, "%s: expected an object, got %s", where, json_type_name(obj));
    }
    memset(cam, 0, sizeof *cam);
    bool has_name = false, has_eye = false, has_target = false;
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *key = it->string;
        char field[160] = "";
        snprintf(field, sizeof field, "%s.%s", where, key);
        if (is_comment_key(key)) continue;
        if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
        ob_error err = OB_OK;
        if (strcmp(key, "name") == 0) {
            if (!cJSON_IsString(it)) {
                return fail(path, "%s: expected a string, got %s", field, json_type_name(it));
            }
            size_t len = strlen(it->valuestring);
            if (len == 0 || len >= sizeof cam->name) {
                return fail(path, "%s: must be 1 to %zu characters", field,
                            sizeof cam->name - 1);
            }
            memcpy(cam->name, it->valuestring, len + 1);
            has_name = true;
        } else if (strcmp(key, "eye") == 0) {
            err = read_vec3(path, field, it, cam->eye);
            has_eye = true;
        } else if (strcmp(key, "target") == 0) {
            err = read_vec3(path, field, it, cam->target);
            has_target = true;
        } else if (strcmp(key, "up") == 0) {
            err = read_vec3(path, field, it, cam->up);
        } else if (strcmp(key, "fov") == 0) {
            err = read_number(path, field, it, &cam->fov_y_deg);
            if (err == OB_OK && !(cam->fov_y_deg > 1.0f && cam->fov_y_deg < 179.0f)) {
                return fail(path, "%s: %g degrees is outside (1, 179)", field,
                            (double)cam->fov_y_deg);
            }
        } else {
            static const char *const keys[] = {"name", "eye", "target", "up", "fov"};
            return unknown_key(path, field, key, keys, 5, "");
        }
        if (err != OB_OK) return err;
    }
    if (!has_name) return fail(path, "%s: missing \"name\"", where);
    if (!has_eye) return fail(path, "%s (\"%s\"): missing \"eye\"", where, cam->name);
    if (!has_target) return fail(path, "%s (\"%s\"): missing \"target\"", where, cam->name);

    /* The same check as a camera from the options or a host (ob_check_camera), named here. */
    if (ob_check_camera(cam) != OB_OK) {
        char named[200]; /* where (96) + name (64) + quotes */
        snprintf(named, sizeof named, "%s (\"%s\")", where, cam->name);
        return fail_check(path, named);
    }
    return OB_OK;
}

/* One keyframe of paths[index].keys[k]. */
static ob_error parse_key(const char *path, const char *where, const cJSON *obj, ob_camera_path *p, int k)
{
    if (!cJSON_IsObject(obj)) return fail(path, "%s: expected an object, got %s", where, json_type_name(obj));
    bool has_time = false, has_eye = false, has_target = false;
    p->fov[k] = 60.0f;
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *key = it->string;
        char field[200] = "";
        snprintf(field, sizeof field, "%s.%s", where, key);
        if (is_comment_key(key)) continue;
        if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
        ob_error err = OB_OK;
        if (strcmp(key, "time") == 0) {
            err = read_number(path, field, it, &p->time[k]);
            /* Times are interpolated as differences: beyond 1e9 two keys' difference can overflow
             * a float (3e38 made every camera between them NaN). */
            if (err == OB_OK && !(fabsf(p->time[k]) <= 1e9f))
                return fail(path, "%s: %g is beyond +-1e9", field, (double)p->time[k]);
            has_time = true;
        } else if (strcmp(key, "eye") == 0) {
            err = read_vec3(path, field, it, p->eye[k]);
            has_eye = true;
        } else if (strcmp(key, "target") == 0) {
            err = read_vec3(path, field, it, p->target[k]);
            has_target = true;
        } else if (strcmp(key, "fov") == 0) {
            err = read_number(path, field, it, &p->fov[k]);
            if (err == OB_OK && !(p->fov[k] > 1.0f && p->fov[k] < 179.0f))
                return fail(path, "%s: %g degrees is outside (1, 179)", field, (double)p->fov[k]);
        } else {
            static const char *const keys[] = {"time", "eye", "target", "fov"};
            return unknown_key(path, field, key, keys, 4, "");
        }
        if (err != OB_OK) return err;
    }
    if (!has_time) return fail(path, "%s: missing \"time\"", where);
    if (!has_eye) return fail(path, "%s: missing \"eye\"", where);
    if (!has_target) return fail(path, "%s: missing \"target\"", where);
    float fwd[3] = {p->target[k][0] - p->eye[k][0], p->target[k][1] - p->eye[k][1], p->target[k][2] - p->eye[k][2]};
    if (!(len3(fwd) > 0.0f)) return fail(path, "%s: eye == target", where);
    const ob_camera probe = {.eye = {p->eye[k][0], p->eye[k][1], p->eye[k][2]},
                             .target = {p->target[k][0], p->target[k][1], p->target[k][2]},
                             .fov_y_deg = p->fov[k]};
    if (ob_check_camera(&probe) != OB_OK) return fail_check(path, where);
    /* Up is +Y along a path: a key looking straight up or down has no roll. */
    if (sqrtf(fwd[0] * fwd[0] + fwd[2] * fwd[2]) < 1e-4f * len3(fwd))
        return fail(path, "%s: looks straight up or down (a path's up is +Y)", where);
    if (k > 0 && !(p->time[k] > p->time[k - 1]))
        return fail(path, "%s: time %g is not after the previous key's %g", where, (double)p->time[k],
                    (double)p->time[k - 1]);
    return OB_OK;
}

static ob_error parse_path(const char *path, int index, const cJSON *obj, ob_camera_path *p)
{
    char where[96] = "";
    snprintf(where, sizeof where, "paths[%d]", index);
    if (!cJSON_IsObject(obj)) return fail(path, "%s: expected an object, got %s", where, json_type_name(obj));
    memset(p, 0, sizeof *p);
    bool has_name = false, has_keys = false;
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *key = it->string;
        char field[160] = "";
        snprintf(field, sizeof field, "%s.%s", where, key);
        if (is_comment_key(key)) continue;
        if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
        if (strcmp(key, "name") == 0) {
            if (!cJSON_IsString(it)) return fail(path, "%s: expected a string, got %s", field, json_type_name(it));
            size_t len = strlen(it->valuestring);
            if (len == 0 || len >= sizeof p->name)
                return fail(path, "%s: must be 1 to %zu characters", field, sizeof p->name - 1);
            memcpy(p->name, it->valuestring, len + 1);
            has_name = true;
        } else if (strcmp(key, "keys") == 0) {
            if (!cJSON_IsArray(it)) return fail(path, "%s: expected an array, got %s", field, json_type_name(it));
            int n = cJSON_GetArraySize(it);
            if (n < 2 || n > OB_MAX_PATH_KEYS)
                return fail(path, "%s: %d keyframes, expected 2 to %d", field, n, OB_MAX_PATH_KEYS);
            /* Every key is parsed before it is compared with the one before it. */
            for (int k = 0; k < n; ++k) {
                char kw[200] = "";
                snprintf(kw, sizeof kw, "%s[%d]", field, k);
                ob_error err = parse_key(path, kw, cJSON_GetArrayItem(it, k), p, k);
                if (err != OB_OK) return err;
            }
            p->key_count = n;
            has_keys = true;
        } else {
            static const char *const keys[] = {"name", "keys"};
            return unknown_key(path, field, key, keys, 2, "");
        }
    }
    if (!has_name) return fail(path, "%s: missing \"name\"", where);
    if (!has_keys) return fail(path, "%s (\"%s\"): missing \"keys\"", where, p->name);
    return OB_OK;
}

static ob_error parse_light(const char *path, int index, const cJSON *obj, ob_light *light)
{
    char where[96] = "";
    snprintf(where, sizeof where, "lights[%d]", index);
    if (!cJSON_IsObject(obj)) {
        return fail(path, "%s: expected an object, got %s", where, json_type_name(obj));
    }
    ob_light l = {.color = {1.0f, 1.0f, 1.0f}, .intensity = 1.0f, .spot_inner_deg = 20.0f, .spot_outer_deg = 30.0f};
    bool has_direction = false, has_position = false;
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *key = it->string;
        char field[160] = "";
        snprintf(field, sizeof field, "%s.%s", where, key);
        if (is_comment_key(key)) continue;
        if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
        ob_error err = OB_OK;
        if (strcmp(key, "type") == 0) {
            if (cJSON_IsString(it) && strcmp(it->valuestring, "directional") == 0) l.type = OB_LIGHT_DIRECTIONAL;
            else if (cJSON_IsString(it) && strcmp(it->valuestring, "point") == 0) l.type = OB_LIGHT_POINT;
            else if (cJSON_IsString(it) && strcmp(it->valuestring, "spot") == 0) l.type = OB_LIGHT_SPOT;
            else return fail(path, "%s: expected \"directional\", \"point\" or \"spot\"", field);
        } else if (strcmp(key, "position") == 0) {
            err = read_vec3(path, field, it, l.position);
            has_position = true;
        } else if (strcmp(key, "range") == 0) {
            err = read_number(path, field, it, &l.range);
            if (err == OB_OK && !(l.range > 0.0f)) return fail(path, "%s: range must be > 0", field);
        } else if (strcmp(key, "cone") == 0) {
            if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 2 || !cJSON_IsNumber(cJSON_GetArrayItem(it, 0)) ||
                !cJSON_IsNumber(cJSON_GetArrayItem(it, 1)))
                return fail(path, "%s: expected [inner, outer] half-angles in degrees", field);
            l.spot_inner_deg = (float)cJSON_GetArrayItem(it, 0)->valuedouble;
            l.spot_outer_deg = (float)cJSON_GetArrayItem(it, 1)->valuedouble;
            if (!(l.spot_inner_deg >= 0.0f && l.spot_inner_deg <= l.spot_outer_deg && l.spot_outer_deg < 90.0f))
                return fail(path, "%s: need 0 <= inner <= outer < 90 degrees", field);
        } else if (strcmp(key, "direction") == 0) {
            err = read_vec3(path, field, it, l.direction);
            if (err == OB_OK && !ob_normalize_direction(l.direction)) return fail(path, "%s: direction is zero", field);
            has_direction = true;
        } else if (strcmp(key, "color") == 0) {
            err = read_vec3(path, field, it, l.color);
            if (err == OB_OK && (l.color[0] < 0.0f || l.color[1] < 0.0f || l.color[2] < 0.0f)) {
                return fail(path, "%s: colour components must be >= 0", field);
            }
        } else if (strcmp(key, "intensity") == 0) {
            err = read_number(path, field, it, &l.intensity);
            if (err == OB_OK && l.intensity < 0.0f) {
                return fail(path, "%s: intensity must be >= 0", field);
            }
        } else {
            static const char *const keys[] = {"type", "direction", "position", "color", "intensity", "range", "cone"};
            return unknown_key(path, field, key, keys, 7, "");
        }
        if (err != OB_OK) return err;
    }
    if (!has_direction && l.type != OB_LIGHT_POINT) return fail(path, "%s: missing \"direction\"", where);
    if (!has_position && l.type != OB_LIGHT_DIRECTIONAL) return fail(path, "%s: missing \"position\"", where);
    /* The same check as --light and a host's lights (ob_check_light), named here. */
    if (ob_check_light(&l) != OB_OK) return fail_check(path, where);
    *light = l;
    return OB_OK;
}

/* "ground.walls": [{"x": 1.05}, {"z": -0.8, "height": 2}]: each wall names exactly one of x or z,
 * the plane it stands in, and optionally its height (> 0). */
static ob_error parse_walls(const char *path, const cJSON *arr, sidecar *sc)
{
    if (!cJSON_IsArray(arr)) return fail(path, "ground.walls: expected an array, got %s", json_type_name(arr));
    const int n = cJSON_GetArraySize(arr);
    if (n > MAX_WALLS) return fail(path, "ground.walls: %d walls, at most %d", n, MAX_WALLS);
    for (int w = 0; w < n; ++w) {
        const cJSON *obj = cJSON_GetArrayItem(arr, w);
        char where[64];
        snprintf(where, sizeof where, "ground.walls[%d]", w);
        if (!cJSON_IsObject(obj)) return fail(path, "%s: expected an object, got %s", where, json_type_name(obj));
        int axis = -1;
        float at = 0.0f, height = 0.0f;
        for (const cJSON *it = obj->child; it; it = it->next) {
            const char *key = it->string;
            char field[128];
            snprintf(field, sizeof field, "%s.%s", where, key);
            if (is_comment_key(key)) continue;
            if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
            ob_error err = OB_OK;
            if (strcmp(key, "x") == 0 || strcmp(key, "z") == 0) {
                if (axis >= 0) return fail(path, "%s: a wall stands in x = or z =, not both", where);
                axis = key[0] == 'x' ? 0 : 2;
                err = read_number(path, field, it, &at);
            } else if (strcmp(key, "height") == 0) {
                err = read_number(path, field, it, &height);
                if (err == OB_OK && !(height > 0.0f)) return fail(path, "%s: must be > 0, got %g", field, (double)height);
            } else {
                static const char *const keys[] = {"x", "z", "height"};
                return unknown_key(path, field, key, keys, 3, "");
            }
            if (err != OB_OK) return err;
        }
        if (axis < 0) return fail(path, "%s: missing \"x\" or \"z\" (the plane the wall stands in)", where);
        sc->walls[w].axis = axis;
        sc->walls[w].at = at;
        sc->walls[w].height = height;
    }
    sc->wall_count = n;
    return OB_OK;
}

static ob_error parse_ground(const char *path, const cJSON *obj, sidecar *sc)
{
    if (!cJSON_IsObject(obj)) {
        return fail(path, "ground: expected an object, got %s", json_type_name(obj));
    }
    sc->ground = true;
    sc->ground_color[0] = sc->ground_color[1] = sc->ground_color[2] = 0.8f;
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *key = it->string;
        char field[96] = "";
        snprintf(field, sizeof field, "ground.%s", key);
        if (is_comment_key(key)) continue;
        if (seen_before(obj, it)) return fail(path, "%s: duplicate key", field);
        ob_error err = OB_OK;
        if (strcmp(key, "y") == 0) {
            err = read_number(path, field, it, &sc->ground_y);
            sc->ground_has_y = true;
        } else if (strcmp(key, "size") == 0) {
            err = read_number(path, field, it, &sc->ground_size);
            if (err == OB_OK && !(sc->ground_size > 0.0f)) {
                return fail(path, "%s: must be > 0, got %g", field, (double)sc->ground_size);
            }
        } else if (strcmp(key, "color") == 0) {
            err = read_vec3(path, field, it, sc->ground_color);
            for (int i = 0; i < 3 && err == OB_OK; ++i) {
                if (!(sc->ground_color[i] >= 0.0f && sc->ground_color[i] <= 1.0f)) {
                    return fail(path, "%s: an albedo is in [0, 1]", field);
                }
            }
        } else if (strcmp(key, "walls") == 0) {
            err = parse_walls(path, it, sc);
        } else {
            static const char *const keys[] = {"y", "size", "color", "walls"};
            return unknown_key(path, field, key, keys, 4, "");
        }
        if (err != OB_OK) return err;
    }
    return OB_OK;
}

/* Wall w of the ground: a quad in the plane x = at (or z = at) across the ground's whole side,
 * from the ground up, in the ground's material, its normal toward the model's centre (a wall is
 * seen from the model's side; from behind it is a back face like any other). */
static ob_error add_wall(ob_scene *s, const sidecar *sc, const char *path, int w, int mat, const float centre[3], float h,
                         float model_height)
{
    const int axis = sc->walls[w].axis, other = 2 - axis;
    const float at = sc->walls[w].at;
    const float height = sc->walls[w].height > 0.0f ? sc->walls[w].height : 1.5f * model_height;
    if (!(height > 0.0f) || !isfinite(height)) {
        return fail(path, "ground.walls[%d]: the model has no height; give a \"height\"", w);
    }
    ob_mesh *m = ob_scene_add_mesh(s, 4u, 6u, false);
    if (!m) return OB_ERR_OUT_OF_MEMORY;
    const float facing = centre[axis] >= at ? 1.0f : -1.0f;
    const float along[4] = {centre[other] - h, centre[other] + h, centre[other] + h, centre[other] - h};
    const float up[4] = {centre[1], centre[1], centre[1] + height, centre[1] + height};
    for (uint32_t v = 0; v < 4u; ++v) {
        m->positions[3u * v + (uint32_t)axis] = at;
        m->positions[3u * v + (uint32_t)other] = along[v];
        m->positions[3u * v + 1u] = up[v];
        m->normals[3u * v + (uint32_t)axis] = facing;
    }
    /* Vertices 0, 1, 2 in this order turn counter-clockwise about -x for an x wall (their edges'
     * cross product is (-2h·height, 0, 0)) and about +z for a z wall (0, 0, 2h·height): kept where
     * that is the facing, reversed elsewhere. */
    const bool keep = axis == 0 ? facing < 0.0f : facing > 0.0f;
    const uint32_t ccw[6] = {0u, 1u, 2u, 0u, 2u, 3u}, cw[6] = {0u, 2u, 1u, 0u, 3u, 2u};
    memcpy(m->indices, keep ? ccw : cw, sizeof ccw);
    m->material = mat;
    for (uint32_t v = 0; v < 4u; ++v) {
        for (int i = 0; i < 3; ++i) {
            const float p = m->positions[3u * v + (uint32_t)i];
            if (p < s->bounds_min[i]) s->bounds_min[i] = p;
            if (p > s->bounds_max[i]) s->bounds_max[i] = p;
        }
    }
    return OB_OK;
}

/* The default camera (index 0, framing the model from +x, +z: ob_camera_frame_bounds) looked at
 * the model through a wall standing on its side: bunny-corner's "default" showed the backs of its
 * two walls and no bunny. Mirrored across the model's centre on that axis, it looks from the open
 * side into the corner; where walls stand on both sides of an axis there is no open side, and it
 * stays. */
static void default_camera_off_walls(ob_scene *s, const sidecar *sc)
{
    if (s->camera_count == 0 || strcmp(s->cameras[0].name, "default") != 0) return;
    ob_camera *c = &s->cameras[0];
    for (int axis = 0; axis <= 2; axis += 2) {
        const float eye = c->eye[axis] - c->target[axis];
        bool near_side = false, far_side = false;
        for (int w = 0; w < sc->wall_count; ++w) {
            if (sc->walls[w].axis != axis) continue;
            const float wall = sc->walls[w].at - c->target[axis];
            if (wall * eye > 0.0f) near_side = true;
            else far_side = true;
        }
        if (near_side && !far_side) c->eye[axis] = c->target[axis] - eye;
    }
}

/* The sidecar's ground: one quad (two triangles, counter-clockwise seen from +Y) in its own
 * material, and the bounds grown to hold it. The default camera keeps framing the model, from the
 * open side of its walls (default_camera_off_walls). */
static ob_error add_ground(ob_scene *s, const sidecar *sc, const char *path, const char *material)
{
    float ex = s->bounds_max[0] - s->bounds_min[0], ez = s->bounds_max[2] - s->bounds_min[2];
    float size = sc->ground_size > 0.0f ? sc->ground_size : 4.0f * (ex > ez ? ex : ez);
    if (!(size > 0.0f) || !isfinite(size)) {
        return fail(path, "ground: the model has no horizontal extent; give a \"size\"");
    }
    float y = sc->ground_has_y ? sc->ground_y : s->bounds_min[1];
    float cx = 0.5f * (s->bounds_min[0] + s->bounds_max[0]);
    float cz = 0.5f * (s->bounds_min[2] + s->bounds_max[2]);
    float h = 0.5f * size;
    int mat = ob_scene_add_material(s, material, sc->ground_color[0], sc->ground_color[1], sc->ground_color[2]);
    if (mat < 0) return OB_ERR_OUT_OF_MEMORY;
    ob_mesh *m = ob_scene_add_mesh(s, 4u, 6u, false);
    if (!m) {
        --s->material_count; /* leave the scene as it was */
        return OB_ERR_OUT_OF_MEMORY;
    }
    const float corners[4][2] = {{cx - h, cz - h}, {cx + h, cz - h}, {cx + h, cz + h}, {cx - h, cz + h}};
    for (uint32_t v = 0; v < 4u; ++v) {
        m->positions[3u * v + 0u] = corners[v][0];
        m->positions[3u * v + 1u] = y;
        m->positions[3u * v + 2u] = corners[v][1];
        m->normals[3u * v + 1u] = 1.0f;
    }
    /* (x0, z0) -> (x0, z1) -> (x1, z1) turns counter-clockwise about +Y. */
    const uint32_t idx[6] = {0u, 3u, 2u, 0u, 2u, 1u};
    memcpy(m->indices, idx, sizeof idx);
    m->material = mat;
    const float model_height = s->bounds_max[1] - s->bounds_min[1];
    const float lo[3] = {cx - h, y, cz - h}, hi[3] = {cx + h, y, cz + h};
    for (int i = 0; i < 3; ++i) {
        if (lo[i] < s->bounds_min[i]) s->bounds_min[i] = lo[i];
        if (hi[i] > s->bounds_max[i]) s->bounds_max[i] = hi[i];
    }
    for (int w = 0; w < sc->wall_count; ++w) {
        ob_error err = add_wall(s, sc, path, w, mat, (float[3]){cx, y, cz}, h, model_height);
        if (err != OB_OK) return err;
    }
    default_camera_off_walls(s, sc);
    return OB_OK;
}

/* Read the whole file as a NUL-terminated string (malloc'd). */
static ob_error read_text(const char *path, char **out)
{
    *out = NULL;
    /* A FIFO or a device named as a sidecar fails at once instead of blocking (file.h). */
    FILE *f = ob_fopen_regular(path, "sidecar");
    if (!f) return OB_ERR_IO;
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    while (buf) {
        if (len + 1 >= cap) {
            if (cap >= SIDECAR_MAX_BYTES) break;
            char *bigger = realloc(buf, cap * 2);
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - 1 - len, f);
        len += got;
        if (got == 0) break;
    }
    bool read_error = ferror(f) != 0;
    fclose(f);
    if (!buf) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory reading", path);
    if (read_error) {
        free(buf);
        return ob_set_error(OB_ERR_IO, "%s: read error (is it a directory?)", path);
    }
    if (len + 1 >= cap && cap >= SIDECAR_MAX_BYTES) {
        free(buf);
        return fail(path, "larger than %u bytes: not a sidecar", SIDECAR_MAX_BYTES);
    }
    buf[len] = '\0';
    if (strlen(buf) != len) {
        free(buf);
        return fail(path, "contains a NUL byte: not JSON text");
    }
    *out = buf;
    return OB_OK;
}

static ob_error parse_file(const char *path, sidecar *sc)
{
    memset(sc, 0, sizeof *sc);
    if (!path) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "sidecar path is NULL");
    char *text = NULL;
    ob_error err = read_text(path, &text);
    if (err != OB_OK) return err;

    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        /* Line and column of the parse failure, counted from the start of the text. */
        int line = 1, col = 1;
        for (const char *c = text; end && c < end && *c; ++c) {
            if (*c == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
        }
        free(text);
        return fail(path, "not valid JSON (error near line %d, column %d)", line, col);
    }
    free(text);
    if (!cJSON_IsObject(root)) {
        err = fail(path, "top level: expected an object, got %s", json_type_name(root));
        cJSON_Delete(root);
        return err;
    }

    for (const cJSON *it = root->child; it && err == OB_OK; it = it->next) {
        const char *key = it->string;
        if (is_comment_key(key)) continue;
        if (seen_before(root, it)) {
            err = fail(path, "%s: duplicate key", key);
        } else if (strcmp(key, "model") == 0) {
            if (!cJSON_IsString(it) || !it->valuestring[0]) {
                err = fail(path, "model: expected a non-empty path string");
            } else if (strlen(it->valuestring) >= sizeof sc->model) {
                err = fail(path, "model: path too long");
            } else {
                memcpy(sc->model, it->valuestring, strlen(it->valuestring) + 1);
            }
        } else if (strcmp(key, "up") == 0) {
            const char *v = cJSON_IsString(it) ? it->valuestring : "";
            if (strcmp(v, "y") == 0 || strcmp(v, "Y") == 0) {
                sc->up = OB_UP_Y;
            } else if (strcmp(v, "z") == 0 || strcmp(v, "Z") == 0) {
                sc->up = OB_UP_Z;
            } else {
                err = fail(path, "up: expected \"y\" or \"z\"");
            }
        } else if (strcmp(key, "ao_radius") == 0) {
            err = read_number(path, "ao_radius", it, &sc->ao_radius);
            if (err == OB_OK && !(sc->ao_radius > 0.0f)) {
                err = fail(path, "ao_radius: must be > 0, got %g", (double)sc->ao_radius);
            }
        } else if (strcmp(key, "cameras") == 0) {
            int n = 0;
            if ((err = array_entries(path, key, it, OB_MAX_CAMERAS - 1, "presets", &n)) != OB_OK) break;
            for (int i = 0; i < n && err == OB_OK; ++i) {
                err = parse_camera(path, i, cJSON_GetArrayItem(it, i), &sc->cameras[i]);
                for (int j = 0; j < i && err == OB_OK; ++j) {
                    if (strcmp(sc->cameras[j].name, sc->cameras[i].name) == 0) {
                        err = fail(path, "cameras[%d]: name \"%s\" already used by cameras[%d]",
                                   i, sc->cameras[i].name, j);
                    }
                }
            }
            sc->camera_count = n;
        } else if (strcmp(key, "paths") == 0) {
            int n = 0;
            if ((err = array_entries(path, key, it, OB_MAX_PATHS, "paths", &n)) != OB_OK) break;
            for (int i = 0; i < n && err == OB_OK; ++i) {
                err = parse_path(path, i, cJSON_GetArrayItem(it, i), &sc->paths[i]);
                for (int j = 0; j < i && err == OB_OK; ++j)
                    if (strcmp(sc->paths[j].name, sc->paths[i].name) == 0)
                        err = fail(path, "paths[%d]: name \"%s\" already used by paths[%d]", i, sc->paths[i].name, j);
            }
            sc->path_count = n;
        } else if (strcmp(key, "lights") == 0) {
            int n = 0;
            if ((err = array_entries(path, key, it, OB_MAX_LIGHTS, "lights", &n)) != OB_OK) break;
            for (int i = 0; i < n && err == OB_OK; ++i) {
                err = parse_light(path, i, cJSON_GetArrayItem(it, i), &sc->lights[i]);
                if (err == OB_OK) sc->light_count = i + 1;
            }
        } else if (strcmp(key, "ground") == 0) {
            err = parse_ground(path, it, sc);
        } else {
            static const char *const keys[] = {"model", "up", "ao_radius", "cameras", "paths", "lights", "ground"};
            err = unknown_key(path, key, key, keys, 7, ", or _comment");
        }
    }
    cJSON_Delete(root);
    return err;
}

ob_error ob_sidecar_peek(const char *path, char *model_out, size_t model_len, ob_up_axis *up_out)
{
    sidecar *sc = malloc(sizeof *sc);
    if (!sc) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sidecar");
    ob_error err = parse_file(path, sc);
    if (err == OB_OK && model_out && model_len > 0) {
        if (strlen(sc->model) >= model_len) {
            err = fail(path, "model: path too long");
        } else {
            memcpy(model_out, sc->model, strlen(sc->model) + 1);
        }
    }
    if (err == OB_OK && up_out) *up_out = sc->up;
    free(sc);
    return err;
}

ob_error ob_scene_apply_sidecar(ob_scene *s, const char *json_path)
{
    if (!s) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_scene_apply_sidecar: scene is NULL");
    sidecar *sc = malloc(sizeof *sc);
    if (!sc) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sidecar");
    ob_error err = parse_file(json_path, sc);
    if (err != OB_OK) {
        free(sc);
        return err;
    }
    /* Count the slots the new presets need before touching the scene, so a failure leaves it as
     * it was. */
    int fresh = 0;
    for (int i = 0; i < sc->camera_count; ++i) {
        bool replaces = false;
        for (int j = 0; j < s->camera_count; ++j) {
            if (strcmp(s->cameras[j].name, sc->cameras[i].name) == 0) replaces = true;
        }
        if (!replaces) ++fresh;
    }
    if (s->camera_count + fresh > OB_MAX_CAMERAS) {
        err = fail(json_path, "cameras: %d presets would exceed the limit of %d", fresh,
                   OB_MAX_CAMERAS);
        free(sc);
        return err;
    }
    if (sc->ground) {
        err = add_ground(s, sc, json_path, "ground");
        if (err != OB_OK) {
            free(sc);
            return err;
        }
    }
    for (int i = 0; i < sc->camera_count; ++i) ob_scene_add_camera(s, &sc->cameras[i]);
    /* A later sidecar replaces its paths as a whole (a scene has no other source of them). */
    if (sc->path_count > 0) {
        memcpy(s->paths, sc->paths, sizeof sc->paths);
        s->path_count = sc->path_count;
    }
    if (sc->ao_radius > 0.0f) {
        /* AO_R counts occluders within R: past the scene's own diagonal no point has one farther
         * away, so a larger R means nothing, and a huge one (3e38) left every method's radius
         * silently clamped to its table's maximum while the reference traced the sidecar's
         * (no occlusion in the AO, exit 0). Checked after the ground, which is scene too. */
        double d2 = 0.0;
        for (int i = 0; i < 3; ++i) {
            double e = (double)s->bounds_max[i] - (double)s->bounds_min[i];
            d2 += e * e;
        }
        double diagonal = sqrt(d2);
        if (!((double)sc->ao_radius <= diagonal)) {
            err = fail(json_path, "ao_radius: %g is longer than the whole scene (the diagonal of its bounds, ground "
                       "included, is %.6g): expected at most %.6g", (double)sc->ao_radius, diagonal, diagonal);
            free(sc);
            return err;
        }
        s->ao_radius = sc->ao_radius;
    }
    if (sc->light_count > 0) {
        memcpy(s->lights, sc->lights, sizeof sc->lights);
        s->light_count = sc->light_count;
    }
    free(sc);
    return OB_OK;
}

ob_error ob_scene_add_automatic_ground(ob_scene *s, const char *model)
{
    /* A sidecar's "ground": {}: the defaults of parse_ground. */
    sidecar sc = {.ground = true, .ground_color = {0.8f, 0.8f, 0.8f}};
    return add_ground(s, &sc, model, OB_AUTOMATIC_GROUND_MATERIAL);
}
