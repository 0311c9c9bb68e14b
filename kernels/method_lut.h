/* method_lut.h — atmosphere method "lut": the sky from precomputed 4-D scattering tables with
 * all orders of scattering (Bruneton 2017), filled by lut_precompute.cl, laid out and read as
 * lut_scattering.h describes.
 *
 * For a camera at radius r (moved along the ray to the top of the atmosphere when it is above
 * it; a ray that misses the atmosphere sees only the sun) looking along mu:
 *     L = S_R(r, mu, mu_s, nu) p_R(nu) + S_M(r, mu, mu_s, nu) p_M(nu) + M(r, mu, mu_s, nu)
 *       + T(r -> ground) (rho / pi) [E T_sun(R, mu_s,g) max(mu_s,g, 0) + E_ind(R, mu_s,g)]
 * where the last line is for rays that hit the ground (mu_s,g the sun cosine at the ground
 * point), S_R and S_M are the single-scattering tables without phase (the phase functions are
 * applied here with the exact nu), M the sum of orders 2..N (phase included: unlike Bruneton,
 * who divides it by p_R, nothing is assumed about its angular shape), and E_ind the ground
 * irradiance of orders 1..N-1. The sun disc (returned apart) is E / Omega_sun times the
 * transmittance to space. Deterministic: no random numbers.
 *
 * Knobs (scene keys -> atmo_gpu_scene, host/plan_lut.c):
 *   lut.nu_size, lut.mu_s_size, lut.mu_size, lut.r_size -> lut_dims[0] = {nu, mu_s, mu, r}
 *     (defaults 8, 32, 128, 32; mu even: half ground rays, half sky rays)
 *   lut.steps -> method_int[0]: segments per texel ray (default 64)
 *   lut.sphere_samples -> method_int[1]: zenith rings of the sphere grid (even, default 32:
 *     with 16 the sky at the ground came out up to 2.3 % darker than the Monte Carlo reference
 *     for sun zenith <= 80 deg, with 32 within 1.7 %; normalising the phase functions over
 *     the grid did not help, the horizon's bright band in the incoming light is what needs
 *     the rings)
 *   lut.orders -> method_int[2]: scattering orders (default 7: in blue with the sun on the
 *     horizon, where orders fall slowest, order 8 would add at most 0.06 %,
 *     tests/test_lut_method.c). */
#ifndef ATMO_METHOD_LUT_H
#define ATMO_METHOD_LUT_H
#ifndef __OPENCL_VERSION__
#include "compat.h"
#include "atmosphere.h"
#include "geometry.h"
#include "lut_scattering.h"
#include "phase.h"
#include "sky_method.h"
#include "sky_single.h"
#endif

ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r,
                          float mu, float mu_s, float nu, uint pixel, uint sample, vec3 *sky,
                          vec3 *sun)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    ATMO_GLOBAL const int *dims = s->lut_dims[0];
    int tw = s->transmittance_width, th = s->transmittance_height, N = LUT_TEXELS(dims);
    vec3 E = v3_from4(a->solar_irradiance);
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    int looks_at_sun = nu >= s->sun_direction.w;
    (void)pixel;
    (void)sample;
    (void)lut_c; /* scratch of the precompute */
    mu = atmo_clamp_cos(mu);
    mu_s = atmo_clamp_cos(mu_s);
    nu = atmo_clamp_cos(nu);
    r = fmaxf(r, a->bottom_radius);

    if (!atmosphere_enter(a, &r, &mu, &mu_s, nu)) { /* the ray misses the atmosphere */
        if (looks_at_sun)
            *sun = atmosphere_sun_disc_radiance(a, s->sun_direction.w);
        return;
    }

    int ground = geometry_ray_hits_ground(r, mu, a->bottom_radius);
    float p_nu = lut_nu_position(nu, dims[0]), p_mu_s = lut_mu_s_position(a, mu_s, dims[1]);
    float p_mu = lut_mu_position(a, r, mu, ground, dims[2]), p_r = lut_r_position(a, r, dims[3]);
    vec3 L = v3_add(
        v3_add(v3_scale(lut_scattering_fetch(lut_a, dims, p_nu, p_mu_s, p_mu, p_r),
                        phase_rayleigh(nu)),
               v3_scale(lut_scattering_fetch(lut_b, dims, p_nu, p_mu_s, p_mu, p_r),
                        sky_mie_phase(a, nu))),
        lut_scattering_fetch(lut_a + N, dims, p_nu, p_mu_s, p_mu, p_r));
    if (ground) {
        float d = geometry_distance_to_bottom(r, mu, a->bottom_radius);
        float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu) / a->bottom_radius);
        vec3 direct = v3_scale(v3_mul(E, atmosphere_sun_transmittance(a, lut_transmittance, tw,
                                                                      th, a->bottom_radius,
                                                                      mu_s_g)),
                               fmaxf(mu_s_g, 0.0f));
        vec3 indirect = lut_irradiance_lookup(a, lut_b + N, dims, a->bottom_radius, mu_s_g);
        vec3 T = lut_transmittance_to_ground(s, lut_transmittance, r, mu, d);
        L = v3_add(L, v3_mul(v3_mul(T, v3_from4(a->ground_albedo)),
                             v3_scale(v3_add(direct, indirect), 1.0f / ATMO_PI)));
    } else if (looks_at_sun) {
        vec3 to_space = atmosphere_transmittance_to_top(a, lut_transmittance, tw, th, r, mu);
        *sun = v3_mul(atmosphere_sun_disc_radiance(a, s->sun_direction.w), to_space);
    }
    *sky = L;
}

#endif
