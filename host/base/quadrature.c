/* quadrature.c — Gauss-Legendre nodes and weights (atmo/quadrature.h).
 *
 * Node i is a root of the Legendre polynomial P_n, found by Newton's method from the guess
 * cos(pi (i + 3/4) / (n + 1/2)); P_n and P_{n-1} come from the recurrence
 *     l P_l = (2l - 1) z P_{l-1} - (l - 1) P_{l-2},
 * the derivative from (z^2 - 1) P_n' = n (z P_n - P_{n-1}), and the weight is
 *     w_i = 2 / ((1 - z_i^2) P_n'(z_i)^2). */
#include <math.h>
#include "atmo/quadrature.h"

void atmo_gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = z;
            for (int l = 2; l <= n; l++) {
                double p2 = ((2.0 * l - 1.0) * z * p1 - (l - 1.0) * p0) / l;
                p0 = p1, p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-15)
                break;
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}
