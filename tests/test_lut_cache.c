/* test_lut_cache — precomputed LUTs stored in and loaded from the disk cache.
 * labels: kernel unit
 *
 * Oracle: recomputation. A plan whose LUTs are cached (cache_luts = 2: store whatever the
 * precompute time) is precomputed twice: the second run must be a cache hit and give LUT
 * buffers bitwise equal to the first; a change of any scene value the LUTs depend on (here the
 * Rayleigh coefficient) must miss, and a change of camera and sun must hit for a method whose
 * LUTs serve any ray. ctest gives the test its own cache directory. */
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

static int precompute(atmo_cl *cl, cl_program prog, const atmo_plan *plan, float **lut0)
{
    cl_mem scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_LUTS] = {NULL};
    atmo_precompute_info info;
    atmo_err e;
    if (atmo_precompute(cl, prog, plan, scene, luts, &info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
    *lut0 = read_lut(cl, luts[0], plan->lut_bytes[0]);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    return info.cache_hit;
}

int main(void)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
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
    CHECK(!moved.luts_follow_view && precompute(&cl, prog, &moved, &m) == 1);
    free(m);

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
