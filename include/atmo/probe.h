/* probe.h — a method's sky radiance for a list of rays, outside of an image.
 *
 * A probe session opens the device, builds the plan's program, uploads the scene and runs the
 * precompute passes once; atmo_probe_rays() then averages `samples` samples of the method's
 * sky_radiance (the `sky_probe` kernel of kernels/render/sky.cl) for rays given as (r, mu, mu_s, nu),
 * as ATMO_PROBE_BATCHES independent batches (distinct RNG pixel indices) whose spread gives the
 * standard error. atmo_probe_segments() does the same for segments of the rays (aerial
 * perspective). Used by `atmo radiance` and `atmo bench atmosphere`. */
#ifndef ATMO_PROBE_H
#define ATMO_PROBE_H
#include "atmo/cl_runtime.h"
#include "atmo/plan.h"

#define ATMO_PROBE_BATCHES 64

typedef struct atmo_probe {
    atmo_cl cl;
    int cl_open;
    cl_program program;
    cl_mem scene;
    cl_mem buffers[ATMO_PLAN_MAX_BUFFERS]; /* the plan's named buffers */
    const atmo_plan *plan;                 /* the plan it was opened with (must outlive it) */
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
void atmo_probe_close(atmo_probe *p);

#endif
