/* test_terrain_half — the half-float heightmap (terrain.heightmap_format=half;
 * kernels/terrain/terrain_half.h, heightmap.cl, terrain.h's lookups).
 * labels: kernel
 *
 * Oracles:
 *  1. The host conversions against IEEE 754 binary16 itself: every one of the 65536 bit
 *     patterns converts to a float and back to the same bits (NaNs to a NaN), and the finite
 *     ones are increasing in order (so a value's neighbours are the patterns +-1).
 *  2. Round to nearest, ties to even: for 200000 random floats over the half's range (normal
 *     and subnormal, both signs) the rounded half is no farther from the float than either
 *     neighbouring half, and at every exact midpoint between two neighbours (exact in float)
 *     the result is the one with an even fraction; beyond 65520 it is infinity.
 *  3. The device: the heightmap pass in the half format writes bitwise the host rounding of the
 *     float format's texels (vstore_half rounds to nearest even; the same kernel computes the
 *     height in both).
 *  4. The lookups: terrain_height_at over the half heightmap against the float heightmap at 2000
 *     points: the half's rounding, at most 2^-11 of the largest of the four texels (plus 2^-25
 *     for subnormals), carried through bilinear weights that sum to 1, plus the float rounding
 *     of two lookups 4 2^-24 H; the gradient (central differences one texel apart) within twice
 *     that over the 2 texels between the differences. The half's and the float's RMS error
 *     against the double field are printed (atmo bench terrain charts them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"
#include "testlib.h"
#include "testscene.h"

#define MAP 128
#define EXTENT 16384.0

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

static void half_plan(const char *format, atmo_plan *p)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, "terrain.seed=46");
    snprintf(buf, sizeof buf, "terrain.heightmap_size=%d", MAP);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "terrain.heightmap_extent_m=%g", EXTENT);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "terrain.heightmap_format=%s", format);
    test_scene_set(&s, buf);
    test_plan(&s, p);
}

static int is_nan_half(unsigned h)
{
    return (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu);
}

/* the heightmap pass's buffer of plan p */
static void *run_pass(atmo_cl *cl, atmo_plan *p, size_t bytes)
{
    cl_program prog = test_plan_program(cl, p, "");
    cl_int err;
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p->gpu, &p->gpu, &err);
    CHECK(err == CL_SUCCESS);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, p, luts);
    void *map = malloc(bytes);
    test_cl_read(cl, test_plan_buffer(p, luts, "heightmap"), bytes, map);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    return map;
}

int main(void)
{
    /* 1: every pattern round-trips, the finite ones in order */
    for (unsigned h = 0; h < 65536u; h++) {
        float x = terrain_half_to_float((unsigned short)h);
        unsigned back = terrain_half_from_float(x);
        if (is_nan_half(h)) {
            CHECK(isnan(x) && is_nan_half(back));
            continue;
        }
        CHECK(back == h);
    }
    /* increasing order: positive patterns 0x0000..0x7c00, negative mirror them */
    for (unsigned h = 1; h <= 0x7c00u; h++) {
        CHECK(terrain_half_to_float((unsigned short)h) > terrain_half_to_float((unsigned short)(h - 1)));
        CHECK(terrain_half_to_float((unsigned short)(h | 0x8000u)) ==
              -terrain_half_to_float((unsigned short)h));
    }
    CHECK(terrain_half_to_float(0x3c00u) == 1.0f && terrain_half_to_float(0x7bffu) == 65504.0f &&
          terrain_half_to_float(0x0001u) == ldexpf(1.0f, -24));

    /* 2: nearest, ties to even */
    unsigned rng = 99u;
    int ties = 0;
    for (int k = 0; k < 200000; k++) {
        float x = (float)(ldexp(1.0, -26 + (int)(43 * urand(&rng))) * (1 + urand(&rng)));
        if (x >= 65520.0f) {
            CHECK(terrain_half_from_float(x) == 0x7c00u);
            continue;
        }
        if (k & 1)
            x = -x;
        unsigned r = terrain_half_from_float(x), mag = r & 0x7fffu, sign = r & 0x8000u;
        double got = terrain_half_to_float((unsigned short)r), err = fabs((double)x - got);
        if (mag > 0)
            CHECK(err <= fabs((double)x - terrain_half_to_float((unsigned short)(sign | (mag - 1)))));
        CHECK(err <= fabs((double)x - terrain_half_to_float((unsigned short)(sign | (mag + 1)))));
        /* the midpoint between r and its upper neighbour, exact in float */
        if (mag < 0x7bffu) {
            double up = terrain_half_to_float((unsigned short)(mag + 1));
            float mid = (float)(0.5 * (fabs(got) + up));
            CHECK((double)mid == 0.5 * (fabs(got) + up));
            unsigned t = terrain_half_from_float(mid);
            CHECK(t == ((mag & 1u) ? mag + 1 : mag));
            ties++;
        }
    }
    printf("binary16: 65536 patterns round-trip; 200000 roundings nearest, %d midpoints to even\n",
           ties);

    /* 3 and 4: the heightmap pass and the lookups */
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    atmo_plan pf, ph;
    half_plan("float", &pf);
    half_plan("half", &ph);
    float *mf = run_pass(&cl, &pf, sizeof(float) * MAP * MAP);
    unsigned short *mh = run_pass(&cl, &ph, sizeof(unsigned short) * MAP * MAP);
    int same = 0;
    for (int k = 0; k < MAP * MAP; k++)
        same += mh[k] == terrain_half_from_float(mf[k]);
    printf("half heightmap %dx%d: %d of %d texels bitwise the host rounding of the float "
           "format's\n", MAP, MAP, same, MAP * MAP);
    CHECK(same == MAP * MAP);
    const atmo_gpu_terrain_field *ff = &pf.gpu.terrain.field, *fh = &ph.gpu.terrain.field;
    double texel = EXTENT / MAP, H = (double)ff->max_height_m, worst = 0, worst_g = 0;
    double rms_f = 0, rms_h = 0;
    int n = 2000;
    for (int k = 0; k < n; k++) {
        float u = (float)((urand(&rng) - 0.5) * (EXTENT - 4 * texel));
        float v = (float)((urand(&rng) - 0.5) * (EXTENT - 4 * texel));
        terrain_height a = terrain_height_at(ff, mf, u, v), b = terrain_height_at(fh, (const float *)mh, u, v);
        float gx = 0.0f, gy = 0.0f;
        CHECK(terrain_in_heightmap(ff, u, v, &gx, &gy));
        double top = 0;
        for (int dj = -1; dj <= 2; dj++) /* the texels the height and its differences read */
            for (int di = -1; di <= 2; di++) {
                int i = (int)floorf(gx) + di, j = (int)floorf(gy) + dj;
                top = fmax(top, fabs(mf[j * MAP + i]));
            }
        double bound = ldexp(top, -11) + ldexp(1.0, -25) + 4 * ldexp(H, -24);
        worst = fmax(worst, fabs(a.h - b.h) / bound);
        worst_g = fmax(worst_g, fmax(fabs(a.du - b.du), fabs(a.dv - b.dv)) / (2 * bound / texel));
        CHECK(fabs(a.h - b.h) <= bound);
        CHECK(fabs(a.du - b.du) <= 2 * bound / texel && fabs(a.dv - b.dv) <= 2 * bound / texel);
        double truth = terrain_ref_height(ff, u, v, NULL, NULL);
        rms_f += (a.h - truth) * (a.h - truth) / n, rms_h += (b.h - truth) * (b.h - truth) / n;
    }
    printf("half lookups vs float: height worst %.3f, gradient worst %.3f of the bound; RMS "
           "error against the double field over %.0f m texels: float %.3f m, half %.3f m\n",
           worst, worst_g, texel, sqrt(rms_f), sqrt(rms_h));
    free(mf);
    free(mh);
    atmo_plan_free(&pf);
    atmo_plan_free(&ph);
    atmo_cl_close(&cl);
    return test_finish();
}
