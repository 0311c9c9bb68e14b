/* media.h — the medium contract: what the medium integrator (medium.h), the scattering
 * sources of the methods and the Monte Carlo reference (method_reference.h, tracking.h) know of
 * the participating media, and the one medium every scene has, the air.
 *
 * A medium gives, at a point of a ray (ray.h's medium_point), its extinction and the scattering
 * coefficient of each of its components, whose phase functions media_phase evaluates; the sum
 * over the media present is what media_at returns:
 *     sigma_t(x) = sum_m sigma_t,m(x),  sigma_s,k(x) for the components k,  p_k(nu) per steradian
 * The air (atmosphere.h: Rayleigh and Mie scattering with their scale heights, ozone absorbing)
 * holds components MEDIA_RAYLEIGH and MEDIA_MIE. Every other medium is a feature (a cloud
 * shell, an fBm layer) that registers its functions in the plan's registry
 * (host/plan/features.c); the plan numbers the components (MEDIA_COMPONENTS, MEDIA_<NAME>, in
 * the generated prelude) and generates the composition (host/plan/compose.c) that defines,
 * after the media's own fragments,
 *     media_at, media_phase       the sum over the media, the phase of component k
 *     media_sun_attenuate         times the sun's transmittance through the shadowing media
 *     media_sun_surface_attenuate the same to a surface point (a medium's media_sun_surface)
 *     medium_ms_source,           the method's multiple-scattering source and the sky's
 *     medium_ms_ground_irradiance   irradiance on the ground (zero for method single)
 *     media_intervals,            the parts of a ray that a medium integrates with its own
 *     media_interval                stepping, and that stepping (placed after visibility.h)
 * so this file and the integrator name no medium. A medium with its own stepping supplies
 * break points (media_intervals), which the integrator integrates with that medium's stepping
 * (media_interval: it adds the light of everything in its part, air included) and marches the
 * rest with media_at.
 * The path tracer's volume media (path.clouds = volume: a medium that no method sees, which
 * the path tracer's volume stage scatters in itself) are composed apart (MEDIA_VOLUME of them):
 *     media_volume_at             their extinction and scattering at a point
 *     media_volume_phase,         their phase function, a new direction at a scattering by
 *     media_volume_direction,       them, and the roulette gain of a path leaving it
 *     media_volume_roulette_gain
 * and the one majorant walk (media_walk.h) runs over the scene's media with the air
 * (MEDIA_WALK_MEDIA), toward the sun (MEDIA_WALK_SHADOW) or over the volume media alone
 * (MEDIA_WALK_VOLUME), the walk's mode, which the composed majorant reads too. With
 * path.air = medium the composition's MEDIA_VOLUME_AIR is 1 and the volume mode's free
 * flights scatter in the air as well (media_air_at, media_air_phase, media_air_direction).
 * The deterministic quadrature's piece rule, one for the marches that call it (the pieces of
 * quadrature_walk.h's walk in the integrator, medium.h, and the multiple-scattering LUT's
 * directions, and a medium's own steps): a piece's exact integral for constant coefficients
 * with the transmittance carried past it (medium_piece_weight).
 * Units: 1/m, per steradian. */
#ifndef ATMO_MEDIA_H
#define ATMO_MEDIA_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/frame.h"
#include "common/phase.h"
#include "media/ray.h"
#include "media/quadrature_walk.h"
#include "media/tracking.h"
#include "atmo/gpu_types.h"
#endif

#ifndef MEDIA_COMPONENTS
#error "MEDIA_COMPONENTS comes from the plan's prelude (or, in a host test, its composed header)"
#endif

/* The air's scattering components (each with its own phase function); the plan numbers the
 * other media's components after them. */
#define MEDIA_RAYLEIGH 0
#define MEDIA_MIE 1
#define MEDIA_MAX_INTERVALS QUADRATURE_MAX_PARTS /* parts of one ray with their own stepping */

/* The modes of the one majorant walk (media_walk.h) and of the composed majorant. */
#define MEDIA_WALK_MEDIA 0  /* the scene's media with the air (method reference's rays) */
#define MEDIA_WALK_SHADOW 1 /* the same toward the sun, less the media of exact sun transmittance */
#define MEDIA_WALK_VOLUME 2 /* the path tracer's volume media alone (its free flights add the
                               air where the plan makes it one: MEDIA_VOLUME_AIR) */

typedef struct media_sample {
    vec3 extinction;                   /* sigma_t, 1/m */
    vec3 scattering[MEDIA_COMPONENTS]; /* sigma_s of each component, 1/m */
} media_sample;

ATMO_FN float media_mie_phase(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float nu)
{
    return a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN ? phase_henyey_greenstein(nu, a->mie_g)
                             : phase_cornette_shanks(nu, a->mie_g);
}

/* The air at a point: its extinction and its two components; the other components zero until
 * their media add themselves (media_at). */
ATMO_FN media_sample media_air_at(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_point *q)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    media_sample m;
    float rho_r = expf(-q->h / a->rayleigh_scale_height);
    float rho_m = expf(-q->h / a->mie_scale_height);
    m.scattering[MEDIA_RAYLEIGH] = v3_scale(v3_from4(a->rayleigh_scattering), rho_r);
    m.scattering[MEDIA_MIE] = v3_scale(v3_from4(a->mie_scattering), rho_m);
    for (int k = MEDIA_MIE + 1; k < MEDIA_COMPONENTS; k++)
        m.scattering[k] = v3(0.0f, 0.0f, 0.0f);
    m.extinction = atmosphere_extinction_at(a, q->h, rho_r, rho_m);
    return m;
}

/* The air's phase function for light turned by the angle whose cosine is -nu (nu: the cosine
 * between the view direction and the sun), per steradian: Rayleigh's for MEDIA_RAYLEIGH, the
 * aerosols' for any other k. */
ATMO_FN vec3 media_air_phase(ATMO_GLOBAL const atmo_gpu_scene *s, int k, float nu)
{
    float p = k == MEDIA_RAYLEIGH ? phase_rayleigh(nu) : media_mie_phase(&s->atmosphere, nu);
    return v3(p, p, p);
}

/* The lowest altitude (m) along the ray from radius r with cosine mu up to distance d. */
ATMO_FN float media_min_altitude(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu,
                                 float d)
{
    if (mu >= 0.0f || d <= 0.0f)
        return r - a->bottom_radius;
    if (-r * mu >= d) /* still descending at the end */
        return geometry_altitude_at(r, mu, d, a->bottom_radius);
    float perigee = r * atmo_safe_sqrt(1.0f - mu * mu);
    return fmaxf(perigee - a->bottom_radius, 0.0f);
}

/* The air's majorant (1/m) on the ray from radius r with cosine mu up to distance d: the
 * extinction of every channel is at most Rayleigh's and Mie's at the lowest altitude h of the
 * ray plus the ozone's peak (both densities fall with altitude), times 1.001; h is lowered by
 * 10 m, which covers the float rounding of the altitudes media_air_at sees (~0.5 m at 6400 km). */
ATMO_FN float media_air_majorant(ATMO_GLOBAL const atmo_gpu_scene *s, float r, float mu, float d)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    float h = fmaxf(media_min_altitude(a, r, mu, d) - 10.0f, 0.0f);
    float ozone = h < a->ozone_peak ? 1.0f : atmosphere_ozone_tent(a, h);
    vec3 bound = v3_add(v3_add(v3_scale(v3_from4(a->rayleigh_scattering),
                                        expf(-h / a->rayleigh_scale_height)),
                               v3_scale(v3_from4(a->mie_extinction), expf(-h / a->mie_scale_height))),
                        v3_scale(v3_from4(a->ozone_absorption), ozone));
    return fmaxf(tracking_max3(bound), 1e-12f) * 1.001f;
}

/* A new direction at a scattering by the air's component k of a ray along dir, from the
 * uniform numbers u1 (the cosine) and u2 (azimuth 2 pi u2): Rayleigh (Draine with g = 0,
 * alpha = 1) or the aerosols' Henyey-Greenstein / Cornette-Shanks, sampled exactly (*weight 1). */
ATMO_FN vec3 media_air_direction(ATMO_GLOBAL const atmo_gpu_scene *s, int k, vec3 dir, float u1,
                                 float u2, vec3 *weight)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    *weight = v3(1.0f, 1.0f, 1.0f);
    float c = k == MEDIA_RAYLEIGH ? phase_draine_sample(0.0f, 1.0f, u1)
              : a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN
                  ? phase_henyey_greenstein_sample(a->mie_g, u1)
                  : phase_cornette_shanks_sample(a->mie_g, u1);
    return frame_direction(dir, c, 2.0f * ATMO_PI * u2);
}

/* A piece's weight w = (1 - e^{-x}) / sigma, x = sigma dt, from its transmittance e = e^{-x}:
 * directly where x > 0.1 (1 - e then loses at most ~6e-7 of its relative precision), by the
 * series x (1 - x/2 + x^2/6 - x^3/24 + x^4/120 - x^5/720) below (truncation < 3e-10 relative). One exp
 * per channel and no expm1: on PoCL (Sleef) expm1f costs ten times expf, and a float3 exp is
 * one vector call. */
ATMO_FN float medium_segment_weight(float sigma, float dt, float e)
{
    float x = sigma * dt;
    if (x > 0.1f)
        return (1.0f - e) / sigma;
    float p = 1.0f - x / 5.0f * (1.0f - x / 6.0f);
    p = 1.0f - x / 4.0f * p;
    p = 1.0f - x / 3.0f * p;
    p = 1.0f - x / 2.0f * p;
    return dt * p;
}

/* The weights of a piece with extinction sigma and length dt (medium_segment_weight per
 * channel), and its transmittance e^{-sigma dt} into *step. */
ATMO_FN vec3 medium_segment_step3(vec3 sigma, float dt, vec3 *step)
{
    vec3 e = v3_exp(v3_scale(sigma, -dt));
    *step = e;
    return v3(medium_segment_weight(sigma.x, dt, e.x), medium_segment_weight(sigma.y, dt, e.y),
              medium_segment_weight(sigma.z, dt, e.z));
}

/* A piece of a ray with constant extinction sigma_t, dt long, entered with the transmittance
 * *T from the ray's start: a source S (W m^-3 sr^-1 nm^-1) constant over the piece sends
 *     int_0^dt T e^{-sigma_t t} S dt = T w S,  w = (1 - e^{-sigma_t dt}) / sigma_t
 * to the start (Hillaire 2015), exactly however long the piece. Returns T w (m) and moves *T
 * past the piece, T *= e^{-sigma_t dt}. */
ATMO_FN vec3 medium_piece_weight(vec3 sigma_t, float dt, vec3 *T)
{
    vec3 step;
    vec3 Tw = v3_mul(*T, medium_segment_step3(sigma_t, dt, &step));
    *T = v3_mul(*T, step);
    return Tw;
}

#endif
