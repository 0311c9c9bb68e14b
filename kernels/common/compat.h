/* compat.h — lets the math headers of kernels/ compile both as OpenCL C 1.2 and as host C11.
 *
 * Kernel math (intersections, parametrisations, RNG, phase functions, ...) is written once and
 * tested on the host by calling the very same functions. The rules that make that work:
 *   - functions are declared ATMO_FN (static inline in both languages);
 *   - 3-vectors are `vec3` and are handled only through the v3_* functions below
 *     (float3 in OpenCL C, a plain struct on the host, where C has no vector operators);
 *   - float maths goes through the f* names below (sqrtf, expf, ...), which the host takes from
 *     <math.h> and OpenCL C maps onto its overloaded built-ins; every literal has an `f` suffix,
 *     which the host build checks with -Wdouble-promotion;
 *   - native_* built-ins only through ATMO_NATIVE(fn), which falls back to the exact function
 *     unless ATMO_USE_NATIVE is defined, so tests can compare both.
 * Structs shared with kernels use float, int, uint and float4 only (see include/atmo/gpu_types.h). */
#ifndef ATMO_COMPAT_H
#define ATMO_COMPAT_H

#define ATMO_FN static inline

#ifdef __OPENCL_VERSION__
/* ---------------------------------------------------------------- OpenCL C side */
typedef float3 vec3;
#define v3(x, y, z) ((float3)((x), (y), (z)))
#define sqrtf sqrt
#define expf exp
#define logf log
#define log1pf log1p
#define expm1f expm1
#define sinf sin
#define cosf cos
#define tanf tan
#define tanhf tanh
#define asinf asin
#define acosf acos
#define atanf atan
#define atan2f atan2
#define powf pow
#define fabsf fabs
#define fminf fmin
#define fmaxf fmax
#define floorf floor
#define ceilf ceil
#define fmodf fmod
#define erff erf
#define ATMO_GLOBAL __global
#define ATMO_CONSTANT __constant
ATMO_FN vec3 v3_add(vec3 a, vec3 b) { return a + b; }
ATMO_FN vec3 v3_sub(vec3 a, vec3 b) { return a - b; }
ATMO_FN vec3 v3_mul(vec3 a, vec3 b) { return a * b; }
ATMO_FN vec3 v3_scale(vec3 a, float s) { return a * s; }
ATMO_FN float v3_dot(vec3 a, vec3 b) { return dot(a, b); }
ATMO_FN vec3 v3_cross(vec3 a, vec3 b) { return cross(a, b); }
ATMO_FN float v3_length(vec3 a) { return length(a); }
ATMO_FN vec3 v3_normalize(vec3 a) { return normalize(a); }
ATMO_FN vec3 v3_exp(vec3 a) { return exp(a); }
ATMO_FN vec3 v3_from4(float4 a) { return a.xyz; }
#ifdef ATMO_USE_NATIVE
#define ATMO_NATIVE(fn) native_##fn
#else
#define ATMO_NATIVE(fn) fn
#endif

#else
/* ---------------------------------------------------------------- host C side */
#include <math.h>
#include <stdint.h>
typedef uint32_t uint;
typedef struct { _Alignas(16) float x; float y, z, w; } float4;
typedef struct { _Alignas(8) float x; float y; } float2;
typedef struct { float x, y, z; } vec3;
#define ATMO_GLOBAL
#define ATMO_CONSTANT const
ATMO_FN vec3 v3(float x, float y, float z) { vec3 r = {x, y, z}; return r; }
ATMO_FN vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
ATMO_FN vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
ATMO_FN vec3 v3_mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
ATMO_FN vec3 v3_scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
ATMO_FN float v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
ATMO_FN vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
ATMO_FN float v3_length(vec3 a) { return sqrtf(v3_dot(a, a)); }
ATMO_FN vec3 v3_normalize(vec3 a) { return v3_scale(a, 1.0f / v3_length(a)); }
ATMO_FN vec3 v3_exp(vec3 a) { return v3(expf(a.x), expf(a.y), expf(a.z)); }
ATMO_FN vec3 v3_from4(float4 a) { return v3(a.x, a.y, a.z); }
ATMO_FN float clamp(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }
ATMO_FN float mix(float a, float b, float t) { return a + (b - a) * t; }
#define ATMO_NATIVE(fn) fn##f
#endif

/* Shared by both sides. */
#define ATMO_PI 3.14159265358979323846f
ATMO_FN float atmo_sq(float x) { return x * x; }
/* sqrt that maps the small negative results of rounding to 0 instead of NaN. */
ATMO_FN float atmo_safe_sqrt(float x) { return sqrtf(fmaxf(x, 0.0f)); }
ATMO_FN float atmo_clamp_cos(float mu) { return clamp(mu, -1.0f, 1.0f); }

#endif
