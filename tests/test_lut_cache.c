/* test_lut_cache — precomputed buffers stored in and loaded from the disk cache, each feature's
 * under a key of exactly its own inputs (host/render/precompute.c).
 * labels: kernel unit
 *
 * Oracles: recomputation, and the definition of the key.
 *  1. A plan whose buffers are cached (cache_luts = 2: store whatever the precompute time) is
 *     precomputed twice: the second run must be a cache hit and give buffers bitwise equal to
 *     the first; a change of a scene value the transmittance LUT depends on (the Rayleigh
 *     coefficient) must miss; a change of camera and sun must hit. Method fast's sky-view LUT
 *     follows the view: after a hit made with another sun it is recomputed, equal to a
 *     precompute without the cache.
 *  2. Method lut at reduced table sizes: a plan that differs only in render.view_steps loads
 *     the lut tables from the cache, bitwise equal to a fresh precompute.
 *  3. atmo_product_key of the lut feature, with the embedded sources copied and edited: a
 *     change of sky.cl's text (a fragment its passes do not compile from) keeps the key; a
 *     change of lut_precompute.cl or of atmosphere.h (through the transmittance LUT it needs)
 *     changes it, and so does another device name, vendor or driver version.
 *  4. A damaged cache file (one payload byte flipped; the file cut short) is detected, the
 *     tables are recomputed bitwise equal to the originals and the file is rewritten, so the
 *     next precompute loads it again.
 * ctest gives the test its own cache directory. */
#include <stdlib.h>
#include <string.h>
#include "atmo/embedded.h"
#include "atmo/features.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

static int precompute_info(atmo_cl *cl, cl_program prog, const atmo_plan *plan,
                           const char *buffer, float **out, atmo_precompute_info *info)
{
    cl_mem scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    atmo_err e;
    if (atmo_precompute(cl, prog, plan, scene, luts, info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
    int i = atmo_plan_buffer_index(plan, buffer);
    CHECK(i >= 0);
    *out = malloc(plan->buffers[i].bytes);
    test_cl_read(cl, luts[i], plan->buffers[i].bytes, *out);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    return info->cache_hit;
}

static int precompute(atmo_cl *cl, cl_program prog, const atmo_plan *plan, const char *buffer,
                      float **out)
{
    atmo_precompute_info info;
    return precompute_info(cl, prog, plan, buffer, out, &info);
}

static size_t buffer_bytes(atmo_plan *p, const char *name)
{
    return atmo_plan_buffer_find(p, name)->bytes;
}

/* Part 1: the transmittance LUT of method single and the sky-view LUT of method fast. */
static void test_keys_and_views(atmo_cl *cl)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_scene_set(&scene, "atmosphere.method=single");
    test_scene_set(&scene, "render.transmittance_width=64");
    test_scene_set(&scene, "render.transmittance_height=64");
    test_plan(&scene, &plan);
    plan.cache_luts = 2;
    cl_program prog = test_plan_program(cl, &plan, NULL);
    const char *T = "transmittance_lut";

    float *a, *b, *c;
    int first = precompute(cl, prog, &plan, T, &a);
    int second = precompute(cl, prog, &plan, T, &b);
    CHECK(!first && second);
    CHECK(memcmp(a, b, buffer_bytes(&plan, T)) == 0);

    test_scene_set(&scene, "atmosphere.rayleigh_coefficient=1.3e-6");
    atmo_plan other;
    test_plan(&scene, &other);
    other.cache_luts = 2;
    CHECK(precompute(cl, prog, &other, T, &c) == 0);
    CHECK(memcmp(a, c, buffer_bytes(&plan, T)) != 0);

    /* a view-independent product serves another camera and sun */
    test_scene_set(&scene, "atmosphere.rayleigh_coefficient=1.24062e-6");
    test_scene_set(&scene, "sun.zenith_deg=70");
    test_scene_set(&scene, "camera.yaw_deg=33");
    atmo_plan moved;
    test_plan(&scene, &moved);
    moved.cache_luts = 2;
    float *m;
    CHECK(precompute(cl, prog, &moved, T, &m) == 1);
    free(m);

    /* "fast": its sky-view LUT holds one camera and sun; after a cache hit made with another
     * sun it must be recomputed, equal to a precompute without the cache */
    test_scene_set(&scene, "atmosphere.method=fast");
    atmo_plan f1, f2;
    test_plan(&scene, &f1);
    f1.cache_luts = 2;
    cl_program fprog = test_plan_program(cl, &f1, NULL);
    const char *V = "sky_view_lut";
    float *f_first, *f_hit, *f_fresh;
    CHECK(precompute(cl, fprog, &f1, V, &f_first) == 0);
    test_scene_set(&scene, "sun.zenith_deg=40");
    test_plan(&scene, &f2);
    f2.cache_luts = 2;
    CHECK(precompute(cl, fprog, &f2, V, &f_hit) == 1);
    f2.cache_luts = 0;
    CHECK(precompute(cl, fprog, &f2, V, &f_fresh) == 0);
    CHECK(memcmp(f_hit, f_fresh, buffer_bytes(&f2, V)) == 0);
    CHECK(memcmp(f_hit, f_first, buffer_bytes(&f2, V)) != 0);
    free(f_first);
    free(f_hit);
    free(f_fresh);
    clReleaseProgram(fprog);

    plan.cache_luts = 0; /* off: never a hit */
    float *d;
    CHECK(precompute(cl, prog, &plan, T, &d) == 0);
    free(a);
    free(b);
    free(c);
    free(d);
    clReleaseProgram(prog);
}

/* A copy of the embedded kernel table with one file's text replaced (the caller frees). */
static struct atmo_embedded_file *edited_sources(const char *name, const char *text)
{
    int n = 0;
    while (atmo_kernel_sources[n].name)
        n++;
    struct atmo_embedded_file *t = malloc(sizeof *t * (size_t)(n + 1));
    memcpy(t, atmo_kernel_sources, sizeof *t * (size_t)(n + 1));
    int found = 0;
    for (int i = 0; i < n; i++)
        if (strcmp(t[i].name, name) == 0) {
            t[i].text = text, t[i].size = strlen(text);
            found = 1;
        }
    CHECK(found);
    return t;
}

static int feature_of(const atmo_plan *p, const char *name)
{
    for (int i = 0; i < p->feature_count; i++)
        if (strcmp(p->features[i]->name, name) == 0)
            return i;
    return -1;
}

/* Part 3: the key of the lut feature covers its own sources, the transmittance LUT's and the
 * device; not another fragment. */
static void test_key_inputs(const atmo_cl *cl, const atmo_plan *plan)
{
    int f = feature_of(plan, "lut");
    CHECK(f >= 0);
    atmo_device_identity dev = {cl->device_name, cl->device_vendor, cl->driver_version};
    unsigned long long key = atmo_product_key(plan, f, &dev, atmo_kernel_sources);
    CHECK(key == atmo_product_key(plan, f, &dev, atmo_kernel_sources));

    static const char *const edits[] = {"kernels/render/sky.cl",
                                        "kernels/atmosphere/lut_precompute.cl",
                                        "kernels/atmosphere/atmosphere.h"};
    unsigned long long got[3];
    for (int i = 0; i < 3; i++) {
        const struct atmo_embedded_file *orig = atmo_embedded_find(atmo_kernel_sources, edits[i]);
        char *text = malloc(orig->size + 32);
        memcpy(text, orig->text, orig->size);
        strcpy(text + orig->size, "\n/* edited */\n");
        struct atmo_embedded_file *t = edited_sources(edits[i], text);
        got[i] = atmo_product_key(plan, f, &dev, t);
        free(t);
        free(text);
    }
    CHECK(got[0] == key); /* sky.cl: not a source of lut's passes */
    CHECK(got[1] != key);
    CHECK(got[2] != key); /* through the transmittance LUT the passes read */

    atmo_device_identity other_name = {"another device", cl->device_vendor, cl->driver_version};
    atmo_device_identity other_vendor = {cl->device_name, "another vendor", cl->driver_version};
    atmo_device_identity other_driver = {cl->device_name, cl->device_vendor, "9.9-other"};
    CHECK(atmo_product_key(plan, f, &other_name, atmo_kernel_sources) != key);
    CHECK(atmo_product_key(plan, f, &other_vendor, atmo_kernel_sources) != key);
    CHECK(atmo_product_key(plan, f, &other_driver, atmo_kernel_sources) != key);
    printf("lut key %016llx: sky.cl edit keeps it, lut_precompute.cl / atmosphere.h edits and "
           "another device name, vendor or driver change it\n",
           key);
}

/* Flip the byte from_end bytes before the end, or (keep > 0) cut the file to keep bytes. */
static void damage(const char *path, long from_end, long keep)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f)
        return;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *data = malloc((size_t)n);
    CHECK(fread(data, 1, (size_t)n, f) == (size_t)n);
    fclose(f);
    if (keep == 0)
        data[n - from_end] ^= 0x5a;
    f = fopen(path, "wb");
    fwrite(data, 1, (size_t)(keep > 0 ? keep : n), f);
    fclose(f);
    free(data);
}

/* Parts 2 and 4: method lut's tables across view_steps, and damaged files. */
static void test_lut_tables(atmo_cl *cl)
{
    atmo_plan plan, steps;
    test_sky_plan("lut", 0.0, 30.0, &plan);
    cl_program prog = test_plan_program(cl, &plan, NULL);
    const char *S = "scattering_rayleigh";
    size_t bytes = buffer_bytes(&plan, S);
    float *first, *fresh, *hit;
    atmo_precompute_info info;
    precompute_info(cl, prog, &plan, S, &first, &info);
    CHECK(info.loaded == 0 && info.computed == 2); /* transmittance and lut */

    test_sky_plan("lut", 0.0, 30.0, &steps);
    steps.gpu.view_steps = 2 * plan.gpu.view_steps; /* what render.view_steps sets */
    CHECK(precompute_info(cl, prog, &steps, S, &hit, &info) == 1);
    CHECK(info.loaded == 2 && info.computed == 0);
    steps.cache_luts = 0;
    precompute_info(cl, prog, &steps, S, &fresh, &info);
    CHECK(memcmp(hit, fresh, bytes) == 0 && memcmp(hit, first, bytes) == 0);
    printf("lut tables: view_steps %d -> %d loads them from the cache, bitwise equal\n",
           plan.gpu.view_steps, steps.gpu.view_steps);
    free(hit);
    free(fresh);

    test_key_inputs(cl, &plan);

    char dir[1024], path[1200];
    CHECK(atmo_cache_dir(dir, sizeof dir) == 0);
    atmo_device_identity dev = {cl->device_name, cl->device_vendor, cl->driver_version};
    snprintf(path, sizeof path, "%s/lut-%016llx.bin", dir,
             atmo_product_key(&plan, feature_of(&plan, "lut"), &dev, atmo_kernel_sources));
    for (int kind = 0; kind < 2; kind++) {
        if (kind == 0)
            damage(path, 100, 0); /* a payload byte near the end */
        else
            damage(path, 0, 40);  /* cut inside the header's sizes */
        float *again;
        precompute_info(cl, prog, &plan, S, &again, &info);
        CHECK(info.damaged == 1 && info.loaded == 1 && info.computed == 1 && !info.cache_hit);
        CHECK(memcmp(again, first, bytes) == 0);
        free(again);
        precompute_info(cl, prog, &plan, S, &again, &info); /* rewritten: loads again */
        CHECK(info.damaged == 0 && info.cache_hit && memcmp(again, first, bytes) == 0);
        free(again);
    }
    printf("damaged lut cache files (flipped byte, truncated) detected, recomputed and "
           "rewritten\n");
    free(first);
    clReleaseProgram(prog);
}

int main(void)
{
    test_fresh_cache_dir(); /* hits and misses below assume an empty cache */
    atmo_cl cl;
    test_cl_open(&cl);
    test_keys_and_views(&cl);
    test_lut_tables(&cl);
    atmo_cl_close(&cl);
    return test_finish();
}
