/* plan_terrain.h — the plan's part for the procedural terrain (kernels/terrain/;
 * host/plan/plan_terrain.c). */
#ifndef ATMO_PLAN_TERRAIN_H
#define ATMO_PLAN_TERRAIN_H
#include "atmo/plan.h"

/* Device memory at most given to the heightmap (a usage error beyond it). */
#define ATMO_TERRAIN_HEIGHTMAP_MAX_BYTES ((size_t)1 << 30)

/* Fills gpu.terrain from the scene's terrain.* keys and the camera, declares the buffer
 * heightmap (a 16-byte placeholder for direct evaluation) and, with a heightmap, its pass
 * terrain_heightmap (feature "terrain" of features.c, planned when terrain.enabled). */
int atmo_plan_terrain(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* For a loader of real terrain (host/terrain/dem*.c): after atmo_plan_make of a scene with
 * terrain and a heightmap, hand the heightmap pass a height grid of nx x nz samples in metres
 * above sea level (row-major in z, kept alive by the caller or owned by the plan through
 * atmo_plan_own), its first sample at planar (x0, z0) and spacing (dx, dz) in metres, and the
 * fBm's share `detail` added over it (0: the grid alone). The grid travels as the host table
 * terrain_base and joins the heightmap's cache key; points beyond the heightmap's square stay
 * procedural. */
int atmo_plan_terrain_base(atmo_plan *p, const float *heights, int nx, int nz, double x0,
                           double z0, double dx, double dz, double detail, atmo_err *e);

/* After atmo_plan_terrain_base: the fBm's octaves below cells of cell_m metres are added to
 * the heightmap's lookups (kernels/terrain/terrain_detail.h: the first octave whose lattice
 * period is at most cell_m / 2, TERRAIN_DETAIL_OCTAVES of them, at the fBm's own gain), the
 * sphere tracer's slope bound grows by theirs and its step budget doubles. */
int atmo_plan_terrain_detail(atmo_plan *p, double cell_m, atmo_err *e);

/* The bound on |grad h| the sphere tracer sizes its steps by, the detail's included
 * (plan_terrain.c). */
double atmo_terrain_slope_bound(const atmo_gpu_terrain_field *f);

#endif
