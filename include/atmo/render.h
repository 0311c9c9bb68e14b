/* render.h — a whole render in one call, and the precompute passes a session runs.
 *
 * atmo_render is the convenience wrapper over a render session (atmo/session.h): open, step to
 * the plan's samples (stopped early by settings->cancel), read the mean image, close. Tiles,
 * batches and the launch budget are the session's (atmo/tiles.h): the image is bitwise the same
 * on one device for any tile size, launch budget or batch. A cancelled render returns the mean
 * of the samples each tile got, with interrupted set. */
#ifndef ATMO_RENDER_H
#define ATMO_RENDER_H
#include "atmo/cl_runtime.h"
#include "atmo/plan.h"
#include "atmo/session.h"
#include "atmo/status.h"

typedef struct atmo_render_result {
    int width, height;
    float *rgb;                /* width x height x 3, mean over samples, row 0 = top */
    int samples_requested;
    int samples_min, samples_max; /* per pixel, equal unless interrupted */
    int interrupted;
    unsigned nonfinite;        /* dropped non-finite samples (should be 0) */
    int launches;
    int kernel_cache_hit;
    int lut_cache_hit;
    double seconds_device, seconds_build, seconds_precompute, seconds_render;
    char device_name[256], platform_name[256], driver_version[128];
} atmo_render_result;

int atmo_render(const atmo_plan *plan, const atmo_render_settings *settings,
                atmo_render_result *result, atmo_err *e);
void atmo_render_result_free(atmo_render_result *r);
/* Fill result's device names, cache flags, timings, launches and sample range from a session. */
void atmo_render_result_from_session(const atmo_session *s, atmo_render_result *result);

/* Allocate the plan's LUT buffers (a 16-byte dummy for each unused one) and run its precompute
 * passes in order, waiting for the last. On failure, luts[] holds what was allocated: the
 * caller releases the non-NULL ones either way. */
typedef struct atmo_precompute_info {
    double seconds;
    int cache_hit; /* the LUTs came from the disk cache (plan->cache_luts) */
} atmo_precompute_info;
int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem luts[ATMO_PLAN_LUTS], atmo_precompute_info *info, atmo_err *e);
/* Rerun only the passes that follow the view (follows_view) into the allocated luts[], after
 * the scene struct got another camera or sun; waits for the last. */
int atmo_precompute_view(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                         cl_mem luts[ATMO_PLAN_LUTS], double *seconds, atmo_err *e);

#endif
