/* view_script.h — timed synthetic key events for tests and demos (view_script.c). */
#ifndef ATMO_VIEW_SCRIPT_H
#define ATMO_VIEW_SCRIPT_H
#include "atmo/status.h"

enum { VIEW_ACT_WAIT, VIEW_ACT_WAIT_SAMPLES, VIEW_ACT_PRESS, VIEW_ACT_HOLD, VIEW_ACT_LOOK,
       VIEW_ACT_QUIT };

typedef struct view_action {
    int kind;        /* VIEW_ACT_* */
    int key, mods;   /* PRESS, HOLD: GLFW key code and modifier bits */
    double value;    /* WAIT: seconds; WAIT_SAMPLES: samples; HOLD: seconds held; LOOK: dx */
    double value2;   /* LOOK: dy */
    int line;
} view_action;

typedef struct view_script {
    view_action *actions;
    int count;
    int next;        /* index of the next action */
    double started;  /* when the current WAIT began (seconds), or < 0 */
} view_script;

/* Read and check a whole script before anything runs: ATMO_ERR_USAGE with "FILE:LINE: ..." for
 * the first bad line. */
int view_script_load(view_script *s, const char *path, atmo_err *e);
void view_script_free(view_script *s);

#endif
