/* test_noise_target — the progressive mode's noise target (atmo_session_set_noise_target,
 * atmo/session.h) and the primary sequence's convergence against independent samples.
 * labels: render kernel stat slow
 *
 * 1. Noise target (oracle: a long reference and the chi-square distribution). Thesis view 7's
 *    open box in the uniform test world (no air; sun and sky as test_path_open_box), 16 x 12
 *    pixels in tiles of 4, rendered to a 3 % noise target (at most 4096 samples), and a
 *    reference of 2048 samples with another seed (independent). Per tile, the measured error
 *    E = RMS over its pixels and channels of (mean - reference) / the tile's mean must satisfy
 *    E^2 <= (target^2 + e_ref^2) q, where e_ref is the reference's own relative standard error
 *    (its second moments) and q = chi^2_{48}(p = 1e-4) / 48 = 1.92 bounds the mean of 48 squared
 *    normal deviates (48 = 16 pixels x 3 channels): a tile that stopped before its error was
 *    at the target fails. Tiles that met the target hold fewer samples than the cap.
 *    Determinism: the noise-targeted image is bitwise the same with tiles of 4 and one launch
 *    per sample as with tiles of 4 and no batch bound (its checkpoints do not depend on them).
 * 2. Stratification pays (measured; oracle: a long reference). Emissive spheres and a box
 *    against a black uniform sky, no lighting (sun off, no bounces' light), so a sample's only
 *    randomness is its place in the pixel: the image is the filtered integral over the pixel
 *    footprint. The RMS error against a 4096-sample reference at 16, 32, ..., 256 samples
 *    with Owen-scrambled Sobol (path.sampler = sobol) and with independent random positions
 *    (random): Sobol's error at 64 samples must be below random's by a factor 1.5 (random
 *    converges as N^-1/2; stratified points at pixel edges as N^-3/4, a factor 2.8 at N = 64),
 *    and the samples each needs to get below random's error at 256 are printed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/session.h"
#include "testlib.h"
#include "testscene.h"

#define W 16
#define H 12
#define PIX (W * H)

static void box_scene(atmo_scene *s)
{
    test_scene_preset(s, "thesis-7");
    test_scene_set(s, "path.sky=uniform");
    test_scene_set(s, "path.uniform_sky=0.05,0.08,0.12");
    test_scene_set(s, "path.ground=false");
    test_scene_set(s, "sun.zenith_deg=40");
    test_scene_set(s, "sun.azimuth_deg=-135");
    test_scene_set(s, "path.bounces=2");
    test_scene_set(s, "image.width=16");
    test_scene_set(s, "image.height=12");
}

static atmo_session *open_session(const atmo_scene *s, atmo_plan *p, int tile, int max_batch)
{
    atmo_render_settings rs;
    atmo_session *session = NULL;
    atmo_err e;
    test_plan(s, p);
    atmo_render_settings_default(&rs);
    rs.tile_size = tile;
    rs.max_batch = max_batch;
    if (atmo_session_open(&session, p, &rs, &e)) {
        fprintf(stderr, "session: %s\n", e.msg);
        exit(1);
    }
    return session;
}

static void step_read(atmo_session *session, int samples, float *mean, float *se, int *n)
{
    atmo_step step = {samples, 0.0, NULL, NULL, NULL};
    atmo_step_status st;
    atmo_err e;
    if (atmo_session_step(session, &step, &st, &e) ||
        atmo_session_read(session, mean, se, n, &e)) {
        fprintf(stderr, "render: %s\n", e.msg);
        exit(1);
    }
    CHECK(st.complete);
}

static void test_target(void)
{
    static float ref[PIX * 3], ref_se[PIX * 3], m[PIX * 3], se[PIX * 3], m2[PIX * 3];
    static int n[PIX], n2[PIX];
    atmo_scene s;
    atmo_plan p;
    box_scene(&s);
    s.image.seed = 1;
    atmo_session *r = open_session(&s, &p, 4, 0);
    step_read(r, 2048, ref, ref_se, n);
    atmo_session_close(r);
    atmo_plan_free(&p);
    s.image.seed = 0;
    double target = 0.03;
    atmo_session *a = open_session(&s, &p, 4, 0);
    atmo_session_set_noise_target(a, target);
    step_read(a, 4096, m, se, n);
    atmo_session_close(a);
    atmo_session *b = open_session(&s, &p, 4, 1);
    atmo_session_set_noise_target(b, target);
    step_read(b, 4096, m2, se, n2);
    atmo_session_close(b);
    atmo_plan_free(&p);
    CHECK(memcmp(m, m2, sizeof m) == 0 && memcmp(n, n2, sizeof n) == 0);
    double q = test_chi2_critical_1e4(48) / 48.0;
    int bad = 0, stopped = 0;
    for (int ty = 0; ty < H; ty += 4)
        for (int tx = 0; tx < W; tx += 4) {
            double sum = 0.0, d2 = 0.0, r2 = 0.0;
            for (int y = ty; y < ty + 4; y++)
                for (int x = tx; x < tx + 4; x++)
                    for (int c = 0; c < 3; c++) {
                        int i = 3 * (y * W + x) + c;
                        sum += ref[i];
                        d2 += (double)(m[i] - ref[i]) * (m[i] - ref[i]);
                        r2 += (double)ref_se[i] * ref_se[i];
                    }
            double mean = sum / 48.0, E = sqrt(d2 / 48.0) / mean, e_ref = sqrt(r2 / 48.0) / mean;
            int samples = n[ty * W + tx];
            stopped += samples < 4096;
            bad += E * E > (target * target + e_ref * e_ref) * q;
            printf("tile (%2d, %2d): %4d samples, measured error %.4f (reference's own %.4f)\n",
                   tx, ty, samples, E, e_ref);
        }
    CHECK(bad == 0);
    CHECK(stopped == 12);
}

static double rms_error(const float *m, const float *ref)
{
    double d2 = 0.0, sum = 0.0;
    for (int i = 0; i < PIX * 3; i++) {
        d2 += (double)(m[i] - ref[i]) * (m[i] - ref[i]);
        sum += ref[i];
    }
    return sqrt(d2 / (PIX * 3)) / (sum / (PIX * 3));
}

static void test_stratification(void)
{
    static float ref[PIX * 3], m[PIX * 3];
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "path.sky=uniform");
    test_scene_set(&s, "path.uniform_sky=0,0,0");
    test_scene_set(&s, "sun.irradiance_scale=0");
    test_scene_set(&s, "path.ground=false");
    test_scene_set(&s, "path.bounces=0");
    test_scene_set(&s, "path.sky_nee=false");
    test_scene_set(&s, "camera.position_m=0,100,0");
    test_scene_set(&s, "camera.pitch_deg=0");
    test_scene_set(&s, "image.width=16");
    test_scene_set(&s, "image.height=12");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [-0.6, 100.2, 4], "
                       "\"radius_m\": 0.7, \"emission\": [1, 0.5, 0.2]}, {\"type\": \"sphere\", "
                       "\"center_m\": [0.8, 99.7, 5], \"radius_m\": 0.5, \"emission\": [0.2, 1, "
                       "0.4]}, {\"type\": \"box\", \"min_m\": [-0.3, 99.2, 3], \"size_m\": [0.9, "
                       "0.3, 0.2], \"emission\": [0.3, 0.3, 1]}]");
    s.image.seed = 7;
    atmo_session *r = open_session(&s, &p, 64, 0);
    step_read(r, 4096, ref, NULL, NULL);
    atmo_session_close(r);
    atmo_plan_free(&p);
    double err[2][5];
    for (int k = 0; k < 2; k++) {
        test_scene_set(&s, k == 0 ? "path.sampler=sobol" : "path.sampler=random");
        s.image.seed = 0;
        atmo_session *a = open_session(&s, &p, 64, 0);
        for (int j = 0; j < 5; j++) {
            step_read(a, 16 << j, m, NULL, NULL);
            err[k][j] = rms_error(m, ref);
        }
        atmo_session_close(a);
        atmo_plan_free(&p);
    }
    int need[2] = {-1, -1};
    for (int k = 0; k < 2; k++)
        for (int j = 4; j >= 0; j--)
            if (err[k][j] <= err[1][4])
                need[k] = 16 << j;
    for (int j = 0; j < 5; j++)
        printf("%4d samples: RMS relative error sobol %.4f, random %.4f (ratio %.2f)\n", 16 << j,
               err[0][j], err[1][j], err[1][j] / err[0][j]);
    printf("samples to reach random's error at 256 (%.4f): sobol %d, random %d\n", err[1][4],
           need[0], need[1]);
    CHECK(err[0][2] * 1.5 < err[1][2]);
}

int main(void)
{
    test_require_opencl();
    test_target();
    test_stratification();
    return test_finish();
}
