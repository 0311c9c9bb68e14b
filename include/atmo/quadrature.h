/* quadrature.h — Gauss-Legendre quadrature for the host's double-precision integrals. */
#ifndef ATMO_QUADRATURE_H
#define ATMO_QUADRATURE_H

/* The n nodes x[] (descending) and weights w[] of n-point Gauss-Legendre quadrature on
 * (-1, 1): int_{-1}^{1} f dx ~ sum w_i f(x_i), exact for polynomials of degree <= 2n - 1. */
void atmo_gauss_legendre(int n, double *x, double *w);

#endif
