/* test_quadrature_walk — the deterministic methods' one stepping loop
 * (kernels/media/quadrature_walk.h, host build of the shared header): the pieces and parts it
 * hands out along a ray [0, d].
 * labels: unit
 * composes: atmosphere
 *
 * Rays: d = 1.2e5 m on n = 64 segments, and 121 lengths of 100 m to 1e7 m on 16, 40 and 64
 * segments, without parts; d = 3e4 m on n = 16 with the parts
 * (a) inside one grid segment, (b) across several, (c) two in one segment, (d) one from the
 * ray's start, (e) one to its end; jitter 0.37 and QUADRATURE_GRID_MIDDLE.
 * Oracles (exact relations and closed forms, in double):
 *  1. Tiling: the events, in order, cover [0, d] with no gap and no overlap: each starts where
 *     the one before ended, to the few roundings of a start plus a length (4 ulp(d)), and a
 *     piece after a part exactly at the part's end (the walk passes the same float on); the
 *     last event ends at d to the same bound. Every part comes once, whole ([lo, hi] exactly)
 *     and in order; no piece crosses a grid break d (k/n)^2 (double, to 4 ulp(d)). Without
 *     parts there are exactly n pieces, segment i from d (i/n)^2 to d ((i+1)/n)^2.
 *  2. Sample points: a piece's t is start + jitter dt to one rounding (ulp of t); with
 *     QUADRATURE_GRID_MIDDLE segment i's t is d ((i + 1/2) / n)^2 to 4 ulp, the fraction
 *     (i + 1/4) / (2i + 1) of the segment's length from its start (the closed form of the
 *     middle in the grid's parameter) to 1e-4 of the length.
 *  3. Exactness for constant coefficients: with sigma_t = 1.5 / d constant, the pieces'
 *     transmittance (medium_piece_weight) and the parts' e^{-sigma (hi - lo)} leave
 *     T = e^{-sigma d}, and the light of a unit source, sum T w sigma over the pieces plus the
 *     parts' T (1 - e^{-sigma (hi - lo)}), is 1 - e^{-sigma d} (the weights telescope):
 *     relative 1e-5 (float roundings over <= 70 pieces, each ~1e-7).
 *  4. quadrature_grid_next(t, d, n) is the least break d (k/n)^2, k = 1..n, above t (the float
 *     breaks quadrature_grid_segment gives, searched one by one), at 10^4 points t over
 *     [0, d) and at every break itself.
 *  5. Equal segments (quadrature_begin_equal; 49 lengths of 100 m to 1e6 m, 1 to 199
 *     segments): exactly n pieces, piece i from i d/n (2 ulp(d)), d/n long (1 ulp), sampled at
 *     its middle (i + 1/2) d/n (2 ulp). */
#include <math.h>
#include <stdio.h>
#include "testlib.h"
#include "kernels_composed.h"

#define MAX_EVENTS 256

typedef struct event {
    int kind; /* QUADRATURE_PIECE or QUADRATURE_PART */
    float start, end, t, dt;
} event;

/* The events of the walk over [0, d] with n segments, the sample fraction jitter and the parts
 * [lo, hi] (count of them); returns how many. */
static int walk(float d, int n, float jitter, const float *lo, const float *hi, int count,
                event *ev)
{
    quadrature_walk q = quadrature_begin(d, n, jitter);
    for (int k = 0; k < count; k++)
        q.lo[k] = lo[k], q.hi[k] = hi[k];
    q.parts = count;
    int m = 0;
    for (int e; (e = quadrature_next(&q)) != QUADRATURE_END && m < MAX_EVENTS; m++) {
        ev[m].kind = e;
        ev[m].start = q.start;
        ev[m].end = e == QUADRATURE_PART ? q.end : q.start + q.dt;
        ev[m].t = q.t;
        ev[m].dt = q.dt;
    }
    return m;
}

static double ulp(double x)
{
    return fabs(x) * 1.1920928955078125e-7 + 1e-30;
}

/* Oracles 1 to 3 on one ray; returns the number of pieces. */
static int check_ray(const char *name, float d, int n, float jitter, const float *lo,
                     const float *hi, int count)
{
    event ev[MAX_EVENTS];
    int m = walk(d, n, jitter, lo, hi, count, ev), pieces = 0, part = 0;
    const float sigma = 1.5f / d; /* 1/m: optical depth 1.5 over the ray */
    vec3 T = v3(1.0f, 1.0f, 1.0f);
    double light = 0.0, tol = 4.0 * ulp(d);
    CHECK(m < MAX_EVENTS);
    for (int k = 0; k < m; k++) {
        const event *e = &ev[k];
        double prev_end = k > 0 ? (double)ev[k - 1].end : 0.0;
        CHECK_ABS(e->start, prev_end, tol);
        if (k > 0 && ev[k - 1].kind == QUADRATURE_PART)
            CHECK(e->start == ev[k - 1].end);
        if (e->kind == QUADRATURE_PART) {
            CHECK(part < count && e->start == lo[part] && e->end == hi[part]);
            double x = (double)sigma * ((double)e->end - e->start);
            light += T.y * -expm1(-x);
            T = v3_scale(T, (float)exp(-x));
            part++;
            continue;
        }
        pieces++;
        /* no piece crosses a grid break */
        for (int i = 1; i < n; i++) {
            double g = (double)d * ((double)i / n) * ((double)i / n);
            CHECK(!(e->start < g - tol && e->end > g + tol));
        }
        if (jitter == QUADRATURE_GRID_MIDDLE) {
            int i = k; /* without parts, event k is segment k */
            double want = (double)d * ((i + 0.5) / n) * ((i + 0.5) / n);
            CHECK_ABS(e->t, want, 4.0 * ulp(want));
            CHECK_ABS(((double)e->t - e->start) / e->dt, (i + 0.25) / (2.0 * i + 1.0), 1e-4);
            CHECK_ABS(e->start, (double)d * ((double)i / n) * ((double)i / n), tol);
            CHECK_ABS(e->end, (double)d * ((i + 1.0) / n) * ((i + 1.0) / n), tol);
        } else {
            double want = (double)e->start + (double)jitter * e->dt;
            CHECK_ABS(e->t, want, ulp(want));
        }
        vec3 Tw = medium_piece_weight(v3(sigma, sigma, sigma), e->dt, &T);
        light += (double)Tw.y * sigma;
    }
    CHECK(part == count);
    CHECK(m > 0 && fabs((double)ev[m - 1].end - d) <= tol);
    if (count == 0)
        CHECK(pieces == n);
    double tau = (double)sigma * d;
    CHECK_REL(T.y, exp(-tau), 1e-5);
    CHECK_REL(light, -expm1(-tau), 1e-5);
    if (name)
        printf("%-28s %3d events (%2d pieces, %d parts), T %.7f (exact %.7f), light %.7f "
           "(exact %.7f)\n",
           name, m, pieces, part, (double)T.y, exp(-tau), light, -expm1(-tau));
    return pieces;
}

int main(void)
{
    check_ray("no parts, jitter 0.37", 1.2e5f, 64, 0.37f, NULL, NULL, 0);
    check_ray("no parts, grid middle", 1.2e5f, 64, QUADRATURE_GRID_MIDDLE, NULL, NULL, 0);
    /* rays of many lengths: where the grid's start of a segment rounds below the end of the
     * segment before, a jittered piece is clipped to that end and a grid-middle one is not */
    int swept = 0, failures = test_failures;
    for (int k = 0; k <= 120; k++)
        for (int n = 16; n <= 64; n += 24) {
            float d = (float)(100.0 * pow(10.0, k / 24.0));
            check_ray(NULL, d, n, 0.37f, NULL, NULL, 0);
            check_ray(NULL, d, n, QUADRATURE_GRID_MIDDLE, NULL, NULL, 0);
            swept += 2;
        }
    printf("%d rays of 100 m to 10^7 m, 16 to 64 segments: %d failed checks\n", swept,
           test_failures - failures);

    const float d = 3e4f;
    const int n = 16; /* breaks at d (k/16)^2: 117.2, 468.8, 1054.7, 1875, 2929.7, ... */
    struct {
        const char *name;
        float lo[2], hi[2];
        int count;
    } rays[] = {
        {"(a) inside one segment", {2000.0f, 0.0f}, {2500.0f, 0.0f}, 1},
        {"(b) across segments", {900.0f, 0.0f}, {7000.0f, 0.0f}, 1},
        {"(c) two in one segment", {2000.0f, 2600.0f}, {2300.0f, 2800.0f}, 2},
        {"(d) from the start", {0.0f, 5000.0f}, {300.0f, 5500.0f}, 2},
        {"(e) to the end", {20000.0f, 0.0f}, {30000.0f, 0.0f}, 1},
    };
    for (size_t k = 0; k < sizeof rays / sizeof rays[0]; k++)
        check_ray(rays[k].name, d, n, 0.37f, rays[k].lo, rays[k].hi, rays[k].count);

    /* 5: equal segments */
    int equal_wrong = 0;
    for (int k = 0; k <= 48; k++)
        for (int n_eq = 1; n_eq <= 200; n_eq += 33) {
            float d_eq = (float)(100.0 * pow(10.0, k / 12.0));
            quadrature_walk q = quadrature_begin_equal(d_eq, n_eq);
            int i = 0;
            double len = (double)d_eq / n_eq;
            for (int e; (e = quadrature_next(&q)) != QUADRATURE_END && i <= n_eq; i++) {
                double t = (i + 0.5) * len, start = i * len;
                equal_wrong += e != QUADRATURE_PIECE || fabs((double)q.t - t) > 2.0 * ulp(t) ||
                               fabs((double)q.start - start) > 2.0 * ulp(d_eq) ||
                               fabs((double)q.dt - len) > ulp(len);
            }
            equal_wrong += i != n_eq;
        }
    CHECK(equal_wrong == 0);
    printf("equal segments: %d of 343 rays off\n", equal_wrong);

    /* 4: the next break */
    float breaks[17];
    for (int k = 0; k <= n; k++) {
        float dt;
        breaks[k] = quadrature_grid_segment(d, k, n, &dt);
    }
    int wrong = 0;
    for (int j = 0; j < 10000 + n; j++) {
        float t = j < 10000 ? (float)((double)d * j / 10000.0) : breaks[j - 10000];
        float want = INFINITY;
        for (int k = 1; k <= n; k++)
            if (breaks[k] > t) {
                want = breaks[k];
                break;
            }
        if (quadrature_grid_next(t, d, n) != want && !isinf(want))
            wrong++;
    }
    CHECK(wrong == 0);
    printf("quadrature_grid_next: %d of %d points off the least break above them\n", wrong,
           10000 + n);
    return test_finish();
}
