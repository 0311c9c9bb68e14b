/* testscene.h — scene, plan and LUT helpers for kernel tests (exit 1 with the message on any
 * error, since a broken preset or plan is a test failure). */
#ifndef ATMO_TESTSCENE_H
#define ATMO_TESTSCENE_H
#include "atmo/plan.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "testcl.h"

void test_scene_preset(atmo_scene *s, const char *preset);
void test_scene_set(atmo_scene *s, const char *assignment);
/* image.width, image.height, image.samples and image.seed at once */
void test_scene_image(atmo_scene *s, int width, int height, int samples, int seed);
/* The path tracer's cloud agreement view: a horizontally uniform fBm layer (coverage 1, noise
 * periods of 10^8 m) from 1 to 2 km with 300 m fades, extinction 0.002 /m, albedo 0.95, HG
 * phase, seen from 3 km looking down 50 degrees with a 20-degree field, the sun 30 degrees from
 * the zenith. */
void test_scene_flat_cloud_view(atmo_scene *s);
void test_plan(const atmo_scene *s, atmo_plan *p);
/* The plan of the sky-noon preset with `method`, the camera at altitude_m above (0, 0) and the
 * sun at sun_zenith_deg; method lut at small tables (2 orders: tests of geometry and stability,
 * not of the LUT's accuracy); LUTs through the test's keyed cache (cache_luts = 2), since the
 * view-independent ones (Psi_ms, lut's tables) do not change between such plans. */
void test_sky_plan(const char *method, double altitude_m, double sun_zenith_deg, atmo_plan *p);
/* The plan's program plus a probe kernel. */
cl_program test_plan_program(atmo_cl *cl, const atmo_plan *p, const char *extra);
/* The plan's precompute passes into luts[] (allocated here, one per plan buffer in plan order,
 * the rest NULL; release with test_release_luts). */
void test_precompute(atmo_cl *cl, cl_program prog, cl_mem scene, const atmo_plan *p,
                     cl_mem luts[ATMO_PLAN_MAX_BUFFERS]);
/* Bind luts[0], luts[1], ... up to the first NULL as arguments 1, 2, ... of k (the kernel's
 * ATMO_LUT_PARAMS); returns the index of the kernel's next argument. */
int test_bind_buffers(cl_kernel k, cl_mem luts[ATMO_PLAN_MAX_BUFFERS]);
/* Runs the program's kernel "walks" (arguments: the scene, luts[] as test_bind_buffers binds
 * them, then in, the order of the work-items' ids, out, n, walks) over n work-items twice: in
 * the ids' order into out, in reverse order into out_reversed (n results of out_size bytes
 * each), so a caller can check that a walk's result depends on its id alone. */
void test_run_walks(atmo_cl *cl, cl_program prog, cl_mem scene, cl_mem luts[ATMO_PLAN_MAX_BUFFERS],
                    const void *in, size_t in_bytes, size_t out_size, cl_uint n, cl_uint walks,
                    void *out, void *out_reversed);
/* The plan's buffer `name` in luts[] (exits 1 when the plan has none). */
cl_mem test_plan_buffer(const atmo_plan *p, cl_mem luts[ATMO_PLAN_MAX_BUFFERS], const char *name);
void test_release_luts(cl_mem luts[ATMO_PLAN_MAX_BUFFERS]);
/* Runs kernel `name` of plan p's program with the probe source `extra` (its own device, opened
 * and closed here) over n work-items: its arguments the scene, the plan's buffers
 * (test_bind_buffers), an input buffer of n elements of in_size bytes from in, an output
 * buffer of n elements of out_size bytes read into out, and n (uint). */
void test_plan_points(const atmo_plan *p, const char *extra, const char *name, const void *in,
                      size_t in_size, void *out, size_t out_size, int n);
/* The default cloud layer's phase table in the sampleable format (phase_table.h: *rows the
 * table's rows, *cdf its CDF, return value its size n) from the plan of sky-noon with
 * clouds.enabled, which *p holds until atmo_plan_free; exits 1 when the plan has no table. */
int test_cumulus_phase_table(atmo_plan *p, const void **rows, const void **cdf);

/* One view of the Monte Carlo sky table tests/data/reference_sky.csv (camera on the ground,
 * the sun at azimuth 0; angles in degrees): its radiance L per render wavelength and the
 * standard error se of each. */
typedef struct test_sky_row {
    double sun_zenith, view_zenith, view_azimuth, L[3], se[3];
} test_sky_row;
/* The table's rows (under $ATMO_SOURCE_DIR, else ..), at most max; exits 1 when the file
 * cannot be opened. */
int test_reference_sky(test_sky_row *rows, int max);

/* A rendered image: w x h pixels, per channel the mean and its standard error (linear, RGB
 * interleaved), and n the samples of pixel 0. */
typedef struct test_image {
    int w, h, n;
    float *mean, *se;
} test_image;
/* Scene s rendered to completion by one session step with the given tile size and launch
 * budget (atmo_render_settings' tile_size and max_batch); CHECKs that the step completes with
 * no NaN/Inf pixel, exits 1 on any failure. */
test_image test_render(const atmo_scene *s, int tile, int max_batch);
/* Plan p rendered by one session step with tile size `tile` (0: the default) and launch
 * budget max_batch (atmo_render_settings') into mean[] and se[] (3 floats a pixel) and, unless
 * NULL, samples[] (one int a pixel); CHECKs that the step completes with no NaN/Inf pixel.
 * Returns 1 (the error printed) where the session fails, else 0. */
int test_render_plan(const atmo_plan *p, int tile, int max_batch, float *mean, float *se,
                     int *samples);
void test_image_free(test_image *im);
/* Plan p rendered whole by atmo_render with settings rs (NULL: the defaults) into *r (freed by
 * the caller, atmo_render_result_free); exits 1 (the error printed) where it fails, and CHECKs
 * that no pixel is NaN/Inf. */
void test_render_whole(const atmo_plan *p, const atmo_render_settings *rs, atmo_render_result *r);
/* Images a and b of one scene by two unbiased estimators (named name_a and name_b in the
 * printed lines, which `label` begins), compared by z-tests on their standard errors: per
 * channel the image means' difference z = (sum b - sum a) / sqrt(sum se_a^2 + sum se_b^2),
 * printed and CHECKed below z_bound with both variances positive; and every pixel-channel's z.
 * Returns the pixel-channels with |z| >= z_bound or no variance; *z_max the largest |z|. */
int test_image_agree(const char *label, const char *name_a, const test_image *a,
                     const char *name_b, const test_image *b, double z_bound, double *z_max);

#endif
