/* compose.c — the composition of the kernels' slots (atmo/features.h): the small generated code
 * that joins the functions each planned feature gives (its atmo_slots) into the functions the
 * generic integrator calls (kernels/media/media.h lists them), so the integrator names no
 * feature and a new medium or method is a registry row, not an edit of the integrator.
 *
 * The plan places each group's text where its registry row stands (after the fragments that
 * define the functions it calls, before those that call it); a host test gets the same text in
 * the header tools/compose.c writes for its rows. Every function is generated for every scene,
 * as a sum, a product or a dispatch over the features present (the empty sum is the air alone,
 * the empty product 1, the absent source 0), and each feature's term is applied in registry
 * order with the operations the integrator used before it was composed, so the result is the
 * same float for float. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "atmo/features.h"
#include "atmo/gpu_enums.h"

/* A growing text: appends stop at the first overflow, which finish reports. */
typedef struct text {
    char *out;
    size_t size, used;
    int overflow;
} text;

static void put(text *t, const char *fmt, ...)
{
    if (t->overflow)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(t->out + t->used, t->size - t->used, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= t->size - t->used)
        t->overflow = 1;
    else
        t->used += (size_t)n;
}

#define SLOT(f, name) ((f)->slots ? (f)->slots->name : NULL)

/* The one feature that fills a single slot (at offset `which` in atmo_slots), NULL for none;
 * *twice when two do. */
static const char *single(const atmo_feature *const *f, int n, size_t which, int *twice)
{
    const char *found = NULL;
    for (int i = 0; i < n; i++) {
        const char *name = f[i]->slots ? *(const char *const *)((const char *)f[i]->slots + which)
                                       : NULL;
        if (name && found)
            *twice = 1;
        if (name)
            found = name;
    }
    return found;
}

#define HEAD "ATMO_FN %s %s(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, "

static void compose_media_at(text *t, const atmo_feature *const *f, int n)
{
    put(t, "/* The media at a point (media.h): the air, then each medium's coefficients. */\n");
    put(t, HEAD "const medium_point *q)\n{\n", "media_sample", "media_at");
    put(t, "    media_sample m = media_air_at(s, q);\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], media_add))
            put(t, "    %s(s, ATMO_LUT_ARGS, q, &m);\n", f[i]->slots->media_add);
    put(t, "    return m;\n}\n\n");

    put(t, "/* The phase function of component k (media.h). */\n");
    put(t, HEAD "int k, float nu)\n{\n", "vec3", "media_phase");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], component) && SLOT(f[i], media_phase))
            put(t, "    if (k == MEDIA_%s)\n        return %s(s, ATMO_LUT_ARGS, nu);\n",
                f[i]->slots->component, f[i]->slots->media_phase);
    put(t, "    return media_air_phase(s, k, nu);\n}\n\n");

    put(t, "/* x times the sun's transmittance to q through each shadowing medium. */\n");
    put(t, HEAD "const medium_point *q, vec3 x)\n{\n", "vec3", "media_sun_attenuate");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], media_sun))
            put(t, "    x = v3_mul(x, %s(s, ATMO_LUT_ARGS, q));\n", f[i]->slots->media_sun);
    put(t, "    return x;\n}\n\n");

    put(t, "/* The same at a surface point (each medium's media_sun_surface where it has one). */\n");
    put(t, HEAD "const medium_point *q, vec3 x)\n{\n", "vec3", "media_sun_surface_attenuate");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], media_sun))
            put(t, "    x = v3_mul(x, %s(s, ATMO_LUT_ARGS, q));\n",
                SLOT(f[i], media_sun_surface) ? f[i]->slots->media_sun_surface
                                              : f[i]->slots->media_sun);
    put(t, "    return x;\n}\n\n");
}

/* The condition under which a walk in mode `mode` (media.h's MEDIA_WALK_*) includes medium f's
 * majorant: the volume media only in volume mode, the media of exact sun transmittance only in
 * the walk of the media (not toward the sun), the others in every mode but volume mode (no
 * condition where the composition has no volume medium). */
static const char *walk_condition(const atmo_feature *f, int volumes, int state)
{
    static const char *const begin[3] = {"if (mode == MEDIA_WALK_VOLUME)\n        ",
                                         "if (mode == MEDIA_WALK_MEDIA)\n        ",
                                         "if (mode != MEDIA_WALK_VOLUME)\n        "};
    static const char *const segment[3] = {"if (mm->mode == MEDIA_WALK_VOLUME) ",
                                           "if (mm->mode == MEDIA_WALK_MEDIA) ",
                                           "if (mm->mode != MEDIA_WALK_VOLUME) "};
    int k = f->slots->volume_at ? 0 : f->slots->sun_exact ? 1 : volumes ? 2 : -1;
    return k < 0 ? "" : state ? segment[k] : begin[k];
}

/* The media of the Monte Carlo walk (kernels/media/media_walk.h): their majorants, summed over
 * the media that give one for the walk's mode (a walk toward the sun leaves out those whose sun
 * transmittance is exact and takes that from media_sun_attenuate's terms instead; a walk in
 * volume mode has the volume media alone), the extinction a walk toward the sun tracks, and each
 * component's direction sampling and roulette gain. */
static void compose_majorant(text *t, const atmo_feature *const *f, int n, int volumes)
{
    int tracked = 0, air = 0;
    for (int i = 0; i < n; i++) {
        tracked += SLOT(f[i], majorant_begin) != NULL && !f[i]->slots->volume_at;
        air |= f[i]->slots && f[i]->slots->volume_air;
    }
    put(t, "/* The media with a majorant of their own (beyond the air's), the volume media, and\n"
           " * whether the air is a volume medium of the path tracer's walk too. */\n");
    put(t, "#define MEDIA_TRACKED %d\n#define MEDIA_VOLUME %d\n#define MEDIA_VOLUME_AIR %d\n\n",
        tracked, volumes, air);
    put(t, "/* Their majorants' states along one ray. */\n");
    put(t, "typedef struct media_majorant {\n    int mode; /* the walk's (media.h) */\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], majorant_begin))
            put(t, "    %s %s;\n", f[i]->slots->majorant_state, f[i]->name);
    put(t, "} media_majorant;\n\n");
    put(t, "ATMO_FN void media_majorant_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
           "                                  vec3 origin, vec3 dir, float r, float mu, float end,\n"
           "                                  int mode, media_majorant *mm)\n{\n"
           "    mm->mode = mode;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], majorant_begin))
            put(t, "    %s%s(s, ATMO_LUT_ARGS, origin, dir, r, mu, end, &mm->%s);\n",
                walk_condition(f[i], volumes, 0), f[i]->slots->majorant_begin, f[i]->name);
    put(t, "}\n\n");
    put(t, "/* The media's majorant from t up to *seg_end (the air's is the walk's own). */\n");
    put(t, HEAD "media_majorant *mm, float t, float *seg_end)\n{\n", "float",
        "media_majorant_segment");
    put(t, "    float rate = 0.0f, e = INFINITY;\n    *seg_end = INFINITY;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], majorant_begin))
            put(t, "    %s{\n        rate += %s(s, ATMO_LUT_ARGS, &mm->%s, t, &e);\n"
                   "        *seg_end = fminf(*seg_end, e);\n    }\n",
                walk_condition(f[i], volumes, 1), f[i]->slots->majorant_segment, f[i]->name);
    put(t, "    (void)e;\n    return rate;\n}\n\n");

    put(t, "/* The extinction a walk toward the sun tracks: the media's, less the exact ones'. */\n");
    put(t, HEAD "const medium_point *q)\n{\n", "vec3", "media_tracked_extinction");
    put(t, "    media_sample m = media_air_at(s, q);\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], media_add) && !f[i]->slots->sun_exact)
            put(t, "    %s(s, ATMO_LUT_ARGS, q, &m);\n", f[i]->slots->media_add);
    put(t, "    return m.extinction;\n}\n\n");
    put(t, "/* x times the sun's transmittance to q through the media whose sun is exact. */\n");
    put(t, HEAD "const medium_point *q, vec3 x)\n{\n", "vec3", "media_sun_exact_attenuate");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], media_sun) && f[i]->slots->sun_exact)
            put(t, "    x = v3_mul(x, %s(s, ATMO_LUT_ARGS, q));\n", f[i]->slots->media_sun);
    put(t, "    return x;\n}\n\n");

    put(t, "/* A new direction at a scattering by component k (the air's: its phase, exactly). */\n");
    put(t, HEAD "int k, vec3 dir, vec3 to_sun,\n"
           "                                      vec3 beta, float u1, float u2, rng_stream *g,\n"
           "                                      vec3 *weight)\n{\n", "vec3",
        "media_phase_direction");
    for (int i = 0; i < n; i++) {
        const atmo_slots *sl = f[i]->slots;
        const char *comp = sl ? (sl->walk_component ? sl->walk_component : sl->component) : NULL;
        if (sl && sl->media_direction && comp && !sl->volume_at)
            put(t, "    if (k == MEDIA_%s)\n        return %s(s, ATMO_LUT_ARGS, dir, to_sun, beta, "
                   "u1, u2, g, weight);\n", comp, sl->media_direction);
    }
    put(t, "    return media_air_direction(s, k, dir, u1, u2, weight);\n}\n\n");
    put(t, "/* The factor on a path's roulette survival leaving at cosine nu to the sun. */\n");
    put(t, HEAD "float nu)\n{\n", "float", "media_roulette_gain");
    put(t, "    float gain = 1.0f;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], roulette_gain) && !f[i]->slots->volume_at)
            put(t, "    gain *= %s(s, ATMO_LUT_ARGS, nu);\n", f[i]->slots->roulette_gain);
    put(t, "    return gain;\n}\n\n");
}

/* The path tracer's volume medium (at most one: volume_at's row; media.h): its coefficients,
 * phase function, direction sampling and roulette gain, or no medium (zero extinction, zero
 * phase, weight zero, gain 1) without one. */
static void compose_volume(text *t, const atmo_slots *v)
{
    put(t, "/* The volume medium's extinction at q, its scattering in *scattering. */\n");
    put(t, HEAD "const medium_point *q,\n"
           "                                vec3 *scattering)\n{\n", "vec3", "media_volume_at");
    if (v)
        put(t, "    return %s(s, ATMO_LUT_ARGS, q, scattering);\n}\n\n", v->volume_at);
    else
        put(t, "    (void)q;\n    *scattering = v3(0.0f, 0.0f, 0.0f);\n"
               "    return v3(0.0f, 0.0f, 0.0f);\n}\n\n");
    put(t, "/* Its phase function per steradian at cosine nu. */\n");
    put(t, HEAD "float nu)\n{\n", "vec3", "media_volume_phase");
    if (v)
        put(t, "    return %s(s, ATMO_LUT_ARGS, nu);\n}\n\n", v->media_phase);
    else
        put(t, "    (void)nu;\n    return v3(0.0f, 0.0f, 0.0f);\n}\n\n");
    put(t, "/* A new direction at a scattering by it (weight: phase over the density). */\n");
    put(t, HEAD "vec3 dir, vec3 to_sun, vec3 beta,\n"
           "                                       float u1, float u2, rng_stream *g, "
           "vec3 *weight)\n{\n", "vec3", "media_volume_direction");
    if (v)
        put(t, "    return %s(s, ATMO_LUT_ARGS, dir, to_sun, beta, u1, u2, g, weight);\n}\n\n",
            v->media_direction);
    else
        put(t, "    (void)to_sun, (void)beta, (void)u1, (void)u2, (void)g;\n"
               "    *weight = v3(0.0f, 0.0f, 0.0f);\n    return dir;\n}\n\n");
    put(t, "/* The factor on a path's roulette survival leaving it at cosine nu to the sun. */\n");
    put(t, HEAD "float nu)\n{\n", "float", "media_volume_roulette_gain");
    if (v)
        put(t, "    return %s(s, ATMO_LUT_ARGS, nu);\n}\n\n", v->roulette_gain);
    else
        put(t, "    (void)nu;\n    return 1.0f;\n}\n\n");
}

static int compose_ms(text *t, const atmo_feature *const *f, int n)
{
    int twice = 0;
    const char *src = single(f, n, offsetof(atmo_slots, ms_source), &twice);
    const char *ground = single(f, n, offsetof(atmo_slots, ms_ground_irradiance), &twice);
    put(t, "/* The method's multiple-scattering source toward the viewer at q (zero without "
           "one). */\n");
    put(t, HEAD "const medium_point *q, float nu, const media_sample *m, int ground)\n{\n", "vec3",
        "medium_ms_source");
    if (src)
        put(t, "    return %s(s, ATMO_LUT_ARGS, q, nu, m, ground);\n}\n\n", src);
    else
        put(t, "    return v3(0.0f, 0.0f, 0.0f);\n}\n\n");
    put(t, "/* The method's sky irradiance on the ground at sun cosine mu_s (zero without "
           "one). */\n");
    put(t, HEAD "float mu_s)\n{\n", "vec3", "medium_ms_ground_irradiance");
    if (ground)
        put(t, "    return %s(s, ATMO_LUT_ARGS, mu_s);\n}\n", ground);
    else
        put(t, "    return v3(0.0f, 0.0f, 0.0f);\n}\n");
    return twice ? -1 : 0;
}

static int compose_intervals(text *t, const atmo_feature *const *f, int n)
{
    int twice = 0;
    const char *parts = single(f, n, offsetof(atmo_slots, media_intervals), &twice);
    const char *step = single(f, n, offsetof(atmo_slots, media_interval), &twice);
    if ((parts == NULL) != (step == NULL))
        return -1;
    put(t, "/* The parts of [t_start, t_end] that a medium steps itself (media.h). */\n");
    put(t, "ATMO_FN int media_intervals(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,\n"
           "                            float t_start, float t_end, float *lo, float *hi)\n{\n");
    if (parts)
        put(t, "    return %s(s, m, t_start, t_end, lo, hi);\n}\n\n", parts);
    else
        put(t, "    return 0;\n}\n\n");
    put(t, "/* Interval [t0, t1] of media_intervals integrated by its medium (media.h). */\n");
    put(t, HEAD "const medium_ray *m, float t0, float t1,\n"
           "                            float jitter, int use_ms, int ground, float grid_d,\n"
           "                            int grid_n, vec3 *L, vec3 *T, vec3 *medium_t)\n{\n",
        "void", "media_interval");
    if (step)
        put(t, "    %s(s, ATMO_LUT_ARGS, m, t0, t1, jitter, use_ms, ground, grid_d, grid_n, L, T,\n"
               "       medium_t);\n",
            step);
    put(t, "}\n");
    return twice ? -1 : 0;
}

/* The occluders' product (visibility.h): all of them, or (surfaces) those that also shadow
 * surface points (visibility_sun_surface); each asked only while the sun is still visible, as
 * a ray's state must see the same samples however many occluders come before it. */
static void compose_occluders(text *t, const atmo_feature *const *f, int n, int surfaces)
{
    put(t, "    float v = 1.0f;\n");
    for (int i = 0; i < n; i++) {
        const atmo_slots *sl = f[i]->slots;
        if (sl && sl->sun_occluder && (!surfaces || sl->surface_occluder))
            put(t, "    if (v > 0.0f)\n        v *= %s(s, ATMO_LUT_ARGS, q);\n", sl->sun_occluder);
        if (sl && sl->ray_occluder && !surfaces)
            put(t, "    if (v > 0.0f)\n        v *= %s(s, ATMO_LUT_ARGS, q, vr ? vr->t : 0.0f, "
                   "vr ? &vr->%s : 0);\n",
                sl->ray_occluder, f[i]->name);
    }
    put(t, "    return v;\n}\n\n");
}

static void compose_sun(text *t, const atmo_feature *const *f, int n)
{
    put(t, "/* The occluders' state along one ray (visibility.h). */\n");
    put(t, "typedef struct visibility_ray {\n    float t; /* the sample's distance, m */\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], ray_occluder))
            put(t, "    %s %s;\n", f[i]->slots->ray_state, f[i]->name);
    put(t, "} visibility_ray;\n\n");
    put(t, "ATMO_FN void visibility_ray_begin(ATMO_GLOBAL const atmo_gpu_scene *s, "
           "const medium_ray *m,\n                                  float end, float surface_t, "
           "visibility_ray *vr)\n{\n    vr->t = 0.0f;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], ray_occluder))
            put(t, "    %s(s, m, end, surface_t, &vr->%s);\n", f[i]->slots->ray_begin,
                f[i]->name);
    put(t, "}\n\n");
    put(t, "/* The occluders' visibility of the sun at a sample of a ray with state vr (0: "
           "none). */\n");
    put(t, "ATMO_FN float visibility_sun_occluders_on_ray(ATMO_GLOBAL const atmo_gpu_scene *s,\n"
           "                                              ATMO_LUT_PARAMS, const medium_point *q,\n"
           "                                              visibility_ray *vr)\n{\n");
    compose_occluders(t, f, n, 0);
    put(t, HEAD "const medium_point *q)\n{\n", "float", "visibility_sun_occluders");
    put(t, "    return visibility_sun_occluders_on_ray(s, ATMO_LUT_ARGS, q, 0);\n}\n\n");
    put(t, "/* The occluders that also shadow surface points. */\n");
    put(t, HEAD "const medium_point *q)\n{\n", "float", "visibility_surface_occluders");
    compose_occluders(t, f, n, 1);
}

static void compose_surfaces(text *t, const atmo_feature *const *f, int n)
{
    put(t, "/* The nearest opaque surface other than the ground along the ray, or -1. */\n");
    put(t, HEAD "const medium_ray *m)\n{\n", "float", "visibility_surface_hit");
    put(t, "    float hit = -1.0f;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], surface_hit))
            put(t, "    float t_%d = %s(s, ATMO_LUT_ARGS, m, hit >= 0.0f ? hit : INFINITY);\n"
                   "    if (t_%d >= 0.0f)\n        hit = t_%d;\n",
                i, f[i]->slots->surface_hit, i, i);
    put(t, "    return hit;\n}\n\n");
    put(t, "/* The light of the surface at distance t toward the ray's origin. */\n");
    put(t, HEAD "const medium_ray *m, float t)\n{\n", "vec3", "visibility_surface_radiance");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], surface_radiance))
            put(t, "    vec3 L_%d = %s(s, ATMO_LUT_ARGS, m, t);\n"
                   "    if (L_%d.x >= 0.0f)\n        return L_%d;\n",
                i, f[i]->slots->surface_radiance, i, i);
    put(t, "    return v3(0.0f, 0.0f, 0.0f);\n}\n");
}

/* The path tracer's surfaces (kernels/render/surfaces.h): whether the ground sphere is one,
 * and the features' hits and shadow-ray tests in registry order (each hit replaces the record
 * only where it is nearer, so the order does not change which surface is found). */
static void compose_path_surfaces(text *t, const atmo_feature *const *f, int n)
{
    int ground = 1, marched = 0;
    for (int i = 0; i < n; i++) {
        if (f[i]->slots && f[i]->slots->path_replaces_ground)
            ground = 0;
        marched += SLOT(f[i], cone_start) != NULL;
    }
    put(t, "/* Whether the planet's ground sphere is a surface (no feature's replaces it). */\n");
    put(t, "#define SURFACES_GROUND_SPHERE %d\n\n", ground);
    put(t, "/* How many surfaces are found by a march (and give a cone start). */\n");
    put(t, "#define SURFACES_MARCHED %d\n\n", marched);
    put(t, "/* The features' surfaces along m, each replacing h where it is nearer. */\n");
    put(t, HEAD "const medium_ray *m, path_hit *h)\n{\n", "void", "surfaces_features_hit");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], path_hit))
            put(t, "    %s(s, ATMO_LUT_ARGS, m, h);\n", f[i]->slots->path_hit);
    put(t, "}\n\n");
    put(t, "/* The least of the marched surfaces' cone starts (surfaces.h); 0 without one. */\n");
    put(t, HEAD "const medium_ray *m, float spread)\n{\n", "float",
        "surfaces_features_cone_start");
    put(t, "    float t = INFINITY;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], cone_start))
            put(t, "    t = fminf(t, %s(s, ATMO_LUT_ARGS, m, spread));\n", f[i]->slots->cone_start);
    put(t, "    return t < INFINITY ? t : 0.0f;\n}\n\n");
    put(t, "/* 1 where a feature's surface blocks the shadow ray from o along d. */\n");
    put(t, HEAD "vec3 o, vec3 d)\n{\n", "int", "surfaces_features_occluded");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], path_occluded))
            put(t, "    if (%s(s, ATMO_LUT_ARGS, o, d))\n        return 1;\n",
                f[i]->slots->path_occluded);
    put(t, "    return 0;\n}\n");
}

/* The preview's camera ray (kernels/render/sky.cl): the features' stages in registry order,
 * the first that takes the ray tracing it, else the method's sky_trace over its whole length
 * (nothing without a method: a host test's composition of media alone). */
static void compose_camera(text *t, const atmo_feature *const *f, int n)
{
    int method = 0;
    for (int i = 0; i < n; i++)
        method |= f[i]->is_method;
    if (!method)
        return;
    put(t, "/* The preview's camera ray through the features' stages, else the method. */\n");
    put(t, HEAD "const medium_ray *ray, rng_stream *g,\n"
           "                                  vec3 *sky, vec3 *sun, vec3 *view_t)\n{\n",
        "void", "render_camera_trace");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], camera_stage))
            put(t, "    if (%s(s, ATMO_LUT_ARGS, ray, g, sky, sun, view_t))\n        return;\n",
                f[i]->slots->camera_stage);
    put(t, "    sky_trace(s, ATMO_LUT_ARGS, ray, INFINITY, g, sky, sun, view_t);\n}\n");
}

/* The denoiser's guides (kernels/render/guides.cl): the mode's pattern and pixel filter, and
 * the media's optical depth in front of a ray and of a block of rays. */
static void compose_guides(text *t, const atmo_feature *const *f, int n)
{
    int grid = ATMO_GUIDES_PREVIEW_GRID;
    const char *ray = NULL, *shown = NULL;
    for (int i = 0; i < n; i++) {
        const atmo_slots *sl = f[i]->slots;
        if (sl && sl->guides_grid)
            grid = sl->guides_grid;
        ray = SLOT(f[i], pixel_ray) ? sl->pixel_ray : ray;
        shown = SLOT(f[i], media_shown) ? sl->media_shown : shown;
    }
    put(t, "/* The guides' rays per pixel side (gpu_enums.h). */\n#define GUIDES_GRID %d\n\n",
        grid);
    put(t, "/* The mode's camera ray at (u1, u2) in [0, 1)^2 of pixel (x, y). */\n");
    put(t, "ATMO_FN vec3 guides_pixel_ray(ATMO_GLOBAL const atmo_gpu_scene *s, int x, int y, "
           "float u1,\n                              float u2)\n{\n");
    if (ray)
        put(t, "    return %s(s, x, y, u1, u2);\n}\n\n", ray);
    else
        put(t, "    return camera_ray(&s->camera, (float)x + u1, (float)y + u2);\n}\n\n");
    put(t, "/* Whether the image shows the method's media in front of a surface at t_end. */\n");
    put(t, "ATMO_FN int guides_media_shown(ATMO_GLOBAL const atmo_gpu_scene *s, float t_end)\n{\n");
    if (shown)
        put(t, "    return %s(s, t_end);\n}\n\n", shown);
    else
        put(t, "    (void)s;\n    (void)t_end;\n    return 1;\n}\n\n");
    put(t, "/* The media's optical depth along m over [0, t_end] added to *tau, times their\n"
           " * albedo to *tau_albedo. */\n");
    put(t, "ATMO_FN void guides_media_ray(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,"
           "\n                             float t_end, vec3 *tau, vec3 *tau_albedo)\n{\n"
           "    vec3 d, w;\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], guide_depth))
            put(t, "    d = %s(s, m, t_end, &w);\n    *tau = v3_add(*tau, d);\n"
                   "    *tau_albedo = v3_add(*tau_albedo, v3_mul(d, w));\n",
                f[i]->slots->guide_depth);
    put(t, "    (void)s;\n    (void)m;\n    (void)t_end;\n    (void)d;\n    (void)w;\n}\n\n");
    put(t, "/* The same for a block of n rays ending at ends[k], from one march along m. */\n");
    put(t, "ATMO_FN void guides_media_block(ATMO_GLOBAL const atmo_gpu_scene *s, "
           "const medium_ray *m, int n,\n                               const float *ends, "
           "float step_scale, float tau_stop,\n                               vec3 *tau, "
           "vec3 *tau_albedo)\n{\n");
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], guide_block))
            put(t, "    %s(s, m, n, ends, step_scale, tau_stop, tau, tau_albedo);\n",
                f[i]->slots->guide_block);
    put(t, "    (void)s;\n    (void)m;\n    (void)n;\n    (void)ends;\n    (void)step_scale;\n"
           "    (void)tau_stop;\n    (void)tau;\n    (void)tau_albedo;\n}\n");
}

int atmo_compose(const atmo_feature *const *f, int n, int group, char *out, size_t size)
{
    text t = {out, size, 0, 0};
    int rc = 0;
    if (size == 0)
        return -1;
    out[0] = 0;
    put(&t, "/* %s: generated by the plan (host/plan/compose.c) from the features' slots. */\n",
        atmo_compose_name(group));
    if (group == ATMO_COMPOSE_MEDIA) {
        int volumes = 0;
        const atmo_slots *v = NULL;
        for (int i = 0; i < n; i++)
            if (SLOT(f[i], volume_at))
                v = f[i]->slots, volumes++;
        /* the volume stage's one scattering component; every function it gives is needed */
        if (volumes > 1 || (v && !(v->media_phase && v->majorant_begin && v->media_direction &&
                                   v->roulette_gain)))
            return -1;
        compose_media_at(&t, f, n);
        compose_majorant(&t, f, n, volumes);
        compose_volume(&t, v);
        rc = compose_ms(&t, f, n);
    } else if (group == ATMO_COMPOSE_SUN) {
        compose_sun(&t, f, n);
    } else if (group == ATMO_COMPOSE_SURFACES) {
        compose_surfaces(&t, f, n);
    } else if (group == ATMO_COMPOSE_INTERVALS) {
        rc = compose_intervals(&t, f, n);
    } else if (group == ATMO_COMPOSE_PATH_SURFACES) {
        compose_path_surfaces(&t, f, n);
    } else if (group == ATMO_COMPOSE_CAMERA) {
        compose_camera(&t, f, n);
    } else if (group == ATMO_COMPOSE_GUIDES) {
        compose_guides(&t, f, n);
    } else {
        rc = -1;
    }
    return rc || t.overflow ? -1 : 0;
}

int atmo_compose_components(const atmo_feature *const *f, int n, char *out, size_t size)
{
    text t = {out, size, 0, 0};
    int k = 2; /* after the air's MEDIA_RAYLEIGH and MEDIA_MIE */
    if (size == 0)
        return -1;
    out[0] = 0;
    for (int i = 0; i < n; i++)
        if (SLOT(f[i], component))
            put(&t, "#define MEDIA_%s %d\n", f[i]->slots->component, k++);
    put(&t, "#define MEDIA_COMPONENTS %d\n", k);
    return t.overflow ? -1 : 0;
}

const char *atmo_compose_name(int group)
{
    static const char *const names[ATMO_COMPOSE_GROUPS] = {"", "plan/media", "plan/sun",
                                                           "plan/surfaces", "plan/intervals",
                                                           "plan/path_surfaces", "plan/camera",
                                                           "plan/guides"};
    return group > 0 && group < ATMO_COMPOSE_GROUPS ? names[group] : "";
}
