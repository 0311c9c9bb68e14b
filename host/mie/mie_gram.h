/* mie_gram.h — radius sums of Mie intensities as quadratic forms (host/mie/mie_gram.c). */
#ifndef ATMO_MIE_GRAM_H
#define ATMO_MIE_GRAM_H
#include "atmo/status.h"

/* E and D: n x n, row-major, upper triangles (j >= i) used. */
typedef struct mie_gram {
    int n;
    double *e, *d;
} mie_gram;

int mie_gram_alloc(mie_gram *g, int n, atmo_err *e);
void mie_gram_free(mie_gram *g);
void mie_gram_zero(mie_gram *g);
/* dst += src, upper triangles */
void mie_gram_add(mie_gram *dst, const mie_gram *src);
/* E += Xe^T Xe, D += Xd^T Xd over `rows` rows (a multiple of 4) of length ld, of which the first
 * m columns (m <= g->n) may be non-zero. */
void mie_gram_update(mie_gram *g, int rows, int m, int ld, const double *xe, const double *xd);
/* acc[j] = (phi+^T E phi+ + phi-^T D phi-) / 4 at cosine mu[j], j = 0..n_mu-1, summing the
 * first m terms (phi+- = pi_n +- tau_n). */
int mie_gram_eval(const mie_gram *g, int m, int n_mu, const double *mu, double *acc, atmo_err *e);

#endif
