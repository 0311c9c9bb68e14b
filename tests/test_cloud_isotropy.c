/* test_cloud_isotropy — the cloud noise's contours (kernels/clouds/cloud_noise.h's turned fBm)
 * have no preferred direction at the lattice's axes.
 * labels: unit stat
 *
 * Oracle: for a statistically isotropic field the normals of a level set, weighted by area, are
 * uniform on the sphere; random lines of uniform direction through uniform points cross a
 * surface element at a rate proportional to its area times |cos| of its normal with the line,
 * which averaged over the directions is the same for every normal (Crofton's formula), so the
 * normals at the crossings of such lines are area-weighted. The share of uniform directions
 * within an angle a of one of the axes +-x, +-y, +-z is p0 = 3 (1 - cos a) (0.0114 for 5
 * degrees, 0.0456 for 10); the count of normals within those cones among N crossings is
 * binomial(N, p0) if the contours have no preference for the axes, and the test takes its
 * z-score
 *     z = (count - N p0) / sqrt(N p0 (1 - p0)).
 * Field: the 6-octave fBm of the cloud layer's shape at the level 0.3 (the low tail where the
 * layer's cloud lies: fbm < coverage x fade <= 0.3) and at its median 0.5, in lattice units of
 * the first octave (the layer's per-axis frequencies are a diagonal map, which sends the
 * lattice's axes to the world's). Crossings: 40000 lines (10000 at the median, whose level
 * set is larger) of length 4 cells from uniform points of [-8, 8]^3, sampled every 1/128
 * cell, each crossing found by bisection; the normal is the gradient by central differences
 * 1/1024 cell wide (a thirtieth of the finest octave's cell), divided by the float
 * coordinates' actual spacing.
 * Bound: z < Z_MAX = 4 for the turned fBm, at both levels and both cones (5 and 10 degrees).
 * Crossings along one line are not independent (one contour can cross a line twice), which
 * widens the count's spread beyond the binomial's; the bound leaves room for that. The test
 * has power: the same statistic on the unturned fBm (the same octaves without the octave
 * rotation, the lattice's planes along the world's axes) must exceed Z_MAX. Printed too: the
 * share of normals near the first octave's turned axes (the rows of R), where its own planes
 * lie. Measured (z at 5 and 10 degrees): the turned fBm -1.5 and -2.6 at the level 0.3, -1.6
 * and -3.0 at 0.5 (slightly fewer normals near the world's axes than uniform), +0.7 and +0.6,
 * +2.0 and +1.2 near its turned axes; the unturned fBm +5.9 and +14.1, +8.1 and +14.0. */
#include <math.h>
#include <stdio.h>
#include "common/compat.h"
#include "common/rng.h"
#include "clouds/cloud_noise.h"
#include "testlib.h"

#define OCTAVES 6
#define SEED 11u
#define RAY_CELLS 4.0
#define MARCH_STEP (1.0 / 128.0)
#define GRADIENT_STEP (1.0 / 1024.0)
#define Z_MAX 4.0

typedef float (*field_fn)(vec3 p);

static float turned(vec3 p) { return noise_fbm(p, OCTAVES, SEED); }

/* The same octaves, weights and lattice offsets without the octave rotation. */
static float unturned(vec3 p)
{
    float sum = 0.0f, norm = 0.0f, amp = 1.0f;
    for (int i = 0; i < OCTAVES; i++) {
        sum += amp * noise_value(noise_octave_point(p, i), SEED + (uint)i);
        norm += amp;
        amp *= 0.5f;
        p = v3_scale(p, 2.0f);
    }
    return sum / norm;
}

static float field_at(field_fn f, const double p[3])
{
    return f(v3((float)p[0], (float)p[1], (float)p[2]));
}

/* The gradient at p by central differences over the float coordinates' actual spacing. */
static void gradient(field_fn f, const double p[3], double g[3])
{
    for (int k = 0; k < 3; k++) {
        double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]};
        a[k] = (float)(p[k] + GRADIENT_STEP);
        b[k] = (float)(p[k] - GRADIENT_STEP);
        g[k] = ((double)field_at(f, a) - field_at(f, b)) / (a[k] - b[k]);
    }
}

static const double cone_deg[2] = {5.0, 10.0};

typedef struct tally {
    long n, near_axes[2], near_turned[2]; /* per cone of cone_deg */
} tally;

/* The normals at the crossings of the level along `rays` random lines. */
static tally crossings(field_fn f, double level, uint rays)
{
    double turned_axes[3][3] = {{9, 24, 32}, {24, 23, -24}, {-32, 24, -9}}; /* 41 R */
    tally t = {0, {0, 0}, {0, 0}};
    int steps = (int)(RAY_CELLS / MARCH_STEP);
    for (uint r = 0; r < rays; r++) {
        double o[3], d[3], z = 2.0 * rng_uniform(3u, r, 0u, 3u) - 1.0;
        double phi = 2.0 * M_PI * rng_uniform(3u, r, 0u, 4u), s = sqrt(1.0 - z * z);
        for (int k = 0; k < 3; k++)
            o[k] = 16.0 * rng_uniform(3u, r, 0u, (uint)k) - 8.0;
        d[0] = s * cos(phi), d[1] = s * sin(phi), d[2] = z;
        double p[3], prev = 0.0;
        for (int i = 0; i <= steps; i++) {
            double tt = i * MARCH_STEP;
            for (int k = 0; k < 3; k++)
                p[k] = o[k] + tt * d[k];
            double v = field_at(f, p) - level;
            if (i > 0 && (v < 0.0) != (prev < 0.0)) {
                double lo = tt - MARCH_STEP, hi = tt, q[3], g[3];
                for (int b = 0; b < 40; b++) {
                    double mid = 0.5 * (lo + hi);
                    for (int k = 0; k < 3; k++)
                        q[k] = o[k] + mid * d[k];
                    double w = field_at(f, q) - level;
                    if ((w < 0.0) == (prev < 0.0))
                        lo = mid;
                    else
                        hi = mid;
                }
                gradient(f, q, g);
                double l = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                if (l > 0.0) {
                    t.n++;
                    double m = fmax(fabs(g[0]), fmax(fabs(g[1]), fabs(g[2]))) / l;
                    double mt = 0.0;
                    for (int a = 0; a < 3; a++) {
                        double e = turned_axes[a][0] * g[0] + turned_axes[a][1] * g[1] +
                                   turned_axes[a][2] * g[2];
                        mt = fmax(mt, fabs(e) / (41.0 * l));
                    }
                    for (int c = 0; c < 2; c++) {
                        double cc = cos(cone_deg[c] * M_PI / 180.0);
                        t.near_axes[c] += m >= cc;
                        t.near_turned[c] += mt >= cc;
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

int main(void)
{
    double levels[2] = {0.3, 0.5};
    uint rays[2] = {40000u, 10000u};
    for (int l = 0; l < 2; l++) {
        tally a = crossings(turned, levels[l], rays[l]);
        tally b = crossings(unturned, levels[l], rays[l]);
        printf("level %.1f: turned fBm %ld normals, unturned %ld\n", levels[l], a.n, b.n);
        for (int c = 0; c < 2; c++) {
            double p0 = 3.0 * (1.0 - cos(cone_deg[c] * M_PI / 180.0));
            double za = z_score(a.near_axes[c], a.n, p0), zb = z_score(b.near_axes[c], b.n, p0);
            printf("  within %.0f deg of the axes (uniform: %.4f): turned %.4f (z %+.2f), "
                   "unturned %.4f (z %+.2f); of the first octave's turned axes: turned %.4f "
                   "(z %+.2f)\n",
                   cone_deg[c], p0, (double)a.near_axes[c] / a.n, za,
                   (double)b.near_axes[c] / b.n, zb, (double)a.near_turned[c] / a.n,
                   z_score(a.near_turned[c], a.n, p0));
            CHECK(za < Z_MAX);
            CHECK(zb > Z_MAX);
        }
    }
    return test_finish();
}
