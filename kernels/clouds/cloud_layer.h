/* cloud_layer.h — the fBm cloud layer: a planet-wide medium of coverage x shaped fBm between two
 * altitudes, compiled only under -DATMO_CLOUDS. Its density, its optics and the sun's light
 * through it; the layer as a medium of the methods is cloud_layer_medium.h, its own stepping
 * along view rays cloud_march.h.
 *
 * Density at a camera-relative point p of altitude h (x = p + origin, origin the camera's world
 * position minus the wind's displacement w t, so the field moves with the wind):
 *     c(x, h) = clamp(C (fbm_4(f_c x) - 1/2) + coverage, 0, 1) fade(h)
 *     d(x, h) = density max(c - fbm_N(f * (x + A warp(f x / 4))), 0)^sharpness
 * (the thesis' model, presets.md: a very-large-scale coverage field minus an N-octave 3-D fBm
 * of frequency f per axis, domain-warped, raised to a power; fade(h) a smoothstep over fade_m
 * above the bottom and below the top, so towers round off). C = CLOUDS_COVERAGE_CONTRAST turns
 * the coverage field into clear regions (c = 0) and cloudy ones, f_c = 1 / coverage_scale_m.
 * The fBm lies in [0, 1) (cloud_noise.h), so d <= density everywhere (the majorant of the
 * Monte Carlo walk) and d = 0 wherever c = 0: the cheap coverage test (the coverage field
 * before the fade, 4 octaves instead of N + 3) is exact at its point for skipping clear air.
 * Level of detail: far from the camera a pixel spans many of the fBm's cells, and the density
 * point-sampled there changes from sample to sample and pixel to pixel (sparkle, speckled cloud
 * fields from orbit). The shape fBm is therefore filtered to the footprint F = footprint |p| of
 * a pixel at the point's distance |p| from the camera (footprint: the pixel's angle times
 * clouds.lod, from the plan; 0 with clouds.lod = 0): cloud_noise.h's noise_fbm_lod replaces
 * the octaves finer than F (in lattice units of the axis of highest frequency) by their mean.
 * The threshold c - fbm then moves only where the unresolved octaves would have moved it both
 * ways, so the fraction of a region under cloud is kept (the mean of a far view within 2 % of
 * the point-sampled one on thesis-4 and thesis-5, tests/test_clouds_lod.c; how much depends on
 * the view, docs/notes/clouds-lod.md), where the expected density over the footprint would
 * spread opaque cloud over every partly covered pixel (12 % brighter). The
 * filtered fBm stays in [0, 1), so d <= density c^sharpness still bounds it for the majorants.
 * The coverage field is not filtered: its finest cells (coverage_scale_m / 8) are wider than a
 * pixel's footprint within the far planes. The path tracer's bounces and the light march
 * toward the sun use the same rule (the distance from the camera), so every method sees one
 * medium.
 * Optics (host/features/clouds/plan_clouds.c): sigma_t = d x extinction per unit density, sigma_s =
 * albedo sigma_t, the phase function the droplet distribution's Mie table (phase_table.h), its
 * Henyey-Greenstein with the table's g, or Jendersie & d'Eon 2023.
 *
 * The light march (the sun's transmittance through the layer, cloud_layer_medium.h's
 * clouds_media_sun): the part of the ray toward the sun inside the layer's shell, cut to
 * light_distance_m from where it enters, in light_steps steps growing as (i/n)^2 (short near
 * the point, where the light changes fastest), each sampled at one point:
 *     D = sum_i d(x_i) dt_i,   T_sun = exp(-extinction D)
 * The sample's offset inside the steps is a hash of the point's bits: decorrelated from pixel
 * to pixel and step to step (no banding, no shared pattern between neighbours), and the same
 * for the same point on every run; it stops once the optical depth passes CLOUDS_TAU_OPAQUE.
 * exp(-D) of a jittered estimate of the optical depth
 * over-estimates the transmittance on average (Jensen's inequality; tests/test_clouds_tracking.c
 * measures how much); the Monte Carlo reference uses ratio tracking instead. The cut is the
 * march of the samples inside clouds (cloud_march.h); a point in clear air or on a surface
 * (the terrain, an object) spreads its steps over the whole chord instead, uncut, a surface in
 * at least CLOUDS_SURFACE_LIGHT_STEPS (cloud_layer_medium.h's clouds_chord_density).
 *
 * Parameters (scene keys clouds.*, `atmo params`): bottom_m 1000, top_m 8000, fade_m 2000,
 * coverage 0.25, density 5, sharpness 1.05, frequency_per_m (8, 16, 8) 1e-5, coverage_scale_m
 * 500 km, octaves 6, warp_m 3000, extinction 10.354e-3 1/m and albedo 0.9512 at unit density
 * (the thesis) or from the distribution (extinction_per_m = 0), light_steps 4 over
 * light_distance_m 8000. The thesis' own layer (500 m to 20 km, 5 km fades, coverage features
 * to 2500 km) is --set clouds.bottom_m=500 clouds.top_m=20000 clouds.fade_m=5000
 * clouds.coverage_scale_m=2.5e6: its 13 km towers leave the air below them in shadow, so the
 * defaults keep its noise and optics in a 7 km layer of fair-weather cumulus instead
 * (docs/notes/clouds.md). Units: metres, 1/m. */
#ifndef ATMO_CLOUDS_CLOUD_LAYER_H
#define ATMO_CLOUDS_CLOUD_LAYER_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "common/rng.h"
#include "media/ray.h"
#include "media/quadrature_walk.h"
#include "clouds/cloud_noise.h"
#include "media/phase_table.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUDS_COVERAGE_OCTAVES 4
#define CLOUDS_COVERAGE_CONTRAST 3.0f
#define CLOUDS_WARP_FREQUENCY 0.25f /* of the warp noise, relative to the shape's */
#define CLOUDS_TAU_OPAQUE 16.0f     /* the light march stops there: e^-16 = 1e-7 */
#define CLOUDS_SURFACE_LIGHT_STEPS 32 /* the march toward the sun from a surface point */
/* the marcher's steps (cloud_march.h), which the shadow bench (host/bench) samples too */
#define CLOUDS_CLEAR_STRIDE 4.0f
#define CLOUDS_STEP_GROWTH 0.002f

/* A number in [0, 1) that is a hash of the point p (the light march's offset). */
ATMO_FN float clouds_point_jitter(vec3 p, uint seed)
{
    return (float)(rng_point_hash(p, seed) >> 8) * (1.0f / 16777216.0f);
}

/* The height fade: 0 at the bottom and the top, 1 more than fade_m inside, smoothstep between. */
ATMO_FN float clouds_fade(ATMO_GLOBAL const atmo_gpu_clouds *c, float h)
{
    float f = clamp(fminf(h - c->bottom_m, c->top_m - h) / c->fade_m, 0.0f, 1.0f);
    return f * f * (3.0f - 2.0f * f);
}

/* The coverage field before the height fade at the world noise point x, 0..1. */
ATMO_FN float clouds_coverage_field(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 x)
{
    float n = noise_fbm(v3_scale(x, c->frequency.w), CLOUDS_COVERAGE_OCTAVES, c->seed ^ 0x5bd1e995u);
    return clamp(CLOUDS_COVERAGE_CONTRAST * (n - 0.5f) + c->coverage, 0.0f, 1.0f);
}

/* The coverage c(x, h) at the world noise point x (0 outside the layer). */
ATMO_FN float clouds_coverage_world(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 x, float h)
{
    if (h <= c->bottom_m || h >= c->top_m)
        return 0.0f;
    return clouds_coverage_field(c, x) * clouds_fade(c, h);
}

/* The cheap test of the marcher: 0 where the coverage field (before the fade, which changes
 * fast near the layer's bottom and top) leaves no cloud at any altitude of the layer. */
ATMO_FN float clouds_coverage(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 p)
{
    return clouds_coverage_field(c, v3_add(p, v3_from4(c->origin)));
}

/* The density d at the world noise point x, given its coverage cov > 0, filtered to a footprint
 * of footprint_m metres (0: every octave). */
ATMO_FN float clouds_density_covered(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 x, float cov,
                                     float footprint_m)
{
    vec3 f = v3_from4(c->frequency);
    vec3 warp = noise_warp(v3_scale(v3_mul(x, f), CLOUDS_WARP_FREQUENCY), c->seed);
    vec3 xw = v3_add(x, v3_scale(warp, c->warp_m));
    float fp = footprint_m * fmaxf(f.x, fmaxf(f.y, f.z));
    float d = cov - noise_fbm_lod(v3_mul(xw, f), c->octaves, fp, c->seed);
    return d > 0.0f ? c->density * powf(d, c->sharpness) : 0.0f;
}

/* The density at a camera-relative point p of altitude h (0 outside the layer), filtered to
 * the pixel's footprint at p's distance from the camera. */
ATMO_FN float clouds_density(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 p, float h)
{
    vec3 x = v3_add(p, v3_from4(c->origin));
    float cov = clouds_coverage_world(c, x, h);
    float footprint_m = c->footprint > 0.0f ? c->footprint * v3_length(p) : 0.0f;
    return cov > 0.0f ? clouds_density_covered(c, x, cov, footprint_m) : 0.0f;
}

/* The phase function per steradian at view-sun cosine nu, per wavelength. */
ATMO_FN vec3 clouds_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *table,
                          float nu)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    return cloud_phase_eval(c->phase, v3_from4(c->g), c->diameter_um, table, c->table_size, nu);
}

/* The new direction at a layer vertex reached along d by a path of throughput beta, the sun
 * toward `sun` (unit vectors of one frame): phase_table.h's cloud_phase_direction with the
 * layer's phase and clouds.sun_guiding, uniform numbers u1, u2 (and one from g for
 * Jendersie-d'Eon); *weight the phase over the sampling density. */
ATMO_FN vec3 clouds_phase_direction(ATMO_GLOBAL const atmo_gpu_scene *s,
                                    ATMO_GLOBAL const float4 *table, ATMO_GLOBAL const float *cdf,
                                    vec3 d, vec3 sun, vec3 beta, float u1, float u2,
                                    rng_stream *g, vec3 *weight)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    return cloud_phase_direction(c->phase, v3_from4(c->g), c->diameter_um, table, cdf,
                                 c->table_size, d, sun, c->sun_guiding, beta, u1, u2, g, weight);
}

/* The density integral D (m) from the point q toward the sun over the layer: the part of the
 * ray in the shell cut to `distance` from where it enters, in n steps growing as (i/n)^2 (the
 * quadrature walk's grid, quadrature_grid_segment) with the sample offset `jitter` in [0, 1),
 * stopping once the optical depth passes tau_stop. */
ATMO_FN float clouds_sun_density_steps(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_point *q,
                                       float jitter, int n, float distance, float tau_stop)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float R = s->atmosphere.bottom_radius, lo[2], hi[2];
    int parts = geometry_shell_parts(R, c->bottom_m, c->top_m, q->r, q->mu_s, 0.0f, INFINITY, lo, hi);
    if (parts == 0)
        return 0.0f;
    float a = lo[0], len = fminf(hi[parts - 1], a + distance) - a;
    vec3 sun = v3_from4(s->sun_direction);
    float D = 0.0f;
    for (int i = 0; i < n; i++) {
        float dt, t = a + quadrature_grid_segment(len, i, n, &dt) + jitter * dt;
        float h = geometry_altitude_at(q->r, q->mu_s, t, R);
        D += clouds_density(c, v3_add(q->p, v3_scale(sun, t)), h) * dt;
        if (D * c->extinction.y > tau_stop)
            break;
    }
    return D;
}

/* The marcher's step (cloud_march.h) at distance t_c from the camera: step_m + CLOUDS_STEP_GROWTH
 * t_c, so the step follows the pixel's footprint, CLOUDS_CLEAR_STRIDE times longer where the
 * coverage test finds clear air (`cloudy` 0). */
ATMO_FN float clouds_march_step(ATMO_GLOBAL const atmo_gpu_clouds *c, float t_c, int cloudy)
{
    float dt = c->step_m + CLOUDS_STEP_GROWTH * t_c;
    return cloudy ? dt : dt * CLOUDS_CLEAR_STRIDE;
}

/* The density integrals (m) along the view ray m over [t0, t1], a part of the ray inside the
 * layer's shell, on the marcher's steps (clouds_march_step: the same lengths and coverage test,
 * up to the far plane max_distance_m and `steps` steps, a sized quadrature walk) times
 * step_scale, each sampled at its midpoint (no jitter: the result is a function of the ray
 * alone), stopping once the optical depth (channel y) passes tau_stop. Returns the integral
 * over the whole part, and adds to D[k] the integral over [t0, min(t1, ends[k])] for each of
 * the n end distances (the density of a step times the length of the step before ends[k]).
 * The denoiser's guides take the view transmittance through the layer, exp(-extinction D),
 * from it for a block of rays that share the march and end at their own surfaces
 * (render/guides.cl). */
ATMO_FN float clouds_view_density_ends(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                       float t0, float t1, float step_scale, float tau_stop, int n,
                                       const float *ends, float *D)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float start = v3_length(m->origin); /* the camera's distance to the ray's origin */
    float far = c->max_distance_m - start, total = 0.0f;
    quadrature_walk w = quadrature_begin_sized(t0, t1, c->steps, 0.5f);
    while (quadrature_more(&w) && w.done < far && total * c->extinction.y <= tau_stop) {
        medium_point q = medium_ray_at(m, w.done, s->atmosphere.bottom_radius);
        int cloudy = clouds_coverage(c, q.p) > 0.0f;
        quadrature_step(&w, step_scale * clouds_march_step(c, start + w.done, cloudy));
        if (cloudy) {
            medium_point x = medium_ray_at(m, w.t, s->atmosphere.bottom_radius);
            float d = clouds_density(c, x.p, x.h);
            total += d * w.dt;
            for (int k = 0; k < n; k++)
                D[k] += d * clamp(ends[k] - w.start, 0.0f, w.dt);
        }
    }
    return total;
}

/* The light march over the whole chord from q toward the sun through the layer, uncut, in n
 * steps with the sample offset `jitter` in [0, 1): D (m), for a point in clear air or on a
 * surface (the header). */
ATMO_FN float clouds_sun_density_chord(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_point *q,
                                       float jitter, int n)
{
    return clouds_sun_density_steps(s, q, jitter, n, INFINITY, CLOUDS_TAU_OPAQUE);
}

/* The light march from the point q toward the sun: the density integral D (m) over the layer,
 * with the steps' sample offset `jitter` in [0, 1). */
ATMO_FN float clouds_sun_density(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_point *q,
                                 float jitter)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    return clouds_sun_density_steps(s, q, jitter, c->light_steps, c->light_distance_m,
                                    CLOUDS_TAU_OPAQUE);
}

/* The layer's optical depth per channel in front of each of a block of n view rays that end
 * at ends[k] (their surfaces, INFINITY for the sky, 0 for a ray whose layer the image does not
 * show), added to tau[k], and its single-scattering albedo times that depth added to
 * tau_albedo[k]: one march along the block's ray m (clouds_view_density_ends, on step_scale
 * times the marcher's steps, to the optical depth tau_stop), each ray's share taken up to its
 * own end. The denoiser's guides (render/guides.cl; the slot `guide_block`). */
ATMO_FN void clouds_guide_block(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m, int n,
                                const float *ends, float step_scale, float tau_stop, vec3 *tau,
                                vec3 *tau_albedo)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float D[ATMO_GUIDES_BLOCK_RAYS], t_far = 0.0f, lo[2], hi[2];
    for (int k = 0; k < n; k++) {
        D[k] = 0.0f;
        t_far = fmaxf(t_far, ends[k]);
    }
    int parts = t_far > 0.0f ? geometry_shell_parts(s->atmosphere.bottom_radius, c->bottom_m,
                                                  c->top_m, m->r, m->mu, 0.0f, t_far, lo, hi)
                             : 0;
    float total = 0.0f;
    for (int k = 0; k < parts; k++)
        total += clouds_view_density_ends(s, m, lo[k], hi[k], step_scale,
                                          tau_stop - total * c->extinction.y, n, ends, D);
    for (int k = 0; k < n; k++) {
        vec3 layer = v3_scale(v3_from4(c->extinction), D[k]);
        tau[k] = v3_add(tau[k], layer);
        tau_albedo[k] = v3_add(tau_albedo[k], v3_mul(layer, v3_from4(c->albedo)));
    }
}

#endif
