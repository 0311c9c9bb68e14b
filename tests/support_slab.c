/* support_slab.c — adding-doubling for a homogeneous plane-parallel slab (testslab.h).
 *
 * Radiance is split into azimuthal Fourier modes, I(mu, phi) = sum_m I^m(mu) cos(m phi), and the
 * (truncated) phase function into
 *     p^m(mu_a, mu_b) = (2 - delta_m0) / (4 pi) sum_{l=m}^{M-1} (2l + 1) chi'_l
 *                       lambda_l^m(mu_a) lambda_l^m(mu_b)
 * (the addition theorem; lambda_l^m = sqrt((l-m)!/(l+m)!) P_l^m, signed cosines along the
 * downward normal), so that int p I dOmega' has mode m equal to c_m int p^m I^m dmu',
 * c_0 = 2 pi, c_m = pi. A layer is a pair of kernels per mode, reflection R(mu, mu') and
 * diffuse transmission T(mu, mu') (I_out^m(mu) = int K(mu, mu') I_in^m(mu') dmu'), and its
 * direct transmission e(mu) = exp(-tau / mu). On the cosine nodes (Gauss-Legendre on (0, 1) with
 * weights w, and the beam's and views' cosines with weight 0, so their kernel values are
 * computed without entering the quadrature) a kernel is a matrix and a composition K_a W K_b.
 *
 * Thin layer (tau_0 = tau' 2^-n <= 1e-10, exact single scattering; its error, O(tau_0) of the
 * layer's reflection, grows to O(tau tau_0) after doubling):
 *     R(i, j) = omega' c_m p^m(-mu_i, mu_j) mu_j / (mu_i + mu_j) (1 - exp(-tau_0 (1/mu_i + 1/mu_j)))
 *     T(i, j) = omega' c_m p^m(mu_i, mu_j) (tau_0 / mu_i) exp(-tau_0 / mu_j) E1(x),
 *               x = tau_0 (mu_i - mu_j) / (mu_i mu_j), E1(x) = (e^x - 1) / x
 * Doubling a layer (R, T, e; the same from above and below, the layer being homogeneous):
 *     Q = R W R,  S = (I - Q W)^-1 Q          (the reflections between the two halves)
 *     D = T + S e + S W T                     (diffuse light going down at the middle)
 *     U = R e + R W D                         (going up at the middle)
 *     R' = R + e U + T W U,  T' = e D + T e + T W D,  e' = e^2
 * (e U multiplies row i by e_i, S e column j by e_j; Hansen & Travis 1974, sec. 4). The beam
 * of irradiance 1 at mu0 has modes I^m = delta(mu - mu0) / c_m, so I_r^m(mu) = R(mu, mu0) / c_m.
 * Delta-M (Wiscombe 1977) keeps M <= 2N moments: f = chi_M, chi'_l = (chi_l - f) / (1 - f),
 * tau' = (1 - omega f) tau, omega' = omega (1 - f) / (1 - omega f). TMS (Nakajima & Tanaka
 * 1988): the truncated problem's single scattering, omega' p'(Theta) in the slab tau', is taken
 * out of every Fourier mode (what is summed is its multiple scattering, smooth in azimuth, so
 * the series stops once three modes in a row change no view by SLAB_MODE_TOLERANCE), and the
 * single scattering of the exact phase function in the scaled slab is added in closed form,
 * with S = omega p(Theta) / (1 - omega f) (the forward peak's light stays in the beam):
 *     reflected   S mu0 / (mu + mu0) (1 - exp(-tau' (1/mu + 1/mu0)))
 *     transmitted S (tau' / mu) exp(-tau' / mu0) E1(tau' (mu - mu0) / (mu mu0)).
 * M = 2N resolves a moderately peaked p (HG g = 0.85: f = 0.85^M); for a Mie table whose
 * moments decay slowly (cumulus: chi_64 = 0.31, chi_256 = 0.013) M is kept below 2N, so the
 * quadrature resolves p', and the answer's independence of M and N is what shows the
 * truncation and the quadrature converged (tests/test_cloud_slab.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/quadrature.h"
#include "testslab.h"

#define SLAB_MAX_VIEWS 16
/* the azimuth series stops after three modes in a row whose multiple scattering changes no
 * view's radiance by this fraction */
#define SLAB_MODE_TOLERANCE 1e-7

void slab_moments(slab_phase_fn phase, const void *ctx, int count, double *chi)
{
    /* theta_k = pi (k / K)^2: segments of ~1e-7 rad at the forward peak, 3e-3 rad at pi */
    enum { K = 4000, G = 4 };
    double gx[G], gw[G], *pl = malloc(sizeof *pl * (size_t)count);
    atmo_gauss_legendre(G, gx, gw);
    memset(chi, 0, sizeof *chi * (size_t)count);
    for (int k = 0; k < K; k++) {
        double a = M_PI * (double)k * k / ((double)K * K);
        double b = M_PI * (double)(k + 1) * (k + 1) / ((double)K * K);
        for (int q = 0; q < G; q++) {
            double th = 0.5 * (a + b) + 0.5 * (b - a) * gx[q], c = cos(th);
            double f = 2.0 * M_PI * phase(c, ctx) * sin(th) * 0.5 * (b - a) * gw[q];
            pl[0] = 1.0;
            if (count > 1)
                pl[1] = c;
            for (int l = 2; l < count; l++)
                pl[l] = ((2 * l - 1) * c * pl[l - 1] - (l - 1) * pl[l - 2]) / l;
            for (int l = 0; l < count; l++)
                chi[l] += f * pl[l];
        }
    }
    free(pl);
}

/* lambda_l^m(mu) for l = m..L-1 into lam[l] (lam[l < m] = 0). */
static void assoc_legendre(int m, int L, double mu, double *lam)
{
    for (int l = 0; l < L; l++)
        lam[l] = 0.0;
    double s = sqrt(fmax(1.0 - mu * mu, 0.0)), v = 1.0;
    for (int k = 1; k <= m; k++)
        v *= sqrt((2.0 * k - 1.0) / (2.0 * k)) * s;
    if (m >= L)
        return;
    lam[m] = v;
    if (m + 1 < L)
        lam[m + 1] = mu * sqrt(2.0 * m + 1.0) * v;
    for (int l = m + 2; l < L; l++)
        lam[l] = ((2.0 * l - 1.0) * mu * lam[l - 1] -
                  sqrt((double)(l - 1) * (l - 1) - (double)m * m) * lam[l - 2]) /
                 sqrt((double)l * l - (double)m * m);
}

static double ex1(double x) { return fabs(x) < 1e-8 ? 1.0 + 0.5 * x : expm1(x) / x; }

/* c = a b (n x n, row-major), with the diagonal wd between them when wd is not NULL. */
static void mat_mul(int n, const double *a, const double *wd, const double *b, double *c)
{
    for (int i = 0; i < n; i++) {
        double *ci = c + (size_t)i * n;
        for (int j = 0; j < n; j++)
            ci[j] = 0.0;
        for (int k = 0; k < n; k++) {
            double f = a[(size_t)i * n + k] * (wd ? wd[k] : 1.0);
            if (f == 0.0)
                continue;
            const double *bk = b + (size_t)k * n;
            for (int j = 0; j < n; j++)
                ci[j] += f * bk[j];
        }
    }
}

/* Solves a x = b in place (b: n x n right-hand sides, a destroyed), partial pivoting. */
static int mat_solve(int n, double *a, double *b)
{
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(a[(size_t)r * n + c]) > fabs(a[(size_t)piv * n + c]))
                piv = r;
        if (a[(size_t)piv * n + c] == 0.0)
            return -1;
        if (piv != c)
            for (int j = 0; j < n; j++) {
                double t = a[(size_t)c * n + j];
                a[(size_t)c * n + j] = a[(size_t)piv * n + j], a[(size_t)piv * n + j] = t;
                t = b[(size_t)c * n + j];
                b[(size_t)c * n + j] = b[(size_t)piv * n + j], b[(size_t)piv * n + j] = t;
            }
        for (int r = 0; r < n; r++) {
            if (r == c)
                continue;
            double f = a[(size_t)r * n + c] / a[(size_t)c * n + c];
            if (f == 0.0)
                continue;
            for (int j = c; j < n; j++)
                a[(size_t)r * n + j] -= f * a[(size_t)c * n + j];
            for (int j = 0; j < n; j++)
                b[(size_t)r * n + j] -= f * b[(size_t)c * n + j];
        }
    }
    for (int r = 0; r < n; r++) {
        double d = a[(size_t)r * n + r];
        for (int j = 0; j < n; j++)
            b[(size_t)r * n + j] /= d;
    }
    return 0;
}

static double scatter_cos(double mu_out, double mu0, double phi, int reflected)
{
    double s = sqrt(fmax(1.0 - mu_out * mu_out, 0.0)) * sqrt(fmax(1.0 - mu0 * mu0, 0.0));
    return (reflected ? -mu_out * mu0 : mu_out * mu0) + s * cos(phi);
}

/* Single scattering, reflected or transmitted, of a slab (omega p at the view's angle). */
static double single(double op, double tau, double mu, double mu0, int reflected)
{
    if (reflected)
        return op * mu0 / (mu + mu0) * -expm1(-tau * (1.0 / mu + 1.0 / mu0));
    return op * (tau / mu) * exp(-tau / mu0) * ex1(tau * (mu - mu0) / (mu * mu0));
}

int slab_solve(const slab_problem *p, int nv, const double *mu_v, const double *phi_v,
               double *refl, double *trans, slab_fluxes *fl)
{
    int N = p->streams, M = p->moments ? p->moments : 2 * N, n = N + 1 + nv, rc = -1;
    if (N < 1 || M > 2 * N || nv > SLAB_MAX_VIEWS || p->mu0 <= 0.0 || p->mu0 > 1.0 || p->tau <= 0.0)
        return -1;
    size_t nn = (size_t)n * n;
    double *chi = malloc(sizeof *chi * (size_t)(M + 1)), *mu = malloc(sizeof *mu * (size_t)n);
    double *w = calloc((size_t)n, sizeof *w), *lam = malloc(sizeof *lam * (size_t)n * M);
    double *buf = malloc(sizeof *buf * nn * 9), *e = malloc(sizeof *e * (size_t)n);
    double *x = malloc(sizeof *x * (size_t)N), *gw = malloc(sizeof *gw * (size_t)N);
    if (!chi || !mu || !w || !lam || !buf || !e || !x || !gw)
        goto done;
    double *R = buf, *T = R + nn, *Q = T + nn, *S = Q + nn, *A = S + nn, *D = A + nn, *U = D + nn;
    double *t1 = U + nn, *t2 = t1 + nn;

    /* delta-M */
    slab_moments(p->phase, p->ctx, M + 1, chi);
    double f = chi[M] / chi[0];
    for (int l = 0; l < M; l++)
        chi[l] = (chi[l] / chi[0] - f) / (1.0 - f);
    double tau = (1.0 - p->omega * f) * p->tau, omega = p->omega * (1.0 - f) / (1.0 - p->omega * f);
    int doublings = 0;
    while (ldexp(tau, -doublings) > 1e-10)
        doublings++;
    double tau0 = ldexp(tau, -doublings);

    atmo_gauss_legendre(N, x, gw);
    for (int i = 0; i < N; i++)
        mu[i] = 0.5 * (x[i] + 1.0), w[i] = 0.5 * gw[i];
    mu[N] = p->mu0;
    for (int i = 0; i < nv; i++)
        mu[N + 1 + i] = mu_v[i];
    for (int i = 0; i < n; i++)
        if (!(mu[i] > 0.0 && mu[i] <= 1.0))
            goto done;
    for (int i = 0; i < nv; i++)
        refl[i] = trans[i] = 0.0;
    double po[SLAB_MAX_VIEWS], ps[SLAB_MAX_VIEWS];

    int quiet = 0; /* modes in a row whose multiple scattering is below SLAB_MODE_TOLERANCE */
    for (int m = 0; m < M && quiet < 3; m++) {
        double cm = m == 0 ? 2.0 * M_PI : M_PI, k = (m == 0 ? 1.0 : 2.0) / (4.0 * M_PI);
        for (int i = 0; i < n; i++)
            assoc_legendre(m, M, mu[i], lam + (size_t)i * M);
        for (int i = 0; i < n; i++) {
            const double *li = lam + (size_t)i * M;
            for (int j = 0; j < n; j++) {
                const double *lj = lam + (size_t)j * M;
                double same = 0.0, opposite = 0.0; /* p^m(mu_i, mu_j), p^m(-mu_i, mu_j) */
                for (int l = m; l < M; l++) {
                    double t = (2 * l + 1) * chi[l] * li[l] * lj[l];
                    same += t;
                    opposite += (l + m) % 2 ? -t : t; /* lambda(-mu) = (-1)^(l+m) lambda(mu) */
                }
                double mi = mu[i], mj = mu[j];
                if (i > N && j == N)
                    po[i - N - 1] = k * opposite, ps[i - N - 1] = k * same;
                R[(size_t)i * n + j] = omega * cm * k * opposite * mj / (mi + mj) *
                                       -expm1(-tau0 * (1.0 / mi + 1.0 / mj));
                T[(size_t)i * n + j] = omega * cm * k * same * (tau0 / mi) * exp(-tau0 / mj) *
                                       ex1(tau0 * (mi - mj) / (mi * mj));
            }
            e[i] = exp(-tau0 / mu[i]);
        }
        for (int d = 0; d < doublings; d++) {
            mat_mul(n, R, w, R, Q);
            for (size_t q = 0; q < nn; q++) /* A = I - Q W */
                A[q] = -Q[q] * w[q % (size_t)n];
            for (int i = 0; i < n; i++)
                A[(size_t)i * n + i] += 1.0;
            memcpy(S, Q, sizeof *S * nn);
            if (mat_solve(n, A, S))
                goto done;
            mat_mul(n, S, w, T, D); /* D = T + S e + S W T */
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                    D[(size_t)i * n + j] += T[(size_t)i * n + j] + S[(size_t)i * n + j] * e[j];
            mat_mul(n, R, w, D, U); /* U = R e + R W D */
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                    U[(size_t)i * n + j] += R[(size_t)i * n + j] * e[j];
            mat_mul(n, T, w, U, t1); /* R' = R + e U + T W U */
            mat_mul(n, T, w, D, t2); /* T' = e D + T e + T W D */
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    size_t q = (size_t)i * n + j;
                    double r_new = R[q] + e[i] * U[q] + t1[q];
                    T[q] = e[i] * D[q] + T[q] * e[j] + t2[q];
                    R[q] = r_new;
                }
            for (int i = 0; i < n; i++) /* e^2, computed anew (squaring would double its
                                           rounding error at every step) */
                e[i] = exp(-ldexp(tau0, d + 1) / mu[i]);
        }
        /* the mode of the multiple scattering: the truncated problem's radiance less its
         * single scattering (po, ps: omega' p'^m at the view for the beam) */
        double largest = 0.0;
        for (int v = 0; v < nv; v++) {
            int i = N + 1 + v;
            size_t q = (size_t)i * n + N;
            double mv = mu[i], ms_r = R[q] / cm - single(omega * po[v], tau, mv, p->mu0, 1);
            double ms_t = T[q] / cm - single(omega * ps[v], tau, mv, p->mu0, 0);
            refl[v] += ms_r * cos(m * phi_v[v]);
            trans[v] += ms_t * cos(m * phi_v[v]);
            largest = fmax(largest, fmax(fabs(ms_r) / fmax(fabs(refl[v]), 1e-300),
                                         fabs(ms_t) / fmax(fabs(trans[v]), 1e-300)));
        }
        quiet = largest < SLAB_MODE_TOLERANCE ? quiet + 1 : 0;
        if (m == 0 && fl) {
            fl->reflected = fl->diffuse = 0.0;
            for (int i = 0; i < N; i++) {
                fl->reflected += w[i] * mu[i] * R[(size_t)i * n + N] / p->mu0;
                fl->diffuse += w[i] * mu[i] * T[(size_t)i * n + N] / p->mu0;
            }
            fl->direct = exp(-tau / p->mu0);
            fl->truncated = f;
        }
    }
    for (int v = 0; v < nv; v++) { /* TMS: the exact single scattering */
        double cr = scatter_cos(mu_v[v], p->mu0, phi_v[v], 1);
        double ct = scatter_cos(mu_v[v], p->mu0, phi_v[v], 0);
        double k = p->omega / (1.0 - p->omega * f);
        refl[v] += single(k * p->phase(cr, p->ctx), tau, mu_v[v], p->mu0, 1);
        trans[v] += single(k * p->phase(ct, p->ctx), tau, mu_v[v], p->mu0, 0);
    }
    rc = 0;
done:
    free(gw), free(x), free(e), free(buf), free(lam), free(w), free(mu), free(chi);
    return rc;
}
