/* features.h — the feature registry: what a scene can contain, one row per feature.
 *
 * A feature is an atmosphere method, a part that methods share (the view-ray integrator, the
 * Psi_ms LUT), the cloud shell, and later terrain, fBm clouds and objects. Its row declares
 *   - when a scene contains it (wanted),
 *   - its kernel fragments, appended to the program in registry order (so a shared part comes
 *     before the methods that call it and a medium before the methods that integrate it: no
 *     insertion by name), and the -D flags it adds,
 *   - its typed GPU struct (a member of atmo_gpu_scene, in its own header of include/atmo/) and
 *     the other fields of the scene struct its passes read (params: the cache key covers them),
 *   - the fragments its passes are compiled from and the features whose buffers they read
 *     (sources, needs: the cache key covers those too, atmo/render.h),
 *   - a plan function that fills its GPU struct from the scene, sizes its named buffers
 *     (atmo_plan_add_buffer) and lists its precompute passes (atmo_plan_add_pass).
 * atmo_plan_make walks the rows in order and plans the wanted ones; the kernels then see only
 * the fragments, flags and buffers of the features the scene contains. */
#ifndef ATMO_FEATURES_H
#define ATMO_FEATURES_H
#include <stddef.h>
#include "atmo/plan.h"

/* A span of atmo_gpu_scene (offset and size in bytes) that a feature's passes read. */
typedef struct atmo_gpu_field {
    size_t offset, size;
} atmo_gpu_field;
#define ATMO_GPU_FIELD(member)                                                                     \
    {offsetof(atmo_gpu_scene, member), sizeof(((atmo_gpu_scene *)0)->member)}

typedef struct atmo_feature {
    const char *name;
    int method;                      /* ATMO_METHOD_* for an atmosphere method, else -1 */
    int (*wanted)(const atmo_scene *s);
    const char *const *fragments;    /* NULL-terminated */
    const char *defines;             /* "-DNAME ..." or "" */
    const atmo_gpu_field *params;    /* {0, 0}-terminated; NULL: no passes */
    const char *const *sources;      /* NULL-terminated; NULL: no passes */
    const char *const *needs;        /* NULL-terminated names of features; NULL: none */
    int (*plan)(const atmo_scene *s, atmo_plan *p, atmo_err *e); /* NULL: nothing to plan */
    int luts_follow_view; /* a method whose buffers hold one camera and sun (its probes of
                             other rays are only valid for that sun) */
} atmo_feature;

extern const atmo_feature atmo_features[];
extern const int atmo_feature_count;

/* The row with this name, or NULL. */
const atmo_feature *atmo_feature_find(const char *name);
/* The atmosphere method's row (ATMO_METHOD_*), or NULL. */
const atmo_feature *atmo_feature_method(int method);
/* "single, march, ..." for messages. */
const char *atmo_plan_available_methods(void);

#endif
