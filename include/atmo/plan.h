/* plan.h — from a validated scene to what the device needs.
 *
 * The plan assembles the features the scene contains from the registry (atmo/features.h): their
 * kernel fragments in registry order, their -D flags, their named buffers and their precompute
 * passes, and fills the typed GPU structs of gpu_types.h from the scene's double-precision
 * values: the atmosphere at the render wavelengths, the camera basis and its distance to the
 * planet centre (computed in double, so planet-scale coordinates never reach a kernel), the sun
 * direction, and the factors that turn radiance into the output quantity.
 *
 * Buffers are named: the plan generates, in `prelude` (source placed before the fragments),
 *   #define ATMO_LUT_PARAMS      ATMO_GLOBAL const T0 *name0, ATMO_GLOBAL const T1 *name1, ...
 *   #define ATMO_LUT_OUT_PARAMS  ATMO_GLOBAL T0 *name0, ATMO_GLOBAL T1 *name1, ...
 *   #define ATMO_LUT_ARGS        name0, name1, ...
 * for the buffers of the assembled features in plan order (and the numbers of the media's
 * scattering components, MEDIA_COMPONENTS and MEDIA_<name>, kernels/media/media.h), so every sky kernel takes
 * (scene, <the named buffers>, its own args), every precompute kernel (scene, <the named
 * buffers>, int arg), and a method's code refers to its buffers by name. The host binds them
 * from the plan's buffer list in the same order (atmo_bind_buffers, atmo/render.h). */
#ifndef ATMO_PLAN_H
#define ATMO_PLAN_H
#include <stddef.h>
#include "atmo/atmosphere.h"
#include "atmo/dem.h"
#include "atmo/gpu_types.h"
#include "atmo/scene.h"
#include "atmo/status.h"

#define ATMO_PLAN_MAX_FRAGMENTS 96
#define ATMO_PLAN_MAX_PASSES 64
#define ATMO_PLAN_MAX_BUFFERS 12
#define ATMO_PLAN_MAX_FEATURES 32
#define ATMO_PLAN_MAX_OWNED 4
#define ATMO_PLAN_COMPOSE_GROUPS 8 /* ATMO_COMPOSE_GROUPS of atmo/features.h */

/* A named device buffer. bytes == 0: the feature declares it but this scene needs no data in it
 * (e.g. the sky-view LUT of a camera above the atmosphere); a 16-byte placeholder is bound,
 * since OpenCL has no empty buffers. */
typedef struct atmo_plan_buffer {
    const char *name;      /* the kernels' parameter name, e.g. "ms_lut" */
    const char *type;      /* element type in the kernels, e.g. "float4" */
    size_t bytes;
    int follows_view;      /* holds one camera and sun: recomputed per view, never cached */
    const void *host_data; /* a host table copied in before the passes (bytes long), or NULL;
                              static or owned by the plan (atmo_plan_own) */
    int feature;           /* index in plan->features of the feature that owns it */
} atmo_plan_buffer;

/* One precompute launch: kernel(scene, <buffers>, arg) over width x height x depth items; it
 * writes buffers of its feature (and reads those of the features the registry row needs). */
typedef struct atmo_plan_pass {
    const char *kernel;
    int width, height, depth;
    int arg;
    int feature;           /* index in plan->features */
} atmo_plan_pass;

struct atmo_feature;

typedef struct atmo_plan {
    atmo_gpu_scene gpu;
    atmo_atmosphere atmosphere;
    const char *method;            /* the atmosphere method's name, for reports */
    const char *render_kernel;     /* the kernel a session renders with: sky_render, or
                                      path_render in path mode (same arguments) */
    int pass_planes;               /* render passes: float4 planes the kernel also sums into
                                      (an argument after nonfinite), 0 for none */
    const struct atmo_feature *features[ATMO_PLAN_MAX_FEATURES]; /* in registry order */
    int feature_count;
    const char *fragments[ATMO_PLAN_MAX_FRAGMENTS];
    unsigned char fragment_group[ATMO_PLAN_MAX_FRAGMENTS]; /* a generated fragment's group
                                      (its text composed[group]), 0 for an embedded file */
    int fragment_count;
    char defines[256];
    char prelude[1024];            /* generated: the buffer parameter and argument lists, the
                                      media's components */
    char composed[ATMO_PLAN_COMPOSE_GROUPS][8192]; /* generated: the slots' composition
                                      (atmo/features.h, atmo_compose), per group */
    atmo_plan_buffer buffers[ATMO_PLAN_MAX_BUFFERS];
    int buffer_count;
    atmo_plan_pass passes[ATMO_PLAN_MAX_PASSES];
    int pass_count;
    int cache_luts;                /* disk cache of precomputed buffers: 0 off, 1 those whose
                                      passes took > 20 ms, 2 all */
    int cache_tables;              /* host tables built while planning (Mie phase tables) go
                                      through the disk cache: 0 off, 1 on */
    void *owned[ATMO_PLAN_MAX_OWNED]; /* heap blocks the host tables live in (atmo_plan_own) */
    int owned_count;
    atmo_dem dem;                  /* the scene's terrain.heightmap_file, read and checked while
                                      planning (width 0: none); the terrain's heightmap pass
                                      resamples it (atmo_dem_resample) into its host table */
    int width, height, samples;
} atmo_plan;

/* Plan a validated scene. On failure nothing is left to release; on success the caller
 * releases the plan with atmo_plan_free once no session or probe opened with it is left. */
int atmo_plan_make(const atmo_scene *s, atmo_plan *p, atmo_err *e);
/* The method atmosphere.method = auto plans the scene with (atmo_plan_make resolves it): march
 * where the scene has a medium that fast and lut do not integrate (the fBm cloud layer as a
 * medium of the methods, the cloud shell, the observer; march is the cheapest method with
 * multiple scattering that does), else fast. *why (unless NULL) says which, for the user. */
int atmo_plan_auto_method(const atmo_scene *s, const char **why);
/* The camera's world position in metres for scene s as plan p (made from s) places it:
 * camera.position_m, its y above the terrain's surface with camera.on_terrain. */
void atmo_plan_camera_world(const atmo_plan *p, const atmo_scene *s, double out[3]);
/* *out = s with its camera placed in the world (camera.on_terrain off, position_m absolute),
 * from a plan of s; for callers that move the camera in world metres (the viewer). */
int atmo_plan_place_camera(const atmo_scene *s, atmo_scene *out, atmo_err *e);
/* atmo_plan_make with the disk caches chosen: cache_luts as the field of that name (plain
 * atmo_plan_make: 0, for the caller to set), cache_tables for the host tables (plain: 1). */
int atmo_plan_make_cached(const atmo_scene *s, int cache_luts, int cache_tables, atmo_plan *p,
                          atmo_err *e);
/* Release what the plan owns (its host tables, the DEM) and zero it. */
void atmo_plan_free(atmo_plan *p);
/* For a feature's plan function: the plan takes the heap block (malloc'd) that a host table
 * lives in and frees it in atmo_plan_free; on failure the block is freed at once. */
int atmo_plan_own(atmo_plan *p, void *block, atmo_err *e);

/* For a feature's plan function (features.h): declare a buffer or a pass of the feature being
 * planned (the last one in p->features). */
int atmo_plan_add_buffer(atmo_plan *p, const char *name, const char *type, size_t bytes,
                         int follows_view, const void *host_data, atmo_err *e);
int atmo_plan_add_pass(atmo_plan *p, const char *kernel, int width, int height, int depth, int arg,
                       atmo_err *e);
/* The buffer with this name, or NULL. */
atmo_plan_buffer *atmo_plan_buffer_find(atmo_plan *p, const char *name);
/* The fragments' texts for atmo_cl_build_options.texts: texts[i] = the generated text of
 * fragment i (in p, so p must outlive them), NULL for an embedded file. */
void atmo_plan_fragment_texts(const atmo_plan *p, const char *texts[ATMO_PLAN_MAX_FRAGMENTS]);
/* Its index in p->buffers (the order of ATMO_LUT_PARAMS), or -1. */
int atmo_plan_buffer_index(const atmo_plan *p, const char *name);

/* Unit vector towards the sun for zenith and azimuth in degrees (scene.h's convention). */
void atmo_sun_direction(double zenith_deg, double azimuth_deg, double out[3]);

/* Camera basis of the thesis' Euler angles (presets.md): forward, right, up. */
void atmo_camera_basis(double pitch_deg, double yaw_deg, double forward[3], double right[3],
                       double up[3]);

#endif
