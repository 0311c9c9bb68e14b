/* Test helpers that need a whole scene: see testscene.h. */
#include <stdio.h>
#include <stdlib.h>
#include "atmo/render.h"
#include "testscene.h"

void test_scene_preset(atmo_scene *s, const char *preset)
{
    atmo_err e;
    atmo_scene_defaults(s);
    if (atmo_scene_apply_preset(s, preset, &e)) {
        fprintf(stderr, "preset %s: %s\n", preset, e.msg);
        exit(1);
    }
}

void test_scene_set(atmo_scene *s, const char *assignment)
{
    atmo_err e;
    if (atmo_scene_assign(s, assignment, "test", &e)) {
        fprintf(stderr, "%s: %s\n", assignment, e.msg);
        exit(1);
    }
}

void test_plan(const atmo_scene *s, atmo_plan *p)
{
    atmo_err e;
    if (atmo_plan_make(s, p, &e)) {
        fprintf(stderr, "plan: %s\n", e.msg);
        exit(1);
    }
}

cl_program test_plan_program(atmo_cl *cl, const atmo_plan *p, const char *extra)
{
    return test_cl_build_defines(cl, p->fragments, p->fragment_count, p->defines, extra);
}

void test_precompute(atmo_cl *cl, cl_program prog, cl_mem scene, const atmo_plan *p,
                     cl_mem luts[ATMO_PLAN_LUTS])
{
    atmo_err e;
    atmo_precompute_info info;
    if (atmo_precompute(cl, prog, p, scene, luts, &info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
}

void test_release_luts(cl_mem luts[ATMO_PLAN_LUTS])
{
    for (int i = 0; i < ATMO_PLAN_LUTS; i++)
        if (luts[i])
            clReleaseMemObject(luts[i]);
}
