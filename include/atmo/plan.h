/* plan.h — from a validated scene to what the device needs.
 *
 * The plan decides which kernels exist (only those the scene needs are assembled), the sizes of
 * the LUTs, and fills the float structs of gpu_types.h from the scene's double-precision values:
 * the atmosphere at the render wavelengths, the camera basis and its distance to the planet
 * centre (computed in double, so planet-scale coordinates never reach a kernel), the sun
 * direction, and the factors that turn radiance into the output quantity. */
#ifndef ATMO_PLAN_H
#define ATMO_PLAN_H
#include "atmo/atmosphere.h"
#include "atmo/gpu_types.h"
#include "atmo/scene.h"
#include "atmo/status.h"

#define ATMO_PLAN_MAX_FRAGMENTS 32
#define ATMO_PLAN_MAX_PASSES 64
#define ATMO_PLAN_LUTS 4 /* LUT buffers every sky kernel gets (kernels/atmosphere/sky_method.h) */

/* One precompute launch: kernel(scene, lut0..lut3, arg) over width x height x depth items. */
typedef struct atmo_plan_pass {
    const char *kernel;
    int width, height, depth;
    int arg;
    int follows_view; /* writes a LUT that holds one camera and sun: runs even on a cache hit */
} atmo_plan_pass;

/* Host data copied into a LUT buffer before the passes run (e.g. a phase table computed on
 * the host), at a byte offset: features that need tables place them after the method's data in
 * buffer 0, behind the transmittance LUT, and find them there by an offset in the scene. */
typedef struct atmo_plan_upload {
    int lut;            /* buffer index 0..ATMO_PLAN_LUTS-1 */
    size_t offset;      /* bytes */
    size_t bytes;
    const void *data;   /* must outlive the render */
    void *owned;        /* data when the plan owns it (atmo_plan_free releases it), else NULL */
} atmo_plan_upload;

#define ATMO_PLAN_MAX_UPLOADS 4

typedef struct atmo_plan {
    atmo_gpu_scene gpu;
    atmo_atmosphere atmosphere;
    const char *method;            /* the atmosphere method's name, for reports */
    const char *fragments[ATMO_PLAN_MAX_FRAGMENTS];
    int fragment_count;
    char defines[256];
    size_t lut_bytes[ATMO_PLAN_LUTS]; /* 0: unused (a dummy is bound) */
    atmo_plan_pass passes[ATMO_PLAN_MAX_PASSES];
    int pass_count;
    atmo_plan_upload uploads[ATMO_PLAN_MAX_UPLOADS];
    int upload_count;
    int cache_luts;                /* disk cache of LUTs: 0 off, 1 those that took > 0.5 s, 2 all */
    int lut_follows_view[ATMO_PLAN_LUTS]; /* buffer holds one camera and sun: never cached */
    int width, height, samples;
} atmo_plan;

int atmo_plan_make(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* Releases what the plan owns (its uploads' host tables); the plan is empty afterwards. Safe on
 * a plan that atmo_plan_make failed on or that owns nothing. */
void atmo_plan_free(atmo_plan *p);

/* A method's part of the plan: it appends its kernel fragments (the headers that define
 * sky_radiance and the .cl files of its precompute kernels), sets lut_bytes[1..3], the
 * gpu.lut_dims / method_int / method_float it uses, and appends its precompute passes (after the
 * transmittance LUT's, which every method gets first). */
typedef struct atmo_plan_method {
    const char *name;
    int (*plan)(const atmo_scene *s, atmo_plan *p, atmo_err *e);
    int luts_follow_view; /* 1 if its LUTs hold one camera and sun (probes of other rays are
                             then only valid for that sun); 0 if they serve any ray */
} atmo_plan_method;
extern const atmo_plan_method atmo_plan_methods[]; /* in ATMO_METHOD_* order */
const char *atmo_plan_available_methods(void);
int atmo_plan_add_fragments(atmo_plan *p, const char *const *names, int count, atmo_err *e);
int atmo_plan_add_pass(atmo_plan *p, const char *kernel, int width, int height, int depth, int arg,
                       atmo_err *e);

/* Unit vector towards the sun for zenith and azimuth in degrees (scene.h's convention). */
void atmo_sun_direction(double zenith_deg, double azimuth_deg, double out[3]);

/* Camera basis of the thesis' Euler angles (presets.md): forward, right, up. */
void atmo_camera_basis(double pitch_deg, double yaw_deg, double forward[3], double right[3],
                       double up[3]);

#endif
