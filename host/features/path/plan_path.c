/* plan_path.c — the path tracer's settings in the plan (atmo/plan_path.h).
 *
 * The path tracer's settings are copied from the scene's path.* keys; its render kernel is
 * path_render (kernels/render/path.cl), which a session launches in place of sky_render; with
 * path.air = medium the air is the paths' medium and its scattering the sky, so the sky
 * sampling (whose table is the method's sky) is off (gpu.path.sky_nee = 0), and
 * atmo_plan_path_air refuses the uniform test world, which has no air; with path.passes it is
 * compiled with -DATMO_RENDER_PASSES and sums the render passes into pass_planes more planes. */
#include <stdio.h>
#include <string.h>
#include "atmo/plan_path.h"

static float4 col4(const double v[3])
{
    float4 r = {(float)v[0], (float)v[1], (float)v[2], 0.0f};
    return r;
}

int atmo_plan_path(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    atmo_gpu_path *g = &p->gpu.path;
    g->uniform_sky = col4(s->path.uniform_sky);
    g->bounces = s->path.bounces;
    g->secondary = s->path.secondary;
    g->rr_bounce = s->path.rr_bounce;
    g->sun_nee = s->path.sun_nee;
    /* with the air a medium of the paths, the sky is its scattering: no sky term to sample */
    g->sky_nee = s->path.sky_nee && s->path.air != ATMO_PATH_AIR_MEDIUM;
    g->sky = s->path.sky;
    g->ground = s->path.ground;
    g->sampler = s->path.sampler;
    g->filter_radius = (float)s->path.filter_radius_px;
    g->filter_sigma = (float)s->path.filter_sigma_px;
    g->aperture_m = (float)s->path.aperture_m;
    g->focus_m = (float)s->path.focus_m;
    g->volume_bounces = s->path.volume_bounces;
    g->air_collisions = s->path.air_collisions;
    p->render_kernel = "path_render";
    /* the sky's radiance table of the sky sampling (kernels/render/light_sky.h): 32 x 16
     * texels and 16 rows of CDF, made for this camera and sun */
    int texels = ATMO_PATH_SKY_TEXELS + ATMO_PATH_SKY_ROWS, rc;
    if ((rc = atmo_plan_add_buffer(p, "sky_env", "float4", sizeof(float4) * (size_t)texels, 1,
                                   NULL, e)) ||
        (rc = atmo_plan_add_pass(p, "path_sky_env", ATMO_PATH_SKY_COLUMNS, ATMO_PATH_SKY_ROWS, 1,
                                 0, e)) ||
        (rc = atmo_plan_add_pass(p, "path_sky_cdf", 1, 1, 1, 0, e)))
        return rc;
    if (!s->path.passes)
        return ATMO_OK;
    size_t used = strlen(p->defines);
    int n = snprintf(p->defines + used, sizeof p->defines - used, "%s-DATMO_RENDER_PASSES",
                     used ? " " : "");
    if (n < 0 || (size_t)n >= sizeof p->defines - used)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "plan text overflows (a build bug)");
    p->pass_planes = ATMO_PATH_PASS_PLANES;
    return ATMO_OK;
}

int atmo_plan_path_air(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    (void)p;
    if (s->path.sky == ATMO_PATH_SKY_UNIFORM)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "path.air=medium needs the atmosphere's air, and path.sky=uniform is a "
                         "world without air; set path.sky=atmosphere, or path.air=method");
    return ATMO_OK;
}
