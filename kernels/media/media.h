/* media.h — the participating media of the scene, composed in one place for the medium
 * integrator (medium.h) and the Monte Carlo reference (method_reference.h, tracking.h).
 *
 * A medium gives, at a point of a ray (ray.h's medium_point), its extinction and the scattering
 * coefficient of each of its components, whose phase functions media_phase evaluates; the sum
 * over the media present is what media_at returns:
 *     sigma_t(x) = sum_m sigma_t,m(x),  sigma_s,k(x) for the components k,  p_k(nu) per steradian
 * The atmosphere is always present (atmosphere.h: Rayleigh and Mie scattering with their scale
 * heights, ozone absorbing); the homogeneous cloud shell (cloud_shell.h) is added under
 * -DATMO_CLOUD, the fBm cloud layer (cloud_layer.h, cloud_march.h) under -DATMO_CLOUDS (the two
 * exclude each other: plan_clouds.c). A medium that needs its own stepping (the cloud shell's
 * optical-depth steps, the layer's marcher) also supplies break points: the parts of a ray inside
 * it (media_intervals), which the integrator integrates with that medium's stepping
 * (media_interval: it adds the light of everything in its part, air included) and marches the
 * rest with media_at. Units: 1/m, per steradian. */
#ifndef ATMO_MEDIA_H
#define ATMO_MEDIA_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/phase.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#ifdef ATMO_CLOUD
#include "media/cloud_shell.h"
#endif
#ifdef ATMO_CLOUDS
#include "media/cloud_layer.h"
#endif
#include "atmo/gpu_types.h"
#endif

/* The scattering components (each with its own phase function). */
#define MEDIA_RAYLEIGH 0
#define MEDIA_MIE 1
#ifdef ATMO_CLOUD
#define MEDIA_CLOUD 2
#define MEDIA_SHELL_END 3
#else
#define MEDIA_SHELL_END 2
#endif
#ifdef ATMO_CLOUDS
#define MEDIA_CLOUDS MEDIA_SHELL_END
#define MEDIA_COMPONENTS (MEDIA_SHELL_END + 1)
#else
#define MEDIA_COMPONENTS MEDIA_SHELL_END
#endif
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

/* The media at a point (the buffers hold what a medium needs of them: a density grid). */
ATMO_FN media_sample media_at(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_point *q)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    media_sample m;
    float rho_r = expf(-q->h / a->rayleigh_scale_height);
    float rho_m = expf(-q->h / a->mie_scale_height);
    m.scattering[MEDIA_RAYLEIGH] = v3_scale(v3_from4(a->rayleigh_scattering), rho_r);
    m.scattering[MEDIA_MIE] = v3_scale(v3_from4(a->mie_scattering), rho_m);
    m.extinction = atmosphere_extinction_at(a, q->h, rho_r, rho_m);
#ifdef ATMO_CLOUD
    vec3 cloud = cloud_shell_extinction(s, q->h);
    m.scattering[MEDIA_CLOUD] = v3_mul(cloud, v3_from4(s->cloud.albedo));
    m.extinction = v3_add(m.extinction, cloud);
#endif
#ifdef ATMO_CLOUDS
    vec3 layer = v3_scale(v3_from4(s->clouds.extinction), clouds_density(&s->clouds, q->p, q->h));
    m.scattering[MEDIA_CLOUDS] = v3_mul(layer, v3_from4(s->clouds.albedo));
    m.extinction = v3_add(m.extinction, layer);
#endif
    return m;
}

/* Phase function of component k for light turned by the angle whose cosine is -nu (nu: the
 * cosine between the view direction and the sun), per steradian, per wavelength. */
ATMO_FN vec3 media_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, int k, float nu)
{
    if (k == MEDIA_RAYLEIGH) {
        float p = phase_rayleigh(nu);
        return v3(p, p, p);
    }
#ifdef ATMO_CLOUD
    if (k == MEDIA_CLOUD)
        return cloud_phase(s, cloud_phase_table, nu);
#endif
#ifdef ATMO_CLOUDS
    if (k == MEDIA_CLOUDS)
        return clouds_phase(s, clouds_phase_table, nu);
#endif
    float p = media_mie_phase(&s->atmosphere, nu);
    return v3(p, p, p);
}

/* The parts of [t_start, t_end] that a medium integrates with its own stepping, in order
 * along the ray: returns their count (<= MEDIA_MAX_INTERVALS), their ends in lo[], hi[]. */
ATMO_FN int media_intervals(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                            float t_start, float t_end, float *lo, float *hi)
{
#if defined(ATMO_CLOUDS)
    return clouds_shell_parts(s->atmosphere.bottom_radius, s->clouds.bottom_m, s->clouds.top_m,
                              m->r, m->mu, t_start, t_end, lo, hi);
#elif defined(ATMO_CLOUD)
    return cloud_shell_intervals(s, m, t_start, t_end, lo, hi);
#else
    return 0;
#endif
}

#ifdef ATMO_CLOUDS
/* the layer's marcher, in kernels/media/cloud_march.h (after the integrator, whose pieces it
 * uses) */
ATMO_FN void clouds_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const medium_ray *m, float t0, float t1, float jitter, int use_ms,
                             int ground, vec3 *L, vec3 *T, vec3 *medium_t);
#endif

/* Interval [t0, t1] of media_intervals integrated by its medium: adds its light to *L with
 * the running view transmittance *T, and multiplies *medium_t by the transmittance of the
 * media other than the air over it (for the sun disc behind it). use_ms and ground are those of
 * medium_integrate (a medium whose part holds air adds the air's multiple scattering too), and
 * so is its air grid, break points grid_d (i / grid_n)^2, for a medium that steps the air at
 * least as finely as the grid. */
ATMO_FN void media_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                            const medium_ray *m, float t0, float t1, float jitter, int use_ms,
                            int ground, float grid_d, int grid_n, vec3 *L, vec3 *T,
                            vec3 *medium_t)
{
#if defined(ATMO_CLOUDS)
    (void)grid_d, (void)grid_n;
    clouds_interval(s, ATMO_LUT_ARGS, m, t0, t1, jitter, use_ms, ground, L, T, medium_t);
#elif defined(ATMO_CLOUD)
    cloud_shell_interval(s, ATMO_LUT_ARGS, m, t0, t1, jitter, use_ms, ground, grid_d, grid_n, L,
                         T, medium_t);
#else
    (void)use_ms, (void)ground, (void)grid_d, (void)grid_n;
#endif
}

#endif
