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
 * transmittance to space. The whole ray is deterministic (no random numbers); a segment, the
 * aerial perspective to a point (below), marches with a random offset per sample.
 *
 * Knobs (scene keys -> s->lut, atmo_gpu_lut; host/features/atmosphere/plan_lut.c), and the buffers
 * scattering_rayleigh, scattering_mie and scattering_scratch (layout in lut_scattering.h):
 *   lut.nu_size, lut.mu_s_size, lut.mu_size, lut.r_size -> lut.dims = {nu, mu_s, mu, r}
 *     (defaults 8, 32, 128, 32; mu even: half ground rays, half sky rays)
 *   lut.steps -> lut.steps: segments per texel ray (default 64)
 *   lut.sphere_samples -> lut.rings: zenith rings of the sphere grid (even, default 32: the
 *     horizon's bright band in the incoming light is what needs the rings; measured choices:
 *     docs/notes/lut_method.md)
 *   lut.orders -> lut.orders: scattering orders (default 7: in blue with the sun on the
 *     horizon, where orders fall slowest, order 8 would add at most 0.06 %,
 *     tests/test_lut_method.c). */
#ifndef ATMO_METHOD_LUT_H
#define ATMO_METHOD_LUT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "atmosphere/lut_scattering.h"
#include "common/phase.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/medium.h"
#include "media/visibility.h"
#endif

/* The three tables at (r, mu, mu_s, nu), phase functions applied: S_R p_R + S_M p_M + M, for a
 * ray on the `ground` side of the horizon. */
ATMO_FN vec3 lut_scattered(ATMO_GLOBAL const atmo_gpu_scene *s,
                           ATMO_GLOBAL const float4 *scattering_rayleigh,
                           ATMO_GLOBAL const float4 *scattering_mie, float r, float mu, float mu_s,
                           float nu, int ground)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    ATMO_GLOBAL const int *dims = s->lut.dims;
    float p_nu = lut_nu_position(nu, dims[0]), p_mu_s = lut_mu_s_position(a, mu_s, dims[1]);
    float p_mu = lut_mu_position(a, r, mu, ground, dims[2]), p_r = lut_r_position(a, r, dims[3]);
    vec3 rayleigh = lut_scattering_fetch(scattering_rayleigh, dims, p_nu, p_mu_s, p_mu, p_r);
    vec3 mie = lut_scattering_fetch(scattering_mie, dims, p_nu, p_mu_s, p_mu, p_r);
    vec3 multiple = lut_scattering_fetch(scattering_rayleigh + LUT_TEXELS(dims), dims, p_nu, p_mu_s, p_mu, p_r);
    return v3_add(v3_add(v3_scale(rayleigh, phase_rayleigh(nu)),
                         v3_scale(mie, media_mie_phase(a, nu))),
                  multiple);
}

/* The sky along a ray from inside the atmosphere (r, mu already entered): the tables and, for a
 * ray that hits the ground at distance d_ground, the lit ground seen through T (view_t gets T,
 * or the transmittance to the top for a sky ray). */
ATMO_FN vec3 lut_sky(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                       float mu_s, float nu, int ground, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    ATMO_GLOBAL const int *dims = s->lut.dims;
    int tw = s->transmittance_width, th = s->transmittance_height;
    (void)scattering_scratch; /* scratch of the precompute */
    vec3 L = lut_scattered(s, scattering_rayleigh, scattering_mie, r, mu, mu_s, nu, ground);
    if (!ground) {
        *view_t = atmosphere_transmittance_to_top(a, transmittance_lut, tw, th, r, mu);
        return L;
    }
    float d = geometry_distance_to_bottom(r, mu, a->bottom_radius);
    float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu) / a->bottom_radius);
    medium_point g; /* the ground point, for the visibility sources */
    g.p = v3(0.0f, 0.0f, 0.0f);
    g.r = a->bottom_radius, g.h = 0.0f, g.mu = mu, g.mu_s = mu_s_g;
    vec3 direct = v3_scale(medium_sunlight(s, ATMO_LUT_ARGS, &g), fmaxf(mu_s_g, 0.0f));
    vec3 indirect = lut_irradiance_lookup(a, scattering_mie + LUT_TEXELS(dims), dims, a->bottom_radius,
                                          mu_s_g);
    *view_t = lut_transmittance_to_ground(s, transmittance_lut, r, mu, d);
    return v3_add(L, v3_mul(v3_mul(*view_t, v3_from4(a->ground_albedo)),
                            v3_scale(v3_add(direct, indirect), 1.0f / ATMO_PI)));
}

/* The whole ray from the tables (deterministic: no random numbers). */
ATMO_FN void lut_whole_ray(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                           float mu_s, float nu, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = v3(1.0f, 1.0f, 1.0f);
    int looks_at_sun = nu >= s->sun_direction.w;
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
    *sky = lut_sky(s, ATMO_LUT_ARGS, r, mu, mu_s, nu, ground, view_t);
    if (!ground && looks_at_sun)
        *sun = v3_mul(atmosphere_sun_disc_radiance(a, s->sun_direction.w), *view_t);
}

/* The method's ray (sky_method.h): the whole ray from the tables (lut_whole_ray). A segment
 * [0, d] that reaches the ground or the top is the whole ray too. A shorter one is marched: the
 * medium integrator (kernels/media/medium.h: single scattering with the transmittance LUT)
 * plus, at each sample, the stored density of orders
 * >= 2 (LUT_DENSITY_SUM) -- the integral that lut_multiple (lut_precompute.cl) evaluates over
 * whole texel rays, here stopped at d -- with s->view_steps segments and one random offset per
 * sample (the first number of the method's stream), as methods single and march do.
 * Why not Bruneton's two-lookup difference S(x, v) - T(x, y) S(y, v), y at distance d (both
 * lookups on the camera ray's side of the horizon): it subtracts the radiances of two whole
 * rays, so the lookups' interpolation error (a few tenths of a percent) is multiplied by
 * S(x) / L_segment, which near the horizon is about a hundred for 1 km; and at the horizon,
 * where a segment that ends in the air is continuous, the two halves of the mu axis
 * interpolate differently, which makes a band. Interpolating across a narrow band of mu around
 * the horizon (Bruneton 2008) would address the band only, not the short segments above it.
 * The march has neither error: it reads the density, a local quantity continuous across the
 * horizon, never a difference; measured within 2.2 % of the table
 * tests/data/reference_segments.csv for sun zenith <= 80 deg (reduced tables; 2.1 % with the
 * default ones), no step at the horizon larger than 1.03 times its neighbours
 * (tests/test_aerial.c, which also checks that the difference still fails; its numbers:
 * docs/notes/lut_method.md). It costs view_steps lookups of the density table and of the
 * transmittance LUT instead of six table lookups.
 * With a volume medium of the path tracer (MEDIA_VOLUME > 0: path.clouds = volume) the air's
 * sunlight at each sample passes it (media_walk.h's media_walk_volume_sun), which the tables
 * cannot hold: every ray is marched then, a whole one with its lit ground and sun disc
 * (medium_integrate). */
#define LUT_TABLE_RAYS (MEDIA_VOLUME == 0) /* the tables know no shadows of a volume medium */

ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                       float t_max, rng_stream *g, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    medium_result res;
    if (!(t_max < INFINITY) && LUT_TABLE_RAYS) {
        lut_whole_ray(s, ATMO_LUT_ARGS, m->r, m->mu, m->mu_s, m->nu, sky, sun, view_t);
        return;
    }
    if (!(t_max < INFINITY)) { /* the whole ray marched, sun disc and lit ground included */
        medium_integrate(s, ATMO_LUT_ARGS, m, 0.0f, INFINITY, s->view_steps, rng_next(g), 1,
                         &res);
        *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, m->nu);
        *sun = res.sun;
        *view_t = res.view_t;
        return;
    }
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = v3(1.0f, 1.0f, 1.0f);
    medium_ray c = *m;
    c.mu = atmo_clamp_cos(c.mu);
    c.mu_s = atmo_clamp_cos(c.mu_s);
    c.nu = atmo_clamp_cos(c.nu);
    c.r = fmaxf(c.r, a->bottom_radius);
    float d_in = t_max - atmosphere_entry_distance(a, c.r, c.mu);
    float r_in = c.r, mu_in = c.mu, mu_s_in = c.mu_s;
    if (!atmosphere_enter(a, &r_in, &mu_in, &mu_s_in, c.nu) || d_in <= 0.0f)
        return;
    int ground = geometry_ray_hits_ground(r_in, mu_in, a->bottom_radius);
    float d_end = ground ? geometry_distance_to_bottom(r_in, mu_in, a->bottom_radius)
                         : geometry_distance_to_top(r_in, mu_in, a->top_radius);
    if (d_in >= d_end && LUT_TABLE_RAYS) {
        *sky = lut_sky(s, ATMO_LUT_ARGS, r_in, mu_in, mu_s_in, c.nu, ground, view_t);
        return;
    }
    medium_integrate(s, ATMO_LUT_ARGS, &c, 0.0f, t_max, s->view_steps, rng_next(g), 1, &res);
    *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, c.nu);
    *view_t = res.view_t;
}

#endif
