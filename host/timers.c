#include "timers.h"

#include <string.h>
#include <time.h>

#include "error.h"

#define AMSPH_PHASE_NAME(id, name) name,
const char *const amsph_phase_names[AMSPH_PHASE_COUNT] = {"none", AMSPH_PHASES(AMSPH_PHASE_NAME)};
#undef AMSPH_PHASE_NAME

double amsph_wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void amsph_timers_reset(amsph_timers *t, int enabled)
{
    memset(t, 0, sizeof *t);
    t->enabled = enabled;
}

int amsph_timers_switch(amsph_timers *t, amsph_backend *b, amsph_phase next, amsph_phase *previous)
{
    if (previous)
        *previous = t->current;
    if (t->enabled) {
        AMSPH_CHECK(amsph_sync(b));
        const double now = amsph_wall_seconds();
        if (t->current != AMSPH_PHASE_NONE)
            t->seconds[t->current] += now - t->since;
        t->used[next] = 1;
        t->since = now;
    }
    t->current = next;
    return 0;
}
