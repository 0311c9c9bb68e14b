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
 *     its middle (i + 1/2) d/n (2 ulp).
 *  6. Sized pieces (quadrature_begin_sized over [t0, t1], at most n pieces, jitter 0.37): the
 *     first piece starts at t0 and each next one exactly where the one before ended (start +
 *     dt, the same float: no gap, no overlap); each is sampled at start + jitter dt (ulp).
 *     (f) constant length 64 m over [1024, 1696] m (every value exact in float): 11 pieces,
 *     piece k at 1024 + 64 k, the last cut to 32 m, ending at t1 exactly; (g) the same with
 *     n = 4: 4 pieces, stopped by the count at 1280 m; (h) lengths growing as a + b start
 *     (a = 50 m, b = 0.02, the marcher's rule) over [2000, 30000] m: piece k starts at the
 *     closed form (t0 + a/b)(1 + b)^k - a/b (relative 4 (k + 1) ulp: a few roundings per
 *     step, carried on), as many pieces as the closed form has starts below t1, the last
 *     ending at t1 (4 ulp); (i) pieces ending at the next of two sets of break points
 *     (quadrature_step_to, the shell's rule: t0 + j (t1 - t0)/7 and the grid's breaks of
 *     d = 12000 m on 16 segments) over [500, 9000] m: the pieces end exactly at the sorted
 *     union of the breaks inside (t0, t1), then at t1; (j) t0 = t1: no piece. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

/* The pieces of the sized walk over [t0, t1] (at most n, jitter 0.37) with lengths
 * a + b start (want_end 0) or ending at the next of the breaks t0 + j (t1 - t0) / 7 and the
 * grid's of grid_d on grid_n segments (want_end 1); checks oracle 6's tiling and sample points
 * and returns how many pieces, their starts in start[], the walk's end in *done. */
static int sized_walk(float t0, float t1, int n, float a, float b, int want_end, float grid_d,
                      int grid_n, float *start, float *done)
{
    const float jitter = 0.37f, A = (t1 - t0) / 7.0f;
    quadrature_walk q = quadrature_begin_sized(t0, t1, n, jitter);
    int m = 0, j = 1;
    float end = t0;
    while (quadrature_more(&q) && m < MAX_EVENTS) {
        if (want_end) {
            float tc = j < 7 ? t0 + (float)j * A : t1;
            quadrature_step_to(&q, fminf(tc, quadrature_grid_next(q.done, grid_d, grid_n)));
            j += q.done >= tc;
        } else {
            quadrature_step(&q, a + b * q.done);
        }
        CHECK(q.start == end); /* where the piece before ended */
        double want_t = (double)q.start + (double)jitter * q.dt;
        CHECK_ABS(q.t, want_t, ulp(want_t));
        CHECK(q.dt > 0.0f);
        end = q.start + q.dt;
        CHECK(q.done == end);
        start[m++] = q.start;
    }
    CHECK(m < MAX_EVENTS);
    *done = q.done;
    return m;
}

static int float_less(const void *x, const void *y)
{
    float a = *(const float *)x, b = *(const float *)y;
    return (a > b) - (a < b);
}

/* Oracle 6: the sized walk's cases (f) to (j). */
static void check_sized(void)
{
    float start[MAX_EVENTS], done;
    /* (f), (g): constant length */
    int m = sized_walk(1024.0f, 1696.0f, 100, 64.0f, 0.0f, 0, 0.0f, 0, start, &done);
    int off = m != 11 || done != 1696.0f;
    for (int k = 0; k < m; k++)
        off += start[k] != 1024.0f + 64.0f * (float)k;
    CHECK(off == 0);
    printf("(f) constant 64 m:         %2d pieces (exact 11), end %.1f m (exact 1696)\n", m,
           (double)done);
    m = sized_walk(1024.0f, 1696.0f, 4, 64.0f, 0.0f, 0, 0.0f, 0, start, &done);
    CHECK(m == 4 && done == 1280.0f);
    printf("(g) the same, n = 4:       %2d pieces (exact 4), end %.1f m (exact 1280)\n", m,
           (double)done);

    /* (h): growing lengths, against the closed form */
    const double a = 50.0, b = 0.02, t0 = 2000.0, t1 = 30000.0;
    m = sized_walk((float)t0, (float)t1, 1000, (float)a, (float)b, 0, 0.0f, 0, start, &done);
    int want = 0;
    double worst = 0.0;
    while ((t0 + a / b) * pow(1.0 + b, want) - a / b < t1)
        want++;
    for (int k = 0; k < m; k++) {
        double exact = (t0 + a / b) * pow(1.0 + b, k) - a / b;
        CHECK_ABS(start[k], exact, 4.0 * (k + 1) * ulp(exact));
        worst = fmax(worst, fabs((double)start[k] - exact) / ulp(exact));
    }
    CHECK(m == want);
    CHECK_ABS(done, t1, 4.0 * ulp(t1));
    printf("(h) growing a + b t:       %2d pieces (closed form %d), starts within %.1f ulp, "
           "end %.3f m\n", m, want, worst, (double)done);

    /* (i): the next of two sets of break points */
    const float lo = 500.0f, hi = 9000.0f, grid_d = 12000.0f, A = (hi - lo) / 7.0f;
    const int grid_n = 16;
    m = sized_walk(lo, hi, 7 + grid_n + 1, 0.0f, 0.0f, 1, grid_d, grid_n, start, &done);
    float breaks[32];
    int nb = 0;
    for (int j = 1; j < 7; j++)
        breaks[nb++] = lo + (float)j * A;
    for (int k = 1; k <= grid_n; k++) {
        float dt, g = quadrature_grid_segment(grid_d, k, grid_n, &dt);
        if (g > lo && g < hi)
            breaks[nb++] = g;
    }
    qsort(breaks, nb, sizeof breaks[0], float_less);
    int uniq = 0;
    for (int k = 0; k < nb; k++)
        if (uniq == 0 || breaks[k] != breaks[uniq - 1])
            breaks[uniq++] = breaks[k];
    breaks[uniq++] = hi;
    off = m != uniq || done != hi;
    for (int k = 1; k < m && k < uniq; k++)
        off += start[k] != breaks[k - 1];
    CHECK(off == 0);
    printf("(i) to the next break:     %2d pieces (the union of the breaks: %d), end %.1f m\n", m,
           uniq, (double)done);

    /* (j): an empty walk */
    m = sized_walk(700.0f, 700.0f, 10, 64.0f, 0.0f, 0, 0.0f, 0, start, &done);
    CHECK(m == 0 && done == 700.0f);
    printf("(j) t0 = t1:               %2d pieces\n", m);
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

    check_sized();
    return test_finish();
}
