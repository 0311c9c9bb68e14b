/* quadrature_walk.h — the one stepping loop of the deterministic methods: the pieces of a ray
 * [0, d] that a quadrature samples once each, handed one at a time to the caller, which
 * evaluates each one (an iterator with the shape of majorant_walk.h's: OpenCL C has no function
 * pointers, so the per-piece evaluation is the caller's loop body). The medium integrator
 * (medium.h: single, march, fast's and lut's segments), the multiple-scattering LUT's
 * directions (ms_lut.h), method lut's precompute (lut_precompute.cl) and the transmittance LUT
 * (atmosphere.h's atmosphere_optical_depth_to_top) walk it on its grids; the media's own
 * stepping in their parts (cloud_march.h's clouds_march, cloud_shell_march.h's
 * cloud_shell_interval, cloud_layer.h's clouds_view_density_ends) walks it in sized pieces.
 *
 *     quadrature_walk q = quadrature_begin(d, n, jitter);
 *     q.parts = media_intervals(..., q.lo, q.hi);            (optional: break points)
 *     for (int ev; (ev = quadrature_next(&q)) != QUADRATURE_END;) {
 *         if (ev == QUADRATURE_PART) { ... the medium's own stepping over [q.start, q.end] ... }
 *         else { ... a piece [q.start, q.start + q.dt], coefficients at q.t ... }
 *     }
 *
 * Grids. quadrature_begin cuts [0, d] into n segments growing as (i/n)^2 from the ray's start,
 *     [d (i/n)^2, d ((i+1)/n)^2]   (quadrature_grid_segment),
 * short where the density changes fastest along rays that start low (medium.h says how well);
 * quadrature_begin_equal into n equal ones, [i d/n, (i+1) d/n], each sampled at its middle
 * t = (i + 1/2) d/n (the midpoint rule of the LUTs that integrate each segment's mean density).
 * Parts. The caller may give up to QUADRATURE_MAX_PARTS parts [lo, hi] (sorted, disjoint: a
 * medium's own stepping, media.h's media_intervals) after quadrature_begin; the walk hands each
 * one out once (QUADRATURE_PART), where the grid reaches it, and clips the grid's segments to
 * the rest, so a grid segment that meets no part is handed out whole and a ray without parts
 * walks exactly the grid. A piece starts where the one before it ended: the grid's start of
 * segment i, d (i/n)^2, can lie a rounding below the end of segment i - 1 (its start plus its
 * length), and the piece then starts at that end instead (clipped like a piece after a part),
 * so no sliver is counted twice.
 * Sample point. A piece [a, a + dt] is sampled at t = a + jitter dt, jitter in [0, 1) (a random
 * number per sample in the renderer, so averaging samples removes the banding of a fixed
 * point), or, with jitter = QUADRATURE_GRID_MIDDLE and no parts, each grid segment i exactly as
 * quadrature_grid_segment gives it (no clipping at the segment before), at
 *     t = d ((i + 1/2) / n)^2,
 * the middle of the segment in the grid's parameter sqrt(t / d), a fraction (i + 1/4) / (2i + 1)
 * of its length from its start (the LUT's directions: no samples to average a jitter over, and
 * the light a segment sends to the ray's start comes more from its near part;
 * docs/notes/ms_lut.md). The caller integrates each piece (media.h's medium_piece_weight, exact
 * for constant coefficients; the LUTs' own rules for their mean densities).
 * Sized pieces. quadrature_begin_sized walks [t0, t1] in pieces whose size the caller picks
 * one at a time, by a length (quadrature_step: the piece [done, done + dt]) or by its end
 * (quadrature_step_to: [done, b]), both cut at t1; each is sampled at t = start + jitter dt
 * like the grid's. quadrature_more says whether a piece is left: fewer than n handed out and
 * some of [t0, t1] not yet walked (a length cut at t1 can end a rounding short of it, and the
 * sliver is walked too). The caller adds its own stop conditions to the loop:
 *     quadrature_walk q = quadrature_begin_sized(t0, t1, n, jitter);
 *     while (quadrature_more(&q) && ...) {
 *         quadrature_step(&q, rule(q.done));
 *         ... the piece [q.start, q.start + q.dt], coefficients at q.t ...
 *     }
 * Units: metres. */
#ifndef ATMO_MEDIA_QUADRATURE_WALK_H
#define ATMO_MEDIA_QUADRATURE_WALK_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

#define QUADRATURE_MAX_PARTS 2 /* parts of one ray (media.h's MEDIA_MAX_INTERVALS) */

/* quadrature_next's events */
#define QUADRATURE_END 0   /* past the ray's end */
#define QUADRATURE_PIECE 1 /* a piece [q.start, q.start + q.dt] with its sample point q.t */
#define QUADRATURE_PART 2  /* a part [q.start, q.end] that the caller steps itself */
/* the jitter that samples each grid segment at its middle in the grid's parameter */
#define QUADRATURE_GRID_MIDDLE (-1.0f)

typedef struct quadrature_walk {
    float d;                       /* the ray's end (a sized walk's t1), m */
    int n;                         /* grid segments (a sized walk's most pieces) */
    float jitter;                  /* the sample's fraction of a piece, or QUADRATURE_GRID_MIDDLE */
    int equal;                     /* equal segments (quadrature_begin_equal) */
    float step;                    /* their length, m */
    float lo[QUADRATURE_MAX_PARTS]; /* the caller's parts [lo, hi], m (sorted, disjoint) */
    float hi[QUADRATURE_MAX_PARTS];
    unsigned parts;                /* how many (0 after quadrature_begin) */
    int i;                         /* the next grid segment (a sized walk: pieces so far) */
    unsigned next;                 /* the next part */
    int clipping;                  /* the current grid segment is being cut at parts */
    int gap_given;                 /* the piece before part `next` has been handed out */
    float seg_end;                 /* the current grid segment's end, m */
    float pos;                     /* the current grid segment is walked up to pos, m */
    float done;                    /* the walk has handed out [0 or t0, done], m */
    float start, dt, t;            /* the piece: its start, length and sample point, m */
    float end;                     /* a part's end, m (a part starts at start) */
} quadrature_walk;

/* Segment i of the n that cut [0, d] of a ray, growing as (i/n)^2 from its start:
 * [d (i/n)^2, d ((i+1)/n)^2]. Returns where it starts (m); *dt = its length (m). */
ATMO_FN float quadrature_grid_segment(float d, int i, int n, float *dt)
{
    float x0 = (float)i / (float)n, x1 = (float)(i + 1) / (float)n;
    *dt = d * (x1 * x1 - x0 * x0);
    return d * x0 * x0;
}

/* The first of the grid's break points d (i / n)^2 beyond t (m): where the grid segment that
 * holds t ends (a medium's own stepping that also stops there resolves the air at least as
 * finely as the grid). */
ATMO_FN float quadrature_grid_next(float t, float d, int n)
{
    float x = (float)n * sqrtf(fmaxf(t, 0.0f) / d);
    int i = (int)x + 1;
    float g = d * ((float)i / (float)n) * ((float)i / (float)n);
    return g > t ? g : d * ((float)(i + 1) / (float)n) * ((float)(i + 1) / (float)n);
}

/* The walk over [0, d] on n grid segments, each piece sampled at the fraction jitter of it (or
 * QUADRATURE_GRID_MIDDLE); no parts until the caller sets q.parts, q.lo, q.hi. */
ATMO_FN quadrature_walk quadrature_begin(float d, int n, float jitter)
{
    quadrature_walk q;
    q.d = d;
    q.n = n;
    q.jitter = jitter;
    q.equal = 0;
    q.step = 0.0f;
    q.parts = 0u;
    q.i = 0;
    q.next = 0u;
    q.clipping = 0;
    q.gap_given = 0;
    q.seg_end = 0.0f;
    q.pos = 0.0f;
    q.done = 0.0f;
    q.start = 0.0f;
    q.dt = 0.0f;
    q.t = 0.0f;
    q.end = 0.0f;
    for (int k = 0; k < QUADRATURE_MAX_PARTS; k++)
        q.lo[k] = q.hi[k] = 0.0f;
    return q;
}

/* The walk over [0, d] on n equal segments, each sampled at its middle (the midpoint rule);
 * no parts. */
ATMO_FN quadrature_walk quadrature_begin_equal(float d, int n)
{
    quadrature_walk q = quadrature_begin(d, n, QUADRATURE_GRID_MIDDLE);
    q.equal = 1;
    q.step = d / (float)n;
    return q;
}

/* Hands out the piece [start, start + dt], sampled at the jitter's fraction of it. */
ATMO_FN int quadrature_piece(quadrature_walk *q, float start, float dt)
{
    q->start = start;
    q->dt = dt;
    q->t = start + q->jitter * dt;
    return QUADRATURE_PIECE;
}

/* The walk over [t0, t1] in at most n pieces that the caller sizes (quadrature_step,
 * quadrature_step_to), each sampled at the fraction jitter of it. */
ATMO_FN quadrature_walk quadrature_begin_sized(float t0, float t1, int n, float jitter)
{
    quadrature_walk q = quadrature_begin(t1, n, jitter);
    q.done = t0;
    q.start = t0;
    return q;
}

/* Whether a sized walk has a piece left: fewer than n handed out, and [done, d] not empty. */
ATMO_FN int quadrature_more(const quadrature_walk *q)
{
    return q->i < q->n && q->done < q->d;
}

/* A sized walk's next piece: dt long (m), cut at the walk's end. */
ATMO_FN void quadrature_step(quadrature_walk *q, float dt)
{
    float start = q->done;
    dt = fminf(dt, q->d - start);
    q->done = start + dt;
    q->i++;
    quadrature_piece(q, start, dt);
}

/* A sized walk's next piece: up to b (m), cut at the walk's end. */
ATMO_FN void quadrature_step_to(quadrature_walk *q, float b)
{
    float start = q->done;
    q->done = fminf(b, q->d);
    q->i++;
    quadrature_piece(q, start, q->done - start);
}

/* The next event (see the top of the file). */
ATMO_FN int quadrature_next(quadrature_walk *q)
{
    for (;;) {
        if (!q->clipping) { /* at the start of grid segment i */
            if (q->i >= q->n)
                return QUADRATURE_END;
            if (q->equal) { /* segment i of equal ones, at its middle */
                q->start = (float)q->i * q->step;
                q->dt = q->step;
                q->t = ((float)q->i + 0.5f) * q->step;
                q->i++;
                return QUADRATURE_PIECE;
            }
            float dt, ga = quadrature_grid_segment(q->d, q->i, q->n, &dt), gb = ga + dt;
            if ((q->next >= q->parts || q->lo[q->next] >= gb) &&
                (q->done <= ga || q->jitter == QUADRATURE_GRID_MIDDLE)) {
                /* the grid segment meets no part: handed out whole */
                q->start = ga;
                q->dt = dt;
                q->t = q->jitter == QUADRATURE_GRID_MIDDLE
                           ? q->d * atmo_sq(((float)q->i + 0.5f) / (float)q->n)
                           : ga + q->jitter * dt;
                q->done = gb;
                q->i++;
                return QUADRATURE_PIECE;
            }
            q->seg_end = gb;
            q->pos = fmaxf(ga, q->done);
            q->clipping = 1;
        }
        if (q->next < q->parts && q->lo[q->next] < q->seg_end) {
            float lo = q->lo[q->next];
            if (lo > q->pos && !q->gap_given) { /* the grid's piece before the part */
                q->gap_given = 1;
                return quadrature_piece(q, q->pos, lo - q->pos);
            }
            q->start = lo;
            q->end = q->hi[q->next];
            q->pos = fmaxf(q->pos, q->end);
            q->next++;
            q->gap_given = 0;
            return QUADRATURE_PART;
        }
        /* the rest of the grid segment after its parts */
        float pos = q->pos, gb = q->seg_end;
        q->clipping = 0;
        q->i++;
        q->done = fmaxf(pos, gb);
        if (pos < gb)
            return quadrature_piece(q, pos, gb - pos);
    }
}

#endif
