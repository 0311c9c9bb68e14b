/* test_lut_param — ray geometry and the transmittance LUT parametrisation (kernels/common/geometry.h,
 * kernels/atmosphere/atmosphere.h), compiled on the host exactly as the kernels use them.
 * labels: unit
 *
 * Oracles: closed forms of sphere geometry (distance to the top straight up = top - bottom;
 * horizontal from the ground = sqrt(top^2 - bottom^2); the horizon cosine
 * -sqrt(1 - bottom^2/r^2) separates ground and sky rays), the definition of the mapping
 * (texel centres at the ends: u = 0.5/W <-> looking straight up, u = 1 - 0.5/W <-> the ray
 * grazing the ground,
 * v = 0.5/H <-> the ground, v = 1 - 0.5/H <-> the top), and round trips (r, mu) -> (u, v) ->
 * (r, mu), compared by r and by the ray's length d to the top (what the mapping parametrises;
 * mu itself is ill-conditioned for short upward rays near the top, where T = 1 anyway).
 * Float tolerances: r to 1 m (float spacing at 6.4e6 m is 0.5 m); d to 1e-5 of the longest ray
 * (17.5 m of 1750 km: mu carries 6e-8 relative rounding, which near the horizon the slope
 * dd/dmu ~ r^2 / sqrt(discriminant) amplifies; 17.5 m is 1/400 of a texel of a 256-wide LUT). */
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "testlib.h"

int main(void)
{
    atmo_gpu_atmosphere a = {0};
    a.bottom_radius = 6360e3f;
    a.top_radius = 6420e3f;
    const float R = a.bottom_radius, T = a.top_radius;
    const int W = 256, H = 64;

    CHECK_ABS(geometry_distance_to_top(R, 1.0f, T), 60000.0, 0.5);
    CHECK_REL(geometry_distance_to_top(R, 0.0f, T), sqrt(6420e3 * 6420e3 - 6360e3 * 6360e3), 1e-6);
    CHECK_ABS(geometry_distance_to_bottom(R + 1000.0f, -1.0f, R), 1000.0, 0.5);
    double r = 6361e3, mu_h = -sqrt(1.0 - 6360e3 * 6360e3 / (r * r));
    CHECK(geometry_ray_hits_ground((float)r, (float)(mu_h - 1e-4), R));
    CHECK(!geometry_ray_hits_ground((float)r, (float)(mu_h + 1e-4), R));
    /* altitude along a ray: vertical and horizontal closed forms, to well under a metre */
    CHECK_ABS(geometry_altitude_at(R + 10.0f, 1.0f, 1234.5f, R), 1244.5, 0.01);
    CHECK_ABS(geometry_altitude_at(R, 0.0f, 100e3f, R), sqrt(6360e3 * 6360e3 + 1e10) - 6360e3, 0.01);

    /* texel centres at the ends of the parametrisation */
    float u, v;
    atmosphere_transmittance_uv(&a, R, 1.0f, W, H, &u, &v);
    CHECK_ABS(u, 0.5 / W, 1e-6);
    CHECK_ABS(v, 0.5 / H, 1e-6);
    double mu_top_horizon = -sqrt(1.0 - 6360e3 * 6360e3 / (6420e3 * 6420e3));
    atmosphere_transmittance_uv(&a, T, (float)mu_top_horizon, W, H, &u, &v);
    CHECK_ABS(u, 1.0 - 0.5 / W, 1e-6);
    CHECK_ABS(v, 1.0 - 0.5 / H, 1e-6);
    atmosphere_transmittance_uv(&a, (float)r, (float)mu_h, W, H, &u, &v);
    CHECK_ABS(u, 1.0 - 0.5 / W, 2e-4);

    float rr, mm;
    atmosphere_transmittance_r_mu(&a, 0.5f / W, 0.5f / H, W, H, &rr, &mm);
    CHECK_ABS(rr, R, 1.0);
    CHECK_ABS(mm, 1.0, 1e-6);
    atmosphere_transmittance_r_mu(&a, 1.0f - 0.5f / W, 1.0f - 0.5f / H, W, H, &rr, &mm);
    CHECK_ABS(rr, T, 1.0);
    CHECK_ABS(mm, mu_top_horizon, 2e-4);

    /* round trips over the whole domain of sky rays */
    double worst_r = 0.0, worst_d = 0.0;
    /* at the very top every upward ray has length 0 and maps to u = 0.5/W: stop below it */
    for (int i = 0; i < 40; i++)
        for (int j = 0; j <= 40; j++) {
            float r0 = R + (T - R) * (float)i / 40.0f;
            float mu_min = -sqrtf(fmaxf(1.0f - (R / r0) * (R / r0), 0.0f));
            float mu0 = mu_min + (1.0f - mu_min) * (float)j / 40.0f;
            atmosphere_transmittance_uv(&a, r0, mu0, W, H, &u, &v);
            atmosphere_transmittance_r_mu(&a, u, v, W, H, &rr, &mm);
            worst_r = fmax(worst_r, fabs(rr - r0));
            /* the parametrisation is of the ray's length d, so that is what must come back */
            float d0 = geometry_distance_to_top(r0, mu0, T), d1 = geometry_distance_to_top(rr, mm, T);
            worst_d = fmax(worst_d, fabs(d1 - d0));
        }
    CHECK_ABS(worst_r, 0.0, 1.0);
    CHECK_ABS(worst_d, 0.0, 17.5);
    printf("round trip: worst r %.3f m, worst ray length %.3f m\n", worst_r, worst_d);

    /* texcoord <-> unit are inverses, and map [0, 1] to the texel centres */
    CHECK_ABS(atmosphere_texcoord_from_unit(0.0f, W), 0.5 / W, 1e-7);
    CHECK_ABS(atmosphere_unit_from_texcoord(atmosphere_texcoord_from_unit(0.37f, W), W), 0.37, 1e-6);
    return test_finish();
}
