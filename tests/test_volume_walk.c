/* test_volume_walk — the path tracer's volume medium on the one majorant walk
 * (kernels/media/media_walk.h in volume mode: media_walk_volume_flight, the free flight of
 * render/volume_stage.h, and media_walk_sun_transmittance(..., MEDIA_WALK_VOLUME, ...), the
 * shadow query of path.h's path_shadow) over the composed volume medium (the fBm layer's row
 * clouds_path_volume: cloud_track.h's majorant grid and coefficients). Scene: thesis-6 in path
 * mode with path.clouds = volume (a grey layer: clouds.extinction_per_m > 0, albedo 0.9512).
 * labels: kernel stat
 *
 * Rays: 4 rays 20 km long from random points in and below the layer in random directions, each
 * with a cloud optical depth tau(20 km) in [0.3, 3] (green) and, toward the sun from its origin,
 * tau_sun in [0.1, 3] (the quadrature below with 2048 steps decides). 8192 walks per ray.
 * Oracles (closed forms of the walk's estimators, with the optical depth
 * tau(t) = int_0^t sigma_t dt of the layer alone (no air in volume mode) by a double-precision
 * midpoint quadrature of the host build of clouds_density at the walk's points o + t d and
 * altitudes geometry_altitude_at, 2^16 steps; its error is taken as the difference from 2^15
 * steps, three times the error of the finer one):
 *   - the free flight (spectral tracking, absorption in the weight w): the passing walks'
 *     mean of w (0 for a walk that scatters) is T(0, L) = exp(-tau(L)); the mean of w over the
 *     walks that scatter before t_j (0 for the others) is a (1 - exp(-tau(t_j))), a the albedo,
 *     at the three distances t_j where tau reaches 1/4, 1/2 and 3/4 of tau(L): the exponential
 *     free-flight CDF at three points;
 *   - the shadow query (ratio tracking with roulette): the mean of T toward the sun from the
 *     ray's origin is exp(-tau_sun) to the top of the atmosphere;
 * each a z-test: |mean - oracle| <= 4.5 standard errors (sample standard deviation /
 * sqrt(8192)) plus the quadrature's error. 20 z-tests. A broken walk fails them: with the
 * volume medium left out of the volume mode's majorant (compose.c's walk condition inverted)
 * the flights never scatter and T = 1, and all 20 fail. What they cannot see, by design: a
 * majorant below the extinction (the layer's rate x 0.5 or x 0.1) or held over a whole part
 * (the grid's cell ends ignored) leaves these estimators unbiased (ratio tracking's weight is
 * unbiased for any positive rate, and spectral tracking's weight carries the deficit; measured:
 * all 20 pass), so only a zero rate where the medium has extinction, or a wrong extinction,
 * biases them.
 *   - determinism: the same walks run in reverse order give the same floats bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "common/geometry.h"
#include "clouds/cloud_layer.h"
#include "media/ray.h"
#include "testlib.h"
#include "testscene.h"

#define RAYS 4
#define WALKS 8192
#define CANDIDATES 2048
#define LENGTH_M 20000.0f
#define FINE (1 << 16)
#define Z_MAX 4.5

static const char probe[] =
    "__kernel void walks(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *rays, __global const uint *order,\n"
    "                    __global float4 *out, uint n, uint walks) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  uint item = order[i];\n"
    "  float4 o = rays[2u * (item / walks)], d = rays[2u * (item / walks) + 1u];\n"
    "  medium_ray m = medium_ray_make(s, v3(o.x, o.y, o.z), v3(d.x, d.y, d.z));\n"
    "  rng_stream g = rng_stream_stage(21u, item, 0u, 0u);\n"
    "  float t = -1.0f; vec3 w;\n"
    "  int hit = media_walk_volume_flight(s, ATMO_LUT_ARGS, &m, d.w, &g, &t, &w) != WALK_NULL;\n"
    "  medium_point q = medium_ray_at(&m, 0.0f, s->atmosphere.bottom_radius);\n"
    "  rng_stream h = rng_stream_stage(23u, item, 0u, 0u);\n"
    "  vec3 T = media_walk_sun_transmittance(s, ATMO_LUT_ARGS, &q, MEDIA_WALK_VOLUME, &h);\n"
    "  out[item] = (float4)(hit ? t : -1.0f, w.y, T.y, 0.0f);\n"
    "}\n";

/* The layer's green extinction at t along origin + t dir (radius r, cosine mu at the origin). */
static double extinction(const atmo_gpu_scene *s, vec3 o, vec3 d, float r, float mu, double t)
{
    float h = geometry_altitude_at(r, mu, (float)t, s->atmosphere.bottom_radius);
    vec3 p = v3_add(o, v3_scale(d, (float)t));
    return (double)clouds_density(&s->clouds, p, h) * s->clouds.extinction.y;
}

/* The optical depth over [0, L] by the midpoint rule with n steps; with cum, its running values
 * at the ends of the steps. */
static double depth(const atmo_gpu_scene *s, vec3 o, vec3 d, float r, float mu, double L, int n,
                    double *cum)
{
    double dt = L / n, tau = 0.0;
    for (int j = 0; j < n; j++) {
        tau += extinction(s, o, d, r, mu, (j + 0.5) * dt) * dt;
        if (cum)
            cum[j] = tau;
    }
    return tau;
}

static float uniform(uint i, uint k) { return rng_uniform(9u, i, 0u, k); }

typedef struct ray {
    vec3 o, d;
    double tau, tau_err, t_j[3], tau_j[3], sun, sun_err;
} ray;

/* A candidate ray m: 1 where its optical depths are in range, with the fine quadratures. */
static int pick(const atmo_gpu_scene *s, uint m, ray *out, double *cum)
{
    const atmo_gpu_atmosphere *a = &s->atmosphere;
    float x = (uniform(m, 0) - 0.5f) * 3e4f, z = (uniform(m, 1) - 0.5f) * 3e4f;
    float y = 500.0f + uniform(m, 2) * 5500.0f - (s->camera.local_up.w - a->bottom_radius);
    vec3 o = v3(x, y, z);
    float cz = 2.0f * uniform(m, 3) - 1.0f, phi = 6.2831853f * uniform(m, 4);
    float sz = sqrtf(fmaxf(1.0f - cz * cz, 0.0f));
    vec3 d = v3(sz * cosf(phi), cz, sz * sinf(phi));
    medium_ray ry = medium_ray_make(s, o, d);
    if (geometry_ray_hits_ground(ry.r, ry.mu_s, a->bottom_radius))
        return 0;
    float d_top = geometry_distance_to_top(ry.r, ry.mu_s, a->top_radius);
    vec3 sun = v3_from4(s->sun_direction);
    double tau = depth(s, o, d, ry.r, ry.mu, LENGTH_M, 2048, NULL);
    if (tau < 0.3 || tau > 3.0)
        return 0;
    double tau_sun = depth(s, o, sun, ry.r, ry.mu_s, d_top, 2048, NULL);
    if (tau_sun < 0.1 || tau_sun > 3.0)
        return 0;
    out->o = o, out->d = d;
    double coarse = depth(s, o, d, ry.r, ry.mu, LENGTH_M, FINE / 2, NULL);
    out->tau = depth(s, o, d, ry.r, ry.mu, LENGTH_M, FINE, cum);
    out->tau_err = fabs(out->tau - coarse);
    for (int k = 0; k < 3; k++) { /* where tau reaches (k + 1) / 4 of tau(L) */
        int j = 0;
        while (j < FINE - 1 && cum[j] < 0.25 * (k + 1) * out->tau)
            j++;
        out->t_j[k] = (j + 1) * (double)LENGTH_M / FINE;
        out->tau_j[k] = cum[j];
    }
    double sun_coarse = depth(s, o, sun, ry.r, ry.mu_s, d_top, FINE / 2, NULL);
    out->sun = depth(s, o, sun, ry.r, ry.mu_s, d_top, FINE, NULL);
    out->sun_err = fabs(out->sun - sun_coarse);
    return 1;
}

/* A z-test of a mean against its oracle with the oracle's own error. */
static void z_test(const char *what, int r, double sum, double sum2, double want, double err)
{
    double mean = sum / WALKS;
    double se = sqrt(fmax(sum2 / WALKS - mean * mean, 0.0) / (WALKS - 1));
    printf("ray %d, %s: %.5f +- %.5f, oracle %.5f (+- %.1e), z %+.2f\n", r, what, mean, se, want,
           err, se > 0.0 ? (mean - want) / se : 0.0);
    CHECK_ABS(mean, want, Z_MAX * se + err);
}

int main(void)
{
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-6");
    test_scene_set(&sc, "render.mode=path");
    test_scene_set(&sc, "path.clouds=volume");
    test_scene_set(&sc, "clouds.look=physical");
    test_scene_set(&sc, "post.flare=false");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    atmo_plan p;
    test_plan(&sc, &p);
    const atmo_gpu_scene *s = &p.gpu;
    CHECK(s->clouds.extinction.x == s->clouds.extinction.y); /* the grey layer of the oracle */

    ray rays[RAYS];
    double *cum = malloc(sizeof(double) * FINE);
    CHECK(cum != NULL);
    int found = 0;
    for (uint m = 0; m < CANDIDATES && found < RAYS; m++)
        found += pick(s, m, &rays[found], cum);
    free(cum);
    CHECK(found == RAYS);
    if (found < RAYS)
        return test_finish();

    atmo_cl cl;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, &p, probe);
    cl_mem scene = test_cl_buffer(&cl, sizeof p.gpu, &p.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS] = {0};
    test_precompute(&cl, prog, scene, &p, luts);
    float4 geometry[2 * RAYS];
    for (int r = 0; r < RAYS; r++) {
        geometry[2 * r].x = rays[r].o.x, geometry[2 * r].y = rays[r].o.y;
        geometry[2 * r].z = rays[r].o.z, geometry[2 * r].w = 0.0f;
        geometry[2 * r + 1].x = rays[r].d.x, geometry[2 * r + 1].y = rays[r].d.y;
        geometry[2 * r + 1].z = rays[r].d.z, geometry[2 * r + 1].w = LENGTH_M;
    }
    uint n = RAYS * WALKS, walks = WALKS;
    float4 *out = malloc(sizeof(float4) * n), *out2 = malloc(sizeof(float4) * n);
    CHECK(out && out2);
    test_run_walks(&cl, prog, scene, luts, geometry, sizeof geometry, sizeof(float4), n, walks, out,
                   out2);
    CHECK(memcmp(out, out2, sizeof(float4) * n) == 0);

    double albedo = s->clouds.albedo.y;
    for (int r = 0; r < RAYS; r++) {
        const ray *ry = &rays[r];
        double pass = 0, pass2 = 0, sun = 0, sun2 = 0, before[3] = {0}, before2[3] = {0};
        for (int w = 0; w < WALKS; w++) {
            float4 v = out[r * WALKS + w];
            double wt = v.y;
            if (v.x < 0.0f)
                pass += wt, pass2 += wt * wt;
            for (int j = 0; j < 3; j++)
                if (v.x >= 0.0f && v.x < ry->t_j[j])
                    before[j] += wt, before2[j] += wt * wt;
            sun += v.z, sun2 += (double)v.z * v.z;
        }
        printf("ray %d: tau(20 km) %.4f, tau_sun %.4f\n", r, ry->tau, ry->sun);
        z_test("flight passes: w vs exp(-tau(L))", r, pass, pass2, exp(-ry->tau),
               exp(-ry->tau) * ry->tau_err);
        for (int j = 0; j < 3; j++) {
            char what[96];
            snprintf(what, sizeof what, "flight scatters before %.0f m: w vs a (1 - exp(-tau))",
                     ry->t_j[j]);
            double want = albedo * (1.0 - exp(-ry->tau_j[j]));
            z_test(what, r, before[j], before2[j], want,
                   albedo * exp(-ry->tau_j[j]) * ry->tau_err);
        }
        z_test("sun transmittance vs exp(-tau_sun)", r, sun, sun2, exp(-ry->sun),
               exp(-ry->sun) * ry->sun_err);
    }
    free(out2), free(out);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    atmo_plan_free(&p);
    return test_finish();
}
