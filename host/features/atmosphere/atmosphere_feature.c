/* atmosphere_feature.c — the air (kernels/atmosphere/): its transmittance LUT, which every
 * program reads, and the atmosphere methods (single, march, fast, lut, reference) with the
 * tables they share (Psi_ms) and their own; planned here and by plan_march.c (Psi_ms),
 * plan_lut.c, plan_fast.c and plan_reference.c. */
#include "atmo/features.h"
#include "atmo/plan_fast.h"
#include "atmo/plan_lut.h"
#include "atmo/plan_march.h"
#include "atmo/plan_reference.h"

static int always(const atmo_scene *s) { return s != NULL; }
static int ms_methods(const atmo_scene *s)
{
    return s->atmosphere.method == ATMO_METHOD_MARCH || s->atmosphere.method == ATMO_METHOD_FAST;
}
static int is_single(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_SINGLE; }
static int is_march(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_MARCH; }
static int is_fast(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_FAST; }
static int is_lut(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_LUT; }
static int is_reference(const atmo_scene *s)
{
    return s->atmosphere.method == ATMO_METHOD_REFERENCE;
}

/* The transmittance LUT, which every method gets first. */
static int plan_atmosphere(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    (void)s;
    int w = p->gpu.transmittance_width, h = p->gpu.transmittance_height;
    int rc = atmo_plan_add_buffer(p, "transmittance_lut", "float4",
                                  sizeof(float4) * (size_t)w * (size_t)h, 0, NULL, e);
    return rc ? rc : atmo_plan_add_pass(p, "transmittance_lut", w, h, 1, 0, e);
}

/* The headers every kernel is compiled with: the shared GPU structs (each feature's in its own
 * header, before the scene struct that holds them), math, the deterministic quadrature's walk
 * (the atmosphere's transmittance integral walks it), the atmosphere, the camera, the
 * camera-relative ray that the media and the integrator take, the hit record that the
 * surfaces' slots fill (render/path_hit.h), the media's contract and the air, the planet as
 * the first occluder of the sun, and the free-flight and ratio-tracking steps of the Monte
 * Carlo walks. */
static const char *const atmosphere_fragments[] = {
    "kernels/common/compat.h",        "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",  "include/atmo/gpu_ms_lut.h",
    "include/atmo/gpu_sky_view.h",    "include/atmo/gpu_lut.h",
    "include/atmo/gpu_reference.h",   "include/atmo/gpu_cloud.h",
    "include/atmo/gpu_clouds.h",      "include/atmo/gpu_path.h",
    "include/atmo/gpu_terrain.h",
    "include/atmo/gpu_types.h",       "kernels/common/rng.h",
    "kernels/common/geometry.h",      "kernels/common/frame.h",
    "kernels/common/phase.h",         "kernels/media/quadrature_walk.h",
    "kernels/atmosphere/atmosphere.h", "kernels/common/camera.h",
    "kernels/atmosphere/sky_method.h", "kernels/media/ray.h",
    "kernels/render/path_hit.h",      "kernels/media/tracking.h",
    "kernels/media/majorant_walk.h",
    "kernels/media/media.h",          "kernels/media/planet.h",
    "kernels/atmosphere/transmittance.cl", NULL};
static const atmo_slots atmosphere_slots = {.sun_occluder = "planet_sun_visibility",
                                            .surface_occluder = 1};
static const atmo_gpu_field atmosphere_params[] = {ATMO_GPU_FIELD(atmosphere),
                                                   ATMO_GPU_FIELD(transmittance_width),
                                                   ATMO_GPU_FIELD(transmittance_height),
                                                   {0, 0}};
static const char *const atmosphere_sources[] = {
    "kernels/common/compat.h",       "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h", "include/atmo/gpu_types.h",
    "kernels/common/geometry.h",     "kernels/media/quadrature_walk.h",
    "kernels/atmosphere/atmosphere.h", "kernels/atmosphere/transmittance.cl", NULL};
static const char *const needs_transmittance[] = {"atmosphere", NULL};

/* the medium integrator's files, which the passes of Psi_ms and lut march with */
#define MEDIUM_SOURCES                                                                             \
    "kernels/media/ray.h", "kernels/media/tracking.h", "kernels/media/media.h",                    \
        "kernels/media/quadrature_walk.h", "kernels/media/visibility.h",                           \
        "kernels/cloud_shell/observer.h", "kernels/media/medium.h"

/* Psi_ms: its lookups (the source of march and fast) before the media's composition, its
 * passes (which march with the integrator) after the integrator. */
static const char *const ms_lut_fragments[] = {"kernels/atmosphere/ms_lut_source.h", NULL};
static const char *const ms_lut_pass_fragments[] = {"kernels/atmosphere/ms_lut.h",
                                                    "kernels/atmosphere/ms_lut.cl", NULL};
static const atmo_slots ms_lut_slots = {.ms_source = "ms_lut_ms_source",
                                        .ms_ground_irradiance = "ms_lut_ms_ground_irradiance"};
static const atmo_gpu_field ms_lut_params[] = {ATMO_GPU_FIELD(atmosphere), ATMO_GPU_FIELD(ms),
                                               {0, 0}};
static const char *const ms_lut_sources[] = {
    "kernels/common/compat.h",        "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",  "include/atmo/gpu_ms_lut.h",
    "include/atmo/gpu_types.h",       "kernels/common/geometry.h",
    "kernels/common/phase.h",         "kernels/atmosphere/atmosphere.h",
    "kernels/atmosphere/sky_method.h", MEDIUM_SOURCES,
    "kernels/atmosphere/ms_lut_source.h", "kernels/atmosphere/ms_lut.h",
    "kernels/atmosphere/ms_lut.cl",   NULL};

/* method lut: its tables' lookups (and the integrator's source) before the media's composition,
 * the method and its passes after the integrator */
static const char *const lut_fragments[] = {"kernels/atmosphere/lut_scattering.h",
                                            "kernels/atmosphere/lut_source.h", NULL};
static const char *const lut_pass_fragments[] = {"kernels/atmosphere/method_lut.h",
                                                 "kernels/atmosphere/lut_precompute.cl", NULL};
static const atmo_slots lut_slots = {.ms_source = "lut_ms_source",
                                     .ms_ground_irradiance = "lut_ms_ground_irradiance"};
static const atmo_gpu_field lut_params[] = {ATMO_GPU_FIELD(atmosphere), ATMO_GPU_FIELD(lut),
                                            {0, 0}};
static const char *const lut_sources[] = {
    "kernels/common/compat.h",           "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",     "include/atmo/gpu_lut.h",
    "include/atmo/gpu_types.h",          "kernels/common/rng.h",
    "kernels/common/geometry.h",         "kernels/common/phase.h",
    "kernels/atmosphere/atmosphere.h",   "kernels/atmosphere/sky_method.h",
    MEDIUM_SOURCES,                       "kernels/atmosphere/lut_scattering.h",
    "kernels/atmosphere/lut_source.h",
    "kernels/atmosphere/method_lut.h",   "kernels/atmosphere/lut_precompute.cl",
    NULL};

static const char *const single_fragments[] = {"kernels/atmosphere/method_single.h", NULL};
static const char *const march_fragments[] = {"kernels/atmosphere/method_march.h", NULL};
static const char *const fast_fragments[] = {"kernels/atmosphere/method_fast.h",
                                             "kernels/atmosphere/fast_luts.cl", NULL};
static const char *const reference_fragments[] = {"kernels/atmosphere/method_reference.h", NULL};

static const atmo_feature rows[] = {
    {.name = "atmosphere", .order = ATMO_BAND_BASE, .wanted = always,
     .fragments = atmosphere_fragments, .params = atmosphere_params,
     .sources = atmosphere_sources, .plan = plan_atmosphere, .slots = &atmosphere_slots},
    /* Psi_ms, shared by march and fast: the multiple-scattering source of the integrator */
    {.name = "ms_lut", .order = ATMO_BAND_MEDIA + 50, .wanted = ms_methods,
     .fragments = ms_lut_fragments, .params = ms_lut_params, .sources = ms_lut_sources,
     .needs = needs_transmittance, .plan = atmo_plan_ms_lut, .slots = &ms_lut_slots},
    /* the density of orders >= 2: the integrator's source for aerial perspective */
    {.name = "lut", .order = ATMO_BAND_MEDIA + 51, .is_method = 1, .method = ATMO_METHOD_LUT,
     .wanted = is_lut, .fragments = lut_fragments, .params = lut_params, .sources = lut_sources,
     .needs = needs_transmittance, .plan = atmo_plan_lut, .slots = &lut_slots},
    {.name = "ms_lut_passes", .order = ATMO_BAND_METHODS + 10, .wanted = ms_methods,
     .fragments = ms_lut_pass_fragments},
    {.name = "lut_passes", .order = ATMO_BAND_METHODS + 20, .wanted = is_lut,
     .fragments = lut_pass_fragments},
    {.name = "single", .order = ATMO_BAND_METHODS + 30, .is_method = 1,
     .method = ATMO_METHOD_SINGLE, .wanted = is_single, .fragments = single_fragments},
    {.name = "march", .order = ATMO_BAND_METHODS + 31, .is_method = 1,
     .method = ATMO_METHOD_MARCH, .wanted = is_march, .fragments = march_fragments},
    /* the sky-view LUT follows the view: never cached, so no key */
    {.name = "fast", .order = ATMO_BAND_METHODS + 32, .is_method = 1, .method = ATMO_METHOD_FAST,
     .wanted = is_fast, .fragments = fast_fragments, .plan = atmo_plan_fast,
     .luts_follow_view = 1},
    {.name = "reference", .order = ATMO_BAND_METHODS + 33, .is_method = 1,
     .method = ATMO_METHOD_REFERENCE, .wanted = is_reference,
     .fragments = reference_fragments, .plan = atmo_plan_reference},
};
ATMO_FEATURE_SET(atmosphere, rows);
