/* test_session — render sessions (atmo/session.h): steps, view updates, cancelling, and the
 * standard error from the second moments.
 * labels: render kernel stat
 *
 * 1. Steps and view updates. Oracle: the renderer's contract that the per-pixel sums are built
 *    in sample order (bitwise determinism). For `fast` (its sky-view LUT follows the view: the
 *    plan marks that pass follows_view) and `march`: a session on view A renders a few budgeted
 *    steps, moves to view B (camera 1.5 km higher, sun 8 degrees lower), renders B to the end,
 *    moves back to A and renders A in one-launch steps to the end. B's image must equal a fresh
 *    one-call render of B, and A's a fresh render of A, with memcmp: a stale view-dependent LUT,
 *    a leftover sum or a miscounted sample would all break the equality.
 * 2. Cancelling. Oracle: the same contract. A step of one-tile launches cancelled from the tile
 *    callback after 7 launches stops after the launch in flight (exactly 7 launches); the
 *    callback's reports add up to each tile's sample count; every pixel is finite; each tile
 *    holding n samples equals, bitwise, a complete render of n samples per pixel; the unreached
 *    tiles are 0. A step after the cancel finishes the image, equal to the one-call render.
 * 3. Standard error. Oracle: a statistical test. Two seeds of `reference` (Monte Carlo, n
 *    samples per pixel) give independent estimates of the same pixel mean with the same
 *    per-sample variance sigma^2. With the unbiased sample variances, z = (m_A - m_B) /
 *    sqrt(se_A^2 + se_B^2) is Student-t with nu = 2n - 2 degrees of freedom for normal samples
 *    (the pooled two-sample t statistic for equal n), so E[z^2] = nu / (nu - 2) and
 *    Var[z^2] = 3 nu^2 / ((nu - 2)(nu - 4)) - E[z^2]^2; the mean of z^2 over the N pixels (one
 *    channel; the channels of a pixel are correlated) must lie within 4.4 sqrt(Var[z^2] / N)
 *    of it (two-sided p ~ 1e-5). Normality is an approximation for skewed Monte Carlo samples,
 *    so a second check needs none: E[(m_A - m_B)^2] = E[se_A^2 + se_B^2] = 2 sigma^2 / n
 *    exactly, so R = sum (m_A - m_B)^2 / sum (se_A^2 + se_B^2) must be within 4.4 of its own
 *    standard errors (delta method over the pixels) of 1. The scene is sky-noon (the sun out
 *    of the frame, whose disc edge would make a few pixels dominate R), 48 x 32 pixels at 16
 *    samples: the bands are then about 0.18 and 0.22, and a standard error off by a factor 1.2
 *    moves both statistics by 0.3 to 0.5.
 * 4. Scene updates (the spectral mode's path). Oracle: the determinism contract again. The
 *    glory preset (cloud shell with Mie tables uploaded per wavelength) renders at its
 *    wavelengths (680, 550, 440 nm), then atmo_session_set_scene moves the same session to 680,
 *    550, 450 nm (other scene struct, another phase table for the third channel, all passes
 *    rerun, no rebuild) and renders again: that image must equal a fresh render at 680, 550,
 *    450 nm with memcmp. A plan with other kernels
 *    (another method) is refused. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/session.h"
#include "testlib.h"
#include "testscene.h"

#define W 29
#define H 19
#define PIXELS (W * H)

static void plan_view(const char *method, int view_b, int samples, atmo_plan *p)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-sunset");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    test_scene_set(&s, "camera.kind=panorama");
    snprintf(buf, sizeof buf, "image.width=%d", W);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.height=%d", H);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.samples=%d", samples);
    test_scene_set(&s, buf);
    test_scene_set(&s, "render.view_steps=8");
    if (view_b) {
        test_scene_set(&s, "camera.position_m=0,1500,0");
        test_scene_set(&s, "sun.zenith_deg=80");
    }
    test_plan(&s, p);
}

static void settings(atmo_render_settings *rs, int tile, int max_batch)
{
    atmo_render_settings_default(rs);
    rs->tile_size = tile;
    rs->max_batch = max_batch;
}

static float *render_once(const atmo_plan *plan)
{
    atmo_render_settings rs;
    atmo_render_result r;
    atmo_err e;
    settings(&rs, 64, 0);
    if (atmo_render(plan, &rs, &r, &e)) {
        fprintf(stderr, "render: %s\n", e.msg);
        exit(1);
    }
    CHECK(!r.interrupted && r.nonfinite == 0);
    return r.rgb;
}

static void must(int rc, const atmo_err *e)
{
    if (rc) {
        fprintf(stderr, "session: %s\n", e->msg);
        exit(1);
    }
}

static float *read_mean(atmo_session *s, float *se, int *samples)
{
    atmo_err e;
    float *m = malloc(sizeof(float) * 3 * PIXELS);
    must(atmo_session_read(s, m, se, samples, &e), &e);
    return m;
}

/* ------------------------------------------------------------------ 1 */

static void check_steps(const char *method)
{
    atmo_plan a, b;
    atmo_err e;
    plan_view(method, 0, 7, &a);
    plan_view(method, 1, 7, &b);
    int view_buffers = 0;
    for (int i = 0; i < a.buffer_count; i++)
        view_buffers += a.buffers[i].follows_view;
    float *want_a = render_once(&a), *want_b = render_once(&b);
    CHECK(memcmp(want_a, want_b, sizeof(float) * 3 * PIXELS) != 0);

    atmo_render_settings rs;
    settings(&rs, 8, 2);
    atmo_session *s;
    must(atmo_session_open(&s, &a, &rs, &e), &e);
    atmo_step one = {0, 1e-9, NULL, NULL, NULL}; /* one launch per step */
    atmo_step st;
    atmo_step_status status;
    for (int i = 0; i < 5; i++) {
        must(atmo_session_step(s, &one, &status, &e), &e);
        CHECK(status.launches == 1 && !status.complete);
    }
    must(atmo_session_set_view(s, &b, &e), &e);
    memset(&st, 0, sizeof st);
    must(atmo_session_step(s, &st, &status, &e), &e);
    CHECK(status.complete);
    float *got_b = read_mean(s, NULL, NULL);
    CHECK(memcmp(got_b, want_b, sizeof(float) * 3 * PIXELS) == 0);

    must(atmo_session_set_view(s, &a, &e), &e);
    int steps = 0;
    for (status.complete = 0; !status.complete; steps++)
        must(atmo_session_step(s, &one, &status, &e), &e);
    float *got_a = read_mean(s, NULL, NULL);
    CHECK(memcmp(got_a, want_a, sizeof(float) * 3 * PIXELS) == 0);
    CHECK(atmo_session_get_info(s)->nonfinite == 0);
    printf("1. %-5s %d view buffer(s); B after 5 steps and an update, then A again in %d steps: "
           "%s\n", method, view_buffers, steps,
           memcmp(got_a, want_a, sizeof(float) * 3 * PIXELS) == 0 &&
                   memcmp(got_b, want_b, sizeof(float) * 3 * PIXELS) == 0
               ? "bitwise equal to one-call renders"
               : "DIFFERENT");

    plan_view(method, 1, 7, &b); /* a plan that changes more than the view is refused */
    b.gpu.view_steps = 9;
    CHECK(atmo_session_set_view(s, &b, &e) == ATMO_ERR_USAGE);
    atmo_session_close(s);
    free(got_a);
    free(got_b);
    free(want_a);
    free(want_b);
    if (strcmp(method, "fast") == 0)
        CHECK(view_buffers > 0);
}

/* ------------------------------------------------------------------ 2 */

typedef struct cancel_log {
    atmo_cancel token;
    int launches, cancel_after;
    int tile_samples[64], tile_added[64];
} cancel_log;

#define CANCEL_TILE 8

static void on_tile(void *user, const atmo_tile *t)
{
    cancel_log *log = user;
    int columns = (W + CANCEL_TILE - 1) / CANCEL_TILE;
    for (int r = 0; r < t->tiles_down; r++)
        for (int c = 0; c < t->tiles_across; c++) {
            log->tile_samples[t->index + r * columns + c] = t->samples;
            log->tile_added[t->index + r * columns + c] += t->sample_count;
        }
    if (++log->launches == log->cancel_after)
        atmo_cancel_request(&log->token);
}

static void check_cancel(void)
{
    enum { SPP = 6, TILE = CANCEL_TILE };
    atmo_plan plan;
    atmo_err e;
    plan_view("march", 0, SPP, &plan);
    atmo_render_settings rs;
    settings(&rs, TILE, 2);
    rs.max_tiles = 1; /* a launch per tile: 7 launches leave most of the image without samples */
    atmo_session *s;
    cancel_log log;
    memset(&log, 0, sizeof log);
    log.cancel_after = 7;
    must(atmo_session_open(&s, &plan, &rs, &e), &e);
    atmo_step step = {0, 0.0, on_tile, &log, &log.token};
    atmo_step_status status;
    must(atmo_session_step(s, &step, &status, &e), &e);
    CHECK(status.cancelled && !status.complete && status.launches == 7 && log.launches == 7);

    float se[3 * PIXELS];
    int n[PIXELS];
    float *mean = read_mean(s, se, n);
    int columns = (W + TILE - 1) / TILE, consistent = 1, finite = 1, min = SPP, max = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x, t = y / TILE * columns + x / TILE;
            consistent &= n[i] == log.tile_samples[t] && n[i] == log.tile_added[t];
            min = n[i] < min ? n[i] : min;
            max = n[i] > max ? n[i] : max;
            for (int c = 0; c < 3; c++)
                finite &= isfinite(mean[3 * i + c]) && isfinite(se[3 * i + c]) &&
                          (n[i] > 1 || se[3 * i + c] == FLT_MAX);
        }
    CHECK(consistent && finite);
    CHECK(min == 0 && max > min);

    /* each tile's mean over its n samples is the complete render of n samples */
    int matched = 0, pixels_with = 0;
    for (int k = 0; k <= max; k++) {
        float *want = NULL;
        if (k > 0) {
            atmo_plan pk = plan;
            pk.samples = k;
            want = render_once(&pk);
        }
        for (int i = 0; i < PIXELS; i++) {
            if (n[i] != k)
                continue;
            pixels_with++;
            int same = 1;
            for (int c = 0; c < 3; c++)
                same &= k ? mean[3 * i + c] == want[3 * i + c] : mean[3 * i + c] == 0.0f;
            matched += same;
        }
        free(want);
    }
    CHECK(matched == PIXELS && pixels_with == PIXELS);

    atmo_cancel_clear(&log.token);
    log.cancel_after = -1;
    must(atmo_session_step(s, &step, &status, &e), &e);
    CHECK(status.complete && !status.cancelled);
    float *full = read_mean(s, NULL, n), *want = render_once(&plan);
    CHECK(memcmp(full, want, sizeof(float) * 3 * PIXELS) == 0);
    printf("2. cancelled after 7 launches: %d to %d samples per pixel, %d of %d pixels equal to "
           "the complete render of their count; resumed: %s\n", min, max, matched, PIXELS,
           memcmp(full, want, sizeof(float) * 3 * PIXELS) == 0 ? "equal" : "DIFFERENT");
    free(full);
    free(want);
    free(mean);
    atmo_session_close(s);
}

/* ------------------------------------------------------------------ 3 */

#define ZW 48
#define ZH 32
#define ZPIXELS (ZW * ZH)

static void render_seed(const atmo_plan *plan, unsigned seed, float *mean, float *se)
{
    atmo_plan p = *plan;
    atmo_err e;
    atmo_render_settings rs;
    settings(&rs, 64, 0);
    p.gpu.seed = seed;
    atmo_session *s;
    atmo_step step = {0, 0.0, NULL, NULL, NULL};
    atmo_step_status status;
    must(atmo_session_open(&s, &p, &rs, &e), &e);
    must(atmo_session_step(s, &step, &status, &e), &e);
    CHECK(status.complete);
    must(atmo_session_read(s, mean, se, NULL, &e), &e);
    atmo_session_close(s);
}

static void check_standard_error(void)
{
    enum { SPP = 16, CHANNEL = 1 };
    atmo_scene scene;
    atmo_plan plan;
    char buf[64];
    test_scene_preset(&scene, "sky-noon"); /* the sun out of the frame: no disc-edge outliers */
    test_scene_set(&scene, "atmosphere.method=reference");
    snprintf(buf, sizeof buf, "image.width=%d", ZW);
    test_scene_set(&scene, buf);
    snprintf(buf, sizeof buf, "image.height=%d", ZH);
    test_scene_set(&scene, buf);
    snprintf(buf, sizeof buf, "image.samples=%d", SPP);
    test_scene_set(&scene, buf);
    test_plan(&scene, &plan);
    static float ma[3 * ZPIXELS], sa[3 * ZPIXELS], mb[3 * ZPIXELS], sb[3 * ZPIXELS];
    static double a[ZPIXELS], b[ZPIXELS];
    render_seed(&plan, 11u, ma, sa);
    render_seed(&plan, 12u, mb, sb);
    double z2 = 0.0, num = 0.0, den = 0.0;
    int used = 0, zero_ok = 1;
    for (int i = 0; i < ZPIXELS; i++) {
        double d = (double)ma[3 * i + CHANNEL] - mb[3 * i + CHANNEL];
        double v = (double)sa[3 * i + CHANNEL] * sa[3 * i + CHANNEL] +
                   (double)sb[3 * i + CHANNEL] * sb[3 * i + CHANNEL];
        if (v == 0.0) { /* a pixel without noise must then agree exactly */
            zero_ok &= d == 0.0;
            continue;
        }
        a[used] = d * d;
        b[used] = v;
        z2 += d * d / v;
        num += d * d;
        den += v;
        used++;
    }
    CHECK(zero_ok && used > ZPIXELS / 2);
    double nu = 2.0 * SPP - 2.0, ez2 = nu / (nu - 2.0);
    double var_z2 = 3.0 * nu * nu / ((nu - 2.0) * (nu - 4.0)) - ez2 * ez2;
    double mean_z2 = z2 / used, band_z2 = 4.4 * sqrt(var_z2 / used);
    double r = num / den, q = 0.0;
    for (int i = 0; i < used; i++)
        q += (a[i] - r * b[i]) * (a[i] - r * b[i]);
    double se_r = sqrt(q / (used - 1.0) / used) / (den / used);
    printf("3. reference, %d spp, %d pixels: mean z^2 = %.3f (t_%g: %.3f +- %.3f); "
           "R = %.3f +- %.3f (4.4 SE)\n", SPP, used, mean_z2, nu, ez2, band_z2, r, 4.4 * se_r);
    CHECK_ABS(mean_z2, ez2, band_z2);
    CHECK_ABS(r, 1.0, 4.4 * se_r);
}

/* ------------------------------------------------------------------ 4 */

static void plan_glory(const char *wavelengths, atmo_plan *p)
{
    atmo_scene scene;
    char buf[64];
    test_scene_preset(&scene, "glory");
    snprintf(buf, sizeof buf, "image.width=%d", W);
    test_scene_set(&scene, buf);
    snprintf(buf, sizeof buf, "image.height=%d", H);
    test_scene_set(&scene, buf);
    test_scene_set(&scene, "image.samples=3");
    if (wavelengths) {
        snprintf(buf, sizeof buf, "render.wavelengths_nm=%s", wavelengths);
        test_scene_set(&scene, buf);
    }
    test_plan(&scene, p);
}

static void check_set_scene(void)
{
    atmo_plan first, second, other;
    atmo_err e;
    plan_glory(NULL, &first);
    plan_glory("680,550,450", &second);
    CHECK(first.gpu.cloud.table_size > 0 && second.gpu.cloud.table_size > 0);
    float *want = render_once(&second);
    atmo_render_settings rs;
    settings(&rs, 16, 0);
    atmo_session *s;
    atmo_step step = {0, 0.0, NULL, NULL, NULL};
    atmo_step_status status;
    must(atmo_session_open(&s, &first, &rs, &e), &e);
    must(atmo_session_step(s, &step, &status, &e), &e);
    float *at_first = read_mean(s, NULL, NULL);
    must(atmo_session_set_scene(s, &second, &e), &e);
    must(atmo_session_step(s, &step, &status, &e), &e);
    CHECK(status.complete);
    float *got = read_mean(s, NULL, NULL);
    int equal = memcmp(got, want, sizeof(float) * 3 * PIXELS) == 0;
    CHECK(equal);
    CHECK(memcmp(at_first, want, sizeof(float) * 3 * PIXELS) != 0);
    plan_view("fast", 0, 3, &other);
    CHECK(atmo_session_set_scene(s, &other, &e) == ATMO_ERR_USAGE);
    printf("4. glory at its wavelengths, then set_scene to 680, 550, 450 nm (phase table %d -> "
           "%d rows): %s a fresh render\n", first.gpu.cloud.table_size,
           second.gpu.cloud.table_size, equal ? "bitwise equal to" : "DIFFERENT from");
    atmo_session_close(s);
    free(got);
    free(at_first);
    free(want);
}

int main(void)
{
    test_require_opencl();
    check_steps("fast");
    check_steps("march");
    check_cancel();
    check_standard_error();
    check_set_scene();
    return test_finish();
}
