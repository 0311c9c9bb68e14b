/* render.h — the render pipeline: device, kernel build, precompute, tiles x sample batches.
 *
 * The image is cut into square tiles of a fixed size (--tile-size, default 64) launched with one
 * fixed local size (8 x 8); global sizes are padded to it and the kernel bounds-checks. Samples
 * are added in passes over all tiles (progressive): each launch renders a batch of samples of one
 * tile, and the batch adapts so that a launch stays under the launch budget (--launch-budget-ms,
 * default 100: GPU watchdogs kill kernels after about 2 s). The random numbers and the order of
 * the per-pixel sums do not depend on tile size, batch or tile order, so the image is bitwise
 * the same on one device for any of them. An interrupt (SIGINT, see atmo_render_interrupt) stops
 * after the launch in flight; the image is then the average of the samples each tile got. */
#ifndef ATMO_RENDER_H
#define ATMO_RENDER_H
#include "atmo/cl_runtime.h"
#include "atmo/plan.h"
#include "atmo/status.h"

typedef struct atmo_render_settings {
    const char *device;        /* selector, or NULL for ATMO_DEVICE / the default */
    int tile_size;             /* pixels, > 0 */
    double launch_budget_ms;   /* > 0 */
    int max_batch;             /* upper bound on samples per launch (0 = no bound; tests use it) */
    int progress;              /* 0 none, 1 plain lines, 2 terminal bar */
    const char *dump_dir;      /* --dump-kernels DIR */
    int use_kernel_cache;
} atmo_render_settings;

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

void atmo_render_settings_default(atmo_render_settings *s);
int atmo_render(const atmo_plan *plan, const atmo_render_settings *settings,
                atmo_render_result *result, atmo_err *e);
void atmo_render_result_free(atmo_render_result *r);

/* Allocate the plan's LUT buffers (a 16-byte dummy for each unused one) and run its precompute
 * passes in order, waiting for the last. On failure, luts[] holds what was allocated: the
 * caller releases the non-NULL ones either way. */
typedef struct atmo_precompute_info {
    double seconds;
    int cache_hit; /* the LUTs came from the disk cache (plan->cache_luts) */
} atmo_precompute_info;
int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem luts[ATMO_PLAN_LUTS], atmo_precompute_info *info, atmo_err *e);

/* Ask a running render to stop after the current launch (async-signal-safe). */
void atmo_render_interrupt(void);
/* Clear the request (before a new render). */
void atmo_render_clear_interrupt(void);

#endif
