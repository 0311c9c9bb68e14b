/* plan_terrain.h — the plan's part for the procedural terrain (kernels/terrain/;
 * host/features/terrain/plan_terrain.c). */
#ifndef ATMO_PLAN_TERRAIN_H
#define ATMO_PLAN_TERRAIN_H
#include "atmo/plan.h"

/* Device memory at most given to the heightmap (a usage error beyond it). */
#define ATMO_TERRAIN_HEIGHTMAP_MAX_BYTES ((size_t)1 << 30)

/* Fills gpu.terrain from the scene's terrain.* keys and the camera, declares the buffer
 * heightmap (a 16-byte placeholder for direct evaluation) and, with a heightmap, its pass
 * terrain_heightmap (feature "terrain" of host/features/, planned when terrain.enabled). */
int atmo_plan_terrain(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* With terrain.sun_visibility = map, outside path mode (feature "terrain_sun_map", flag
 * -DATMO_TERRAIN_SUN_MAP; host/features/terrain/plan_terrain_sun.c): fills gpu.terrain's
 * sun_map_* (the map's frame from the camera's vertical and the sun) and declares the buffer
 * terrain_sun_map (N x N floats, following the view) and its pass terrain_sun_map_rows; with
 * the sun below the camera's horizon (or at its zenith) the map is empty (sun_map_size 0) and
 * every point marches. */
int atmo_plan_terrain_sun_map(const atmo_scene *s, atmo_plan *p, atmo_err *e);

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

/* After atmo_plan_terrain (and the DEM's base, for terrain.heightmap_file): the terrain's
 * height above sea level at planar (u, v) as the renderer draws it: a DEM's heightmap texels
 * read back bilinearly (kernels/terrain/terrain.h's terrain_height_at, float) inside the
 * heightmap's square, the double-precision procedural field (host/terrain/terrain_ref.c)
 * elsewhere and without a DEM. */
double atmo_plan_terrain_height(const atmo_plan *p, double u, double v);

/* The world Y of the terrain's surface (at least sea level) over world (x, z), planet radius R
 * (plan_terrain.c). */
double atmo_plan_terrain_surface_y(const atmo_plan *p, double R, double x, double z);

/* The bound on |grad h| the sphere tracer sizes its steps by, the detail's included
 * (plan_terrain.c). */
double atmo_terrain_slope_bound(const atmo_gpu_terrain_field *f);

/* Under the domain warp, the fBm's slope bound per unit of the warp's stretch ||J|| (L_F), and
 * how fast L_F ||J|| can grow per metre along a ray; both 0 without a warp (plan_terrain.c). */
double atmo_terrain_stretch_slope(const atmo_gpu_terrain_field *f);
double atmo_terrain_slope_growth(const atmo_gpu_terrain_field *f);

#endif
