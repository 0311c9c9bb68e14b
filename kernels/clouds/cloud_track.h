/* cloud_track.h — the fBm cloud layer in the one majorant walk (majorant_walk.h, media_walk.h):
 * its majorant along a ray over the majorant grid, its coefficients, phase function, scattering
 * direction and roulette gain there: the slots of the walk where the layer is a medium of
 * method reference (row clouds_tracked) or the path tracer's volume medium (path.clouds =
 * volume, row clouds_path_volume: no method sees it then; media_walk.h's volume mode tracks it
 * for the path tracer's free flights and shadow rays and for the air's samples' sun).
 *
 * Majorant (clouds_track_begin, clouds_track_segment). The layer's extinction is
 * sigma_t(x) = d(x) k, d the density (cloud_layer.h) and k its extinction per unit density per
 * wavelength. Along the ray origin + t dir it is zero outside the layer's shell, so the majorant
 * is zero outside the parts of the ray inside the shell (geometry_shell_parts: at most two, in
 * order; the shell's radii widened by CLOUDS_TRACK_MARGIN_M, which covers the float rounding
 * of the altitudes the density sees), and piecewise constant inside them:
 *     sigma_bar = b_cell max_c k_c x 1.001   inside the majorant grid (cloud_majorant.h's DDA,
 *                                            b_cell the cell's density bound)
 *     sigma_bar = density max_c k_c x 1.001  beyond the grid (the global bound d <= density)
 * and 0 between the parts (no point and no random number there: the walk moves to the next
 * part's start). The one majorant walk spends each tentative point's optical depth
 * -ln(1 - u) over these segments.
 *
 * Coefficients (clouds_volume_at): sigma_t = d k and sigma_s = sigma_t albedo, per channel;
 * for a grey layer (clouds.extinction_per_m > 0: k and the albedo the same in every channel)
 * the walk's spectral tracking is delta tracking with the absorption in the weight.
 * Units: metres, 1/m. */
#ifndef ATMO_CLOUDS_CLOUD_TRACK_H
#define ATMO_CLOUDS_CLOUD_TRACK_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "common/rng.h"
#include "media/ray.h"
#include "media/tracking.h"
#include "clouds/cloud_layer.h"
#include "clouds/cloud_majorant.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUDS_TRACK_MARGIN_M 10.0f /* the majorant covers the shell's radii +- this */

typedef struct clouds_track {
    clouds_grid_walk grid;
    float scale;        /* density -> extinction bound: max_c k_c x 1.001, 1/m */
    float outside;      /* the rate beyond the grid, 1/m */
    float lo[2], hi[2]; /* the ray's parts inside the shell */
    int parts, part;    /* their count; the one the walk is in or before */
} clouds_track;

/* The layer's majorant on the ray origin + t dir (camera-relative, dir unit; radius r and
 * cosine mu at the origin) over [0, end]. */
ATMO_FN void clouds_track_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 origin,
                                vec3 dir, float r, float mu, float end, clouds_track *m)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    m->parts = geometry_shell_parts(s->atmosphere.bottom_radius, c->bottom_m - CLOUDS_TRACK_MARGIN_M,
                                  c->top_m + CLOUDS_TRACK_MARGIN_M, r, mu, 0.0f, end, m->lo,
                                  m->hi);
    m->part = 0;
    m->scale = tracking_max3(v3_from4(c->extinction)) * 1.001f;
    m->outside = c->majorant * m->scale;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    m->grid = clouds_grid_begin(&f, origin, dir, m->parts > 0 ? m->hi[m->parts - 1] : 0.0f);
}

/* The majorant from t (not before the last call's) up to *seg_end (see the top of the file). */
ATMO_FN float clouds_track_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   clouds_track *m, float t, float *seg_end)
{
    while (m->part < m->parts && t >= m->hi[m->part])
        m->part++;
    if (m->part >= m->parts) {
        *seg_end = INFINITY;
        return 0.0f;
    }
    if (t < m->lo[m->part]) {
        *seg_end = m->lo[m->part];
        return 0.0f;
    }
    float e, b = clouds_grid_segment(&m->grid, clouds_majorant, t, &e);
    *seg_end = fminf(e, m->hi[m->part]);
    return b < 0.0f ? m->outside : b * m->scale;
}

/* A new direction at a scattering by the layer (cloud_layer.h's sampling, shared with the path
 * tracer's cloud vertices). */
ATMO_FN vec3 clouds_media_direction(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 dir,
                                    vec3 to_sun, vec3 beta, float u1, float u2, rng_stream *g,
                                    vec3 *weight)
{
    return clouds_phase_direction(s, clouds_phase_table, clouds_phase_cdf, dir, to_sun, beta, u1,
                                  u2, g, weight);
}

/* The roulette gain of a path leaving at cosine nu to the sun (phase_table.h). */
ATMO_FN float clouds_roulette_gain(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float nu)
{
    return cloud_roulette_gain(clouds_phase(s, clouds_phase_table, nu));
}

/* The layer's extinction at q, its scattering in *scattering (the volume medium's slot). */
ATMO_FN vec3 clouds_volume_at(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_point *q, vec3 *scattering)
{
    float d = clouds_density(&s->clouds, q->p, q->h);
    vec3 sigma_t = v3_scale(v3_from4(s->clouds.extinction), d);
    *scattering = v3_mul(sigma_t, v3_from4(s->clouds.albedo));
    return sigma_t;
}

/* The layer's phase function per steradian at cosine nu (the volume medium's slot). */
ATMO_FN vec3 clouds_volume_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float nu)
{
    return clouds_phase(s, clouds_phase_table, nu);
}

#endif
