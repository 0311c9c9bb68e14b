/* test_dem_detail_miss_rate — the sphere tracer's miss rate below 1e-4 over a DEM with the
 * fBm's detail below its cells (terrain.heightmap_detail), demonstrated: over 3e4 rays that
 * hit, none may be missed or mistraced.
 * labels: kernel
 *
 * Oracle: the brute-force double-precision march over the same float heightmap plus the double
 * detail (terrain_ref_hit_map), with the classes of error of test_terrain_trace
 * (tests/support_terrain_trace.c); the DEM is test_dem_detail's (thesis-1's terrain at 128 m
 * texels, detail octaves 10..13, periods 32.6..4.1 m). Rays: as test_terrain_miss_rate's,
 * 12000 downward from 300 m above thesis-1's site, 18000 grazing and 15000 skimming, from
 * another seed, at the plan's step budget over the detail (twice terrain.steps: at 300 steps 6
 * of 32356 hits went wrong, every one a ray that had run into the fallback). Statistics: 0 errors in n >= 30000 reference hits bound the rate below
 * 3.0 / n < 1e-4 at 95 % confidence (the chi-square bound of test_terrain_miss_rate). */
#include <stdio.h>
#include "testlib.h"
#include "testterrain.h"

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    int hits = 0, errors = test_trace_dem_run(&cl, 12000, 18000, 15000, 20261202u, &hits);
    CHECK(hits >= 30000);
    CHECK(errors == 0);
    atmo_cl_close(&cl);
    return test_finish();
}
