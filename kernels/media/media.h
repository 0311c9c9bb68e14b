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
 *     medium_ms_source,           the method's multiple-scattering source and the sky's
 *     medium_ms_ground_irradiance   irradiance on the ground (zero for method single)
 *     media_intervals,            the parts of a ray that a medium integrates with its own
 *     media_interval                stepping, and that stepping (placed after visibility.h)
 * so this file and the integrator name no medium. A medium with its own stepping supplies
 * break points (media_intervals), which the integrator integrates with that medium's stepping
 * (media_interval: it adds the light of everything in its part, air included) and marches the
 * rest with media_at. Units: 1/m, per steradian. */
#ifndef ATMO_MEDIA_H
#define ATMO_MEDIA_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/phase.h"
#include "media/ray.h"
#include "atmo/gpu_types.h"
#endif

#ifndef MEDIA_COMPONENTS
#error "MEDIA_COMPONENTS comes from the plan's prelude (or, in a host test, its composed header)"
#endif

/* The air's scattering components (each with its own phase function); the plan numbers the
 * other media's components after them. */
#define MEDIA_RAYLEIGH 0
#define MEDIA_MIE 1
#define MEDIA_MAX_INTERVALS 2 /* parts of one ray with their own stepping */

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

#endif
