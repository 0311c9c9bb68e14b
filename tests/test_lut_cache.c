/* test_lut_cache — precomputed LUTs stored in and loaded from the disk cache.
 * labels: kernel unit
 *
 * Oracle: recomputation. A plan whose LUTs are cached (cache_luts = 2: store whatever the
 * precompute time) is precomputed twice: the second run must be a cache hit and give LUT
 * buffers bitwise equal to the first; a change of any scene value the LUTs depend on (here the
 * Rayleigh coefficient) must miss, and a change of camera and sun must hit (cached LUTs serve
 * any ray). ctest gives the test its own cache directory. */
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

static float *read_lut(atmo_cl *cl, cl_mem b, size_t bytes)
{
    float *data = malloc(bytes);
    test_cl_read(cl, b, bytes, data);
    return data;
}

static int precompute_lut(atmo_cl *cl, cl_program prog, const atmo_plan *plan, int index,
                          float **out)
{
    cl_mem scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_LUTS] = {NULL};
    atmo_precompute_info info;
    atmo_err e;
    if (atmo_precompute(cl, prog, plan, scene, luts, &info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
    *out = read_lut(cl, luts[index], plan->lut_bytes[index]);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    return info.cache_hit;
}

static int precompute(atmo_cl *cl, cl_program prog, const atmo_plan *plan, float **lut0)
{
    return precompute_lut(cl, prog, plan, 0, lut0);
}

int main(void)
{
    test_fresh_cache_dir(); /* hits and misses below assume an empty cache */
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_scene_set(&scene, "atmosphere.method=single");
    test_scene_set(&scene, "render.transmittance_width=64");
    test_scene_set(&scene, "render.transmittance_height=64");
    test_plan(&scene, &plan);
    plan.cache_luts = 2;
    atmo_cl cl;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, &plan, NULL);

    float *a, *b, *c;
    int first = precompute(&cl, prog, &plan, &a);
    int second = precompute(&cl, prog, &plan, &b);
    CHECK(!first && second);
    CHECK(memcmp(a, b, plan.lut_bytes[0]) == 0);

    test_scene_set(&scene, "atmosphere.rayleigh_coefficient=1.3e-6");
    atmo_plan other;
    test_plan(&scene, &other);
    other.cache_luts = 2;
    CHECK(precompute(&cl, prog, &other, &c) == 0);
    CHECK(memcmp(a, c, plan.lut_bytes[0]) != 0);

    /* a view-independent method's LUTs serve another camera and sun */
    test_scene_set(&scene, "atmosphere.rayleigh_coefficient=1.24062e-6");
    test_scene_set(&scene, "sun.zenith_deg=70");
    test_scene_set(&scene, "camera.yaw_deg=33");
    atmo_plan moved;
    test_plan(&scene, &moved);
    moved.cache_luts = 2;
    float *m;
    CHECK(precompute(&cl, prog, &moved, &m) == 1);
    free(m);

    /* "fast": its sky-view LUT (buffer 2) holds one camera and sun; after a cache hit made with
     * another sun it must be recomputed, equal to a precompute without the cache */
    test_scene_set(&scene, "atmosphere.method=fast");
    atmo_plan f1, f2;
    test_plan(&scene, &f1);
    f1.cache_luts = 2;
    cl_program fprog = test_plan_program(&cl, &f1, NULL);
    float *f_first, *f_hit, *f_fresh;
    CHECK(precompute_lut(&cl, fprog, &f1, 2, &f_first) == 0);
    test_scene_set(&scene, "sun.zenith_deg=40");
    test_plan(&scene, &f2);
    f2.cache_luts = 2;
    CHECK(precompute_lut(&cl, fprog, &f2, 2, &f_hit) == 1);
    f2.cache_luts = 0;
    CHECK(precompute_lut(&cl, fprog, &f2, 2, &f_fresh) == 0);
    CHECK(memcmp(f_hit, f_fresh, f2.lut_bytes[2]) == 0);
    CHECK(memcmp(f_hit, f_first, f2.lut_bytes[2]) != 0);
    free(f_first);
    free(f_hit);
    free(f_fresh);
    clReleaseProgram(fprog);

    plan.cache_luts = 0; /* off: never a hit */
    float *d;
    CHECK(precompute(&cl, prog, &plan, &d) == 0);
    free(a);
    free(b);
    free(c);
    free(d);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
