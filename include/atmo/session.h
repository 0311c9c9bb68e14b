/* session.h — a render session: one device, one program, the precomputed data, and an image
 * that accumulates in budgeted steps.
 *
 * Lifecycle. atmo_session_open opens the device, builds the plan's program (once; the build
 * cache makes a rebuild cheap, but a session never rebuilds), uploads the scene struct and runs
 * the plan's precompute passes. atmo_session_step renders until a sample target, a time budget
 * or a cancel token stops it, calling a callback after every launch with the tile it finished.
 * atmo_session_set_view takes a plan of the same scene with another camera or sun: it rewrites
 * the scene struct, reruns only the passes that follow the view (atmo_plan_pass.follows_view,
 * e.g. the sky-view LUT of `fast`) and restarts the accumulation; the view-independent LUTs stay.
 * atmo_session_set_scene takes a plan with the same program but other parameters (another
 * atmosphere, other wavelengths: the spectral mode's triplets) and reruns every pass.
 * atmo_session_read gives the mean, its standard error and the sample count per pixel
 * (atmo_session_read_sums the raw sums they come from);
 * atmo_session_close releases everything in reverse order.
 *
 * Accumulation. Two float4 buffers per pixel: accum holds S1 = sum_k L_k per channel (xyz; w
 * unused) and accum_sq holds S2 = sum_k L_k^2 per channel (xyz; w unused), each sum built in
 * sample order k = 0, 1, ... whatever the tiles and batches, so the image is bitwise the same
 * for any tile size, launch budget or split into steps. The samples per pixel are those of its
 * tile (the scheduler's per-tile counts, atmo/tiles.h). With n samples the mean is S1/n and its
 * standard error is the square root of the unbiased sample variance over n,
 *     se = sqrt((S2 - S1^2/n) / (n (n - 1))),
 * evaluated in double from the float sums (negative rounding residues clamp to 0); a pixel with
 * fewer than 2 samples has no variance estimate and reports se = FLT_MAX.
 *
 * Noise target (atmo_session_set_noise_target). At each of its checkpoints (atmo/tiles.h: 16, 32, 64, ...
 * samples) a tile's relative standard error is measured from its sums,
 *     e = sqrt(mean over its pixels and channels of se^2) / mean over them of the mean,
 * (the RMS standard error of its pixels relative to its mean radiance), and the tile stops
 * when e <= the target; the others continue up to the step's sample target. A step with a noise
 * target is complete when every tile has converged or reached the target. The decision is
 * taken on the same sums whatever the tile size or launch budget, so the image stays
 * deterministic.
 *
 * Cancelling. An atmo_cancel is owned by the caller; atmo_cancel_request only stores to a
 * volatile sig_atomic_t, so a signal handler may call it. The session checks the token between
 * launches: a step stops after the launch in flight, and the image is then the mean of the
 * samples each tile got (atmo_session_read's counts say how many). */
#ifndef ATMO_SESSION_H
#define ATMO_SESSION_H
#include <signal.h>
#include "atmo/cl_runtime.h"
#include "atmo/plan.h"
#include "atmo/status.h"
#include "atmo/tiles.h"

typedef struct atmo_render_settings {
    const char *device;        /* selector, or NULL for ATMO_DEVICE / the default */
    int tile_size;             /* pixels, > 0 */
    double launch_budget_ms;   /* > 0 */
    int max_batch;             /* upper bound on samples per launch (0 = no bound; tests use it) */
    int max_tiles;             /* upper bound on tiles per launch (0 = no bound, 1 = a launch
                                  per tile, as the tests of per-tile launches want) */
    int progress;              /* 0 none, 1 plain lines, 2 terminal bar */
    const char *dump_dir;      /* --dump-kernels DIR */
    int use_kernel_cache;
    struct atmo_cancel *cancel; /* token for atmo_render / atmo_spectral_render (may be NULL) */
    int part, parts;           /* render only part `part` (1 .. parts) of the image's bands
                                  (atmo/tiles.h); parts = 0: the whole image */
    double noise_target;       /* atmo_render: the step's noise target (0: none) */
    double time_limit_s;       /* atmo_render: no new launch after this long (0: none) */
    int guides;                /* atmo_render: also the denoiser's guides (atmo/guides.h) */
} atmo_render_settings;

void atmo_render_settings_default(atmo_render_settings *s);

typedef struct atmo_cancel {
    volatile sig_atomic_t requested;
} atmo_cancel;

void atmo_cancel_request(atmo_cancel *c); /* async-signal-safe */
void atmo_cancel_clear(atmo_cancel *c);
int atmo_cancel_requested(const atmo_cancel *c); /* 0 for NULL */

/* Called after each launch with the tile it rendered (its rectangle and its new sample count). */
typedef void (*atmo_tile_callback)(void *user, const atmo_tile *tile);

typedef struct atmo_step {
    int samples;                /* target per pixel (0: the plan's image.samples) */
    double budget_seconds;      /* no new launch after this long (0: no limit) */
    atmo_tile_callback on_tile; /* may be NULL */
    void *user;
    atmo_cancel *cancel;        /* may be NULL */
} atmo_step;

typedef struct atmo_step_status {
    int complete;   /* every tile has the step's target */
    int cancelled;  /* the token stopped the step */
    int launches;   /* in this step */
} atmo_step_status;

/* What the session did so far (timings in seconds; precompute and render summed over updates). */
typedef struct atmo_session_info {
    char device_name[256], platform_name[256], driver_version[128];
    int kernel_cache_hit, lut_cache_hit;
    double seconds_device, seconds_build, seconds_precompute, seconds_render;
    double seconds_read; /* in atmo_session_read, summed */
    int launches;
    unsigned nonfinite; /* dropped non-finite samples since the last restart (should be 0) */
} atmo_session_info;

typedef struct atmo_session atmo_session;

/* *out is NULL on failure (everything opened so far is released). */
int atmo_session_open(atmo_session **out, const atmo_plan *plan, const atmo_render_settings *rs,
                      atmo_err *e);
int atmo_session_step(atmo_session *s, const atmo_step *step, atmo_step_status *status,
                      atmo_err *e);
/* The noise target of the following steps (relative standard error per tile, e.g. 0.01; 0:
 * none). */
void atmo_session_set_noise_target(atmo_session *s, double noise);
/* Same scene, other camera and/or sun: only gpu.camera, gpu.sun_direction and gpu.observer
 * may differ from the session's plan, and its host tables must hold the same bytes (a scene
 * with objects, whose rows are camera-relative, changes them with the camera): ATMO_ERR_USAGE
 * otherwise, and atmo_session_set_scene takes such a plan. */
int atmo_session_set_view(atmo_session *s, const atmo_plan *plan, atmo_err *e);
/* Same program (fragments and -D flags) and image size, any other parameters. */
int atmo_session_set_scene(atmo_session *s, const atmo_plan *plan, atmo_err *e);
/* Any of mean (W x H x 3), se (W x H x 3) and samples (W x H) may be NULL; row 0 = top. */
int atmo_session_read(atmo_session *s, float *mean, float *se, int *samples, atmo_err *e);
/* The raw accumulators as they are on the device: s1 = S1 and s2 = S2 (W x H x 3 each, the
 * sums in sample order) and the samples per pixel (W x H); any may be NULL. These are what a
 * part of a split render stores, so that merging parts repeats atmo_session_read bit for bit. */
int atmo_session_read_sums(atmo_session *s, float *s1, float *s2, int *samples, atmo_err *e);
/* The mean atmo_session_read gives for a sum of `samples` samples: sum * (1/samples), 0 for none. */
float atmo_session_mean(float sum, int samples);
/* The render passes' means (plan.pass_planes planes of W x H x 4 floats, plane k at
 * out + 4 W H k, row 0 = top; what each plane holds: kernels/render/path.cl); usage error when
 * the plan has none. */
int atmo_session_read_passes(atmo_session *s, float *out, atmo_err *e);
void atmo_session_close(atmo_session *s); /* NULL is fine */

const atmo_session_info *atmo_session_get_info(const atmo_session *s);
const atmo_plan *atmo_session_plan(const atmo_session *s);
/* Fewest and most samples per pixel over the image. */
void atmo_session_samples(const atmo_session *s, int *min, int *max);

/* For kernels of one's own on the session's program and data (the probe, tests). */
atmo_cl *atmo_session_cl(atmo_session *s);
cl_program atmo_session_program(const atmo_session *s);
/* Bind the scene struct and the plan's buffers as the kernel's first arguments, from *arg on;
 * *arg is left at the next free index. */
int atmo_session_bind(const atmo_session *s, cl_kernel k, cl_uint *arg, atmo_err *e);

#endif
