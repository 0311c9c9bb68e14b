/* mie.c — Lorenz–Mie solution for a homogeneous sphere, in double precision.
 *
 * For size parameter x = 2 pi r / lambda and relative index m (Bohren & Huffman 1983, ch. 4):
 *   a_n = [(D_n/m + n/x) psi_n - psi_{n-1}] / [(D_n/m + n/x) xi_n - xi_{n-1}]        (4.88)
 *   b_n = [(m D_n + n/x) psi_n - psi_{n-1}] / [(m D_n + n/x) xi_n - xi_{n-1}]
 * with Riccati-Bessel psi_n(x) = x j_n(x), xi_n = psi_n - i chi_n, chi_n = -x y_n(x) (upward
 * recurrence, stable up to the last term used) and D_n(mx) = psi_n'(mx)/psi_n(mx) by downward
 * recurrence D_{n-1} = n/z - 1/(D_n + n/z). Its start decides accuracy at large x:
 *   - Lentz (1976): D_N = -N/z + J_{N-1/2}(z)/J_{N+1/2}(z), the Bessel ratio by the continued
 *     fraction 2v/z - 1/(2(v+1)/z - 1/(2(v+2)/z - ...)), v = N + 1/2, evaluated with the modified
 *     Lentz algorithm (Thompson & Barnett 1986) to 1e-15;
 *   - zero far enough: D = 0 at N = max(nstop, |z| + 10|z|^(1/3)) + 15 (Wiscombe 1979);
 *   - the textbook BHMIE start, 0 at max(nstop, |z|) + 15, kept only for the test that shows
 *     it fails at cloud sizes.
 * Number of terms (Wiscombe 1980): x + 4 x^(1/3) + 1 (x <= 8), x + 4.05 x^(1/3) + 2 (x < 4200),
 * x + 4 x^(1/3) + 2 above.
 * Small spheres (|m| x <= 0.1): Wiscombe's (1979, NCAR TN-140, eqs. for SMALL1) series of
 * a1, b1, a2 to order x^4 relative; all other coefficients are below double precision there.
 * Efficiencies (B&H 4.61, 4.62, Wiscombe): Q_ext = 2/x^2 sum (2n+1) Re(a_n + b_n),
 *   Q_sca = 2/x^2 sum (2n+1)(|a_n|^2 + |b_n|^2), Q_back = 1/x^2 |sum (2n+1)(-1)^n (a_n - b_n)|^2,
 *   g Q_sca = 4/x^2 sum [n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1}) + (2n+1)/(n(n+1)) Re(a_n b*_n)].
 * Amplitudes: S1 = sum (2n+1)/(n(n+1)) (a_n pi_n + b_n tau_n), S2 likewise with pi, tau swapped;
 *   pi_n = ((2n-1) mu pi_{n-1} - n pi_{n-2})/(n-1), tau_n = n mu pi_n - (n+1) pi_{n-1}.
 * The computation runs in Bohren & Huffman's convention (m = n + ik); results are conjugated into
 * MIEV0's (m = n - ik), see mie.h. */
#include <math.h>
#include <stdlib.h>
#include "atmo/mie.h"

/* the imaginary unit in double (I alone is a complex float) */
#define MIE_I CMPLX(0.0, 1.0)

int mie_nterms(double x)
{
    double c = cbrt(x);
    double n = x <= 8.0 ? x + 4.0 * c + 1.0 : (x < 4200.0 ? x + 4.05 * c + 2.0 : x + 4.0 * c + 2.0);
    int nt = (int)n;
    return nt < 1 ? 1 : nt;
}

/* p / q by Smith's (1962) algorithm: no overflow of |q|^2, and no call into the run-time
 * library's Annex G division (which dominated the cost of the coefficients) */
static inline double complex mie_div(double complex p, double complex q)
{
    double a = creal(p), b = cimag(p), c = creal(q), d = cimag(q);
    if (fabs(c) >= fabs(d)) {
        double r = d / c, t = 1.0 / (c + d * r);
        return CMPLX((a + b * r) * t, (b - a * r) * t);
    }
    double r = c / d, t = 1.0 / (c * r + d);
    return CMPLX((a * r + b) * t, (b * r - a) * t);
}

/* J_{v-1}(z)/J_v(z) with v = N + 1/2 by the modified Lentz algorithm. */
static double complex mie_lentz_ratio(double complex z, int N)
{
    const double tiny = 1e-300;
    double v = N + 0.5;
    double complex f = 2.0 * v / z, C = f, D = 0.0;
    if (f == 0.0)
        f = C = tiny;
    int max_iter = 10 * (int)(cabs(z) + N) + 1000;
    for (int j = 1; j < max_iter; j++) {
        double complex bj = 2.0 * (v + j) / z;
        D = bj - D;
        C = bj - 1.0 / C;
        if (D == 0.0)
            D = tiny;
        if (C == 0.0)
            C = tiny;
        D = 1.0 / D;
        double complex delta = C * D;
        f *= delta;
        if (cabs(delta - 1.0) < 1e-15)
            break;
    }
    return f;
}

/* D_1..D_count of z into d[1..count] (d has count + 1 entries). */
static void mie_log_derivative(double complex z, int count, int nstop, mie_dn_start start,
                                 double complex *d)
{
    double az = cabs(z);
    if (start == MIE_DN_LENTZ) {
        double complex zi = mie_div(1.0, z);
        d[count] = -count * zi + mie_lentz_ratio(z, count);
        for (int n = count; n > 1; n--)
            d[n - 1] = n * zi - mie_div(1.0, d[n] + n * zi);
        return;
    }
    int top = start == MIE_DN_ZERO_FAR ? (int)ceil(az + 10.0 * cbrt(az)) : (int)ceil(az);
    if (top < nstop)
        top = nstop;
    top += 15;
    if (top < count)
        top = count;
    double complex dn = 0.0;
    for (int n = top; n > 1; n--) {
        if (n <= count)
            d[n] = dn;
        dn = n / z - 1.0 / (dn + n / z);
    }
    d[1] = dn;
}

/* Wiscombe's small-sphere series, MIEV0 convention: a1 = x^3 ah1, b1 = x^3 bh1, a2 = x^3 ah2. */
static void mie_small(double x, double complex m, double complex *a, double complex *b, int count)
{
    double complex m2 = m * m;
    double x2 = x * x, x3 = x2 * x, x4 = x2 * x2;
    double complex den = m2 + 2.0 + (1.0 - 0.7 * m2) * x2 -
                         (8.0 * m2 * m2 - 385.0 * m2 + 350.0) / 1400.0 * x4 +
                         2.0 * MIE_I * (m2 - 1.0) * x3 * (1.0 - 0.1 * x2) / 3.0;
    double complex ah1 = 2.0 * MIE_I * (m2 - 1.0) / 3.0 * (1.0 - 0.1 * x2 + (4.0 * m2 + 5.0) * x4 / 1400.0) / den;
    double complex bh1 = MIE_I * x2 * (m2 - 1.0) / 45.0 * (1.0 + (2.0 * m2 - 5.0) / 70.0 * x2) /
                         (1.0 - (2.0 * m2 - 5.0) / 30.0 * x2);
    double complex ah2 = MIE_I * x2 * (m2 - 1.0) / 15.0 * (1.0 - x2 / 14.0) /
                         (2.0 * m2 + 3.0 - (2.0 * m2 - 7.0) / 14.0 * x2);
    for (int i = 0; i < count; i++)
        a[i] = b[i] = 0.0;
    a[0] = x3 * ah1;
    b[0] = x3 * bh1;
    if (count > 1)
        a[1] = x3 * ah2;
}

void mie_radius_limits_um(double wavelength_nm, double *r_min_um, double *r_max_um)
{
    double per_x_um = wavelength_nm * 1e-3 / (2.0 * M_PI);
    *r_min_um = MIE_X_MIN * per_x_um;
    *r_max_um = fmin(MIE_X_MAX * per_x_um, MIE_RADIUS_MAX_UM);
}

int mie_check_radius(double radius_um, double wavelength_nm, atmo_err *e)
{
    double r_min, r_max;
    mie_radius_limits_um(wavelength_nm, &r_min, &r_max);
    if (radius_um >= r_min && radius_um <= r_max)
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "radius %g um is outside %.6g-%.6g um, the radii the Mie solver resolves "
                     "at %g nm (size parameter 2 pi r / lambda in [%g, %g], r <= %g um); "
                     "choose a radius in that range",
                     radius_um, r_min, r_max, wavelength_nm, MIE_X_MIN, MIE_X_MAX,
                     MIE_RADIUS_MAX_UM);
}

static int mie_check(double x, double n, double k, atmo_err *e)
{
    if (!(x >= MIE_X_MIN) || !(x <= MIE_X_MAX))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "Mie size parameter x = %g is outside [%g, %g]; use a radius within "
                         "[%g, %g] lambda / 2 pi", x, MIE_X_MIN, MIE_X_MAX, MIE_X_MIN, MIE_X_MAX);
    if (!(n > 0.0) || !isfinite(n) || !(k >= 0.0) || !isfinite(k))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "refractive index %g + %gi is invalid; need n > 0 and absorption k >= 0",
                         n, k);
    return ATMO_OK;
}

static int mie_small_sphere(double x, double n, double k)
{
    return sqrt(n * n + k * k) * x <= 0.1;
}

int mie_coefficients(double x, double n, double k, mie_dn_start start, int count,
                     double complex *a, double complex *b, atmo_err *e)
{
    int rc = mie_check(x, n, k, e);
    if (rc)
        return rc;
    if (mie_small_sphere(x, n, k)) {
        mie_small(x, n - MIE_I * k, a, b, count);
        return ATMO_OK;
    }
    double complex m = n + MIE_I * k, z = m * x, mi = mie_div(1.0, m);
    double complex *d = malloc(sizeof *d * (size_t)(count + 1));
    if (!d)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d Mie terms", count);
    mie_log_derivative(z, count, mie_nterms(x), start, d);
    /* psi_{-1} = cos x, psi_0 = sin x; chi_{-1} = -sin x, chi_0 = cos x */
    double psi0 = cos(x), psi1 = sin(x), chi0 = -sin(x), chi1 = cos(x);
    double complex xi1 = psi1 - MIE_I * chi1;
    for (int i = 1; i <= count; i++) {
        double f = (2.0 * i - 1.0) / x;
        double psi = f * psi1 - psi0, chi = f * chi1 - chi0;
        double complex xi = psi - MIE_I * chi;
        double complex ta = d[i] * mi + i / x, tb = m * d[i] + i / x;
        double complex an = mie_div(ta * psi - psi1, ta * xi - xi1);
        double complex bn = mie_div(tb * psi - psi1, tb * xi - xi1);
        a[i - 1] = conj(an);
        b[i - 1] = conj(bn);
        psi0 = psi1;
        psi1 = psi;
        chi0 = chi1;
        chi1 = chi;
        xi1 = xi;
    }
    free(d);
    return ATMO_OK;
}

/* S1, S2 at n_mu cosines. The loop over terms is outside the loop over angles so the inner loop
 * has no division and vectorises across angles (5x faster than one angle at a time). */
static int mie_amplitudes(int N, const double complex *a, const double complex *b, int n_mu,
                            const double *mu, double complex *s1, double complex *s2, atmo_err *e)
{
    double *w = malloc(sizeof *w * 6 * (size_t)n_mu);
    if (!w)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d angles", n_mu);
    double *p = w, *pm1 = w + n_mu, *r1 = w + 2 * n_mu, *i1 = w + 3 * n_mu, *r2 = w + 4 * n_mu,
           *i2 = w + 5 * n_mu;
    for (int j = 0; j < n_mu; j++)
        p[j] = 1.0, pm1[j] = r1[j] = i1[j] = r2[j] = i2[j] = 0.0; /* pi_1, pi_0 */
    for (int i = 1; i <= N; i++) {
        double f = (2.0 * i + 1.0) / ((double)i * (i + 1.0));
        double ar = f * creal(a[i - 1]), ai = f * cimag(a[i - 1]);
        double br = f * creal(b[i - 1]), bi = f * cimag(b[i - 1]);
        double c1 = (2.0 * i + 1.0) / i, c2 = (i + 1.0) / i, n1 = i + 1.0;
        for (int j = 0; j < n_mu; j++) {
            double pj = p[j], tau = i * mu[j] * pj - n1 * pm1[j];
            r1[j] += ar * pj + br * tau;
            i1[j] += ai * pj + bi * tau;
            r2[j] += ar * tau + br * pj;
            i2[j] += ai * tau + bi * pj;
            p[j] = c1 * mu[j] * pj - c2 * pm1[j];
            pm1[j] = pj;
        }
    }
    for (int j = 0; j < n_mu; j++) {
        s1[j] = CMPLX(r1[j], i1[j]);
        s2[j] = CMPLX(r2[j], i2[j]);
    }
    free(w);
    return ATMO_OK;
}

int mie_sphere_nterms(double x, double n, double k)
{
    /* Wiscombe's count plus x^(1/3): at x = 1e4 partial-wave resonances just past Wiscombe's
     * count still move S(180) by 4e-6 relative (MIEV0 case 11); Q and g are unchanged. */
    return mie_small_sphere(x, n, k) ? 2 : mie_nterms(x) + (int)ceil(cbrt(x));
}

int mie_sphere_coefficients(double x, double n, double k, mie_dn_start start, double complex *a,
                            double complex *b, mie_efficiencies *q, atmo_err *e)
{
    int N = mie_sphere_nterms(x, n, k);
    int rc = mie_coefficients(x, n, k, start, N, a, b, e);
    if (rc)
        return rc;
    a[N] = b[N] = 0.0; /* the g sum reads a_{N+1} */
    double sext = 0.0, ssca = 0.0, sg = 0.0;
    double complex sback = 0.0;
    for (int i = 1; i <= N; i++) {
        double complex an = a[i - 1], bn = b[i - 1];
        double w = 2.0 * i + 1.0;
        sext += w * creal(an + bn);
        ssca += w * (creal(an) * creal(an) + cimag(an) * cimag(an) + creal(bn) * creal(bn) +
                     cimag(bn) * cimag(bn));
        sback += (i % 2 ? -w : w) * (an - bn);
        sg += (double)i * (i + 2.0) / (i + 1.0) * creal(an * conj(a[i]) + bn * conj(b[i])) +
              w / ((double)i * (i + 1.0)) * creal(an * conj(bn));
    }
    double x2 = x * x;
    q->qext = 2.0 / x2 * sext;
    q->qsca = 2.0 / x2 * ssca;
    q->qback = (creal(sback) * creal(sback) + cimag(sback) * cimag(sback)) / x2;
    q->g = ssca > 0.0 ? 2.0 * sg / ssca : 0.0;
    q->nterms = N;
    return ATMO_OK;
}

int mie_sphere(double x, double n, double k, mie_dn_start start, int n_mu, const double *mu,
               double complex *s1, double complex *s2, mie_efficiencies *q, atmo_err *e)
{
    int rc = mie_check(x, n, k, e);
    if (rc)
        return rc;
    int N = mie_sphere_nterms(x, n, k);
    double complex *a = malloc(sizeof *a * (size_t)(N + 1));
    double complex *b = malloc(sizeof *b * (size_t)(N + 1));
    if (!a || !b) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d Mie terms", N);
        goto cleanup;
    }
    rc = mie_sphere_coefficients(x, n, k, start, a, b, q, e);
    if (rc)
        goto cleanup;
    if (n_mu > 0) {
        rc = mie_amplitudes(N, a, b, n_mu, mu, s1, s2, e);
        if (rc)
            goto cleanup;
    }
cleanup:
    free(a);
    free(b);
    return rc;
}
