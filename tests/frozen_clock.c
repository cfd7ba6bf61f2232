/* Preloaded into glxgears by tests/end_to_end/raster_vs_mesa.rs: gettimeofday, the only clock
 * glxgears reads, always answers the same instant, so every frame shows the gears at angle 0.
 * Only this one function is replaced (libfaketime also freezes the clocks that the drivers'
 * worker threads wait on, which breaks rendering). */
#include <stddef.h>
#include <sys/time.h>

int gettimeofday(struct timeval *tv, void *tz) {
    (void)tz;
    if (tv != NULL) {
        tv->tv_sec = 1577836800; /* 2020-01-01 00:00:00 UTC */
        tv->tv_usec = 0;
    }
    return 0;
}
