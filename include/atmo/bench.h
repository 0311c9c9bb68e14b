/* bench.h — benchmark suites run by `atmo bench` (host/cmd_bench.c dispatches). */
#ifndef ATMO_BENCH_H
#define ATMO_BENCH_H
#include "atmo/status.h"

/* `atmo bench mie`: phase options against the tabulated Mie phase, and table build times
 * (host/bench_mie.c). Writes DIR/mie.csv, DIR/mie_table.csv and DIR/mie.svg. */
int bench_mie(const char *dir, int quick, atmo_err *e);

#endif
