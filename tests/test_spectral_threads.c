/* test_spectral_threads.c — the spectral tables are parsed correctly when several threads ask
 * for them first at the same moment.
 * labels: unit
 *
 * The tables of data/ are parsed on first use (host/colour/spectral.c). The viewer asks for
 * them from two threads at once: its render thread while planning (the solar and ozone tables
 * for the atmosphere, the colour matching functions for the luminance factors) and its window
 * thread while drawing (the sun's white point for the white balance). Each trial here is a fresh
 * process (fork, so no table is parsed yet) in which THREADS threads wait at a barrier and then
 * each ask for every table, in an order rotated per thread so that different tables meet.
 *
 * Oracle: the CSV text itself. Each table must hold exactly the numbers of its embedded file
 * (strtod of every field of every line after the header, compared bit for bit), and every
 * thread must get the same table for a name. A trial fails when a check fails or the child dies
 * (a corrupted heap aborts it). The race is a window of microseconds per process, so no single
 * trial can show its absence; TRIALS trials make a race that corrupts even 1 trial in 50 fail
 * this test with probability 1 - (49/50)^TRIALS > 0.98. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "atmo/embedded.h"
#include "atmo/spectral.h"
#include "testlib.h"

#define THREADS 8
#define TRIALS 200
#define MAX_TABLES 16

static const char *names[MAX_TABLES];
static int name_count;
static pthread_barrier_t start;
static const spectral_table *got[THREADS][MAX_TABLES];

static void *ask(void *arg)
{
    int id = (int)(size_t)arg;
    pthread_barrier_wait(&start);
    for (int k = 0; k < name_count; k++) {
        int i = (k + id) % name_count;
        got[id][i] = spectral_table_get(names[i]);
    }
    return NULL;
}

/* 1 when t holds exactly the numbers of the CSV text (header line skipped). */
static int same_as_text(const spectral_table *t, const char *text)
{
    const char *p = strchr(text, '\n');
    int row = 0;
    while (p && *++p) {
        for (int c = 0; c < t->columns; c++) {
            char *end;
            double v = strtod(p, &end);
            if (end == p || row >= t->rows || memcmp(&v, &t->values[row * t->columns + c],
                                                     sizeof v) != 0)
                return 0;
            p = end + (*end == ',');
        }
        if (*p != '\n' && *p != '\r')
            return 0; /* more fields in the line than the table has columns */
        row++;
        p = strchr(p, '\n');
    }
    return row == t->rows;
}

/* One fresh process: the threads race for the tables, then every table is checked. */
static int trial(void)
{
    pthread_t th[THREADS];
    if (pthread_barrier_init(&start, NULL, THREADS))
        return 2;
    for (int i = 0; i < THREADS; i++)
        if (pthread_create(&th[i], NULL, ask, (void *)(size_t)i))
            return 2;
    for (int i = 0; i < THREADS; i++)
        pthread_join(th[i], NULL);
    for (int i = 0; i < name_count; i++) {
        const spectral_table *t = got[0][i];
        if (!t || !same_as_text(t, atmo_embedded_find(atmo_data_files, names[i])->text))
            return 1;
        for (int k = 1; k < THREADS; k++)
            if (got[k][i] != t)
                return 1;
    }
    return 0;
}

int main(void)
{
    for (const struct atmo_embedded_file *f = atmo_data_files; f->name; f++)
        if (name_count < MAX_TABLES && strstr(f->name, ".csv"))
            names[name_count++] = f->name;
    CHECK(name_count >= 5); /* solar, ozone, colour matching functions, two water tables */
    int failed = 0, died = 0;
    for (int n = 0; n < TRIALS; n++) {
        fflush(NULL);
        pid_t pid = fork();
        if (pid < 0) {
            CHECK(pid >= 0);
            break;
        }
        if (pid == 0)
            _exit(trial());
        int status = 0;
        if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
            died++;
        else if (WEXITSTATUS(status) != 0)
            failed++;
    }
    printf("%d trials of %d threads racing for %d tables: %d with a wrong or unequal table, "
           "%d children died\n", TRIALS, THREADS, name_count, failed, died);
    CHECK(failed == 0);
    CHECK(died == 0);
    return test_finish();
}
