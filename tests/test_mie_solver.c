/* test_mie_solver.c — the single-sphere Lorenz–Mie solver against published values.
 * labels: unit
 *
 * Oracles (all from ../shared/reference/mie.md):
 *   - Wiscombe's MIEV0 test cases (NCAR TN-140, 1979): Q_ext, Q_sca, g, S1, S2. Each value is
 *     compared within max(1e-6 relative, half a unit of its last printed digit) — the solver's
 *     target is 1e-6, and a value printed with fewer digits cannot be checked more tightly than
 *     its rounding. Amplitudes (complex) within 1e-6 |S| (printed to 7 significant digits, so the
 *     rounding of both parts together is at most 7.1e-7 |S|).
 *   - First coefficients a1, b1 from a high-precision computation, to 1e-9 absolute.
 *   - Bohren & Huffman's sample calculation (Appendix A), to half a unit of the printed digit.
 *   - The optical theorem Q_ext = 4/x^2 Re S(0) (an identity between two different sums; the
 *     sums have ~N terms of size <= 2n+1, so 1e-10 relative bounds their rounding).
 *   - The D_n start at x = 1000: zero started far enough agrees with Lentz to 1e-6 in S11(180),
 *     while the textbook BHMIE start does not (a test of the solver's stability). */
#include <stdlib.h>
#include <string.h>
#include "atmo/mie.h"
#include "testlib.h"

#define PI 3.14159265358979323846
#define J CMPLX(0.0, 1.0)

/* A printed reference value and half a unit of its last digit. */
static double half_ulp(const char *s)
{
    const char *dot = strchr(s, '.');
    const char *ex = strpbrk(s, "eE");
    int decimals = 0;
    if (dot)
        decimals = (int)((ex ? ex : s + strlen(s)) - dot - 1);
    int exponent = ex ? atoi(ex + 1) : 0;
    return 0.5 * pow(10.0, exponent - decimals);
}

/* Within max(1e-6 relative, half a unit of the last printed digit). */
static void check_printed(const char *what, double got, const char *ref)
{
    if (getenv("MIE_VERBOSE"))
        printf("%-24s %.10g  ref %s\n", what, got, ref);
    double want = strtod(ref, NULL);
    double tol = fmax(1e-6 * fabs(want), half_ulp(ref));
    if (!test_check_abs(__FILE__, __LINE__, what, got, want, tol))
        fprintf(stderr, "  (reference %s)\n", ref);
}

static void check_amp(const char *what, double complex got, double re, double im)
{
    double complex want = re + J * im;
    if (!test_check_abs(__FILE__, __LINE__, what, cabs(got - want), 0.0, 1e-6 * cabs(want)))
        fprintf(stderr, "  got %.9g %+.9gi want %.9g %+.9gi\n", creal(got), cimag(got), re, im);
}

static mie_efficiencies run(double x, double n, double k, int nmu, const double *mu,
                            double complex *s1, double complex *s2)
{
    mie_efficiencies q = {0};
    atmo_err e;
    if (mie_sphere(x, n, k, MIE_DN_LENTZ, nmu, mu, s1, s2, &q, &e) != ATMO_OK) {
        fprintf(stderr, "mie_sphere failed: %s\n", e.msg);
        CHECK(0);
    }
    return q;
}

static void test_miev0_water(void)
{
    double mu2[2] = {1.0, -1.0};
    double complex s1[7], s2[7];
    mie_efficiencies q = run(1.0, 1.33, 1e-5, 2, mu2, s1, s2);
    check_printed("case 9 Qext", q.qext, "0.09395198");
    check_printed("case 9 Qsca", q.qsca, "0.093923");
    check_printed("case 9 g", q.g, "0.184517");
    check_amp("case 9 S1(0)", s1[0], 0.02348800, 0.2281705);
    check_amp("case 9 S1(180)", s1[1], 0.02243622, 0.1437106);

    static const double deg[7] = {0, 30, 60, 90, 120, 150, 180};
    static const double ref1[7][2] = {{5253.302, -124.3188}, {-55.34573, -29.71881},
                                      {17.10488, -15.20096}, {-3.655758, 8.769860},
                                      {2.414318, 0.5380874}, {-1.222996, 32.83917},
                                      {-56.59205, 46.50974}};
    static const double ref2[7][2] = {{5253.302, -124.3188}, {-84.67204, -19.99470},
                                      {33.10764, -2.709787}, {-6.550512, -4.675370},
                                      {6.039011, -11.69971}, {-9.653812, 14.74455},
                                      {56.59205, -46.50974}};
    double mu[7];
    for (int i = 0; i < 7; i++)
        mu[i] = cos(deg[i] * PI / 180.0);
    mu[3] = 0.0; /* cos(90 deg) exactly */
    q = run(100.0, 1.33, 1e-5, 7, mu, s1, s2);
    check_printed("case 10 Qext", q.qext, "2.101321");
    check_printed("case 10 Qsca", q.qsca, "2.096594");
    check_printed("case 10 g", q.g, "0.868959");
    for (int i = 0; i < 7; i++) {
        char w[64];
        snprintf(w, sizeof w, "case 10 S1(%g)", deg[i]);
        check_amp(w, s1[i], ref1[i][0], ref1[i][1]);
        snprintf(w, sizeof w, "case 10 S2(%g)", deg[i]);
        check_amp(w, s2[i], ref2[i][0], ref2[i][1]);
    }
    static const char *inten[4] = {"2.76126e7", "5.75775e3", "8.13553e2", "7.75217e1"};
    for (int i = 0; i < 4; i++) {
        double s11 = 0.5 * (pow(cabs(s1[i]), 2) + pow(cabs(s2[i]), 2));
        check_printed("case 10 S11", s11, inten[i]);
    }

    q = run(10000.0, 1.33, 1e-5, 2, mu2, s1, s2);
    check_printed("case 11 Qext", q.qext, "2.004089");
    check_printed("case 11 Qsca", q.qsca, "1.723857");
    check_printed("case 11 g", q.g, "0.907840");
    check_amp("case 11 S1(0)", s1[0], 5.010222e7, -1.535815e5);
    check_amp("case 11 S1(180)", s1[1], -182.1162, -951.9097);
    check_amp("case 11 S2(180)", s2[1], 182.1162, 951.9097);
}

static void test_miev0_other(void)
{
    double mu2[2] = {1.0, -1.0};
    double complex s1[2], s2[2];
    mie_efficiencies q = run(10.0, 0.75, 0.0, 2, mu2, s1, s2);
    check_printed("m=0.75 x=10 Qsca", q.qsca, "2.232265");
    check_printed("m=0.75 x=10 g", q.g, "0.896473");
    check_amp("m=0.75 x=10 S1(0)", s1[0], 55.80662, -9.758097);
    check_amp("m=0.75 x=10 S1(180)", s1[1], -1.078568, -0.03608807);

    q = run(1000.0, 0.75, 0.0, 2, mu2, s1, s2);
    check_printed("m=0.75 x=1000 Qsca", q.qsca, "1.997908");
    check_printed("m=0.75 x=1000 g", q.g, "0.844944");
    check_amp("m=0.75 x=1000 S1(0)", s1[0], 4.994770e5, -1.336502e4);
    check_amp("m=0.75 x=1000 S1(180)", s1[1], 17.05778, 484.2510);

    q = run(0.055, 1.5, 1.0, 0, NULL, NULL, NULL);
    check_printed("m=1.5-i x=0.055 Qext", q.qext, "0.101491");
    check_printed("m=1.5-i x=0.055 Qsca", q.qsca, "1.1e-5");
    check_printed("m=1.5-i x=0.055 g", q.g, "0.000491");
    CHECK(q.nterms == 2); /* the small-sphere series was used (|m| x = 0.099) */

    q = run(1.0, 1.5, 1.0, 2, mu2, s1, s2);
    check_printed("m=1.5-i x=1 Qext", q.qext, "2.336321");
    check_printed("m=1.5-i x=1 Qsca", q.qsca, "0.6634538");
    check_printed("m=1.5-i x=1 g", q.g, "0.192136");
    check_amp("m=1.5-i x=1 S1(0)", s1[0], 0.584080, 0.190515);

    q = run(100.0, 1.5, 1.0, 0, NULL, NULL, NULL);
    check_printed("m=1.5-i x=100 Qext", q.qext, "2.097502");
    check_printed("m=1.5-i x=100 Qsca", q.qsca, "1.283697");
    check_printed("m=1.5-i x=100 g", q.g, "0.850252");
    q = run(10000.0, 1.5, 1.0, 0, NULL, NULL, NULL);
    check_printed("m=1.5-i x=1e4 Qext", q.qext, "2.004368");
    check_printed("m=1.5-i x=1e4 Qsca", q.qsca, "1.236575");
    /* MIEV0's printed g = 0.846309 is 1.1e-6 relative below the value that a 40-digit
     * evaluation of the same series (mpmath, downward D_n from far past |mx|, 10130 terms)
     * gives, 0.846309958109; we check against that. */
    check_printed("m=1.5-i x=1e4 g", q.g, "0.846309958109");

    static const double xs[3] = {1.0, 100.0, 10000.0};
    static const char *qs[3] = {"2.049405", "1.836785", "1.795393"};
    static const char *gs[3] = {"-0.110664", "0.556215", "0.548194"};
    for (int i = 0; i < 3; i++) {
        q = run(xs[i], 10.0, 10.0, 0, NULL, NULL, NULL);
        check_printed("m=10-10i Qsca", q.qsca, qs[i]);
        check_printed("m=10-10i g", q.g, gs[i]);
    }
}

static void test_first_coefficients(void)
{
    double complex a[1], b[1];
    atmo_err e;
    /* These published values are in Bohren & Huffman's convention (imaginary parts opposite to
     * MIEV0's; our case-10 amplitudes above fix our convention as MIEV0's), so compare the
     * conjugates. */
    CHECK(mie_coefficients(50.0, 4.0 / 3.0, 0.0, MIE_DN_LENTZ, 1, a, b, &e) == ATMO_OK);
    CHECK_ABS(cabs(conj(a[0]) - (0.5311058892948412 - 0.4990314856310943 * J)), 0.0, 1e-9);
    CHECK_ABS(cabs(conj(b[0]) - (0.7919244759352005 - 0.4059311522289938 * J)), 0.0, 1e-9);
    CHECK(mie_coefficients(2.0, 1.5, 1.0, MIE_DN_LENTZ, 1, a, b, &e) == ATMO_OK);
    CHECK_ABS(cabs(conj(a[0]) - (0.5465202033970915 - 0.1523738572575972 * J)), 0.0, 1e-9);
    CHECK_ABS(cabs(conj(b[0]) - (0.3897147278879423 + 0.227896075256 * J)), 0.0, 1e-9);
}

static void test_bohren_huffman(void)
{
    double mu[4] = {1.0, cos(36.0 * PI / 180.0), 0.0, -1.0};
    double complex s1[4], s2[4];
    double x = 2.0 * PI * 0.525 / 0.6328; /* 5.21282, unrounded as B&H compute it */
    mie_efficiencies q = run(x, 1.55, 0.0, 4, mu, s1, s2);
    check_printed("B&H Qext", q.qext, "3.10543");
    check_printed("B&H Qsca", q.qsca, "3.10543");
    check_printed("B&H Qback", q.qback, "2.92534");
    check_printed("B&H g", q.g, "0.63314");
    double s11[4];
    for (int i = 0; i < 4; i++)
        s11[i] = 0.5 * (pow(cabs(s1[i]), 2) + pow(cabs(s2[i]), 2));
    check_printed("B&H S11(36)/S11(0)", s11[1] / s11[0], "0.0355355");
    check_printed("B&H S11(90)/S11(0)", s11[2] / s11[0], "0.0124601");
    check_printed("B&H S11(180)/S11(0)", s11[3] / s11[0], "0.0383189");

    q = run(x, 1.55, 0.1, 0, NULL, NULL, NULL);
    check_printed("B&H absorbing Qext", q.qext, "2.86165188243");
    check_printed("B&H absorbing Qsca", q.qsca, "1.66424911991");
    check_printed("B&H absorbing Qback", q.qback, "0.20599534080");
    check_printed("B&H absorbing g", q.g, "0.80128972639");
}

static void test_optical_theorem(void)
{
    static const double cases[][3] = {{0.05, 1.33, 0.0}, {1.0, 1.33, 1e-5}, {30.0, 1.5, 0.01},
                                      {700.0, 1.33, 1e-8}, {5000.0, 1.33, 0.0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double mu = 1.0;
        double complex s1, s2;
        mie_efficiencies q = run(cases[i][0], cases[i][1], cases[i][2], 1, &mu, &s1, &s2);
        double x = cases[i][0];
        CHECK_REL(4.0 / (x * x) * creal(s1), q.qext, 1e-10);
        CHECK_ABS(cabs(s1 - s2), 0.0, 1e-12 * cabs(s1));
        /* no absorption: nothing removed but scattered (above the small-sphere series, whose
         * Q_ext and Q_sca are truncated separately) */
        if (cases[i][2] == 0.0 && x > 0.1)
            CHECK_REL(q.qsca, q.qext, 1e-10);
        /* S(180) fixes Q_back: Q_back = 4 |S1(180)|^2 / x^2 */
        mu = -1.0;
        run(x, cases[i][1], cases[i][2], 1, &mu, &s1, &s2);
        CHECK_REL(4.0 * pow(cabs(s1), 2) / (x * x), q.qback, 1e-9);
    }
}

/* Small spheres switch to Wiscombe's series at |m| x = 0.1: both sides of the switch agree to
 * the series' truncation error, O(x^4) relative to its leading terms' corrections: < 1e-6. */
static void test_small_sphere_switch(void)
{
    mie_efficiencies lo = run(0.1 / 1.5 * (1.0 - 1e-9), 1.5, 0.0, 0, NULL, NULL, NULL);
    mie_efficiencies hi = run(0.1 / 1.5 * (1.0 + 1e-9), 1.5, 0.0, 0, NULL, NULL, NULL);
    CHECK_REL(lo.qsca, hi.qsca, 1e-6);
    CHECK_REL(lo.g, hi.g, 1e-6);
    mie_efficiencies tiny = run(1e-6, 1.33, 0.0, 0, NULL, NULL, NULL);
    /* Rayleigh limit: Q_sca = 8/3 x^4 |(m^2-1)/(m^2+2)|^2 */
    double L = (1.33 * 1.33 - 1.0) / (1.33 * 1.33 + 2.0);
    CHECK_REL(tiny.qsca, 8.0 / 3.0 * 1e-24 * L * L, 1e-9);
}

/* x = 1000, m = 1.33: S11(180) with D_n started from zero far enough matches Lentz to 1e-6;
 * the BHMIE start at max(nstop, |mx|) + 15 does not (mie.md: tens of % at cloud sizes; we ask
 * only for > 1e-3 to show it). Also a1 at x = 50 with the BHMIE start. */
static void test_dn_start(void)
{
    double mu = -1.0, x = 1000.0;
    double complex s1[3], s2[3];
    mie_efficiencies q;
    atmo_err e;
    mie_dn_start starts[3] = {MIE_DN_LENTZ, MIE_DN_ZERO_FAR, MIE_DN_ZERO_BHMIE};
    double s11[3];
    for (int i = 0; i < 3; i++) {
        CHECK(mie_sphere(x, 1.33, 1e-8, starts[i], 1, &mu, &s1[i], &s2[i], &q, &e) == ATMO_OK);
        s11[i] = 0.5 * (pow(cabs(s1[i]), 2) + pow(cabs(s2[i]), 2));
    }
    CHECK_REL(s11[1], s11[0], 1e-6);
    double bh_err = fabs(s11[2] - s11[0]) / s11[0];
    printf("x = 1000 S11(180): Lentz %.9g, zero far %.9g, BHMIE start %.9g (%.2g relative)\n",
           s11[0], s11[1], s11[2], bh_err);
    CHECK(bh_err > 1e-3);
}

int main(void)
{
    test_miev0_water();
    test_miev0_other();
    test_first_coefficients();
    test_bohren_huffman();
    test_optical_theorem();
    test_small_sphere_switch();
    test_dn_start();
    return test_finish();
}
