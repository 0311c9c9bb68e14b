/* plan_clouds.c — the fBm cloud layer in the plan (atmo/plan_clouds.h).
 *
 * Optics at unit density, per render wavelength: sigma_t = clouds.extinction_per_m and the
 * albedo clouds.albedo (the thesis' 10.354e-3 1/m and 0.9512 by default), or, with
 * extinction_per_m = 0, sigma_t = (sigma_ext / LWC) x clouds.lwc_g_m3 and the albedo of the
 * Mie solution of the droplet distribution clouds.dsd (a preset or a SPEC of atmo mie --dsd, ""
 * for cumulus; atmo_plan_mie_optics, plan_cloud.c). The
 * phase table is always the distribution's (phase_table.h's rows), normalised and given its
 * sampling CDF by atmo_plan_phase_cdf (plan_cloud.c).
 *
 * Level of detail: the kernels filter the noise to a footprint of clouds.lod pixels at each
 * point's distance (cloud_layer.h), from a pixel's angle at the image's centre.
 *
 * Placement: the noise's origin is the camera's world position (double) minus the wind's
 * displacement v t (direction (sin a, 0, cos a), a = clouds.wind_azimuth_deg), rounded to float
 * once, so a kernel's noise point p + origin is exact to float rounding of the sum. The global
 * majorant of the Monte Carlo walk is clouds.density (the density's bound, cloud_layer.h); the
 * majorant grid (cloud_majorant.h) of the reference's walk and of the path tracer's volume stage
 * (path.clouds = volume: cloud_track.h) refines it around the camera: a buffer of
 * CLOUDS_GRID_NX x NY x NZ cell bounds, filled by its pass for each view. The sun shadow map
 * (clouds.shadow_map, cloud_shadow_map.h) of the methods single and march is a buffer of
 * size^2 x levels density integrals toward the sun, filled by its pass for each view. With path.clouds =
 * volume in path mode the layer is the path tracer's volume medium alone (registry row
 * clouds_path_volume: the one majorant walk in volume mode), so every atmosphere method can be
 * the air's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_cloud.h"
#include "atmo/plan_clouds.h"
#include "clouds/cloud_majorant.h"

/* A pixel's angle (rad) at the image's centre: the perspective's 2 tan(fov/2) / height, the
 * panorama's 2 pi / width, the fisheye's fov / height. */
static double pixel_angle(const atmo_scene *s)
{
    double fov = s->camera.fov_deg * M_PI / 180.0;
    if (s->camera.kind == ATMO_CAMERA_PANORAMA)
        return 2.0 * M_PI / s->image.width;
    if (s->camera.kind == ATMO_CAMERA_FISHEYE)
        return fov / s->image.height;
    return 2.0 * tan(0.5 * fov) / s->image.height;
}

void atmo_plan_clouds_origin(const atmo_scene *s, float4 *origin)
{
    double a = s->clouds.wind_azimuth_deg * M_PI / 180.0;
    double shift = s->clouds.wind_m_s * s->clouds.time_s;
    origin->x = (float)(s->camera.position_m[0] - shift * sin(a));
    origin->y = (float)s->camera.position_m[1];
    origin->z = (float)(s->camera.position_m[2] - shift * cos(a));
    origin->w = 0.0f;
}

int atmo_plan_clouds_volume(const atmo_scene *s)
{
    return s->clouds.enabled && s->path.mode == ATMO_RENDER_PATH &&
           s->path.clouds == ATMO_PATH_CLOUDS_VOLUME;
}

int atmo_plan_clouds(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int m = s->atmosphere.method, rc;
    int volume = atmo_plan_clouds_volume(s);
    if (!volume && m != ATMO_METHOD_SINGLE && m != ATMO_METHOD_MARCH && m != ATMO_METHOD_REFERENCE)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "clouds.enabled works with atmosphere.method=single, march or reference "
                         "(got %s); set one of those, or render.mode=path with path.clouds=volume",
                         p->method);
    if (volume && s->clouds.look == ATMO_CLOUDS_LOOK_THESIS)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "clouds.look=thesis is the marcher's look, which path.clouds=volume does "
                         "not march; set clouds.look=physical or path.clouds=march");
    if (s->cloud.enabled)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.enabled (the homogeneous shell) and clouds.enabled (the fBm layer) "
                         "exclude each other; set one of them to false");
    if (s->clouds.top_m <= s->clouds.bottom_m)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "clouds.top_m (%g) must be above clouds.bottom_m (%g); raise the top",
                         s->clouds.top_m, s->clouds.bottom_m);
    atmo_mie_optics o;
    if ((rc = atmo_plan_mie_optics(s, "clouds.dsd",
                                        s->clouds.dsd[0] ? s->clouds.dsd : "cumulus", 1, p, &o, e)))
        return rc;
    atmo_gpu_clouds *g = &p->gpu.clouds;
    for (int i = 0; i < 3; i++) {
        int from_dsd = s->clouds.extinction_per_m == 0.0;
        (&g->extinction.x)[i] = (float)(from_dsd ? o.sigma_ext_per_lwc[i] * s->clouds.lwc_g_m3
                                                 : s->clouds.extinction_per_m);
        (&g->albedo.x)[i] = (float)(from_dsd ? o.albedo[i] : s->clouds.albedo);
        (&g->g.x)[i] = (float)o.g[i];
    }
    atmo_plan_clouds_origin(s, &g->origin);
    g->frequency.x = (float)s->clouds.frequency_per_m[0];
    g->frequency.y = (float)s->clouds.frequency_per_m[1];
    g->frequency.z = (float)s->clouds.frequency_per_m[2];
    g->frequency.w = (float)(1.0 / s->clouds.coverage_scale_m);
    g->bottom_m = (float)s->clouds.bottom_m;
    g->top_m = (float)s->clouds.top_m;
    g->fade_m = (float)s->clouds.fade_m;
    g->coverage = (float)s->clouds.coverage;
    g->density = (float)s->clouds.density;
    g->sharpness = (float)s->clouds.sharpness;
    g->warp_m = (float)s->clouds.warp_m;
    g->step_m = (float)s->clouds.step_m;
    g->light_distance_m = (float)s->clouds.light_distance_m;
    g->max_distance_m = (float)s->clouds.max_distance_m;
    g->ms_a = (float)s->clouds.ms_a;
    g->ms_b = (float)s->clouds.ms_b;
    g->ms_c = (float)s->clouds.ms_c;
    g->ms_d = (float)s->clouds.ms_d;
    g->majorant = (float)s->clouds.density;
    g->diameter_um = (float)o.diameter_um;
    g->sun_guiding = (float)s->clouds.sun_guiding;
    g->phase = s->clouds.phase;
    g->table_size = o.count;
    g->octaves = s->clouds.octaves;
    g->steps = s->clouds.steps;
    g->light_steps = s->clouds.light_steps;
    g->ms_octaves = s->clouds.ms_octaves;
    g->look = s->clouds.look;
    g->seed = (uint)s->clouds.seed;
    g->footprint = (float)(s->clouds.lod * pixel_angle(s));
    float *cdf = NULL;
    if ((rc = atmo_plan_phase_cdf(o.rows, o.count, p, &cdf, e)))
        return rc;
    if ((rc = atmo_plan_add_buffer(p, "clouds_phase_table", "float4",
                                   sizeof(float4) * (size_t)o.count, 0, o.rows, e)))
        return rc;
    return atmo_plan_add_buffer(p, "clouds_phase_cdf", "float", sizeof(float) * (size_t)o.count,
                                0, cdf, e);
}

int atmo_plan_clouds_majorant(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    (void)s;
    size_t cells = (size_t)CLOUDS_GRID_NX * CLOUDS_GRID_NY * CLOUDS_GRID_NZ;
    int rc = atmo_plan_add_buffer(p, "clouds_majorant", "float", sizeof(float) * cells, 1, NULL, e);
    return rc ? rc
              : atmo_plan_add_pass(p, "clouds_majorant_grid", CLOUDS_GRID_NX, CLOUDS_GRID_NY,
                                   CLOUDS_GRID_NZ, 0, e);
}

int atmo_plan_clouds_shadow_map(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int n = s->clouds.shadow_map_size, levels = s->clouds.shadow_map_levels;
    size_t bytes = sizeof(float) * (size_t)n * (size_t)n * (size_t)levels;
    if (bytes > ATMO_CLOUDS_SHADOW_MAP_MAX_BYTES)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "clouds.shadow_map_size=%d x clouds.shadow_map_levels=%d needs %.0f MiB, "
                         "over the %.0f MiB limit; lower either",
                         n, levels, bytes / 1048576.0, ATMO_CLOUDS_SHADOW_MAP_MAX_BYTES / 1048576.0);
    atmo_gpu_clouds *g = &p->gpu.clouds;
    g->shadow_map_size = n;
    g->shadow_map_levels = levels;
    g->shadow_map_steps = s->clouds.shadow_map_steps;
    int rc = atmo_plan_add_buffer(p, "clouds_shadow_map", "float", bytes, 1, NULL, e);
    return rc ? rc : atmo_plan_add_pass(p, "clouds_shadow_map_nodes", n, levels, n, 0, e);
}
