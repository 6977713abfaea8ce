/* Ray-traced ground truth (Embree 3): AO_R (Belonogov 2018 eq. 2.6-2.7, t = 1) and a one-bounce diffuse
 * reference, both from the very G-buffer points the screen-space methods see, so error maps
 * compare like with like (docs/architecture.md "Conventions").
 *
 * Estimator: cosine-weighted directions (SSDO thesis eq. 5.2, p = cos(theta)/pi) make
 * AO_R = 1/pi * integral V cos = E[V], the plain mean of the ray visibilities; its standard error
 * is that of a Bernoulli mean, sqrt(p (1 - p) / (n - 1)). Independent random numbers (not
 * stratified) on purpose: then that standard error is honest, and the tests can hold the estimate
 * to 3 of them against an independent quadrature.
 *
 * Determinism: points are handed out in chunks to pthreads, but each point's PCG32 is seeded from
 * (seed, point index) and writes only its own outputs, so the bytes do not depend on the thread
 * count or the schedule. */
#include "eval/reference.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "base/progress.h"
#include "sampling/sampling.h"
#include "scene/scene.h"

/* 512: the mean per-point standard error at 640x480 is 0.0088 on the Cornell box (R = 0.1 m),
 * where 256 gave 0.0125; corner and FZK-Haus were under 0.01 already at 256. */
#define REF_DEFAULT_SPP 512
/* Points per work item: big enough that the atomic counter is not contended, small enough that
 * two threads finish together on 640x480 (1200 chunks). */
#define REF_CHUNK 256
/* Ray origins leave the surface by this fraction of the scene's bounds diagonal: well above float
 * round-off at the scene's scale (1e-7 relative), well below any feature an AO radius resolves. */
#define REF_EPS_REL 1e-4f

/* ---- small vector helpers ------------------------------------------------------------------- */

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* An orthonormal basis around a unit n (Duff et al. 2017, "Building an Orthonormal Basis,
 * Revisited"): branch-free and continuous except at one sign flip, so no direction is favoured. */
static void basis(const float n[3], float t[3], float b[3])
{
    float sign = copysignf(1.0f, n[2]);
    float a = -1.0f / (sign + n[2]);
    float c = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

static bool normalize3(const float in[3], float out[3])
{
    float len = sqrtf(dot3(in, in));
    if (!(len > 0.0f) || !isfinite(len)) return false;
    for (int k = 0; k < 3; ++k) out[k] = in[k] / len;
    return true;
}

/* ---- lights: the CPU twin of shaders/lighting.glsl ------------------------------------------ */

static float smoothstepf(float e0, float e1, float x)
{
    float t = e1 != e0 ? (x - e0) / (e1 - e0) : (x < e0 ? 0.0f : 1.0f);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

bool ob_reference_light(const ob_light *light, const float p[3], const float n[3], float l_out[3], float *dist_out,
                        float rgb_out[3])
{
    /* Direction normalised as ob_lighting_setup does, +Y when it is zero. */
    float dir[3] = {0.0f, 1.0f, 0.0f};
    if (!normalize3(light->direction, dir)) {
        dir[0] = 0.0f;
        dir[1] = 1.0f;
        dir[2] = 0.0f;
    }
    float falloff = 1.0f;
    float dist = INFINITY;
    float l[3] = {dir[0], dir[1], dir[2]};
    if (light->type != OB_LIGHT_DIRECTIONAL) {
        float to[3] = {light->position[0] - p[0], light->position[1] - p[1], light->position[2] - p[2]};
        float dist2 = fmaxf(dot3(to, to), 1e-8f);
        dist = sqrtf(dist2);
        for (int k = 0; k < 3; ++k) l[k] = to[k] / dist;
        falloff = 1.0f / dist2;
        if (light->range > 0.0f) {
            /* The (1 - (d/range)^4)^2 window. */
            float x = dist2 / (light->range * light->range);
            float w = 1.0f - x * x;
            w = w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
            falloff *= w * w;
        }
        if (light->type == OB_LIGHT_SPOT) {
            float cos_inner = cosf(light->spot_inner_deg * 0.01745329252f);
            float cos_outer = cosf(light->spot_outer_deg * 0.01745329252f);
            float neg_l[3] = {-l[0], -l[1], -l[2]};
            falloff *= smoothstepf(cos_outer, cos_inner, dot3(neg_l, dir));
        }
    }
    float ndl = fmaxf(dot3(n, l), 0.0f);
    float scale = ndl * falloff * light->intensity;
    for (int k = 0; k < 3; ++k) {
        l_out[k] = l[k];
        rgb_out[k] = scale > 0.0f ? light->color[k] * scale : 0.0f;
    }
    *dist_out = dist;
    return scale > 0.0f;
}

/* ---- random numbers ------------------------------------------------------------------------- */

void ob_reference_point_rng(struct ob_rng *rng, uint64_t seed, size_t index)
{
    /* SplitMix64 of (seed, index) as the state and the index as the stream: neighbouring points
     * get unrelated sequences even for seeds that differ in one bit. */
    uint64_t z = seed + 0x9e3779b97f4a7c15ull * ((uint64_t)index + 1u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    ob_rng_seed(rng, z, (uint64_t)index);
}

/* ---- Embree scene ----------------------------------------------------------------------------- */

static const char *rtc_error_name(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
    }
    return "unknown Embree error";
}

typedef struct ref_bvh {
    RTCDevice device;
    RTCScene scene;
} ref_bvh;

static void bvh_destroy(ref_bvh *b)
{
    if (b->scene) rtcReleaseScene(b->scene);
    if (b->device) rtcReleaseDevice(b->device);
    b->scene = NULL;
    b->device = NULL;
}

static ob_error bvh_fail(ref_bvh *b, const char *what)
{
    enum RTCError e = b->device ? rtcGetDeviceError(b->device) : rtcGetDeviceError(NULL);
    bvh_destroy(b);
    if (e == RTC_ERROR_OUT_OF_MEMORY) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "Embree %s: out of memory", what);
    return ob_set_error(OB_ERR_MODEL, "Embree %s failed: %s", what, rtc_error_name(e));
}

/* One triangle geometry per mesh, its geometry ID the mesh index, so a hit names its material. */
static ob_error bvh_build(const ob_scene *s, ref_bvh *b)
{
    memset(b, 0, sizeof *b);
    /* verbose=0: library code never prints. */
    b->device = rtcNewDevice("verbose=0");
    if (!b->device) return bvh_fail(b, "rtcNewDevice");
    b->scene = rtcNewScene(b->device);
    if (!b->scene) return bvh_fail(b, "rtcNewScene");
    /* Robust traversal: no rays slipping through shared edges of the walls' grid cells, where a
     * leak would read as spurious visibility. */
    rtcSetSceneFlags(b->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(b->scene, RTC_BUILD_QUALITY_HIGH);
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        uint32_t tris = mesh->index_count / 3u;
        if (tris == 0 || mesh->vertex_count == 0) continue;
        RTCGeometry g = rtcNewGeometry(b->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!g) return bvh_fail(b, "rtcNewGeometry");
        /* Embree's own buffers (not shared ones): it pads them for its 16-byte loads. */
        float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                           mesh->vertex_count);
        unsigned *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                tris);
        if (!v || !idx) {
            rtcReleaseGeometry(g);
            return bvh_fail(b, "rtcSetNewGeometryBuffer");
        }
        memcpy(v, mesh->positions, (size_t)mesh->vertex_count * 3 * sizeof(float));
        memcpy(idx, mesh->indices, (size_t)tris * 3 * sizeof(unsigned));
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(b->scene, g, (unsigned)m);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(b->scene);
    if (rtcGetDeviceError(b->device) != RTC_ERROR_NONE) return bvh_fail(b, "rtcCommitScene");
    return OB_OK;
}

static float scene_eps(const ob_scene *s)
{
    float d[3] = {s->bounds_max[0] - s->bounds_min[0], s->bounds_max[1] - s->bounds_min[1],
                  s->bounds_max[2] - s->bounds_min[2]};
    float diag = sqrtf(dot3(d, d));
    return isfinite(diag) && diag > 0.0f ? REF_EPS_REL * diag : REF_EPS_REL;
}

static void make_ray(struct RTCRay *r, const float o[3], const float d[3], float tfar)
{
    memset(r, 0, sizeof *r);
    r->org_x = o[0];
    r->org_y = o[1];
    r->org_z = o[2];
    r->tnear = 0.0f;
    r->dir_x = d[0];
    r->dir_y = d[1];
    r->dir_z = d[2];
    r->time = 0.0f;
    r->tfar = tfar;
    r->mask = 0xFFFFFFFFu;
    r->flags = 0;
}

static bool occluded(RTCScene scene, const float o[3], const float d[3], float tfar)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay r;
    make_ray(&r, o, d, tfar);
    rtcOccluded1(scene, &ctx, &r);
    /* Embree marks an occluded ray by setting tfar to -inf. */
    return r.tfar < 0.0f;
}

/* ---- the worker pool ------------------------------------------------------------------------ */

typedef struct ref_job ref_job;
typedef void (*ref_point_fn)(const ref_job *job, size_t index, struct ob_rng *rng);

struct ref_job {
    const ob_scene *scene;
    RTCScene rtc;
    const float *positions, *normals, *albedo;
    size_t count;
    int spp;
    float radius; /* tfar of the hemisphere rays (INFINITY = unbounded) */
    float eps;
    uint64_t seed;
    const ob_light *lights;
    int light_count;
    float ambient[3];
    float *ao_out, *stderr_out, *rgb_out;
    ref_point_fn fn;
    bool progress;
    const char *what;     /* the progress label: "reference AO" or "reference bounce" */
    ob_progress bar;
    atomic_size_t next_chunk;
};

static void *worker(void *arg)
{
    ref_job *job = arg;
    size_t chunks = (job->count + REF_CHUNK - 1) / REF_CHUNK;
    for (;;) {
        size_t c = atomic_fetch_add(&job->next_chunk, 1);
        if (c >= chunks) break;
        size_t end = (c + 1) * REF_CHUNK < job->count ? (c + 1) * REF_CHUNK : job->count;
        for (size_t i = c * REF_CHUNK; i < end; ++i) {
            ob_rng rng = {0, 0};
            ob_reference_point_rng(&rng, job->seed, i);
            job->fn(job, i, &rng);
        }
        if (job->progress) ob_progress_advance(&job->bar, (long long)(end - c * REF_CHUNK), NULL);
    }
    return NULL;
}

static ob_error run_job(ref_job *job, int threads)
{
    if (threads <= 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    size_t chunks = (job->count + REF_CHUNK - 1) / REF_CHUNK;
    if ((size_t)threads > chunks) threads = chunks > 0 ? (int)chunks : 1;
    atomic_init(&job->next_chunk, 0);
    pthread_t *tids = calloc((size_t)threads, sizeof *tids);
    if (!tids) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "reference: no memory for %d threads", threads);
    if (job->progress) {
        char label[96];
        snprintf(label, sizeof label, "%s (%zu points x %d rays)", job->what, job->count, job->spp);
        ob_progress_begin(&job->bar, label, (long long)job->count);
    }
    int started = 0;
    /* The calling thread works too; extra threads that fail to start only cost speed. */
    for (int t = 1; t < threads; ++t) {
        if (pthread_create(&tids[started], NULL, worker, job) != 0) break;
        ++started;
    }
    worker(job);
    for (int t = 0; t < started; ++t) pthread_join(tids[t], NULL);
    if (job->progress) ob_progress_end(&job->bar);
    free(tids);
    return OB_OK;
}

/* A cosine-weighted direction around n from the point's stream. */
static void cosine_dir(const float n[3], const float t[3], const float b[3], struct ob_rng *rng, float d[3])
{
    double r1 = (double)ob_rng_float(rng);
    double r2 = (double)ob_rng_float(rng);
    float local[3] = {0.0f, 0.0f, 0.0f};
    ob_direction_cosine(r1, r2, local);
    for (int k = 0; k < 3; ++k) d[k] = local[0] * t[k] + local[1] * b[k] + local[2] * n[k];
}

static bool point_normal(const ref_job *job, size_t i, float n[3])
{
    const float *np = job->normals + 3 * i;
    if (np[0] == 0.0f && np[1] == 0.0f && np[2] == 0.0f) return false;
    return normalize3(np, n);
}

/* ---- AO ------------------------------------------------------------------------------------- */

static void ao_point(const ref_job *job, size_t i, struct ob_rng *rng)
{
    float n[3] = {0.0f, 0.0f, 0.0f};
    if (!point_normal(job, i, n)) {
        job->ao_out[i] = 1.0f;
        if (job->stderr_out) job->stderr_out[i] = 0.0f;
        return;
    }
    float t[3] = {0.0f, 0.0f, 0.0f}, b[3] = {0.0f, 0.0f, 0.0f};
    basis(n, t, b);
    const float *p = job->positions + 3 * i;
    float o[3] = {p[0] + job->eps * n[0], p[1] + job->eps * n[1], p[2] + job->eps * n[2]};
    int open = 0;
    for (int s = 0; s < job->spp; ++s) {
        float d[3] = {0.0f, 0.0f, 0.0f};
        cosine_dir(n, t, b, rng, d);
        if (!occluded(job->rtc, o, d, job->radius)) ++open;
    }
    double mean = (double)open / (double)job->spp;
    job->ao_out[i] = (float)mean;
    if (job->stderr_out) {
        double var = job->spp > 1 ? mean * (1.0 - mean) / (double)(job->spp - 1) : 0.0;
        job->stderr_out[i] = (float)sqrt(var);
    }
}

static ob_error check_common(const ob_scene *scene, const float *positions, const float *normals, size_t count,
                             const ob_reference_desc *desc, const void *out, const char *fn)
{
    if (!scene || !desc) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: scene or desc is NULL", fn);
    if (count > 0 && (!positions || !normals || !out))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: positions, normals or output is NULL", fn);
    if (desc->spp < 0 || desc->spp == 1)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: spp %d (need 0 for the default, or >= 2)", fn, desc->spp);
    if (desc->threads < 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: threads %d < 0", fn, desc->threads);
    if (!isfinite(desc->radius)) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: radius is not finite", fn);
    return OB_OK;
}

ob_error ob_reference_ao(const ob_scene *scene, const float *positions, const float *normals, size_t count,
                         const ob_reference_desc *desc, float *ao_out, float *stderr_out)
{
    ob_error err = check_common(scene, positions, normals, count, desc, ao_out, "ob_reference_ao");
    if (err != OB_OK) return err;
    if (!(desc->radius > 0.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_reference_ao: radius %g must be > 0", (double)desc->radius);
    if (count == 0) return OB_OK;
    ref_bvh bvh = {NULL, NULL};
    err = bvh_build(scene, &bvh);
    if (err != OB_OK) return err;
    ref_job job = {
        .scene = scene,
        .rtc = bvh.scene,
        .positions = positions,
        .normals = normals,
        .count = count,
        .spp = desc->spp ? desc->spp : REF_DEFAULT_SPP,
        .radius = desc->radius,
        .eps = scene_eps(scene),
        .seed = desc->seed,
        .ao_out = ao_out,
        .stderr_out = stderr_out,
        .fn = ao_point,
        .progress = desc->progress,
        .what = "reference AO",
    };
    err = run_job(&job, desc->threads);
    bvh_destroy(&bvh);
    return err;
}

/* ---- one bounce ----------------------------------------------------------------------------- */

/* Diffuse direct light at p (no albedo), with a shadow ray per contributing light. */
static void direct_light(const ref_job *job, const float p[3], const float n[3], float out[3])
{
    float o[3] = {p[0] + job->eps * n[0], p[1] + job->eps * n[1], p[2] + job->eps * n[2]};
    out[0] = out[1] = out[2] = 0.0f;
    for (int li = 0; li < job->light_count; ++li) {
        float l[3] = {0.0f, 0.0f, 0.0f}, rgb[3] = {0.0f, 0.0f, 0.0f};
        float dist = 0.0f;
        if (!ob_reference_light(&job->lights[li], p, n, l, &dist, rgb)) continue;
        /* Stop short of a point light so a lamp's own fixture geometry beyond it cannot count. */
        float tfar = isfinite(dist) ? fmaxf(dist - job->eps, 0.0f) : INFINITY;
        if (occluded(job->rtc, o, l, tfar)) continue;
        for (int k = 0; k < 3; ++k) out[k] += rgb[k];
    }
}

/* The hit's interpolated vertex normal, turned toward the ray, and its material's diffuse colour. */
static void hit_surface(const ob_scene *s, const struct RTCHit *h, const float dir[3], float n[3], float albedo[3])
{
    const ob_mesh *m = &s->meshes[h->geomID];
    const uint32_t *tri = m->indices + 3u * h->primID;
    float w0 = 1.0f - h->u - h->v;
    float interp[3] = {0.0f, 0.0f, 0.0f};
    for (int k = 0; k < 3; ++k)
        interp[k] = m->normals ? w0 * m->normals[3 * tri[0] + k] + h->u * m->normals[3 * tri[1] + k] +
                                     h->v * m->normals[3 * tri[2] + k]
                               : 0.0f;
    float ng[3] = {h->Ng_x, h->Ng_y, h->Ng_z};
    if (!normalize3(interp, n)) normalize3(ng, n);
    if (dot3(n, dir) > 0.0f)
        for (int k = 0; k < 3; ++k) n[k] = -n[k];
    if (m->material >= 0 && m->material < s->material_count) {
        for (int k = 0; k < 3; ++k) albedo[k] = s->materials[m->material].diffuse[k];
    } else {
        albedo[0] = albedo[1] = albedo[2] = 1.0f;
    }
}

static void bounce_point(const ref_job *job, size_t i, struct ob_rng *rng)
{
    float *out = job->rgb_out + 3 * i;
    float n[3] = {0.0f, 0.0f, 0.0f};
    if (!point_normal(job, i, n)) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    const float *p = job->positions + 3 * i;
    const float *a = job->albedo + 3 * i;
    float direct[3] = {0.0f, 0.0f, 0.0f};
    direct_light(job, p, n, direct);

    float t[3] = {0.0f, 0.0f, 0.0f}, b[3] = {0.0f, 0.0f, 0.0f};
    basis(n, t, b);
    float o[3] = {p[0] + job->eps * n[0], p[1] + job->eps * n[1], p[2] + job->eps * n[2]};
    double gather[3] = {0.0, 0.0, 0.0};
    for (int s = 0; s < job->spp; ++s) {
        float d[3] = {0.0f, 0.0f, 0.0f};
        cosine_dir(n, t, b, rng, d);
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        struct RTCRayHit rh;
        make_ray(&rh.ray, o, d, job->radius);
        memset(&rh.hit, 0, sizeof rh.hit);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(job->rtc, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            /* Open within R: the ambient sky (the AO_R term). */
            for (int k = 0; k < 3; ++k) gather[k] += (double)job->ambient[k];
            continue;
        }
        float hp[3] = {o[0] + rh.ray.tfar * d[0], o[1] + rh.ray.tfar * d[1], o[2] + rh.ray.tfar * d[2]};
        float hn[3] = {0.0f, 0.0f, 0.0f}, ha[3] = {0.0f, 0.0f, 0.0f}, hd[3] = {0.0f, 0.0f, 0.0f};
        hit_surface(job->scene, &rh.hit, d, hn, ha);
        direct_light(job, hp, hn, hd);
        for (int k = 0; k < 3; ++k) gather[k] += (double)(ha[k] * hd[k]);
    }
    for (int k = 0; k < 3; ++k)
        out[k] = a[k] * (direct[k] + (float)(gather[k] / (double)job->spp));
}

ob_error ob_reference_bounce(const ob_scene *scene, const ob_light *lights, int light_count, const float ambient[3],
                             const float *positions, const float *normals, const float *albedo_rgb, size_t count,
                             const ob_reference_desc *desc, float *rgb_out)
{
    ob_error err = check_common(scene, positions, normals, count, desc, rgb_out, "ob_reference_bounce");
    if (err != OB_OK) return err;
    if (light_count < 0 || light_count > OB_MAX_LIGHTS || (light_count > 0 && !lights))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_reference_bounce: light_count %d (0..%d, lights non-NULL)",
                            light_count, OB_MAX_LIGHTS);
    if (count > 0 && !albedo_rgb) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_reference_bounce: albedo is NULL");
    if (count == 0) return OB_OK;
    if (!lights || light_count == 0) {
        lights = scene->lights;
        light_count = scene->light_count;
    }
    ref_bvh bvh = {NULL, NULL};
    err = bvh_build(scene, &bvh);
    if (err != OB_OK) return err;
    ref_job job = {
        .scene = scene,
        .rtc = bvh.scene,
        .positions = positions,
        .normals = normals,
        .albedo = albedo_rgb,
        .count = count,
        .spp = desc->spp ? desc->spp : REF_DEFAULT_SPP,
        .radius = desc->radius > 0.0f ? desc->radius : INFINITY,
        .eps = scene_eps(scene),
        .seed = desc->seed,
        .lights = lights,
        .light_count = light_count,
        .ambient = {ambient ? ambient[0] : 0.0f, ambient ? ambient[1] : 0.0f, ambient ? ambient[2] : 0.0f},
        .rgb_out = rgb_out,
        .fn = bounce_point,
        .progress = desc->progress,
        .what = "reference bounce",
    };
    err = run_job(&job, desc->threads);
    bvh_destroy(&bvh);
    return err;
}

/* ---- G-buffer to world points --------------------------------------------------------------- */

ob_error ob_reference_points(const float *linear_depth, const float *view_normals, int width, int height,
                             const float proj_info[4], const float inv_view[16], float *positions_out,
                             float *normals_out)
{
    if (!linear_depth || !view_normals || !proj_info || !inv_view || !positions_out || !normals_out)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_reference_points: a NULL argument");
    if (width <= 0 || height <= 0)
        return ob_set_error(OB_ERR_BAD_SIZE, "ob_reference_points: size %dx%d", width, height);
    const float *m = inv_view; /* column-major: m[c * 4 + r] */
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            float d = linear_depth[i];
            float *po = positions_out + 3 * i;
            float *no = normals_out + 3 * i;
            if (!(d > 0.0f)) {
                po[0] = po[1] = po[2] = 0.0f;
                no[0] = no[1] = no[2] = 0.0f;
                continue;
            }
            /* shaders/common.glsl ob_view_position: ndc at the pixel centre, in float as the GPU. */
            float ndc_x = ((float)x + 0.5f) * (1.0f / (float)width) * 2.0f - 1.0f;
            float ndc_y = ((float)y + 0.5f) * (1.0f / (float)height) * 2.0f - 1.0f;
            float v[3] = {(ndc_x + proj_info[2]) * d * proj_info[0], (ndc_y + proj_info[3]) * d * proj_info[1], -d};
            const float *vn = view_normals + 3 * i;
            float wn[3] = {0.0f, 0.0f, 0.0f};
            for (int r = 0; r < 3; ++r) {
                po[r] = m[0 + r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r];
                /* mat3(inv_view): the view matrix is rigid, so no inverse transpose is needed. */
                wn[r] = m[0 + r] * vn[0] + m[4 + r] * vn[1] + m[8 + r] * vn[2];
            }
            if (!normalize3(wn, no)) no[0] = no[1] = no[2] = 0.0f;
        }
    }
    return OB_OK;
}
