/* Test helpers that need a whole scene: see testscene.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/session.h"
#include "testlib.h"
#include "testscene.h"

void test_scene_preset(atmo_scene *s, const char *preset)
{
    atmo_err e;
    atmo_scene_defaults(s);
    if (atmo_scene_apply_preset(s, preset, &e)) {
        fprintf(stderr, "preset %s: %s\n", preset, e.msg);
        exit(1);
    }
}

void test_scene_set(atmo_scene *s, const char *assignment)
{
    atmo_err e;
    if (atmo_scene_assign(s, assignment, "test", &e)) {
        fprintf(stderr, "%s: %s\n", assignment, e.msg);
        exit(1);
    }
}

void test_scene_image(atmo_scene *s, int width, int height, int samples, int seed)
{
    char buf[64];
    snprintf(buf, sizeof buf, "image.width=%d", width);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.height=%d", height);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.samples=%d", samples);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.seed=%d", seed);
    test_scene_set(s, buf);
}

void test_plan(const atmo_scene *s, atmo_plan *p)
{
    atmo_err e;
    if (atmo_plan_make(s, p, &e)) {
        fprintf(stderr, "plan: %s\n", e.msg);
        exit(1);
    }
}

void test_sky_plan(const char *method, double altitude_m, double sun_zenith_deg, atmo_plan *p)
{
    static const char *const small_lut[] = {"lut.r_size=8",   "lut.mu_size=32",
                                            "lut.mu_s_size=8", "lut.nu_size=4",
                                            "lut.orders=2",    "lut.sphere_samples=8",
                                            "lut.steps=16"};
    atmo_scene s;
    char buf[96];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "camera.position_m=0,%.17g,0", altitude_m);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "sun.zenith_deg=%.17g", sun_zenith_deg);
    test_scene_set(&s, buf);
    if (strcmp(method, "lut") == 0)
        for (size_t i = 0; i < sizeof small_lut / sizeof small_lut[0]; i++)
            test_scene_set(&s, small_lut[i]);
    test_plan(&s, p);
    p->cache_luts = 2;
}

int test_cumulus_phase_table(atmo_plan *p, const void **rows, const void **cdf)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "clouds.enabled=true");
    test_plan(&s, p);
    const atmo_plan_buffer *r = atmo_plan_buffer_find(p, "clouds_phase_table");
    const atmo_plan_buffer *c = atmo_plan_buffer_find(p, "clouds_phase_cdf");
    if (!r || !c || !r->host_data || !c->host_data) {
        fprintf(stderr, "plan: no cloud phase table\n");
        exit(1);
    }
    *rows = r->host_data;
    *cdf = c->host_data;
    return p->gpu.clouds.table_size;
}

cl_program test_plan_program(atmo_cl *cl, const atmo_plan *p, const char *extra)
{
    atmo_err e;
    cl_program prog;
    const char *texts[ATMO_PLAN_MAX_FRAGMENTS];
    atmo_plan_fragment_texts(p, texts);
    atmo_cl_build_options o = {p->fragments, p->fragment_count, p->defines, NULL, 1, extra,
                               p->prelude, texts};
    atmo_cl_build_info info;
    if (atmo_cl_build(cl, &o, &prog, &info, &e)) {
        fprintf(stderr, "kernel build failed: %s\n", e.msg);
        exit(1);
    }
    return prog;
}

void test_precompute(atmo_cl *cl, cl_program prog, cl_mem scene, const atmo_plan *p,
                     cl_mem luts[ATMO_PLAN_MAX_BUFFERS])
{
    atmo_err e;
    atmo_precompute_info info;
    if (atmo_precompute(cl, prog, p, scene, luts, &info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
}

int test_bind_buffers(cl_kernel k, cl_mem luts[ATMO_PLAN_MAX_BUFFERS])
{
    int i = 0;
    for (; i < ATMO_PLAN_MAX_BUFFERS && luts[i]; i++) {
        cl_int err = clSetKernelArg(k, (cl_uint)(1 + i), sizeof luts[i], &luts[i]);
        if (err != CL_SUCCESS) {
            fprintf(stderr, "clSetKernelArg(buffer %d): %s\n", i, atmo_cl_error_string(err));
            exit(1);
        }
    }
    return 1 + i;
}

void test_run_walks(atmo_cl *cl, cl_program prog, cl_mem scene, cl_mem luts[ATMO_PLAN_MAX_BUFFERS],
                    const void *in, size_t in_bytes, size_t out_size, cl_uint n, cl_uint walks,
                    void *out, void *out_reversed)
{
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "walks", &err);
    CHECK(err == CL_SUCCESS);
    cl_uint *order = malloc(sizeof(cl_uint) * n);
    CHECK(order != NULL);
    cl_mem b_in = test_cl_buffer(cl, in_bytes, in);
    cl_mem b_out = test_cl_buffer(cl, out_size * n, NULL);
    for (int pass = 0; pass < 2; pass++) {
        for (cl_uint i = 0; i < n; i++)
            order[i] = pass ? n - 1 - i : i;
        cl_mem b_order = test_cl_buffer(cl, sizeof(cl_uint) * n, order);
        CHECK(clSetKernelArg(k, 0, sizeof scene, &scene) == CL_SUCCESS);
        cl_uint arg = (cl_uint)test_bind_buffers(k, luts);
        CHECK(clSetKernelArg(k, arg, sizeof b_in, &b_in) == CL_SUCCESS);
        CHECK(clSetKernelArg(k, arg + 1, sizeof b_order, &b_order) == CL_SUCCESS);
        CHECK(clSetKernelArg(k, arg + 2, sizeof b_out, &b_out) == CL_SUCCESS);
        CHECK(clSetKernelArg(k, arg + 3, sizeof n, &n) == CL_SUCCESS);
        CHECK(clSetKernelArg(k, arg + 4, sizeof walks, &walks) == CL_SUCCESS);
        test_cl_run_1d(cl, k, n);
        test_cl_read(cl, b_out, out_size * n, pass ? out_reversed : out);
        clReleaseMemObject(b_order);
    }
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_in);
    clReleaseKernel(k);
    free(order);
}

cl_mem test_plan_buffer(const atmo_plan *p, cl_mem luts[ATMO_PLAN_MAX_BUFFERS], const char *name)
{
    int i = atmo_plan_buffer_index(p, name);
    if (i < 0) {
        fprintf(stderr, "the plan has no buffer %s\n", name);
        exit(1);
    }
    return luts[i];
}

void test_release_luts(cl_mem luts[ATMO_PLAN_MAX_BUFFERS])
{
    atmo_release_buffers(luts);
}

void test_plan_points(const atmo_plan *p, const char *extra, const char *name, const void *in,
                      size_t in_size, void *out, size_t out_size, int n)
{
    atmo_cl cl;
    cl_int err;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, p, extra);
    cl_mem scene = clCreateBuffer(cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p->gpu, (void *)&p->gpu, &err);
    CHECK(err == CL_SUCCESS);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(&cl, prog, scene, p, luts);
    cl_mem bi = test_cl_buffer(&cl, in_size * (size_t)n, in);
    cl_mem bo = test_cl_buffer(&cl, out_size * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(prog, name, &err);
    CHECK(err == CL_SUCCESS);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint nn = (cl_uint)n;
    clSetKernelArg(k, a++, sizeof bi, &bi);
    clSetKernelArg(k, a++, sizeof bo, &bo);
    clSetKernelArg(k, a++, sizeof nn, &nn);
    test_cl_run_1d(&cl, k, (size_t)n);
    test_cl_read(&cl, bo, out_size * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(bo);
    clReleaseMemObject(bi);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
}

test_image test_render(const atmo_scene *s, int tile, int max_batch)
{
    atmo_plan p;
    test_image im = {s->image.width, s->image.height, 0, NULL, NULL};
    size_t n3 = (size_t)im.w * im.h * 3;
    test_plan(s, &p);
    im.mean = malloc(n3 * sizeof(float));
    im.se = malloc(n3 * sizeof(float));
    int *samples = malloc(n3 / 3 * sizeof(int));
    if (!im.mean || !im.se || !samples) {
        fprintf(stderr, "out of memory for a %d x %d image\n", im.w, im.h);
        exit(1);
    }
    if (test_render_plan(&p, tile, max_batch, im.mean, im.se, samples))
        exit(1);
    im.n = samples[0];
    free(samples);
    atmo_plan_free(&p);
    return im;
}

void test_render_whole(const atmo_plan *p, const atmo_render_settings *rs, atmo_render_result *r)
{
    atmo_render_settings defaults;
    atmo_err e;
    if (!rs) {
        atmo_render_settings_default(&defaults);
        rs = &defaults;
    }
    if (atmo_render(p, rs, r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    CHECK(r->nonfinite == 0);
}

int test_render_plan(const atmo_plan *p, int tile, int max_batch, float *mean, float *se,
                     int *samples)
{
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    if (tile > 0)
        rs.tile_size = tile;
    rs.max_batch = max_batch;
    atmo_session *session = NULL;
    atmo_err e;
    atmo_step step = {0};
    atmo_step_status st;
    int rc = 0;
    if (atmo_session_open(&session, p, &rs, &e) || atmo_session_step(session, &step, &st, &e) ||
        atmo_session_read(session, mean, se, samples, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        rc = 1;
    } else {
        CHECK(st.complete && atmo_session_get_info(session)->nonfinite == 0);
    }
    atmo_session_close(session);
    return rc;
}

void test_image_free(test_image *im)
{
    free(im->mean);
    free(im->se);
}

int test_image_agree(const char *label, const char *name_a, const test_image *a,
                     const char *name_b, const test_image *b, double z_bound, double *z_max)
{
    int n = a->w * a->h, bad = 0;
    *z_max = 0.0;
    for (int c = 0; c < 3; c++) {
        double sa = 0.0, sb = 0.0, va = 0.0, vb = 0.0;
        for (int i = 0; i < n; i++) {
            int j = 3 * i + c;
            double var = (double)a->se[j] * a->se[j] + (double)b->se[j] * b->se[j];
            double z = var > 0.0 ? (b->mean[j] - a->mean[j]) / sqrt(var) : 0.0;
            *z_max = fmax(*z_max, fabs(z));
            bad += fabs(z) >= z_bound || var <= 0.0;
            sa += a->mean[j], sb += b->mean[j];
            va += (double)a->se[j] * a->se[j], vb += (double)b->se[j] * b->se[j];
        }
        double z = (sb - sa) / sqrt(va + vb);
        printf("%s channel %d: %s %.5f (se %.2g), %s %.5f (se %.2g), %+.2f %%, z = %+.2f\n",
               label, c, name_a, sa / n, sqrt(va) / n, name_b, sb / n, sqrt(vb) / n,
               100 * (sb / sa - 1), z);
        CHECK(fabs(z) < z_bound);
        CHECK(va > 0.0 && vb > 0.0);
    }
    return bad;
}

int test_reference_sky(test_sky_row *rows, int max)
{
    const char *dir = getenv("ATMO_SOURCE_DIR");
    char path[4096], line[1024];
    snprintf(path, sizeof path, "%s/tests/data/reference_sky.csv", dir ? dir : "..");
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "cannot open %s (set ATMO_SOURCE_DIR to the source tree)\n", path);
        exit(1);
    }
    int n = 0;
    while (fgets(line, sizeof line, f) && n < max) {
        test_sky_row *r = &rows[n];
        double samples;
        if (line[0] == '#' || strncmp(line, "sun_zenith", 10) == 0)
            continue;
        if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &r->sun_zenith,
                   &r->view_zenith, &r->view_azimuth, &samples, &r->L[0], &r->L[1], &r->L[2],
                   &r->se[0], &r->se[1], &r->se[2]) == 10)
            n++;
    }
    fclose(f);
    return n;
}

void test_scene_flat_cloud_view(atmo_scene *s)
{
    static const char *const keys[] = {
        "clouds.enabled=true",          "clouds.bottom_m=1000",
        "clouds.top_m=2000",            "clouds.fade_m=300",
        "clouds.coverage=1",            "clouds.frequency_per_m=1e-8,1e-8,1e-8",
        "clouds.coverage_scale_m=1e8",  "clouds.extinction_per_m=0.002",
        "clouds.albedo=0.95",           "clouds.phase=hg",
        "camera.position_m=0,3000,0",   "camera.pitch_deg=-50",
        "camera.fov_deg=20",            "sun.zenith_deg=30",
    };
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        test_scene_set(s, keys[i]);
}
