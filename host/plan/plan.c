/* plan.c — scene -> device structs, the features it contains and their kernels, buffers and
 * passes (atmo/plan.h, atmo/features.h). A camera placed on the terrain (camera.on_terrain) is
 * planned twice: once to learn the terrain's height under it, then with its y made absolute. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/colour.h"
#include "atmo/features.h"
#include "atmo/plan.h"
#include "atmo/plan_clouds.h"
#include "atmo/plan_terrain.h"

/* The layout the kernels see: OpenCL C aligns float4 to 16 bytes, as compat.h does on the host. */
_Static_assert(sizeof(float4) == 16, "float4 must be 16 bytes");
_Static_assert(sizeof(atmo_gpu_atmosphere) == 144, "atmo_gpu_atmosphere layout");
_Static_assert(offsetof(atmo_gpu_atmosphere, bottom_radius) == 96, "atmo_gpu_atmosphere layout");
_Static_assert(offsetof(atmo_gpu_atmosphere, sun_angular_radius) == 132, "atmo_gpu_atmosphere");
_Static_assert(sizeof(atmo_gpu_camera) == 80, "atmo_gpu_camera layout");
_Static_assert(offsetof(atmo_gpu_camera, kind) == 64, "atmo_gpu_camera layout");
_Static_assert(sizeof(atmo_gpu_ms_lut) == 32, "atmo_gpu_ms_lut layout");
_Static_assert(offsetof(atmo_gpu_ms_lut, higher_anisotropy) == 20, "atmo_gpu_ms_lut layout");
_Static_assert(sizeof(atmo_gpu_sky_view) == 16, "atmo_gpu_sky_view layout");
_Static_assert(sizeof(atmo_gpu_lut) == 32, "atmo_gpu_lut layout");
_Static_assert(offsetof(atmo_gpu_lut, steps) == 16, "atmo_gpu_lut layout");
_Static_assert(sizeof(atmo_gpu_reference) == 16, "atmo_gpu_reference layout");
_Static_assert(sizeof(atmo_gpu_cloud) == 96, "atmo_gpu_cloud layout");
_Static_assert(offsetof(atmo_gpu_cloud, base_m) == 64, "atmo_gpu_cloud layout");
_Static_assert(offsetof(atmo_gpu_cloud, steps) == 84, "atmo_gpu_cloud layout");
_Static_assert(offsetof(atmo_gpu_scene, camera) == 144, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, sun_direction) == 224, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, view_steps) == 272, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, ms) == 288, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, sky_view) == 320, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, lut) == 336, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, reference) == 368, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, cloud) == 384, "atmo_gpu_scene layout");
_Static_assert(sizeof(atmo_gpu_clouds) == 208, "atmo_gpu_clouds layout");
_Static_assert(offsetof(atmo_gpu_clouds, bottom_m) == 80, "atmo_gpu_clouds layout");
_Static_assert(offsetof(atmo_gpu_clouds, majorant) == 132, "atmo_gpu_clouds layout");
_Static_assert(offsetof(atmo_gpu_clouds, seed) == 164, "atmo_gpu_clouds layout");
_Static_assert(offsetof(atmo_gpu_scene, clouds) == 480, "atmo_gpu_scene layout");
_Static_assert(sizeof(atmo_gpu_object) == 80, "atmo_gpu_object layout");
_Static_assert(offsetof(atmo_gpu_object, kind) == 64, "atmo_gpu_object layout");
_Static_assert(sizeof(atmo_gpu_path) == 80, "atmo_gpu_path layout");
_Static_assert(offsetof(atmo_gpu_path, object_count) == 16, "atmo_gpu_path layout");
_Static_assert(offsetof(atmo_gpu_path, filter_radius) == 52, "atmo_gpu_path layout");
_Static_assert(offsetof(atmo_gpu_scene, path) == 688, "atmo_gpu_scene layout");
_Static_assert(sizeof(atmo_gpu_terrain_field) == 96, "atmo_gpu_terrain_field layout");
_Static_assert(offsetof(atmo_gpu_terrain_field, seed) == 24, "atmo_gpu_terrain_field layout");
_Static_assert(offsetof(atmo_gpu_terrain_field, base_rect) == 48, "atmo_gpu_terrain_field");
_Static_assert(offsetof(atmo_gpu_terrain_field, base_detail) == 64, "atmo_gpu_terrain_field");
_Static_assert(offsetof(atmo_gpu_terrain_field, detail_octave0) == 68, "atmo_gpu_terrain_field");
_Static_assert(offsetof(atmo_gpu_terrain_field, detail_amplitude_m) == 76,
               "atmo_gpu_terrain_field");
_Static_assert(sizeof(atmo_gpu_terrain) == 208, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_terrain, stretch_slope) == 192, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_terrain, camera) == 96, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_terrain, shafts) == 148, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_terrain, sun_map_size) == 156, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_terrain, sun_map_axis) == 176, "atmo_gpu_terrain layout");
_Static_assert(offsetof(atmo_gpu_scene, terrain) == 768, "atmo_gpu_scene layout");
_Static_assert(sizeof(atmo_gpu_scene) == 976, "atmo_gpu_scene layout");

#define DEG (M_PI / 180.0)

void atmo_sun_direction(double zenith_deg, double azimuth_deg, double out[3])
{
    double z = zenith_deg * DEG, a = azimuth_deg * DEG;
    out[0] = sin(z) * sin(a);
    out[1] = cos(z);
    out[2] = sin(z) * cos(a);
}

void atmo_camera_basis(double pitch_deg, double yaw_deg, double forward[3], double right[3],
                       double up[3])
{
    double x = pitch_deg * DEG, y = yaw_deg * DEG;
    forward[0] = -cos(x) * sin(y), forward[1] = sin(x), forward[2] = cos(x) * cos(y);
    right[0] = cos(y), right[1] = 0.0, right[2] = sin(y);
    up[0] = sin(x) * sin(y), up[1] = cos(x), up[2] = -sin(x) * cos(y);
}

static float4 f4(const double v[3], double w)
{
    float4 r = {(float)v[0], (float)v[1], (float)v[2], (float)w};
    return r;
}

static void fill_atmosphere(const atmo_atmosphere *a, atmo_gpu_atmosphere *g)
{
    memset(g, 0, sizeof *g);
    g->rayleigh_scattering = f4(a->rayleigh_scattering_per_m, 0.0);
    g->mie_scattering = f4(a->mie_scattering_per_m, 0.0);
    g->mie_extinction = f4(a->mie_extinction_per_m, 0.0);
    g->ozone_absorption = f4(a->ozone_absorption_per_m, 0.0);
    g->solar_irradiance = f4(a->solar_irradiance, 0.0);
    g->ground_albedo = f4(a->ground_albedo, 0.0);
    g->bottom_radius = (float)a->bottom_radius_m;
    g->top_radius = (float)a->top_radius_m;
    g->rayleigh_scale_height = (float)a->rayleigh_scale_height_m;
    g->mie_scale_height = (float)a->mie_scale_height_m;
    g->mie_g = (float)a->mie_g;
    g->mie_phase = a->mie_phase;
    g->ozone_bottom = (float)a->ozone_bottom_m;
    g->ozone_peak = (float)a->ozone_peak_m;
    g->ozone_top = (float)a->ozone_top_m;
    g->sun_angular_radius = (float)a->sun_angular_radius_rad;
}

static void fill_camera(const atmo_scene *s, const atmo_atmosphere *a, atmo_gpu_camera *c)
{
    double forward[3], right[3], up[3];
    memset(c, 0, sizeof *c);
    if (s->camera.kind == ATMO_CAMERA_PANORAMA) {
        /* panoramas are level: horizontal forward and right, world up */
        atmo_camera_basis(0.0, s->camera.yaw_deg, forward, right, up);
        c->kind = ATMO_CAMERA_PANORAMA;
    } else {
        atmo_camera_basis(s->camera.pitch_deg, s->camera.yaw_deg, forward, right, up);
        c->kind = s->camera.kind;
    }
    c->forward = f4(forward, 0.0);
    c->right = f4(right, 0.0);
    c->up = f4(up, 0.0);
    /* planet centre at (0, -R, 0): the camera's offset from it, in double */
    double p[3] = {s->camera.position_m[0], s->camera.position_m[1] + a->bottom_radius_m,
                   s->camera.position_m[2]};
    double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    double n[3] = {p[0] / r, p[1] / r, p[2] / r};
    c->local_up = f4(n, r);
    c->width = s->image.width;
    c->height = s->image.height;
    /* the perspective's tan(fov/2), the fisheye's sin(fov/4) (kernels/common/camera.h) */
    c->tan_half_fov = (float)(s->camera.kind == ATMO_CAMERA_FISHEYE
                                  ? sin(0.25 * s->camera.fov_deg * DEG)
                                  : tan(0.5 * s->camera.fov_deg * DEG));
}

static int append(char *dst, size_t size, const char *fmt, const char *a, const char *b,
                  atmo_err *e)
{
    size_t used = strlen(dst);
    int n = snprintf(dst + used, size - used, fmt, a, b);
    if (n < 0 || (size_t)n >= size - used)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "plan text overflows (a build bug)");
    return ATMO_OK;
}

int atmo_plan_add_buffer(atmo_plan *p, const char *name, const char *type, size_t bytes,
                         int follows_view, const void *host_data, atmo_err *e)
{
    if (p->buffer_count == ATMO_PLAN_MAX_BUFFERS)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many buffers (a build bug)");
    atmo_plan_buffer b = {name, type, bytes, follows_view, host_data, p->feature_count - 1};
    p->buffers[p->buffer_count++] = b;
    return ATMO_OK;
}

int atmo_plan_add_pass(atmo_plan *p, const char *kernel, int width, int height, int depth, int arg,
                       atmo_err *e)
{
    if (p->pass_count == ATMO_PLAN_MAX_PASSES)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many precompute passes (a build bug)");
    atmo_plan_pass pass = {kernel, width, height, depth, arg, p->feature_count - 1};
    p->passes[p->pass_count++] = pass;
    return ATMO_OK;
}

int atmo_plan_buffer_index(const atmo_plan *p, const char *name)
{
    for (int i = 0; i < p->buffer_count; i++)
        if (strcmp(p->buffers[i].name, name) == 0)
            return i;
    return -1;
}

atmo_plan_buffer *atmo_plan_buffer_find(atmo_plan *p, const char *name)
{
    int i = atmo_plan_buffer_index(p, name);
    return i < 0 ? NULL : &p->buffers[i];
}

/* One feature: its fragments, flags, then its plan function (struct, buffers, passes). */
static int add_feature(const atmo_scene *s, const atmo_feature *f, atmo_plan *p, atmo_err *e)
{
    int rc;
    if (p->feature_count == ATMO_PLAN_MAX_FEATURES)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many features (a build bug)");
    p->features[p->feature_count++] = f;
    if (f->compose) { /* generated once every feature is planned (make_prelude) */
        if (p->fragment_count == ATMO_PLAN_MAX_FRAGMENTS)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "too many kernel fragments (a build bug)");
        p->fragment_group[p->fragment_count] = (unsigned char)f->compose;
        p->fragments[p->fragment_count++] = atmo_compose_name(f->compose);
    }
    for (const char *const *frag = f->fragments; frag && *frag; frag++) {
        if (p->fragment_count == ATMO_PLAN_MAX_FRAGMENTS)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "too many kernel fragments (a build bug)");
        p->fragments[p->fragment_count++] = *frag;
    }
    if (f->defines && (rc = append(p->defines, sizeof p->defines, "%s%s",
                                   p->defines[0] ? " " : "", f->defines, e)))
        return rc;
    return f->plan ? f->plan(s, p, e) : ATMO_OK;
}

void atmo_plan_fragment_texts(const atmo_plan *p, const char *texts[ATMO_PLAN_MAX_FRAGMENTS])
{
    for (int i = 0; i < p->fragment_count; i++)
        texts[i] = p->fragment_group[i] ? p->composed[p->fragment_group[i]] : NULL;
}

/* The buffer parameter and argument lists (plan.h), in buffer order, the media's components,
 * and the composition of the slots the features fill. */
static int make_prelude(atmo_plan *p, atmo_err *e)
{
    _Static_assert(ATMO_PLAN_COMPOSE_GROUPS == ATMO_COMPOSE_GROUPS, "one text per group");
    for (int g = ATMO_COMPOSE_NONE + 1; g < ATMO_COMPOSE_GROUPS; g++)
        if (atmo_compose(p->features, p->feature_count, g, p->composed[g], sizeof p->composed[g]))
            return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot compose the kernels' %s (a build bug)",
                             atmo_compose_name(g));
    static const char *const heads[3] = {"ATMO_LUT_PARAMS", "ATMO_LUT_OUT_PARAMS",
                                         "ATMO_LUT_ARGS"};
    int rc = ATMO_OK;
    p->prelude[0] = 0;
    for (int m = 0; m < 3 && !rc; m++) {
        rc = append(p->prelude, sizeof p->prelude, "#define %s%s", heads[m], "", e);
        for (int i = 0; i < p->buffer_count && !rc; i++) {
            const atmo_plan_buffer *b = &p->buffers[i];
            if (m == 2)
                rc = append(p->prelude, sizeof p->prelude, "%s%s", i ? ", " : " ", b->name, e);
            else
                rc = append(p->prelude, sizeof p->prelude, "%sATMO_GLOBAL %s",
                            i ? ", " : " ", m == 0 ? "const " : "", e) ||
                     append(p->prelude, sizeof p->prelude, "%s *%s", b->type, b->name, e);
        }
        if (!rc)
            rc = append(p->prelude, sizeof p->prelude, "%s%s", "\n", "", e);
    }
    size_t used = strlen(p->prelude);
    if (!rc && atmo_compose_components(p->features, p->feature_count, p->prelude + used,
                                       sizeof p->prelude - used))
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "plan text overflows (a build bug)");
    return rc;
}

void atmo_plan_free(atmo_plan *p)
{
    for (int i = 0; i < p->owned_count; i++)
        free(p->owned[i]);
    atmo_dem_free(&p->dem);
    memset(p, 0, sizeof *p);
}

int atmo_plan_own(atmo_plan *p, void *block, atmo_err *e)
{
    if (p->owned_count == ATMO_PLAN_MAX_OWNED) {
        free(block);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many host tables in the plan (a build bug)");
    }
    p->owned[p->owned_count++] = block;
    return ATMO_OK;
}

static int plan_features(const atmo_scene *s, atmo_plan *p, atmo_err *e);

int atmo_plan_make(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    return atmo_plan_make_cached(s, 0, 1, p, e);
}

/* camera.on_terrain: the scene with the camera's y made absolute (Y_s + y, Y_s the world Y of
 * the terrain's surface under the camera or at camera.terrain_at_m, as the objects' anchors
 * take it: atmo_plan_terrain_surface_y), from a first plan of the scene, which has the terrain
 * (the field, a DEM's heightmap) and nothing that follows the camera yet planned for good. */
void atmo_plan_camera_world(const atmo_plan *p, const atmo_scene *s, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = s->camera.position_m[k];
    if (s->camera.on_terrain == ATMO_CAMERA_TERRAIN_OFF)
        return;
    int at = s->camera.on_terrain == ATMO_CAMERA_TERRAIN_AT;
    double x = at ? s->camera.terrain_at_m[0] : s->camera.position_m[0];
    double z = at ? s->camera.terrain_at_m[1] : s->camera.position_m[2];
    out[1] += atmo_plan_terrain_surface_y(p, s->atmosphere.bottom_radius_m, x, z);
}

/* *out = s with the camera placed by a first plan of s (host tables from the disk cache with
 * cache_tables), which has the terrain (the field, a DEM's heightmap) and nothing that follows
 * the camera planned for good. */
static int place_camera(const atmo_scene *s, int cache_tables, atmo_scene *out, atmo_err *e)
{
    *out = *s;
    if (s->camera.on_terrain == ATMO_CAMERA_TERRAIN_OFF)
        return ATMO_OK;
    atmo_plan first;
    memset(&first, 0, sizeof first);
    first.cache_tables = cache_tables;
    int rc = plan_features(s, &first, e);
    if (!rc) {
        atmo_plan_camera_world(&first, s, out->camera.position_m);
        out->camera.on_terrain = ATMO_CAMERA_TERRAIN_OFF;
    }
    atmo_plan_free(&first);
    return rc;
}

int atmo_plan_make_cached(const atmo_scene *s, int cache_luts, int cache_tables, atmo_plan *p,
                          atmo_err *e)
{
    memset(p, 0, sizeof *p);
    p->cache_luts = cache_luts;
    p->cache_tables = cache_tables;
    int rc;
    if (s->camera.on_terrain == ATMO_CAMERA_TERRAIN_OFF) {
        rc = plan_features(s, p, e);
    } else {
        atmo_scene *placed = malloc(sizeof *placed);
        rc = placed ? place_camera(s, cache_tables, placed, e)
                    : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the scene");
        if (!rc)
            rc = plan_features(placed, p, e);
        free(placed);
    }
    if (rc)
        atmo_plan_free(p);
    return rc;
}

int atmo_plan_place_camera(const atmo_scene *s, atmo_scene *out, atmo_err *e)
{
    return place_camera(s, 1, out, e);
}

/* atmo_plan_make's work: the shared structs, then each wanted feature in registry order. */
int atmo_plan_auto_method(const atmo_scene *s, const char **why)
{
    const char *reason = "a clear sky";
    int method = ATMO_METHOD_MARCH;
    if (s->clouds.enabled && !atmo_plan_clouds_volume(s))
        reason = "the fBm cloud layer";
    else if (s->cloud.enabled)
        reason = "the cloud shell";
    else if (s->observer.enabled)
        reason = "the observer";
    else
        method = ATMO_METHOD_FAST;
    if (why)
        *why = reason;
    return method;
}

static int plan_features(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int rc;
    if (s->atmosphere.method == ATMO_METHOD_AUTO) { /* planned as the method it stands for */
        atmo_scene *chosen = malloc(sizeof *chosen);
        if (!chosen)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the scene");
        *chosen = *s;
        chosen->atmosphere.method = atmo_plan_auto_method(s, NULL);
        rc = plan_features(chosen, p, e);
        free(chosen);
        return rc;
    }
    if ((rc = atmo_scene_validate(s, e)) || (rc = atmo_atmosphere_from_scene(s, &p->atmosphere, e)))
        return rc;
    if (s->dem.file[0]) { /* a bad heightmap fails here, before any device work */
        atmo_dem_options o;
        atmo_dem_options_from_scene(s, &o);
        if ((rc = atmo_dem_load(s->dem.file, &o, &p->dem, e)))
            return rc;
    }
    atmo_gpu_scene *g = &p->gpu;
    fill_atmosphere(&p->atmosphere, &g->atmosphere);
    fill_camera(s, &p->atmosphere, &g->camera);
    double sun[3];
    atmo_sun_direction(s->sun.zenith_deg, s->sun.azimuth_deg, sun);
    g->sun_direction = f4(sun, cos(p->atmosphere.sun_angular_radius_rad));
    double one[3] = {1.0, 1.0, 1.0}, k_sky[3], k_sun[3];
    if (s->render.quantity == ATMO_QUANTITY_LUMINANCE) {
        atmo_luminance_factors(s->render.wavelengths_nm, -3.0, k_sky);
        atmo_luminance_factors(s->render.wavelengths_nm, 0.0, k_sun);
        g->sky_factor = f4(k_sky, 0.0);
        g->sun_factor = f4(k_sun, 0.0);
    } else {
        g->sky_factor = f4(one, 0.0);
        g->sun_factor = f4(one, 0.0);
    }
    g->view_steps = s->render.view_steps;
    g->transmittance_width = s->render.transmittance_width;
    g->transmittance_height = s->render.transmittance_height;
    g->seed = (uint)s->image.seed;
    /* the ground sphere is a surface of render/surfaces.h's rays (the denoiser's guides) in the
     * preview, whose methods all have it; in path mode atmo_plan_path sets the scene's */
    g->path.ground = 1;

    const atmo_feature *m = atmo_feature_method(s->atmosphere.method);
    if (!m)
        return atmo_fail(e, ATMO_ERR_USAGE, "atmosphere.method is not implemented (available: %s)",
                         atmo_plan_available_methods());
    p->method = m->name;
    p->render_kernel = "sky_render";
    for (int i = 0; i < atmo_feature_count(); i++)
        if (atmo_feature_at(i)->wanted(s) && (rc = add_feature(s, atmo_feature_at(i), p, e)))
            return rc;
    if ((rc = make_prelude(p, e)))
        return rc;
    p->width = s->image.width;
    p->height = s->image.height;
    p->samples = s->image.samples;
    return ATMO_OK;
}
