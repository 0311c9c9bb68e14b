/* mie_water.c — complex refractive index of liquid water for the Mie solver.
 *
 * m = n + i k (k >= 0 absorbing) at a vacuum wavelength in nm, from the embedded tables of data/:
 *   n: Daimon & Masumura 2007 (20 C, Sellmeier fit, ~1e-5) where it is tabulated, 200-1125 nm,
 *      linear between its 5 nm nodes; Segelstein 1981 above 1125 nm. Segelstein's n is off by up
 *      to 0.006 in the visible (data/README.md), which moves the fog bow by ~1 degree.
 *   k: Segelstein 1981, interpolated linearly in log k between the source's own nodes (k spans
 *      orders of magnitude; linear interpolation would overstate it between nodes).
 * Valid for 200-2500 nm (the range of Segelstein's table here). */
#include <math.h>
#include "atmo/mie.h"
#include "atmo/spectral.h"

#define MIE_WATER_SEGELSTEIN "data/water_refractive_index.csv"
#define MIE_WATER_DAIMON "data/water_refractive_index_n_daimon2007_20C.csv"

/* log-linear interpolation of column c (positive values) at lambda, inside the table */
static double mie_loglinear(const spectral_table *t, int c, double lambda_nm)
{
    const double *v = t->values;
    int w = t->columns, lo = 0, hi = t->rows - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (v[mid * w] <= lambda_nm)
            lo = mid;
        else
            hi = mid;
    }
    double s = (lambda_nm - v[lo * w]) / (v[hi * w] - v[lo * w]);
    return exp(log(v[lo * w + c]) + s * (log(v[hi * w + c]) - log(v[lo * w + c])));
}

int mie_water_index(double wavelength_nm, double *n, double *k, atmo_err *e)
{
    const spectral_table *seg = spectral_table_get(MIE_WATER_SEGELSTEIN);
    const spectral_table *dai = spectral_table_get(MIE_WATER_DAIMON);
    if (!seg || !dai)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "water refractive index tables missing from the build");
    double lo = seg->values[0], hi = seg->values[(seg->rows - 1) * seg->columns];
    if (!(wavelength_nm >= lo && wavelength_nm <= hi))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "wavelength %g nm is outside the water index table (%g-%g nm); give "
                         "--index N+Ki for other wavelengths", wavelength_nm, lo, hi);
    double dhi = dai->values[(dai->rows - 1) * dai->columns];
    *n = wavelength_nm <= dhi ? spectral_table_lookup(dai, 1, wavelength_nm)
                              : spectral_table_lookup(seg, 1, wavelength_nm);
    *k = mie_loglinear(seg, 2, wavelength_nm);
    return ATMO_OK;
}
