/* hb-sampler.c - watches the heartbeat GPIO line from inside the test VM.
 *
 * usage: hb-sampler VALUE_FILE PID OUT_FILE
 * Reads VALUE_FILE (gpio-sim's sim_gpioN/value: "0" or "1") every 2 ms
 * while process PID lives and for 0.6 s after it exits (or 120 s in all),
 * and writes one line: alive_s, changes while alive, dead_s, changes after
 * the exit. A shell loop cannot do this: under emulation one fork+exec
 * takes longer than a frame. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s VALUE_FILE PID OUT_FILE\n", argv[0]);
        return 2;
    }
    const int fd = open(argv[1], O_RDONLY);
    if (fd < 0) {
        fprintf(stderr, "hb-sampler: %s: %d\n", argv[1], errno);
        return 1;
    }
    const pid_t pid = (pid_t)atol(argv[2]);
    const double t0 = now_s();
    double t_prev = t0, alive_s = 0.0, dead_s = 0.0;
    int prev = -1, changes_alive = 0, changes_dead = 0;
    const struct timespec step = {0, 2000000};
    for (long i = 0; i < 60000; ++i) { /* 2 ms steps: at most 120 s */
        char c = '?';
        if (pread(fd, &c, 1, 0) != 1 || (c != '0' && c != '1')) {
            fprintf(stderr, "hb-sampler: cannot read %s\n", argv[1]);
            return 1;
        }
        const int v = c - '0';
        const int alive = kill(pid, 0) == 0;
        const double t = now_s();
        if (alive) alive_s += t - t_prev; else dead_s += t - t_prev;
        if (prev >= 0 && v != prev) {
            if (alive) ++changes_alive; else ++changes_dead;
        }
        prev = v;
        t_prev = t;
        if (!alive && dead_s >= 0.6) break;
        (void)nanosleep(&step, NULL);
    }
    FILE *f = fopen(argv[3], "w");
    if (f == NULL) return 1;
    fprintf(f, "%.3f %d %.3f %d\n", alive_s, changes_alive, dead_s, changes_dead);
    return fclose(f) == 0 ? 0 : 1;
}
