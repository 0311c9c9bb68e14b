/* cloud_shell_walk.h — the homogeneous cloud shell (cloud_shell.h) in the Monte Carlo walk
 * (majorant_walk.h, media_walk.h): its majorant along a ray, and a scattering's new direction
 * and roulette gain.
 *
 * Majorant. The shell's extinction is sigma_c (per channel) between the spheres of radii
 * R + base and R + top, zero elsewhere. Along origin + t dir (radius r, cosine mu at the origin)
 * the distances to a sphere of radius R + z are the roots of t^2 + 2 r mu t + (h - z)(r + R + z),
 * h = r - R (geometry_sphere_roots); between the roots of the top sphere and outside those of
 * the base sphere the ray is in the shell: at most two parts. The majorant is
 * max_c sigma_c x 1.001 over those parts, widened by CLOUD_SHELL_MARGIN_M on both radii (the
 * margin covers the float rounding of the altitude cloud_shell_extinction tests, < 1 m at
 * 6400 km, so the majorant bounds the extinction everywhere), and 0 elsewhere, so the clear air
 * above and below keeps the air's majorant alone. Its sun transmittance is exact (the chord,
 * cloud_shell_media_sun), so walks toward the sun leave it out (the slot's sun_exact).
 * New directions: its phase mixed with its lobe around the sun (phase_table.h's
 * cloud_phase_direction, cloud.sun_guiding); roulette gain: phase_table.h's cloud_roulette_gain
 * of its phase toward the sun. Units: metres, 1/m. */
#ifndef ATMO_CLOUD_SHELL_WALK_H
#define ATMO_CLOUD_SHELL_WALK_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/tracking.h"
#include "media/phase_table.h"
#include "cloud_shell/cloud_shell.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUD_SHELL_MARGIN_M 10.0f /* the majorant covers the shell's radii +- this */

typedef struct cloud_shell_majorant {
    int parts;           /* the parts of the ray inside the shell (0..2), in order */
    float lo[2], hi[2];  /* their ends, m along the ray */
    float rate;          /* the majorant there, 1/m */
} cloud_shell_majorant;

ATMO_FN void cloud_shell_majorant_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        vec3 origin, vec3 dir, float r, float mu, float end,
                                        cloud_shell_majorant *m)
{
    float R = s->atmosphere.bottom_radius, h = r - R, b = r * mu;
    float base = s->cloud.base_m - CLOUD_SHELL_MARGIN_M;
    float top = s->cloud.top_m + CLOUD_SHELL_MARGIN_M, o0, o1, i0, i1;
    m->parts = 0;
    m->rate = tracking_max3(v3_from4(s->cloud.extinction)) * 1.001f;
    if (!(s->cloud.top_m > s->cloud.base_m) ||
        !geometry_sphere_roots(b, (h - top) * (r + R + top), &o0, &o1))
        return;
    float lo[2] = {o0, 0.0f}, hi[2] = {o1, 0.0f};
    int parts = 1;
    if (base > 0.0f && geometry_sphere_roots(b, (h - base) * (r + R + base), &i0, &i1))
        hi[0] = i0, lo[1] = i1, hi[1] = o1, parts = 2;
    for (int k = 0; k < parts; k++) {
        float l = fmaxf(lo[k], 0.0f), u = fminf(hi[k], end);
        if (u > l) {
            m->lo[m->parts] = l, m->hi[m->parts] = u;
            m->parts++;
        }
    }
}

ATMO_FN float cloud_shell_majorant_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                           cloud_shell_majorant *m, float t, float *seg_end)
{
    *seg_end = INFINITY;
    for (int k = 0; k < m->parts; k++) {
        if (t < m->lo[k]) { /* clear up to the next part */
            *seg_end = m->lo[k];
            return 0.0f;
        }
        if (t < m->hi[k]) {
            *seg_end = m->hi[k];
            return m->rate;
        }
    }
    return 0.0f;
}

ATMO_FN vec3 cloud_shell_media_direction(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                         vec3 dir, vec3 to_sun, vec3 beta, float u1, float u2,
                                         rng_stream *g, vec3 *weight)
{
    return cloud_phase_direction(s->cloud.phase, v3_from4(s->cloud.g), s->cloud.diameter_um,
                                 cloud_phase_table, cloud_phase_cdf, s->cloud.table_size, dir,
                                 to_sun, s->cloud.sun_guiding, beta, u1, u2, g, weight);
}

ATMO_FN float cloud_shell_roulette_gain(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        float nu)
{
    return cloud_roulette_gain(cloud_shell_media_phase(s, ATMO_LUT_ARGS, nu));
}

#endif
