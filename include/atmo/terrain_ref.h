/* terrain_ref.h — the terrain's height field and ray hits in double precision on the host
 * (host/terrain/terrain_ref.c): the oracle of the kernels' float terrain (kernels/terrain/). */
#ifndef ATMO_TERRAIN_REF_H
#define ATMO_TERRAIN_REF_H
#include "atmo/gpu_terrain.h"

/* h = H coverage e at planar (u, v) metres (kernels/terrain/noise.h), its gradient in grad[2]
 * (may be NULL), and the coverage in *coverage (may be NULL). */
double terrain_ref_height(const atmo_gpu_terrain_field *f, double u, double v, double grad[2],
                          double *coverage);

/* The domain warp's stretch at planar (u, v) metres: the spectral norm of the Jacobian of the
 * fBm's warped lattice point in the unwarped one (kernels/terrain/noise.h's
 * terrain_warp_stretch); 1 without a warp. */
double terrain_ref_warp_stretch(const atmo_gpu_terrain_field *f, double u, double v);

/* The detail below a DEM's cells (kernels/terrain/terrain_detail.h) at (u, v) and its gradient
 * in grad[2] (may be NULL); 0 where the field has none. */
double terrain_ref_detail(const atmo_gpu_terrain_field *f, double u, double v, double grad[2]);

/* The height field as the kernels' lookups define it over a heightmap (terrain.h): inside the
 * square of texel centres the bilinear interpolation (in double) of the float texels hm (the
 * float format: one height per texel) plus the detail, else terrain_ref_height. hm NULL: always
 * terrain_ref_height. */
double terrain_ref_height_map(const atmo_gpu_terrain_field *f, const float *hm, double u,
                              double v);

/* The surface's altitude above the ground sphere of radius R at the world point p (metres, Y
 * up, planet centre (0, -R, 0)) minus the surface's height there, max(h, sea level): > 0
 * above the terrain or the water. */
double terrain_ref_clearance(const atmo_gpu_terrain_field *f, double R, double sea_level_m,
                             const double p[3]);
/* The same over a heightmap (terrain_ref_height_map). */
double terrain_ref_clearance_map(const atmo_gpu_terrain_field *f, const float *hm, double R,
                                 double sea_level_m, const double p[3]);

/* The first hit of the world ray o + t d (d unit), 0 < t <= t_max, found by marching steps of
 * `step` metres (shorter where the clearance allows none smaller) and bisecting the bracket to
 * 1e-9 relative (a ray above the highest terrain and rising ends there); returns 1 and *t on a
 * hit. *min_clearance gets the smallest clearance seen
 * along a ray that misses (how close it skimmed). */
int terrain_ref_hit(const atmo_gpu_terrain_field *f, double R, double sea_level_m,
                    const double o[3], const double d[3], double t_max, double step, double *t,
                    double *min_clearance);
/* The same over a heightmap (terrain_ref_height_map; the shell's top includes the detail). */
int terrain_ref_hit_map(const atmo_gpu_terrain_field *f, const float *hm, double R,
                        double sea_level_m, const double o[3], const double d[3], double t_max,
                        double step, double *t, double *min_clearance);

#endif
