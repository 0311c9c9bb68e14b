/* test_clouds_thesis — the thesis look's soft clamp of the clouds' light (kernels/media/
 * cloud_march.h, host build of the shared headers).
 * labels: unit
 * composes: atmosphere clouds clouds_medium visibility clouds_march medium
 *
 * Oracle: the clamp's closed form, in double precision,
 *     f(L) = L_clamp (1 - e^{-L / L_clamp}),  L_clamp = 3 E_sun / (4 pi)  (per channel),
 * applied to the clouds' light L that the same marcher returns unclamped (clouds_march, the
 * steps that clouds_interval runs before it clamps). On a grey cloud deck under a 45-degree sun
 * with Rayleigh air, over 6 views (towards the sun: the forward peak far above L_clamp; away:
 * far below) and two densities (0.4 and 0.004), clouds_interval's light must equal
 * L_air + f(L) per channel within float rounding: the kernel's float division, expm1f,
 * product and sum, a few ulps (6e-8 each), bounded by REL_FLOAT = 1e-6. Without the clamp the
 * error would be L - f(L) = L^2 / (2 L_clamp) to first order, which must exceed 10 REL_FLOAT
 * of the light on every ray (measured: at least 5.8e-5), so the test fails. Further:
 * the clamped light never exceeds L_clamp; where L < 0.01 L_clamp it equals L to first order
 * (relative deficit at most L / (2 L_clamp)); the views reach both L > 2 L_clamp and
 * L < 0.01 L_clamp, so both ends are tested; the clamp itself, against the closed form on a
 * grid of L / L_clamp from 1e-6 to 1e3, is monotone and below its asymptote; a channel without
 * sunlight stays 0 (not NaN). With the physical look nothing is clamped: clouds_interval's
 * light is bitwise that of the steps and the clouds' separate sum stays 0. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "kernels_composed.h"
#include "testclouds.h"
#include "testlib.h"

#define LUTS                                                                                       \
    lut, lut, lut, lut, lut, lut, NULL, NULL, NULL, lut, lut, cdf, grid, NULL, NULL, NULL, NULL
#define REL_FLOAT 1e-6

static double closed_form(double L, double level) { return -level * expm1(-L / level); }

static double channel(vec3 v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

int main(void)
{
    static float4 lut[16]; /* optical depth 0 everywhere: the air's transmittance is 1 */
    float cdf[2] = {0.0f, 1.0f};
    static float grid[1];
    atmo_gpu_scene s;
    test_overcast_scene(&s);
    s.atmosphere.rayleigh_scattering.x = 5.8e-6f, s.atmosphere.rayleigh_scattering.y = 13.5e-6f;
    s.atmosphere.rayleigh_scattering.z = 33.1e-6f;
    s.atmosphere.solar_irradiance.x = 1.5f, s.atmosphere.solar_irradiance.y = 1.9f;
    s.atmosphere.solar_irradiance.z = 1.7f;
    atmo_gpu_clouds *c = &s.clouds;
    c->light_distance_m = 1e5f;
    c->step_m = 200.0f;
    c->light_steps = 8;

    /* the level per channel, as the header derives it */
    double level[3];
    for (int k = 0; k < 3; k++)
        level[k] = 3.0 * channel(v3_from4(s.atmosphere.solar_irradiance), k) / (4.0 * M_PI);

    /* (elevation, azimuth from the sun) of the views, degrees */
    const double views[][2] = {{45, 0}, {50, 8}, {60, 30}, {30, 90}, {60, 180}, {20, 150}};
    const float densities[] = {0.4f, 0.04f, 0.004f};
    double ratio_max = 0.0, ratio_min = INFINITY, sensitivity = INFINITY;
    for (int d = 0; d < 3; d++) {
        c->density = densities[d];
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            double el = views[v][0] * M_PI / 180.0, az = views[v][1] * M_PI / 180.0;
            vec3 dir = v3((float)(cos(el) * cos(az)), (float)sin(el), (float)(cos(el) * sin(az)));
            medium_ray m = medium_ray_from_camera(&s, dir);
            float lo[2], hi[2];
            int parts = geometry_shell_parts(s.atmosphere.bottom_radius, c->bottom_m, c->top_m,
                                           m.r, m.mu, 0.0f, 1e7f, lo, hi);
            CHECK(parts == 1);

            c->look = ATMO_CLOUDS_LOOK_THESIS;
            vec3 air = v3(0.0f, 0.0f, 0.0f), cloud = v3(0.0f, 0.0f, 0.0f);
            vec3 T = v3(1.0f, 1.0f, 1.0f), medium_t = v3(1.0f, 1.0f, 1.0f);
            clouds_march(&s, LUTS, &m, lo[0], hi[0], 0.5f, 0, 0, &air, &cloud, &T, &medium_t);
            vec3 full = v3(0.0f, 0.0f, 0.0f);
            T = medium_t = v3(1.0f, 1.0f, 1.0f);
            clouds_interval(&s, LUTS, &m, lo[0], hi[0], 0.5f, 0, 0, &full, &T, &medium_t);
            for (int k = 0; k < 3; k++) {
                double L = channel(cloud, k), got = channel(full, k), L_air = channel(air, k);
                double want = L_air + closed_form(L, level[k]), ratio = L / level[k];
                CHECK(L > 0.0);
                CHECK_REL(got, want, REL_FLOAT);
                CHECK(got - L_air <= level[k] + REL_FLOAT * got);
                if (ratio < 0.01) /* first order: f(L) = L (1 - L / (2 L_clamp) + ...) */
                    CHECK(fabs((got - L_air) / L - 1.0) <= 0.5 * ratio + REL_FLOAT * got / L);
                sensitivity = fmin(sensitivity, (L - closed_form(L, level[k])) / want);
                ratio_max = fmax(ratio_max, ratio);
                ratio_min = fmin(ratio_min, ratio);
            }
            printf("density %.3f, view (%2.0f, %3.0f) deg: L / L_clamp %.4g %.4g %.4g, clamped "
                   "%.4g %.4g %.4g, air %.3g\n",
                   densities[d], views[v][0], views[v][1], cloud.x / level[0],
                   cloud.y / level[1], cloud.z / level[2], (full.x - air.x) / level[0],
                   (full.y - air.y) / level[1], (full.z - air.z) / level[2], air.y);

            /* the physical look: nothing clamped, nothing summed apart */
            c->look = ATMO_CLOUDS_LOOK_PHYSICAL;
            vec3 steps = v3(0.0f, 0.0f, 0.0f), none = v3(0.0f, 0.0f, 0.0f);
            T = medium_t = v3(1.0f, 1.0f, 1.0f);
            clouds_march(&s, LUTS, &m, lo[0], hi[0], 0.5f, 0, 0, &steps, &none, &T, &medium_t);
            vec3 physical = v3(0.0f, 0.0f, 0.0f);
            T = medium_t = v3(1.0f, 1.0f, 1.0f);
            clouds_interval(&s, LUTS, &m, lo[0], hi[0], 0.5f, 0, 0, &physical, &T, &medium_t);
            CHECK(memcmp(&physical, &steps, sizeof physical) == 0);
            CHECK(none.x == 0.0f && none.y == 0.0f && none.z == 0.0f);
        }
    }
    printf("L / L_clamp over the views: %.3g ... %.3g; the clamp's smallest share of the light "
           "%.3g\n",
           ratio_min, ratio_max, sensitivity);
    CHECK(ratio_max > 2.0);  /* the clamp bites */
    CHECK(ratio_min < 0.01); /* and the first-order end is reached */
    CHECK(sensitivity > 10.0 * REL_FLOAT); /* every view would fail without the clamp */

    /* the curve alone: closed form, monotone, below the asymptote */
    vec3 lv = v3(0.3f, 0.3f, 0.3f);
    double previous = 0.0;
    for (double x = 1e-6; x <= 1e3; x *= 1.25) {
        vec3 f = clouds_thesis_clamp(v3((float)(x * 0.3f), 0.0f, 0.0f), lv);
        CHECK_REL(f.x, closed_form((double)(float)(x * 0.3f), 0.3f), REL_FLOAT);
        CHECK(f.x >= previous && f.x <= 0.3f);
        previous = f.x;
    }
    CHECK_REL(previous, 0.3f, REL_FLOAT);

    /* a channel without sunlight: no light, no NaN */
    c->look = ATMO_CLOUDS_LOOK_THESIS;
    c->density = 0.4f;
    s.atmosphere.solar_irradiance.z = 0.0f;
    medium_ray m = medium_ray_from_camera(&s, v3(0.6f, 0.8f, 0.0f));
    float lo[2], hi[2];
    CHECK(geometry_shell_parts(s.atmosphere.bottom_radius, c->bottom_m, c->top_m, m.r, m.mu, 0.0f,
                             1e7f, lo, hi) == 1);
    vec3 L = v3(0.0f, 0.0f, 0.0f), T = v3(1.0f, 1.0f, 1.0f), medium_t = T;
    clouds_interval(&s, LUTS, &m, lo[0], hi[0], 0.5f, 0, 0, &L, &T, &medium_t);
    CHECK(L.z == 0.0f && isfinite(L.x) && L.x > 0.0f);
    return test_finish();
}
