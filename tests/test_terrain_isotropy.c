/* test_terrain_isotropy — the terrain's level sets (snow line, grass line) at the scale seen
 * from orbit have no preferred direction at the world's axes: the domain warp of the height
 * fBm (kernels/terrain/noise.h) bends the first octave's square lattice.
 * labels: unit stat
 *
 * Oracle: for a statistically isotropic planar field the normals of a level set, weighted by
 * length, are uniform on the circle; random lines of uniform direction through uniform points
 * cross a curve element at a rate proportional to its length times |cos| of its normal with the
 * line, which averaged over the directions is the same for every normal (Crofton's formula), so
 * the normals at the crossings of such lines are length-weighted. The share of uniform
 * directions within an angle a of one of the four axis directions +-u, +-v is p0 = 4 a / pi
 * (0.111 for 5 degrees, 0.222 for 10); the count of normals within those cones among N
 * crossings is binomial(N, p0) if the contours have no preference for the axes, and the test
 * takes its z-score
 *     z = (count - N p0) / sqrt(N p0 (1 - p0)).
 * Field: the `space` preset's height field (the double reference, host/terrain/terrain_ref.c,
 * with its exact gradient) with land everywhere (land_fraction 1, so the coverage is 1 and the
 * height is H e) and 4 octaves: from 2000 km a pixel of a 1280-wide image spans 1.5 to 3 km of
 * ground, the fourth octave's cell (33 km / 8 = 4 km) the finest it resolves. Levels: the
 * materials' snow line 2800 m and grass line 850 m (terrain_material.h's bands' middles), in
 * lattice units of the first octave. Crossings: 6000 lines per level of length 8 cells from
 * uniform points of [-300, 300]^2 cells, sampled every 1/32 cell (a quarter of the finest
 * octave's cell), each crossing found by bisection; the normal is the reference's gradient.
 * Bound: |z| < Z_MAX = 4 for the warped field (the preset's default warp), at both levels,
 * both cones and four axis sets: the world's axes and the axes turned by 22.5, 36.87 (the
 * octave rotation, along which the warp's own first lattice lies) and 45 degrees, so a warp
 * that trades the world's lattice for its own, or depletes the axes, fails too. Crossings
 * along one line are not independent (one contour can cross a line twice), which widens the
 * count's spread beyond the binomial's; the bound leaves room for that. The test has power:
 * the same statistic at the world's axes on the unwarped field (terrain.warp=0, the field the
 * thesis views keep) must exceed Z_MAX. Measured (z at 5 and 10 degrees, snow line then grass
 * line, world's axes): unwarped +16.2 +24.1, +21.7 +28.3; warped +1.2 +2.0, +0.7 +1.9, and
 * |z| <= 1.3 at the turned axes; other warps: docs/guide/terrain.md. */
#include <math.h>
#include <stdio.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"

#define LINES 6000
#define LINE_CELLS 8.0
#define MARCH_STEP (1.0 / 32.0)
#define AREA_CELLS 300.0
#define Z_MAX 4.0

static const double cone_deg[2] = {5.0, 10.0};

/* the axis sets the cones sit around: the world's axes, then turned by these angles */
#define TURNS 4
static const double turn_deg[TURNS] = {0.0, 22.5, 36.8699, 45.0};

typedef struct tally {
    long n, near_axes[TURNS][2]; /* per axis set of turn_deg and cone of cone_deg */
} tally;

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

/* height minus level at lattice point (x, y) of the first octave */
static double offset(const atmo_gpu_terrain_field *f, double level, double x, double y,
                     double g[2])
{
    double fr = (double)f->frequency_per_m;
    return terrain_ref_height(f, x / fr, y / fr, g, NULL) - level;
}

/* The normals at the crossings of the level along LINES random lines. */
static tally crossings(const atmo_gpu_terrain_field *f, double level)
{
    tally t = {0, {{0, 0}}};
    unsigned rng = 4242u;
    int steps = (int)(LINE_CELLS / MARCH_STEP);
    for (int r = 0; r < LINES; r++) {
        double ox = (2 * urand(&rng) - 1) * AREA_CELLS, oy = (2 * urand(&rng) - 1) * AREA_CELLS;
        double phi = 2 * M_PI * urand(&rng), dx = cos(phi), dy = sin(phi), prev = 0;
        for (int i = 0; i <= steps; i++) {
            double s = i * MARCH_STEP, v = offset(f, level, ox + s * dx, oy + s * dy, NULL);
            if (i > 0 && (v < 0) != (prev < 0)) {
                double lo = s - MARCH_STEP, hi = s, g[2] = {0, 0};
                for (int b = 0; b < 30; b++) {
                    double mid = 0.5 * (lo + hi);
                    double w = offset(f, level, ox + mid * dx, oy + mid * dy, NULL);
                    if ((w < 0) == (prev < 0))
                        lo = mid;
                    else
                        hi = mid;
                }
                double m = 0.5 * (lo + hi);
                offset(f, level, ox + m * dx, oy + m * dy, g);
                double l = hypot(g[0], g[1]);
                if (l > 0) {
                    t.n++;
                    for (int k = 0; k < TURNS; k++) {
                        double ct = cos(turn_deg[k] * M_PI / 180.0);
                        double st = sin(turn_deg[k] * M_PI / 180.0);
                        double a = ct * g[0] + st * g[1], b = ct * g[1] - st * g[0];
                        double closest = fmax(fabs(a), fabs(b)) / l; /* cos to nearest axis */
                        for (int c = 0; c < 2; c++)
                            t.near_axes[k][c] += closest >= cos(cone_deg[c] * M_PI / 180.0);
                    }
                }
            }
            prev = v;
        }
    }
    return t;
}

static double z_score(long count, long n, double p0)
{
    return (count - n * p0) / sqrt(n * p0 * (1.0 - p0));
}

static tally field_crossings(const char *warp, double level)
{
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "space");
    test_scene_set(&s, "terrain.land_fraction=1");
    test_scene_set(&s, "terrain.octaves=4");
    if (warp)
        test_scene_set(&s, warp);
    test_plan(&s, &p);
    tally t = crossings(&p.gpu.terrain.field, level);
    atmo_plan_free(&p);
    return t;
}

int main(void)
{
    static const double levels_m[2] = {2800.0, 850.0};
    for (int l = 0; l < 2; l++) {
        tally a = field_crossings(NULL, levels_m[l]);
        tally b = field_crossings("terrain.warp=0", levels_m[l]);
        printf("level %.0f m: warped field %ld normals, unwarped %ld\n", levels_m[l], a.n, b.n);
        CHECK(a.n > 1000 && b.n > 1000);
        for (int c = 0; c < 2; c++) {
            double p0 = 4.0 * cone_deg[c] * M_PI / 180.0 / M_PI;
            double zb = z_score(b.near_axes[0][c], b.n, p0);
            printf("  within %.0f deg of the axes (uniform: %.4f): unwarped %.4f (z %+.2f); "
                   "warped",
                   cone_deg[c], p0, (double)b.near_axes[0][c] / b.n, zb);
            for (int k = 0; k < TURNS; k++) {
                double za = z_score(a.near_axes[k][c], a.n, p0);
                printf(" %.1f deg: %.4f (z %+.2f)%s", turn_deg[k], (double)a.near_axes[k][c] / a.n,
                       za, k + 1 < TURNS ? "," : "\n");
                CHECK(fabs(za) < Z_MAX);
            }
            CHECK(zb > Z_MAX);
        }
    }
    return test_finish();
}
