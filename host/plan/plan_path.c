/* plan_path.c — the scene's objects and the path tracer's settings in the plan
 * (atmo/plan_path.h).
 *
 * Objects become atmo_gpu_object rows (include/atmo/gpu_path.h) placed camera-relative in the
 * world's axes, the subtraction of the camera's position done in double: a sphere's centre
 * c - p_cam and radius, a box's corners min - p_cam and min + size - p_cam. An object with
 * on_terrain has its anchor's y (the centre's, the min's) above the terrain: y + Y_s, Y_s the
 * world Y of the terrain's surface over world (x, z) = terrain_at_m (or the sphere's centre, the
 * box's base centre) as the renderer draws it, procedural or a DEM
 * (atmo_plan_terrain_surface_y, host/plan/plan_terrain.c). The rows
 * are a host table the plan owns, copied into the buffer `objects` before the passes. The path
 * tracer's settings are copied from the scene's path.* keys; its render kernel is path_render
 * (kernels/render/path.cl), which a session launches in place of sky_render; with path.air =
 * medium the air is the paths' medium and its scattering the sky, so the sky sampling (whose
 * table is the method's sky) is off (gpu.path.sky_nee = 0), and atmo_plan_path_air refuses
 * the uniform test world, which has no air; with path.passes
 * it is compiled with -DATMO_RENDER_PASSES and sums the render passes into pass_planes more
 * planes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_path.h"
#include "atmo/plan_terrain.h"

static float4 rel4(const double v[3], const double cam[3], double w)
{
    float4 r = {(float)(v[0] - cam[0]), (float)(v[1] - cam[1]), (float)(v[2] - cam[2]), (float)w};
    return r;
}

static float4 col4(const double v[3])
{
    float4 r = {(float)v[0], (float)v[1], (float)v[2], 0.0f};
    return r;
}

int atmo_plan_objects(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int n = s->objects.count;
    atmo_gpu_object *rows = calloc((size_t)n, sizeof *rows);
    if (!rows)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d objects", n);
    int rc = atmo_plan_own(p, rows, e);
    if (rc)
        return rc;
    const double *cam = s->camera.position_m;
    for (int i = 0; i < n; i++) {
        atmo_object o = s->objects.list[i];
        atmo_gpu_object *g = &rows[i];
        g->kind = o.type;
        if (o.on_terrain) {
            /* the scene's checks allow it only with the terrain, planned before */
            int sphere = o.type == ATMO_OBJECT_SPHERE;
            double x = o.has_terrain_at ? o.terrain_at_m[0]
                                        : sphere ? o.center_m[0] : o.min_m[0] + 0.5 * o.size_m[0];
            double z = o.has_terrain_at ? o.terrain_at_m[1]
                                        : sphere ? o.center_m[2] : o.min_m[2] + 0.5 * o.size_m[2];
            double y = atmo_plan_terrain_surface_y(p, s->atmosphere.bottom_radius_m, x, z);
            *(sphere ? &o.center_m[1] : &o.min_m[1]) += y;
        }
        if (o.type == ATMO_OBJECT_SPHERE) {
            g->a = rel4(o.center_m, cam, o.radius_m);
        } else {
            double hi[3] = {o.min_m[0] + o.size_m[0], o.min_m[1] + o.size_m[1],
                            o.min_m[2] + o.size_m[2]};
            g->a = rel4(o.min_m, cam, 0.0);
            g->b = rel4(hi, cam, 0.0);
        }
        g->albedo = col4(o.albedo);
        g->emission = col4(o.emission);
    }
    p->gpu.path.object_count = n;
    return atmo_plan_add_buffer(p, "objects", "atmo_gpu_object", (size_t)n * sizeof *rows, 0,
                                rows, e);
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
