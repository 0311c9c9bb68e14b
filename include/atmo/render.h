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
#include "atmo/embedded.h"
#include "atmo/part.h"
#include "atmo/plan.h"
#include "atmo/session.h"
#include "atmo/status.h"

typedef struct atmo_render_result {
    int width, height;
    float *rgb;                /* width x height x 3, mean over samples, row 0 = top */
    int pass_planes;           /* render passes (plan.pass_planes; 0: none, and the next three
                                  are NULL) */
    float *passes;             /* pass_planes x width x height x 4 means (atmo_session_read_passes) */
    float *se;                 /* width x height x 3 standard errors of rgb */
    float *guides;             /* with settings->guides: the denoiser's guides (atmo/guides.h),
                                  ATMO_GUIDES_FLOATS planes: albedo (W H 3), normal (W H 3),
                                  depth (W H), disc (W H); else NULL */
    double seconds_guides;     /* the guide pass */
    int *samples;              /* width x height samples per pixel */
    int noise_tiles;           /* with a noise target: the tiles, and per tile (x, y, w, h,
                                  samples) in tile_rect[5 i ...] and the relative standard
                                  error it reached (atmo/session.h's e) in tile_noise[i] */
    int *tile_rect;
    double *tile_noise;
    int samples_requested;
    int samples_min, samples_max; /* per pixel, equal unless interrupted */
    int interrupted;
    unsigned nonfinite;        /* dropped non-finite samples (should be 0) */
    int launches;
    int kernel_cache_hit;
    int lut_cache_hit;
    double seconds_device, seconds_build, seconds_precompute, seconds_render;
    double seconds_read;       /* the mean read back from the device (atmo_session_read) */
    char device_name[256], platform_name[256], driver_version[128];
} atmo_render_result;

int atmo_render(const atmo_plan *plan, const atmo_render_settings *settings,
                atmo_render_result *result, atmo_err *e);
void atmo_render_result_free(atmo_render_result *r);
/* atmo_render of part settings->part of settings->parts into the raw sums of *part, allocated
 * by the caller for the same part of the plan's image (atmo_part_alloc); fills its device.
 * result->rgb stays NULL. */
int atmo_render_part(const atmo_plan *plan, const atmo_render_settings *settings,
                     atmo_render_result *result, atmo_part *part, atmo_err *e);
/* The denoiser's guides of the plan's image alone, into result->guides (and its device names
 * and timings), from a session that renders no sample: the guides draw no random number, so on
 * one device they are those atmo_render makes with settings->guides, bit for bit (`atmo merge`
 * denoises the parts' image with them). result->rgb stays NULL. */
int atmo_render_guides(const atmo_plan *plan, const atmo_render_settings *settings,
                       atmo_render_result *result, atmo_err *e);
/* Fill result's device names, cache flags, timings, launches and sample range from a session. */
void atmo_render_result_from_session(const atmo_session *s, atmo_render_result *result);

/* Precomputed buffers (host/render/precompute.c).
 *
 * atmo_precompute allocates the plan's named buffers (buffers[i] for plan->buffers[i]; a 16-byte
 * placeholder for an empty one), copies the host tables in and runs the passes feature by
 * feature, waiting for the last. With plan->cache_luts, a feature's buffers come from the disk
 * cache when a file with its key is there and verifies, and are stored after they are computed
 * (mode 1: when its passes took more than 0.5 s; mode 2: always). Buffers that follow the view
 * are never cached; their passes run every time. On failure, buffers[] holds what was
 * allocated: the caller releases the non-NULL ones either way (atmo_release_buffers). */
typedef struct atmo_precompute_info {
    double seconds;
    int cache_hit;  /* every cacheable feature's buffers came from the disk cache */
    int loaded;     /* features whose buffers came from the cache */
    int computed;   /* cacheable features whose passes ran */
    int damaged;    /* cache files that failed verification (recomputed and rewritten) */
} atmo_precompute_info;
/* How the passes are launched: each in slices of whole work-group slabs along its last
 * dimension (rows of a 2-D pass, layers of a 3-D one), each slice sized to about
 * launch_budget_ms at the measured rate, with the cancel token checked between them. */
typedef struct atmo_precompute_control {
    double launch_budget_ms;   /* > 0; 0 runs each pass in one launch */
    int max_slabs;             /* upper bound on slabs per launch (0 = no bound; tests use it) */
    const atmo_cancel *cancel; /* may be NULL */
} atmo_precompute_control;
/* control may be NULL: one launch per pass, not cancellable. A cancelled precompute returns
 * ATMO_INTERRUPTED_EMPTY and caches nothing of the feature it stopped in. */
int atmo_precompute_controlled(atmo_cl *cl, cl_program program, const atmo_plan *plan,
                               cl_mem scene, cl_mem buffers[ATMO_PLAN_MAX_BUFFERS],
                               const atmo_precompute_control *control,
                               atmo_precompute_info *info, atmo_err *e);
/* atmo_precompute_controlled without a control. */
int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem buffers[ATMO_PLAN_MAX_BUFFERS], atmo_precompute_info *info,
                    atmo_err *e);
void atmo_release_buffers(cl_mem buffers[ATMO_PLAN_MAX_BUFFERS]);
/* Rerun only the passes of the features whose buffers follow the view into buffers[], after
 * the scene struct got another camera or sun; waits for the last. */
int atmo_precompute_view(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                         cl_mem buffers[ATMO_PLAN_MAX_BUFFERS],
                         const atmo_precompute_control *control, double *seconds, atmo_err *e);

/* Bind the plan's buffers, in plan order, as arguments first_arg, first_arg + 1, ... of k (the
 * ATMO_LUT_PARAMS of the kernel's signature); returns the index of the next argument, or -1
 * with e set. */
int atmo_bind_buffers(cl_kernel k, int first_arg, const atmo_plan *plan,
                      cl_mem buffers[ATMO_PLAN_MAX_BUFFERS], atmo_err *e);

/* Who computes a cached product: a cache file is only reused on the same device and driver. */
typedef struct atmo_device_identity {
    const char *name, *vendor, *driver;
} atmo_device_identity;

/* The cache key of the buffers of plan->features[feature]: a 64-bit FNV-1a hash of exactly its
 * own inputs: the registry row's name, the text of its sources (looked up in `sources`, the
 * embedded kernel table or a test's copy of it) and its -D flags, the fields of the GPU scene
 * its passes read (row->params), its buffers' names and sizes and host tables, its passes, the
 * keys of the features it needs, and the device identity. Not the camera, the sun, the view
 * steps, the output factors or any other fragment's text. */
unsigned long long atmo_product_key(const atmo_plan *plan, int feature,
                                    const atmo_device_identity *device,
                                    const struct atmo_embedded_file *sources);

#endif
