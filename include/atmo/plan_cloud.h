/* plan_cloud.h — the plan's part for the homogeneous cloud shell and the observer sphere
 * (kernels/cloud_shell/cloud_shell.h; host/features/cloud_shell/plan_cloud.c). */
#ifndef ATMO_PLAN_CLOUD_H
#define ATMO_PLAN_CLOUD_H
#include "atmo/plan.h"

/* Steps equal in optical depth per cloud segment of a view ray. */
#define ATMO_CLOUD_STEPS 32

/* Bulk optics of a droplet size distribution at the render wavelengths (Mie tables built once,
 * then read from the disk cache) and its phase tables packed in phase_table.h's format. */
typedef struct atmo_mie_optics {
    double sigma_ext_per_lwc[3]; /* 1/m per g/m^3 */
    double albedo[3], g[3];
    double diameter_um;          /* effective diameter, clamped to Jendersie-d'Eon's 5-50 um */
    float4 *rows;                /* rows (P_0, P_1, P_2, theta), owned by the plan */
    int count;
} atmo_mie_optics;

/* The optics of the distribution `dsd` (a preset name or a SPEC of mie_dsd_parse; the scene
 * key `key` that holds it names it in the one-line error of a bad one), convolved with the
 * sun's disc when sun_disc is 1. */
int atmo_plan_mie_optics(const atmo_scene *s, const char *key, const char *dsd, int sun_disc,
                         atmo_plan *p, atmo_mie_optics *out, atmo_err *e);

/* Normalises a table of `n` rows (phase_table.h's format) so each channel's interpolant
 * integrates to 4 pi and fills *cdf (n floats, owned by the plan) with the sampling CDF of its
 * middle channel (phase_table.h). */
int atmo_plan_phase_cdf(float4 *rows, int n, atmo_plan *p, float **cdf, atmo_err *e);

/* When the scene enables the cloud or the observer: checks the method (single, march or, for
 * the cloud without an observer, reference), builds (or loads from the cache) the Mie tables
 * at the render wavelengths into the buffers cloud_phase_table and cloud_phase_cdf and fills
 * gpu.cloud (feature "cloud" of host/features/, which is planned only when the scene has a cloud
 * or an observer). */
int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
