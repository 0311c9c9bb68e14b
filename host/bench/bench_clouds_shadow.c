/* bench_clouds_shadow.c — the sun-transmittance error of the fBm layer's shadow term for
 * `atmo bench clouds` (bench_clouds.c): the light march (cloud_layer.h's clouds_sun_density,
 * light_steps steps cut to light_distance_m in cloud and over the whole chord in clear air,
 * jittered by the point's hash) or the sun shadow map
 * (cloud_shadow_map.h's lookup of nodes as its pass computes them) against a double-precision
 * midpoint quadrature of the whole chord toward the sun (BENCH_SHADOW_FINE_STEPS uniform steps;
 * the reference's ratio tracking does not cut the chord either), T = exp(-extinction D) at
 * 550 nm, at the marcher's sample points of the bench's rays.
 *
 * The sample points: the steps of the marcher (cloud_march.h's clouds_interval) along each ray
 * inside the layer's shell with sample offset 1/2: dt = step_m + CLOUDS_STEP_GROWTH t, times
 * CLOUDS_CLEAR_STRIDE where the coverage test finds clear air, up to clouds.steps steps and the
 * far plane; the view's transmittance cut (T < CLOUDS_T_MIN) is not applied, so points deep
 * in a cloud count as much as its lit side. The map's nodes are computed on the host with the
 * kernel's own functions (host build) as the lookups need them, so the error is the map's at
 * its resolution without building it whole. Run on the host's one core; its seconds are not
 * charted. */
#include <math.h>
#include <stdlib.h>
#include "atmo/bench.h"
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "clouds/cloud_layer.h"
#include "clouds/cloud_shadow_map.h"

#define BENCH_SHADOW_FINE_STEPS 2048

/* D over the whole chord from q toward the sun through the layer, in double. */
static double fine_depth(const atmo_gpu_scene *s, const medium_point *q)
{
    const atmo_gpu_clouds *c = &s->clouds;
    double R = (double)s->atmosphere.bottom_radius, r = (double)q->r, mu = (double)q->mu_s;
    double top = R + (double)c->top_m;
    const double p[3] = {(double)q->p.x, (double)q->p.y, (double)q->p.z};
    const double sun[3] = {(double)s->sun_direction.x, (double)s->sun_direction.y,
                           (double)s->sun_direction.z};
    double len = -r * mu + sqrt(fmax(r * r * mu * mu - r * r + top * top, 0.0));
    double dt = len / BENCH_SHADOW_FINE_STEPS, D = 0.0;
    for (int i = 0; i < BENCH_SHADOW_FINE_STEPS; i++) {
        double t = (i + 0.5) * dt, rt = sqrt(r * r + 2.0 * r * mu * t + t * t);
        double h = (t * (t + 2.0 * r * mu) + (r - R) * (r + R)) / (rt + R);
        vec3 x = v3((float)(p[0] + t * sun[0]), (float)(p[1] + t * sun[1]),
                    (float)(p[2] + t * sun[2]));
        D += (double)clouds_density(c, x, (float)h) * dt;
    }
    return D;
}

/* D at q as the configuration computes it; map: the scene's map with its nodes filled lazily
 * (NAN where not yet computed). Without the map, the marcher's rule (cloud_march.h): a point
 * in cloud marches light_steps cut at light_distance_m, a point in clear air the whole chord
 * in as many steps. */
static double config_depth(const atmo_gpu_scene *s, float *map, const clouds_grid_frame *f,
                           const medium_point *q)
{
    float jitter = clouds_point_jitter(q->p, s->clouds.seed);
    if (!map && clouds_density(&s->clouds, q->p, q->h) > 0.0f)
        return (double)clouds_sun_density(s, q, jitter);
    if (!map)
        return (double)clouds_sun_density_chord(s, q, jitter, s->clouds.light_steps);
    int n = s->clouds.shadow_map_size, i, j, k;
    vec3 t;
    if (clouds_shadow_map_cell(s, f, q->p, q->h, &i, &j, &k, &t))
        for (int c = 0; c < 8; c++) {
            int a = i + (c & 1), b = j + ((c >> 1) & 1), d = k + (c >> 2);
            float *node = &map[((size_t)b * n + d) * n + a];
            if (isnan(*node))
                *node = clouds_shadow_map_node(s, f, a, b, d);
        }
    return (double)clouds_shadow_map_density(s, map, q);
}

int bench_clouds_shadow_error(const atmo_plan *plan, const float4 *rays, int n_rays,
                              bench_shadow_error *out, atmo_err *e)
{
    const atmo_gpu_scene *s = &plan->gpu;
    const atmo_gpu_clouds *c = &s->clouds;
    float *map = NULL;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    if (c->shadow_map_size > 0) {
        size_t nodes = (size_t)c->shadow_map_size * c->shadow_map_size * c->shadow_map_levels;
        if (!(map = malloc(sizeof(float) * nodes)))
            return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the shadow map's nodes");
        for (size_t i = 0; i < nodes; i++)
            map[i] = NAN;
    }
    float R = s->atmosphere.bottom_radius;
    double k = (double)c->extinction.y;
    for (int r = 0; r < n_rays; r++) {
        medium_ray m = medium_ray_from_cosines(s, rays[r].x, rays[r].y, rays[r].z, rays[r].w);
        float lo[2], hi[2];
        int parts = geometry_shell_parts(R, c->bottom_m, c->top_m, m.r, m.mu, 0.0f,
                                       c->max_distance_m, lo, hi);
        int steps = 0;
        for (int part = 0; part < parts; part++)
            for (float t = lo[part]; t < hi[part] && steps < c->steps; steps++) {
                float dt = c->step_m + CLOUDS_STEP_GROWTH * t;
                medium_point q = medium_ray_at(&m, t, R);
                int cloudy = clouds_coverage(c, q.p) > 0.0f;
                if (!cloudy)
                    dt *= CLOUDS_CLEAR_STRIDE;
                dt = fminf(dt, hi[part] - t);
                q = medium_ray_at(&m, t + 0.5f * dt, R);
                double T = exp(-k * fine_depth(s, &q));
                double err = exp(-k * config_depth(s, map, &f, &q)) - T;
                out->sq_all += err * err, out->n_all++;
                if (clouds_density(c, q.p, q.h) > 0.0f)
                    out->sq_cloud += err * err, out->n_cloud++;
                t += dt;
            }
    }
    free(map);
    return ATMO_OK;
}
