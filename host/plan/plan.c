/* plan.c — scene -> device structs and kernel list (atmo/plan.h). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/colour.h"
#include "atmo/plan.h"
#include "atmo/plan_cloud.h"
#include "atmo/plan_fast.h"
#include "atmo/plan_lut.h"
#include "atmo/plan_march.h"
#include "atmo/plan_reference.h"

/* The layout the kernels see: OpenCL C aligns float4 to 16 bytes, as compat.h does on the host. */
_Static_assert(sizeof(float4) == 16, "float4 must be 16 bytes");
_Static_assert(sizeof(atmo_gpu_atmosphere) == 144, "atmo_gpu_atmosphere layout");
_Static_assert(offsetof(atmo_gpu_atmosphere, bottom_radius) == 96, "atmo_gpu_atmosphere layout");
_Static_assert(offsetof(atmo_gpu_atmosphere, sun_angular_radius) == 132, "atmo_gpu_atmosphere");
_Static_assert(sizeof(atmo_gpu_camera) == 80, "atmo_gpu_camera layout");
_Static_assert(offsetof(atmo_gpu_camera, kind) == 64, "atmo_gpu_camera layout");
_Static_assert(offsetof(atmo_gpu_scene, camera) == 144, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, sun_direction) == 224, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, view_steps) == 272, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, lut_dims) == 288, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, method_float) == 352, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, cloud_extinction) == 368, "atmo_gpu_scene layout");
_Static_assert(offsetof(atmo_gpu_scene, cloud_phase) == 432, "atmo_gpu_scene layout");
_Static_assert(sizeof(atmo_gpu_scene) == 448, "atmo_gpu_scene layout");

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
        c->kind = ATMO_GPU_CAMERA_PANORAMA;
    } else {
        atmo_camera_basis(s->camera.pitch_deg, s->camera.yaw_deg, forward, right, up);
        c->kind = ATMO_GPU_CAMERA_PERSPECTIVE;
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
    c->tan_half_fov = (float)tan(0.5 * s->camera.fov_deg * DEG);
}

/* Method "single": single scattering only (kernels/atmosphere/method_single.h); no LUTs of its own. */
static int plan_single(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/atmosphere/method_single.h"};
    return atmo_plan_add_fragments(p, fragments, 1, e);
}

/* Methods in ATMO_METHOD_* order; NULL: not implemented yet. */
const atmo_plan_method atmo_plan_methods[] = {
    {"single", plan_single, 0},
    {"march", atmo_plan_march, 0},
    {"fast", atmo_plan_fast, 1}, /* the sky-view LUT is made for one camera and one sun */
    {"lut", atmo_plan_lut, 0},
    {"reference", atmo_plan_reference, 0},
};

const char *atmo_plan_available_methods(void)
{
    static char list[128];
    list[0] = 0;
    for (size_t i = 0; i < sizeof atmo_plan_methods / sizeof atmo_plan_methods[0]; i++)
        if (atmo_plan_methods[i].plan)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "",
                     atmo_plan_methods[i].name);
    return list;
}

int atmo_plan_add_fragments(atmo_plan *p, const char *const *names, int count, atmo_err *e)
{
    if (p->fragment_count + count + 3 > ATMO_PLAN_MAX_FRAGMENTS)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many kernel fragments (a build bug)");
    for (int i = 0; i < count; i++)
        p->fragments[p->fragment_count++] = names[i];
    return ATMO_OK;
}

int atmo_plan_add_pass(atmo_plan *p, const char *kernel, int width, int height, int depth, int arg,
                       atmo_err *e)
{
    if (p->pass_count == ATMO_PLAN_MAX_PASSES)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many precompute passes (a build bug)");
    atmo_plan_pass pass = {kernel, width, height, depth, arg, 0};
    p->passes[p->pass_count++] = pass;
    return ATMO_OK;
}

void atmo_plan_free(atmo_plan *p)
{
    for (int i = 0; i < p->upload_count; i++)
        free(p->uploads[i].owned);
    memset(p, 0, sizeof *p);
}

int atmo_plan_make(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int rc;
    memset(p, 0, sizeof *p);
    if ((rc = atmo_scene_validate(s, e)) || (rc = atmo_atmosphere_from_scene(s, &p->atmosphere, e)))
        return rc;
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

    /* common fragments and the medium integrator (a cloud shell inserts its modules before
     * kernels/media/media.h), then the method's, then the kernels that use them */
    static const char *const common[] = {
        "kernels/common/compat.h",       "include/atmo/gpu_types.h",
        "kernels/common/rng.h",          "kernels/common/geometry.h",
        "kernels/common/phase.h",        "kernels/atmosphere/atmosphere.h",
        "kernels/common/camera.h",       "kernels/atmosphere/sky_method.h",
        "kernels/media/ray.h",           "kernels/media/media.h",
        "kernels/media/visibility.h",    "kernels/media/medium.h",
        "kernels/media/tracking.h",
    };
    for (size_t i = 0; i < sizeof common / sizeof common[0]; i++)
        p->fragments[p->fragment_count++] = common[i];
    p->lut_bytes[0] = sizeof(float4) * (size_t)g->transmittance_width *
                      (size_t)g->transmittance_height;
    atmo_plan_pass transmittance = {"transmittance_lut", g->transmittance_width,
                                    g->transmittance_height, 1, 0, 0};
    p->passes[p->pass_count++] = transmittance;
    const atmo_plan_method *m = &atmo_plan_methods[s->atmosphere.method];
    p->method = m->name;
    if (!m->plan)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "atmosphere.method=%s is not implemented yet (available: %s)", m->name,
                         atmo_plan_available_methods());
    if ((rc = m->plan(s, p, e)) || (rc = atmo_plan_cloud(s, p, e)))
        return rc;
    p->fragments[p->fragment_count++] = "kernels/atmosphere/sky_cosines.h";
    p->fragments[p->fragment_count++] = "kernels/atmosphere/transmittance.cl";
    p->fragments[p->fragment_count++] = "kernels/render/sky.cl";
    p->width = s->image.width;
    p->height = s->image.height;
    p->samples = s->image.samples;
    return ATMO_OK;
}
