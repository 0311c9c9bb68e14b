/* cloud_shell_walk.h — the homogeneous cloud shell (cloud_shell.h) in the Monte Carlo walk
 * (majorant_walk.h, media_walk.h): its majorant along a ray, and a scattering's new direction
 * and roulette gain.
 *
 * Majorant. The shell's extinction is sigma_c (per channel) between the spheres of radii
 * R + base and R + top, zero elsewhere. Along origin + t dir (radius r, cosine mu at the origin)
 * the distances to a sphere of radius R + z are the roots of t^2 + 2 r mu t + (h - z)(r + R + z),
 * h = r - R; between the roots of the top sphere and outside those of the base sphere the ray
 * is in the shell: at most two parts (geometry_shell_parts, the parts the quadrature's
 * intervals take too, cloud_shell_intervals). The majorant is
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
    float base = s->cloud.base_m - CLOUD_SHELL_MARGIN_M;
    float top = s->cloud.top_m + CLOUD_SHELL_MARGIN_M;
    m->parts = 0;
    m->rate = tracking_max3(v3_from4(s->cloud.extinction)) * 1.001f;
    if (!(s->cloud.top_m > s->cloud.base_m))
        return;
    /* a widened base at or below the ground has no inner sphere: the shell reaches down to
     * the planet's centre (altitude -R), which no walk reaches, as every walk through the shell
     * ends at the ground */
    float R = s->atmosphere.bottom_radius;
    m->parts = geometry_shell_parts(R, base > 0.0f ? base : -R, top, r, mu, 0.0f, end, m->lo,
                                    m->hi);
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
