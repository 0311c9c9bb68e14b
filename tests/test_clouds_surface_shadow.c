/* test_clouds_surface_shadow — the fBm cloud layer's shadow on a surface point (the terrain's,
 * an object's: visibility_sun_surface, media_sun_surface_attenuate) and on the air outside the
 * clouds (media_sun_attenuate, cloud_march.h's samples in clear air) takes the whole chord
 * toward the sun through the layer (cloud_layer_medium.h's clouds_chord_density), where the
 * samples inside clouds stop their light march at clouds.light_distance_m.
 * Scene: thesis-8 (the sun 9.8 degrees high: a 7 km layer's chord is 40 km) without its terrain,
 * method march, the light march's default 8 km and 4 steps.
 * labels: kernel stat
 *
 * Oracle: D_fine, a double-precision midpoint quadrature of the density integral toward the
 * sun over the whole chord through the layer (cloud_layer.h's clouds_density, host build,
 * bitwise the device's: test_cloud_noise), FINE_STEPS uniform steps, the points' altitudes in
 * double; its error |D_fine - D_half| / 3 (the midpoint rule's error falls 4 times per halving).
 * The device's marches sample each of their steps at an offset hashed from the point (uniform
 * in [0, 1)): stratified sampling, an unbiased estimate of D over many points. At POINTS
 * random points in and below the layer within 30 km of the camera, with extinction x D_fine
 * below TAU_MAX (so the marches' stop at optical depth 16 seldom cuts):
 *   - surface: the mean of D_surface - D_fine (D_surface from the slot's transmittance, in
 *     CLOUDS_SURFACE_LIGHT_STEPS steps) lies within 4 standard errors (the differences'
 *     spread / sqrt(n)) plus the mean of D_fine's error;
 *   - air: the same for the air's D_air (light_steps steps over the whole chord), and the
 *     air's slot media_sun_attenuate gives exp(-extinction D_air) of that same estimate (the
 *     same hashed offsets: to float rounding);
 *   - power: the light march of the samples inside clouds, cut at 8 km (clouds_sun_density),
 *     misses the clouds beyond: its mean D_cut - D_fine is negative by more than 4 of its
 *     standard errors over the points whose chord is longer than light_distance_m (the air's
 *     and the surfaces' shadow before the whole chord).
 * The per-point spreads are printed (the marches' noise). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "common/compat.h"
#include "common/geometry.h"
#include "common/rng.h"
#include "clouds/cloud_layer.h"
#include "testlib.h"
#include "testscene.h"

#define POINTS 4096
#define FINE_STEPS 1024
#define TAU_MAX 6.0
#define RANGE_M 30000.0

static const char probe_src[] =
    "__kernel void shade(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *p, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  vec3 o = (vec3)(p[i].x, p[i].y, p[i].z), sun = v3_from4(s->sun_direction);\n"
    "  medium_ray m = medium_ray_make(s, o, sun);\n"
    "  medium_point q = medium_ray_at(&m, 0.0f, s->atmosphere.bottom_radius);\n"
    "  vec3 one = (vec3)(1.0f, 1.0f, 1.0f);\n"
    "  vec3 a = media_sun_surface_attenuate(s, ATMO_LUT_ARGS, &q, one);\n"
    "  vec3 b = media_sun_attenuate(s, ATMO_LUT_ARGS, &q, one);\n"
    "  float d_air = clouds_chord_density(s, ATMO_LUT_ARGS, &q, s->clouds.light_steps);\n"
    "  float d_cut = clouds_sun_density(s, &q, clouds_point_jitter(q.p, s->clouds.seed));\n"
    "  out[i] = (float4)(a.y, b.y, d_air, d_cut);\n"
    "}\n";

/* The altitude of p + t sun (mu_s the sun's cosine to the vertical at p, radius r). */
static double altitude(double R, double r, double mu_s, double t)
{
    double rt = sqrt(r * r + 2.0 * r * mu_s * t + t * t);
    return (t * (t + 2.0 * r * mu_s) + (r - R) * (r + R)) / (rt + R);
}

/* D over the chord through the layer from p (altitude h, sun cosine mu_s), n midpoint steps;
 * *chord: the chord's length from where it enters the layer. */
static double fine_depth(const atmo_gpu_scene *s, const double p[3], double h, double mu_s, int n,
                         double *chord)
{
    double R = s->atmosphere.bottom_radius, r = R + h;
    double bottom = R + s->clouds.bottom_m, top = R + s->clouds.top_m;
    double t0 = h < s->clouds.bottom_m
                    ? -r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + bottom * bottom)
                    : 0.0;
    double t1 = -r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + top * top);
    const float *sun = &s->sun_direction.x;
    double dt = (t1 - t0) / n, D = 0.0;
    for (int j = 0; j < n; j++) {
        double t = t0 + (j + 0.5) * dt;
        float x[3];
        for (int a = 0; a < 3; a++)
            x[a] = (float)(p[a] + t * sun[a]);
        D += clouds_density(&s->clouds, v3(x[0], x[1], x[2]), (float)altitude(R, r, mu_s, t)) *
             dt;
    }
    *chord = t1 - t0;
    return D;
}

/* The mean, its standard error and the spread of a sample of differences. */
typedef struct stat {
    int n;
    double sum, sum2;
} stat;

static void stat_add(stat *a, double x) { a->n++, a->sum += x, a->sum2 += x * x; }
static double stat_mean(const stat *a) { return a->sum / a->n; }
static double stat_spread(const stat *a)
{
    double m = stat_mean(a);
    return sqrt(fmax(a->sum2 / a->n - m * m, 0.0) * a->n / (a->n - 1));
}
static double stat_se(const stat *a) { return stat_spread(a) / sqrt((double)a->n); }
static void stat_print(const char *what, const stat *a)
{
    printf("  %s: D - D_fine mean %.3g m (standard error %.3g m), spread %.3g m per point, %d "
           "points\n",
           what, stat_mean(a), stat_se(a), stat_spread(a), a->n);
}

int main(void)
{
    test_require_opencl();
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-8");
    test_scene_set(&sc, "terrain.enabled=false");
    test_scene_image(&sc, 8, 8, 1, 0);
    atmo_plan p;
    test_plan(&sc, &p);
    const atmo_gpu_scene *s = &p.gpu;
    double R = s->atmosphere.bottom_radius, r_c = s->camera.local_up.w, k = s->clouds.extinction.y;
    double up[3] = {s->camera.local_up.x, s->camera.local_up.y, s->camera.local_up.z};
    double e1[3] = {up[1], -up[0], 0.0}, n1 = hypot(e1[0], e1[1]);
    for (int a = 0; a < 3; a++)
        e1[a] /= n1;
    double e2[3] = {up[1] * e1[2] - up[2] * e1[1], up[2] * e1[0] - up[0] * e1[2],
                    up[0] * e1[1] - up[1] * e1[0]};

    /* random points: horizontal offsets within RANGE_M, altitudes 0 .. top */
    static float4 pts[POINTS], out[POINTS];
    static double pd[POINTS][3];
    for (int i = 0; i < POINTS; i++) {
        double x = RANGE_M * (2.0 * rng_uniform(11u, (uint)i, 0u, 0u) - 1.0);
        double z = RANGE_M * (2.0 * rng_uniform(11u, (uint)i, 0u, 1u) - 1.0);
        double h = s->clouds.top_m * rng_uniform(11u, (uint)i, 0u, 2u);
        /* the point at (x, z) on the tangent plane, lifted to altitude h along its vertical */
        double c[3], len = 0.0;
        for (int a = 0; a < 3; a++)
            c[a] = r_c * up[a] + x * e1[a] + z * e2[a], len += c[a] * c[a];
        len = sqrt(len);
        for (int a = 0; a < 3; a++)
            pd[i][a] = c[a] * (R + h) / len - r_c * up[a];
        pts[i] = (float4){(float)pd[i][0], (float)pd[i][1], (float)pd[i][2], 0.0f};
    }
    test_plan_points(&p, probe_src, "shade", pts, sizeof *pts, out, sizeof *out, POINTS);

    stat surface = {0}, air = {0}, cut = {0};
    double sum_err = 0.0, worst_slot = 0.0;
    const float *sun = &s->sun_direction.x;
    for (int i = 0; i < POINTS; i++) {
        /* recompute the point's altitude and sun cosine in double from its float position */
        double q[3] = {pts[i].x, pts[i].y, pts[i].z}, v[3], r = 0.0, mu_s = 0.0;
        for (int a = 0; a < 3; a++)
            v[a] = q[a] + r_c * up[a], r += v[a] * v[a];
        r = sqrt(r);
        for (int a = 0; a < 3; a++)
            mu_s += v[a] / r * sun[a];
        double h = r - R, chord, half_chord;
        double D = fine_depth(s, q, h, mu_s, FINE_STEPS, &chord);
        double D_half = fine_depth(s, q, h, mu_s, FINE_STEPS / 2, &half_chord);
        if (k * D >= TAU_MAX || out[i].x <= 0.0f)
            continue;
        stat_add(&surface, -log(out[i].x) / k - D);
        stat_add(&air, out[i].z - D);
        sum_err += fabs(D - D_half) / 3.0;
        /* the air's slot: exp(-k D_air) of the same estimate (float exp and product) */
        double slot = exp(-k * out[i].z);
        worst_slot = fmax(worst_slot, fabs(out[i].y - slot) / fmax(slot, 1e-30) *
                                          (slot > 1e-30 ? 1.0 : 0.0));
        if (chord > s->clouds.light_distance_m)
            stat_add(&cut, out[i].w - D);
    }
    double err = sum_err / surface.n;
    printf("%d of %d points below optical depth %.0f (D_fine's error %.3g m):\n", surface.n,
           POINTS, TAU_MAX, err);
    stat_print("surface (32 steps, whole chord)", &surface);
    stat_print("air (light_steps, whole chord)", &air);
    stat_print("the cut march, chords over light_distance_m", &cut);
    printf("the air's slot against exp(-k D_air): worst relative difference %.3g\n", worst_slot);
    CHECK(surface.n >= POINTS / 4);
    CHECK(fabs(stat_mean(&surface)) <= 4.0 * stat_se(&surface) + err);
    CHECK(fabs(stat_mean(&air)) <= 4.0 * stat_se(&air) + err);
    CHECK(worst_slot < 1e-5);
    CHECK(cut.n >= POINTS / 8);
    CHECK(stat_mean(&cut) < -4.0 * stat_se(&cut));
    atmo_plan_free(&p);
    return test_finish();
}
