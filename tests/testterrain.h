/* testterrain.h — shared by the sphere-tracing tests (tests/support_terrain_trace.c): rays over
 * thesis-1's site, the device probe that traces them, and their judgement against the
 * brute-force double march (terrain_ref_hit). */
#ifndef ATMO_TESTTERRAIN_H
#define ATMO_TESTTERRAIN_H
#include "atmo/plan.h"
#include "atmo/scene.h"
#include "testcl.h"

#define TEST_TRACE_SITE_X 23796.0
#define TEST_TRACE_SITE_Z 16636.0
#define TEST_TRACE_REF_STEP_M 2.0
#define TEST_TRACE_DEM_MAP 512
#define TEST_TRACE_DEM_EXTENT_M 65536.0

typedef struct test_trace_ray {
    double o[3], d[3]; /* camera-relative origin (float-rounded) and unit direction */
    double t_max;
} test_trace_ray;

typedef struct test_trace_setup {
    atmo_scene scene;
    atmo_plan plan;
    double cam[3];
    const float *heightmap; /* the float heightmap the reference reads (NULL: procedural) */
} test_trace_setup;

typedef struct test_trace_tally {
    int hits, misses, through, false_hits, bad, ref_hits;
    double worst_clear, mean_steps;
} test_trace_tally;

/* The probe kernel: trace(scene, buffers, origins, directions (w: t_max), out (t or -1, steps
 * used), n). */
extern const char test_trace_probe_src[];
/* The planet's radius of the last test_trace_plan_at. */
extern double test_trace_R_m;

double test_trace_urand(unsigned *state);
/* thesis-1's terrain (seed 46) under a sky-noon scene with the camera at cam (world metres) and
 * up to two more KEY=VALUE settings (may be NULL). */
void test_trace_plan_at(test_trace_setup *u, const double cam[3], const char *extra1,
                        const char *extra2);
/* test_trace_plan_at with a third setting (may be NULL). */
void test_trace_plan_at3(test_trace_setup *u, const double cam[3], const char *extra1,
                         const char *extra2, const char *extra3);
/* test_trace_plan_at3 with the camera 300 m above the surface point of thesis-1's site (along
 * its vertical), in u->cam. */
void test_trace_plan_above_site(test_trace_setup *u, const char *extra1, const char *extra2,
                                const char *extra3);
/* The surface point above planar (x, z) and its vertical, world coordinates (hm: a float
 * heightmap under the field, terrain_ref_height_map, or NULL). */
void test_trace_surface_point(const atmo_gpu_terrain_field *f, const float *hm, double sea,
                              double x, double z, double p[3], double n[3]);
void test_trace_make_ray(test_trace_ray *r, const double cam[3], const double origin_world[3],
                         const double d[3], double t_max);
void test_trace_make_rays(const atmo_gpu_terrain_field *f, const float *hm, const double cam[3],
                          int n_down, int n_graze, int n_skim, unsigned *rng,
                          test_trace_ray *rays);
/* Runs the probe over the rays: out[i] = (t or -1, steps used). */
void test_trace_run(atmo_cl *cl, cl_program prog, const atmo_plan *p, const test_trace_ray *rays,
                    int n, float4 *out);
/* The float rounding bound of the height field and the ray's position at world point w. */
double test_trace_delta_m(const atmo_gpu_terrain_field *f, double L, const double w[3], double t);
void test_trace_world_at(const test_trace_setup *u, const test_trace_ray *r, double t,
                         double w[3]);
/* A DEM with detail (test_dem_detail.c): test_trace_plan_at with a 512-texel heightmap over
 * 65536 m whose base grid (returned, malloc'd) holds its texel centres' heights (plane: 500 +
 * 0.05 u + 0.03 v; else the double fBm rounded to float), and the detail below 128 m cells. */
float *test_trace_dem_plan(test_trace_setup *u, const double cam[3], int plane);
/* Traces n_down + n_graze + n_skim rays (test_trace_make_rays from generator state seed) over
 * that DEM with detail from 300 m above the site on the device and judges them against the
 * double march over the device's float heightmap plus the double detail; prints the tallies
 * and returns the errors, *ref_hits the reference's hits. */
int test_trace_dem_run(atmo_cl *cl, int n_down, int n_graze, int n_skim, unsigned seed,
                       int *ref_hits);
/* Counts the tracer's misses, pass-throughs, false and bad hits against the reference. */
test_trace_tally test_trace_judge(const test_trace_setup *u, const test_trace_ray *rays, int n,
                                  const float4 *out, int verbose);

#endif
