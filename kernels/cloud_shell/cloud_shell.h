/* cloud_shell.h — a homogeneous cloud or fog layer between two altitudes (a spherical shell, so
 * the atmosphere stays spherically symmetric): a medium module of the medium integrator
 * (medium.h, media.h), compiled only under -DATMO_CLOUD.
 *
 * Medium: extinction sigma (1/m, per wavelength) = (sigma_ext / LWC) x LWC of a droplet size
 * distribution, albedo omega and a phase function p (per steradian): the 4pi-normalised Mie table
 * P(theta) / 4pi of the distribution (plan_cloud.c builds it with mie_table_get, rows
 * float4 (P_680, P_550, P_440, theta) ascending in theta: phase_table.h's format), or
 * Henyey-Greenstein with the table's g, or Jendersie & d'Eon 2023 for the effective diameter.
 *
 * What it gives the integrator: its break points along a ray (the shell's two spheres: at most
 * two intervals inside it, cloud_shell_intervals), its own stepping inside them
 * (cloud_shell_interval), the light it takes from the sun on the way down to any point (the
 * chord through the shell, analytic: exp(-sigma l_sun), a visibility source in visibility.h),
 * and its coefficients at a point (media.h). An interval integrates everything in its part of
 * the ray: the cloud and the air in it (the air's scattering of the sun and, with use_ms, the
 * method's multiple-scattering source: medium_air_source). Its steps end at the cloud's break
 * points, equal in optical depth (channel y), `cloud.steps` of them up to CLOUD_TAU_CUT (beyond
 * it the view transmittance is below 1e-5), so a cloud of optical thickness 10-1000 is
 * resolved where it is seen, and at the air grid's break points (medium_integrate's), so the
 * air inside the shell is sampled at least as finely as outside it and a shell of negligible
 * optical depth leaves the sky as the air alone makes it. Each step takes its coefficients, the
 * atmosphere's transmittance toward the sun and the sun's occluders (the planet, the observer:
 * visibility_sun_occluders) at the fraction `jitter` of it, sigma_v = the cloud's extinction
 * plus the air's there. Within a step the sun's path length in the shell is taken as linear in
 * t, from l_0 to l_1, so with x(s) = a sigma l(s) + sigma_v s the step integrates exactly
 *     int_0^dt S_0 e^{-x(s)} ds = S_0 dt (e^{-x(0)} - e^{-x(dt)}) / (x(dt) - x(0))
 * (exact for a plane-parallel slab, where the single-scattering radiance has the closed form
 * omega p(theta) E mu_s / (mu_s + mu_v) (1 - e^{-tau (1/mu_s + 1/mu_v)}) used by the tests);
 * the air's source takes octave 0's weight (a = 1: the sun's light reaches the air in the
 * shell through the cloud's chord).
 *
 * Multiple scattering inside the cloud: the octaves of Wrenninge, Kulla & Lundqvist 2013
 * ("Oz: the great and volumetric", SIGGRAPH talk): octave i adds the single-scattering source
 * with the sun's extinction scaled by a^i, the contribution by b^i and the phase anisotropy by
 * c^i (octave 0 is exact single scattering with the true phase; octaves i >= 1 use
 * Henyey-Greenstein with g c^i). a, b, c and the octave count are below; they are chosen by eye
 * so a thick deck (tau >= 30) under a 54-degree sun reflects roughly a third of the light (real
 * decks reflect 0.6-0.8) while the glory and fog bow of octave 0 keep their contrast; the
 * approximation is not energy conserving and has no diffuse light under the deck.
 *
 * Units: metres, 1/m, radians; radiance in W m^-2 sr^-1 nm^-1. */
#ifndef ATMO_CLOUD_SHELL_H
#define ATMO_CLOUD_SHELL_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "media/ray.h"
#include "media/phase_table.h"
#include "media/media.h"
#include "atmosphere/sky_method.h"
#include "atmo/gpu_types.h"
#endif

#ifndef ATMO_CLOUD_OCTAVES
#define ATMO_CLOUD_OCTAVES 5
#endif
#define CLOUD_OCTAVE_A 0.25f /* extinction of the sun's path, per octave */
#define CLOUD_OCTAVE_B 0.7f  /* contribution, per octave */
#define CLOUD_OCTAVE_C 0.5f  /* phase anisotropy, per octave */
#define CLOUD_TAU_CUT 11.5f  /* view optical depth integrated per interval (e^-11.5 = 1e-5) */

/* The shell's base and top altitudes (m). */
ATMO_FN float cloud_shell_base(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    return s->cloud.base_m;
}

ATMO_FN float cloud_shell_top(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    return s->cloud.top_m;
}

/* Length of the half-line t >= 0 inside a sphere, for the roots of geometry_sphere_roots. */
ATMO_FN float cloud_length_inside(float b, float c)
{
    float t0, t1;
    if (!geometry_sphere_roots(b, c, &t0, &t1))
        return 0.0f;
    return fmaxf(t1, 0.0f) - fmaxf(t0, 0.0f);
}

/* Path length through the shell [R + base, R + top] of the half-line from a point at altitude
 * h (above the ground sphere R) and radius r_t, with cosine m to the local vertical. */
ATMO_FN float cloud_shell_chord(float R, float base, float top, float h, float r_t, float m)
{
    float b = r_t * m;
    float c_top = (h - top) * (r_t + R + top), c_base = (h - base) * (r_t + R + base);
    return fmaxf(cloud_length_inside(b, c_top) - cloud_length_inside(b, c_base), 0.0f);
}

/* The cloud's phase function per steradian at view-sun cosine nu, one value per wavelength. */
ATMO_FN vec3 cloud_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *table,
                         float nu)
{
    /* the light turns from -sun to -view: the scattering angle's cosine is nu */
    return cloud_phase_eval(s->cloud.phase, v3_from4(s->cloud.g), s->cloud.diameter_um, table,
                            s->cloud.table_size, nu);
}

/* int_0^dt e^{-x(s)} ds for an exponent linear from x0 to x1 (both >= 0):
 * dt (e^{-x0} - e^{-x1}) / (x1 - x0). Written with the end values so it stays finite when the
 * exponent falls steeply (the sun's path shortening fast along a ray going up). */
ATMO_FN float cloud_exp_mean(float x0, float x1, float dt)
{
    float d = x1 - x0;
    return fabsf(d) > 1e-4f ? dt * (expf(-x0) - expf(-x1)) / d : dt * expf(-x0) * (1.0f - 0.5f * d);
}

ATMO_FN vec3 cloud_exp_mean3(vec3 x0, vec3 x1, float dt)
{
    return v3(cloud_exp_mean(x0.x, x1.x, dt), cloud_exp_mean(x0.y, x1.y, dt),
              cloud_exp_mean(x0.z, x1.z, dt));
}

/* The shell's extinction at a point (1/m): sigma inside [base, top], 0 outside. */
ATMO_FN vec3 cloud_shell_extinction(ATMO_GLOBAL const atmo_gpu_scene *s, float h)
{
    return h >= cloud_shell_base(s) && h <= cloud_shell_top(s) ? v3_from4(s->cloud.extinction)
                                                              : v3(0.0f, 0.0f, 0.0f);
}

/* The sun's light through the shell to a point: exp(-sigma l_sun) with l_sun its chord. */
ATMO_FN vec3 cloud_shell_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s,
                                           const medium_point *q, float bottom_radius)
{
    float chord = cloud_shell_chord(bottom_radius, cloud_shell_base(s), cloud_shell_top(s), q->h,
                                    q->r, q->mu_s);
    return v3_exp(v3_scale(v3_from4(s->cloud.extinction), -chord));
}

/* The parts of [t_start, t_end] of the ray inside the shell, in order: returns their count
 * (0..2) and their ends in lo[], hi[]. */
ATMO_FN int cloud_shell_intervals(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                  float t_start, float t_end, float *lo, float *hi)
{
    return geometry_shell_parts(s->atmosphere.bottom_radius, cloud_shell_base(s),
                                cloud_shell_top(s), m->r, m->mu, t_start, t_end, lo, hi);
}

/* The shell's optical depth along the view ray m over [0, t_end] per channel, its chord
 * through the shell times its extinction (closed form), and its single-scattering albedo in
 * *albedo: the denoiser's guides (render/guides.cl; the slot `guide_depth`). */
ATMO_FN vec3 cloud_shell_guide_depth(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                     float t_end, vec3 *albedo)
{
    float lo[2], hi[2], chord = 0.0f;
    int n = cloud_shell_intervals(s, m, 0.0f, t_end, lo, hi);
    for (int k = 0; k < n; k++)
        chord += hi[k] - lo[k];
    *albedo = v3_from4(s->cloud.albedo);
    return v3_scale(v3_from4(s->cloud.extinction), chord);
}

/* The shell as a medium of the plan's composition (media.h): its coefficients added at a
 * point, its phase function (component MEDIA_CLOUD) and the sun's transmittance through it. */
ATMO_FN void cloud_shell_media_add(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q, media_sample *m)
{
    vec3 cloud = cloud_shell_extinction(s, q->h);
    m->scattering[MEDIA_CLOUD] = v3_mul(cloud, v3_from4(s->cloud.albedo));
    m->extinction = v3_add(m->extinction, cloud);
}

ATMO_FN vec3 cloud_shell_media_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     float nu)
{
    return cloud_phase(s, cloud_phase_table, nu);
}

ATMO_FN vec3 cloud_shell_media_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q)
{
    return cloud_shell_sun_transmittance(s, q, s->atmosphere.bottom_radius);
}

#endif
