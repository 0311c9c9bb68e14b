/* spectral.h — the spectral tables of data/ (embedded at build time), looked up in double.
 *
 * Tables (sources in data/README.md): CIE 1931 2-degree colour matching functions (5 nm),
 * ASTM G-173 extraterrestrial solar irradiance (10 nm bin means), O3 cross-section at 233 K
 * (10 nm bin means), water refractive index (Segelstein 1981: n, k; Daimon & Masumura 2007: n).
 * Lookups interpolate linearly between nodes and clamp to the end values outside the table,
 * except where a function says otherwise. */
#ifndef ATMO_SPECTRAL_H
#define ATMO_SPECTRAL_H

typedef struct spectral_table {
    int rows, columns;  /* columns counts the wavelength column */
    double *values;     /* rows x columns, row-major, column 0 = wavelength in nm */
} spectral_table;

/* Parsed embedded table by file name ("data/cie1931_2deg_cmf.csv"); the tables are parsed once,
 * at the first call from any thread, and kept for the life of the process, so any thread may
 * call this (and the lookups below) at any time. Returns NULL if the name is unknown (a build
 * error, not a user error). */
const spectral_table *spectral_table_get(const char *name);

/* Linear interpolation of column c at lambda, clamped to the end rows. */
double spectral_table_lookup(const spectral_table *t, int c, double lambda_nm);

/* Solar spectral irradiance at the top of the atmosphere, W m^-2 nm^-1 (ASTM G-173). */
double spectral_solar_irradiance(double lambda_nm);

/* O3 absorption cross-section at 233 K, m^2 per molecule. */
double spectral_ozone_cross_section_m2(double lambda_nm);

/* Number density of ozone at the peak of the tent profile for a column of `dobson` DU spread
 * over a tent 15 km wide (Bruneton 2017: 300 DU -> 5.374e18 m^-3). 1 DU = 2.687e20 m^-2. */
double spectral_ozone_peak_density_per_m3(double dobson, double tent_width_m);

#endif
