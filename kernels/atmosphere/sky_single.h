/* sky_single.h — single scattering along one view ray (Nishita et al. 1993's integrand).
 *
 * For a camera at radius r looking along mu, with sun cosine mu_s and view-sun cosine nu,
 *     L = int_0^d T(0, t) [sigma_R(t) p_R(nu) + sigma_M,s(t) p_M(nu)] E T_sun(t) dt
 *       + T(0, d) (rho / pi) E T_sun(d) max(mu_s(d), 0)          if the ray hits the ground
 * with d the distance to the ground or to the top of the atmosphere and T_sun from the
 * transmittance LUT (zero where the planet hides the sun). The integral is cut into n segments
 * growing as (i/n)^2 from the camera, [d (i/n)^2, d ((i+1)/n)^2]: short where the density
 * changes fastest along rays that start low (the aerosols' 1.2 km scale height is shorter than
 * an equal segment of an upward ray; measured against the double-precision reference with 64
 * segments: 0.40 % worst with equal segments, 0.09 % with these; 4096-sample probes of the Monte
 * Carlo table's views: median relative standard error 7.7e-4 -> 5.2e-4, worst 6.1e-3 ->
 * 1.7e-3, and 32 segments of the march agree with 256 within 0.1 % instead of 0.6 %). In
 * each, the coefficients are taken at one point (at the fraction `jitter` of the segment, a
 * random number per sample, so averaging samples removes the banding of a fixed point) and the
 * segment is integrated exactly for constant coefficients:
 *     L += T_acc S (1 - e^{-sigma_t dt}) / sigma_t,   T_acc *= e^{-sigma_t dt}
 * which conserves energy however long the segment (Hillaire 2015). A camera above the
 * atmosphere is first moved to where the ray enters it. The sun disc (radiance E / Omega_sun
 * times the transmittance to space, Omega_sun = 2 pi (1 - cos alpha)) is returned apart so the
 * caller can weigh it with its own luminous efficacy. Method march (ms_lut.h) adds its
 * multiple-scattering terms to the same integrator (sky_integrate with use_ms), so the two
 * methods agree term for term where Psi is zero.
 *
 * Segments (aerial perspective, sky_method.h's sky_segment): with t_max finite the ray ends at
 * a black surface at distance t_max from the camera: d = min(t_max, distance to the ground or
 * the top), the n segments cover [0, d], and the ground term and the sun disc are left out
 * when the surface comes first. The transmittance T(0, d) of the same sum is returned too. */
#ifndef ATMO_SKY_SINGLE_H
#define ATMO_SKY_SINGLE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "atmo/gpu_types.h"
#endif

/* (1 - e^{-sigma dt}) / sigma, with its limit dt where sigma dt is tiny. */
ATMO_FN float sky_segment_weight(float sigma, float dt)
{
    float x = sigma * dt;
    return x > 1e-4f ? -expm1f(-x) / sigma : dt * (1.0f - 0.5f * x);
}

ATMO_FN float sky_mie_phase(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float nu)
{
    return a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN ? phase_henyey_greenstein(nu, a->mie_g)
                             : phase_cornette_shanks(nu, a->mie_g);
}

#ifdef ATMO_MS_LUT
/* method march: the multiple-scattering terms, defined in kernels/atmosphere/ms_lut.h (after this file) */
ATMO_FN vec3 ms_lut_sky_irradiance(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                   ATMO_GLOBAL const float4 *lut, int width, int height,
                                   float mu_s);
ATMO_FN vec3 ms_lut_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *lut,
                           int width, int height, float r, float mu, float mu_s, float nu,
                           vec3 sigma_r, vec3 sigma_m);
#define ATMO_SKY_INTEGRATE_HAS_MS
#endif

#ifdef ATMO_LUT_J
/* method lut: the density J of orders >= 2 toward the ray (the table at scattering_mie + N + I,
 * with `ground` the ray's side of the horizon) and the sky's irradiance on the ground, from its
 * tables; defined in kernels/atmosphere/method_lut.h (after this file) */
ATMO_FN vec3 lut_ms_source(ATMO_GLOBAL const atmo_gpu_scene *s,
                           ATMO_GLOBAL const float4 *scattering_mie, float r, float mu, float mu_s,
                           float nu, int ground);
ATMO_FN vec3 lut_ms_ground_irradiance(ATMO_GLOBAL const atmo_gpu_scene *s,
                                      ATMO_GLOBAL const float4 *scattering_mie, float mu_s);
#endif

/* The shadow hook: visibility of the sun (0..1) from the sample at distance t along the view
 * ray, at radius r_t with sun cosine mu_s_t. The planet's own shadow is already in T_sun. */
ATMO_FN float march_sun_visibility(ATMO_GLOBAL const atmo_gpu_scene *s, float r_t, float mu_s_t,
                                   float t)
{
    return 1.0f;
}

/* The integral above along (r, mu) with sun cosine mu_s and view-sun cosine nu up to distance
 * t_max (INFINITY for the whole ray), n segments with sample offset `jitter`, in parts: nu is
 * constant along a straight ray, so the phase functions factor out of single scattering, L =
 * p_R(nu) *single_r + p_M(nu) *single_m + *rest, with single_r = int T sigma_R E T_sun V dt and
 * single_m likewise for Mie; *rest holds the lit ground and, with use_ms, a multiple-scattering
 * source at each sample and the ground lit by the sky too: method march's (-DATMO_MS_LUT: ms_lut.h,
 * from the LUT `ms` of ms_w x ms_h) or method lut's (-DATMO_LUT_J: its tables, `ms` = its buffer
 * scattering_mie). *sun = the sun disc's radiance where the ray sees it, *view_t = T(0, d). */
ATMO_FN void sky_integrate_parts(ATMO_GLOBAL const atmo_gpu_scene *s,
                                 ATMO_GLOBAL const float4 *transmittance,
                                 ATMO_GLOBAL const float4 *ms, int ms_w, int ms_h, int use_ms,
                                 float r, float mu, float mu_s, float nu, float t_max, int n,
                                 float jitter, vec3 *single_r, vec3 *single_m, vec3 *rest,
                                 vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    int tw = s->transmittance_width, th = s->transmittance_height;
    vec3 E = v3_from4(a->solar_irradiance);
    *single_r = v3(0.0f, 0.0f, 0.0f);
    *single_m = v3(0.0f, 0.0f, 0.0f);
    *rest = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = v3(1.0f, 1.0f, 1.0f);
    int looks_at_sun = nu >= s->sun_direction.w;

    t_max -= atmosphere_entry_distance(a, r, mu);
    if (!atmosphere_enter(a, &r, &mu, &mu_s, nu)) { /* the ray misses the atmosphere */
        if (looks_at_sun)
            *sun = atmosphere_sun_disc_radiance(a, s->sun_direction.w);
        return;
    }
    if (t_max <= 0.0f) /* the surface lies before the atmosphere */
        return;

    int ground = geometry_ray_hits_ground(r, mu, a->bottom_radius);
    float d = ground ? geometry_distance_to_bottom(r, mu, a->bottom_radius)
                     : geometry_distance_to_top(r, mu, a->top_radius);
    int blocked = t_max < d; /* by the black surface at t_max */
    int hits_ground = ground && !blocked;
    if (blocked)
        d = t_max;
    vec3 beta_r = v3_from4(a->rayleigh_scattering), beta_m = v3_from4(a->mie_scattering);
    vec3 L_r = v3(0.0f, 0.0f, 0.0f), L_m = v3(0.0f, 0.0f, 0.0f), L = v3(0.0f, 0.0f, 0.0f);
    vec3 T = v3(1.0f, 1.0f, 1.0f);
    for (int i = 0; i < n; i++) {
        float x0 = (float)i / (float)n, x1 = (float)(i + 1) / (float)n;
        float dt = d * (x1 * x1 - x0 * x0), t = d * x0 * x0 + jitter * dt;
        float r_t = geometry_radius_at(r, mu, t);
        float h = geometry_altitude_at(r, mu, t, a->bottom_radius);
        float mu_s_t = atmo_clamp_cos((r * mu_s + t * nu) / r_t);
        vec3 sigma_r = v3_scale(beta_r, expf(-h / a->rayleigh_scale_height));
        vec3 sigma_m = v3_scale(beta_m, expf(-h / a->mie_scale_height));
        vec3 sigma_t = atmosphere_extinction(a, h);
        vec3 sun_t = v3_scale(atmosphere_sun_transmittance(a, transmittance, tw, th, r_t, mu_s_t),
                              march_sun_visibility(s, r_t, mu_s_t, t));
        vec3 w = v3(sky_segment_weight(sigma_t.x, dt), sky_segment_weight(sigma_t.y, dt),
                    sky_segment_weight(sigma_t.z, dt));
        vec3 lit = v3_mul(v3_mul(T, w), v3_mul(E, sun_t));
        L_r = v3_add(L_r, v3_mul(lit, sigma_r));
        L_m = v3_add(L_m, v3_mul(lit, sigma_m));
#ifdef ATMO_MS_LUT
        if (use_ms)
            L = v3_add(L, v3_mul(v3_mul(T, w),
                                 ms_lut_source(s, ms, ms_w, ms_h, r_t, (r * mu + t) / r_t, mu_s_t,
                                               nu, sigma_r, sigma_m)));
#endif
#ifdef ATMO_LUT_J
        if (use_ms)
            L = v3_add(L, v3_mul(v3_mul(T, w), lut_ms_source(s, ms, r_t, (r * mu + t) / r_t,
                                                             mu_s_t, nu, ground)));
#endif
        T = v3_mul(T, v3_exp(v3_scale(sigma_t, -dt)));
    }
    if (hits_ground) {
        float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu) / a->bottom_radius);
        vec3 sun_t = atmosphere_sun_transmittance(a, transmittance, tw, th, a->bottom_radius,
                                                  mu_s_g);
        vec3 irradiance = v3_scale(v3_mul(E, sun_t), fmaxf(mu_s_g, 0.0f));
#ifdef ATMO_MS_LUT
        if (use_ms) /* plus the sky's */
            irradiance = v3_add(irradiance, ms_lut_sky_irradiance(a, ms, ms_w, ms_h, mu_s_g));
#endif
#ifdef ATMO_LUT_J
        if (use_ms)
            irradiance = v3_add(irradiance, lut_ms_ground_irradiance(s, ms, mu_s_g));
#endif
        L = v3_add(L, v3_mul(T, v3_scale(v3_mul(v3_from4(a->ground_albedo), irradiance),
                                         1.0f / ATMO_PI)));
    } else if (looks_at_sun && !blocked) {
        vec3 to_space = atmosphere_transmittance_to_top(a, transmittance, tw, th, r, mu);
        *sun = v3_mul(atmosphere_sun_disc_radiance(a, s->sun_direction.w), to_space);
    }
    *single_r = L_r;
    *single_m = L_m;
    *rest = L;
    *view_t = T;
}

/* The integral above: sky_integrate_parts with the phase functions applied. */
ATMO_FN void sky_integrate(ATMO_GLOBAL const atmo_gpu_scene *s,
                           ATMO_GLOBAL const float4 *transmittance, ATMO_GLOBAL const float4 *ms,
                           int ms_w, int ms_h, int use_ms, float r, float mu, float mu_s, float nu,
                           float t_max, int n, float jitter, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    vec3 single_r, single_m, rest;
    sky_integrate_parts(s, transmittance, ms, ms_w, ms_h, use_ms, r, mu, mu_s, nu, t_max, n,
                        jitter, &single_r, &single_m, &rest, sun, view_t);
    *sky = v3_add(v3_add(v3_scale(single_r, phase_rayleigh(nu)),
                         v3_scale(single_m, sky_mie_phase(&s->atmosphere, nu))),
                  rest);
}

/* Single scattering alone (method single), with s->view_steps segments. */
ATMO_FN void sky_single_scattering(ATMO_GLOBAL const atmo_gpu_scene *s,
                                   ATMO_GLOBAL const float4 *transmittance, float r, float mu,
                                   float mu_s, float nu, float jitter, vec3 *sky, vec3 *sun)
{
    vec3 view_t;
    sky_integrate(s, transmittance, transmittance, 0, 0, 0, r, mu, mu_s, nu, INFINITY,
                  s->view_steps, jitter, sky, sun, &view_t);
}

/* The same over the segment [0, d] of the ray: in-scattered light and T(0, d). */
ATMO_FN void sky_single_segment(ATMO_GLOBAL const atmo_gpu_scene *s,
                                ATMO_GLOBAL const float4 *transmittance, float r, float mu,
                                float mu_s, float nu, float d, float jitter, vec3 *inscatter,
                                vec3 *view_t)
{
    vec3 sun;
    sky_integrate(s, transmittance, transmittance, 0, 0, 0, r, mu, mu_s, nu, d, s->view_steps,
                  jitter, inscatter, &sun, view_t);
}

#endif
