/* probe.h — a method's sky radiance for a list of rays, outside of an image.
 *
 * A probe holds a render session (atmo/session.h: device, the plan's program, the scene and the
 * precomputed data, opened once); atmo_probe_rays() then averages `samples` samples of the method's
 * sky_radiance (the `sky_probe` kernel of kernels/render/sky.cl) for rays given as (r, mu, mu_s, nu),
 * as ATMO_PROBE_BATCHES independent batches (distinct RNG pixel indices) whose spread gives the
 * standard error. atmo_probe_segments() does the same for segments of the rays (aerial
 * perspective); atmo_probe_sun() gives the sun's visibility at their origins. Used by
 * `atmo radiance` and `atmo bench atmosphere`. */
#ifndef ATMO_PROBE_H
#define ATMO_PROBE_H
#include "atmo/cl_runtime.h"
#include "atmo/plan.h"
#include "atmo/session.h"

#define ATMO_PROBE_BATCHES 64

typedef struct atmo_probe {
    atmo_session *session;
    double seconds_build, seconds_precompute;
} atmo_probe;

/* p must be zeroed before the first open; close it whatever open returned. */
int atmo_probe_open(atmo_probe *p, const atmo_plan *plan, const char *device, atmo_err *e);
/* Mean (and, if se is not NULL, standard error) of each ray's radiance; samples is rounded up
 * to a multiple of ATMO_PROBE_BATCHES. */
int atmo_probe_rays(atmo_probe *p, const float4 *rays, int n, int samples, double (*mean)[3],
                    double (*se)[3], atmo_err *e);
/* Aerial perspective (sky_segment, kernel sky_probe_segment): ray i ends at a black surface at
 * distances[i] metres; mean (and se) of the in-scattered radiance and t_mean (and t_se) of
 * the transmittance T(0, d); either se may be NULL. */
int atmo_probe_segments(atmo_probe *p, const float4 *rays, const float *distances, int n,
                        int samples, double (*mean)[3], double (*se)[3], double (*t_mean)[3],
                        double (*t_se)[3], atmo_err *e);
/* The sun's visibility at each ray's origin (kernel sky_probe_sun: visibility.h's
 * visibility_sun, the occluders and the shadowing media toward the sun per wavelength, without
 * the atmosphere's own transmittance). */
int atmo_probe_sun(atmo_probe *p, const float4 *rays, int n, double (*visibility)[3],
                   atmo_err *e);
void atmo_probe_close(atmo_probe *p);

#endif
