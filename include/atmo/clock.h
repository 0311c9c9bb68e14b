/* clock.h — wall-clock time for the stage timings, progress and launch budgets. */
#ifndef ATMO_CLOCK_H
#define ATMO_CLOCK_H

/* Seconds on the monotonic clock (CLOCK_MONOTONIC): only differences mean anything. */
double atmo_now_seconds(void);

#endif
