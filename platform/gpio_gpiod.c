/* gpio_gpiod.c - discrete inputs and the heartbeat output through libgpiod
 * 1.6 (GPIO character device, uAPI v1). Every libgpiod call of the program
 * is in this file: a libgpiod 2.x port (line requests, edge event buffers)
 * replaces this file only.
 *
 * Open: gpiod_chip_open_lookup (name "gpiochip0", path "/dev/gpiochip0",
 * number "0" or label "ft-gpio-sim"), then per input line
 * gpiod_line_request_both_edges_events and for the output
 * gpiod_line_request_output (driven low), consumer "fixterrain". Lines are
 * checked against the chip's line count first, so a bad offset says "out of
 * range" instead of EINVAL; a line held by another consumer says who holds
 * it. The event file descriptors are switched to O_NONBLOCK, so a read never
 * blocks whatever the caller did before (no separate wait call needed).
 *
 * Heap: libgpiod allocates the chip, the line objects and one small handle
 * per request inside ft_plat_gpio_open, and frees them in
 * ft_plat_gpio_close. Levels, edges and set_output do not allocate (ioctl and
 * read on the request descriptors; libgpiod 1.6 reads events into a
 * 16-entry stack buffer).
 *
 * Edges: uAPI v1 keeps a FIFO of 16 events per line in the kernel; when it
 * is full new events are dropped silently (v1 has no sequence numbers; the
 * debouncer treats two edges in the same direction as a lost one). Edges
 * are physical (no active-low flag is requested): rising = the line went
 * 0 -> 1. In uAPI v1 the kernel's IRQ thread decides rising/falling by
 * reading the level when it runs, so a pulse shorter than that thread's
 * latency shows as two edges of the same direction (or, where the IRQ
 * controller does not latch an edge while the ONESHOT IRQ is masked, as
 * gpio-sim does not, as one edge): the debouncer's repeated-edge rule and
 * ft_debounce_sample with ft_plat_gpio_levels cover both. ft_plat_gpio_read_edges first reads up to cap / in_count events
 * per line, then fills what is left of cap in slot order, so a busy line
 * cannot starve the others, and returns them sorted by time.
 *
 * Timestamps: the kernel stamps a v1 line event in the hard interrupt
 * handler with ktime_get_ns() - CLOCK_MONOTONIC, since Linux 5.7 (checked in
 * 6.1's drivers/gpio/gpiolib-cdev.c, lineevent_irq_handler); before 5.7 it
 * was ktime_get_real_ns(). libgpiod 1.6 only splits that u64 into a struct
 * timespec. On >= 5.7 (Debian 12: 6.1) the stamp is therefore on exactly the
 * base of ft_plat_monotonic_ns (clock_gettime(CLOCK_MONOTONIC)), with no
 * conversion error; the VM test checks it against both clocks. (Chips behind
 * a slow bus, e.g. I2C expanders with nested threaded IRQs, are stamped in
 * the IRQ thread instead: still monotonic, later by the bus latency.) On an older
 * kernel (found with uname at open) a stamp is converted from realtime like
 * the CAN receive times (realtime - monotonic sampled at read; error: the
 * sampling bracket plus any realtime step between the edge and the read). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <stdio.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>

#include "core/platform_api.h"

#define FT_GPIO_CONSUMER "fixterrain"
#define FT_GPIO_READ_BATCH 16u  /* libgpiod 1.6 reads at most 16 events per call */
#define FT_GPIO_EINTR_MAX 8u
#define FT_NS_PER_S 1000000000ull

/* 1 when this kernel stamps v1 line events with CLOCK_REALTIME (< 5.7).
 * A property of the running kernel, so process-wide. */
static int g_events_realtime;

static uint64_t clock_ns(clockid_t id)
{
    struct timespec ts;
    if (clock_gettime(id, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * FT_NS_PER_S + (uint64_t)ts.tv_nsec;
}

static int kernel_stamps_realtime(void)
{
    struct utsname u;
    unsigned major = 0, minor = 0;
    if (uname(&u) != 0 || sscanf(u.release, "%u.%u", &major, &minor) != 2) {
        return 0; /* unknown: assume a current kernel */
    }
    return major < 5u || (major == 5u && minor < 7u);
}

static const char *chip_label(struct gpiod_chip *c)
{
    const char *l = gpiod_chip_label(c);
    return l != NULL ? l : "?";
}

/* Releases whatever open had requested and closes the chip. */
static void release_all(ft_gpio_port *g)
{
    for (uint32_t i = 0; i < FT_GPIO_LINES_MAX; ++i) {
        if (g->in_lines[i] != NULL) {
            gpiod_line_release((struct gpiod_line *)g->in_lines[i]);
            g->in_lines[i] = NULL;
        }
    }
    if (g->out_line != NULL) {
        gpiod_line_release((struct gpiod_line *)g->out_line);
        g->out_line = NULL;
    }
    if (g->chip != NULL) {
        gpiod_chip_close((struct gpiod_chip *)g->chip);
        g->chip = NULL;
    }
    g->in_count = 0;
}

/* Gets line `offset` and requests it (events or output). */
static ft_status request_line(ft_gpio_port *g, const char *chip_descr, int offset, int output,
                              struct gpiod_line **line_out, ft_error *err)
{
    struct gpiod_chip *chip = (struct gpiod_chip *)g->chip;
    unsigned n_lines = gpiod_chip_num_lines(chip);
    const char *what = output ? "output" : "input";
    if (offset < 0 || (unsigned)offset >= n_lines) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "GPIO %s line %d out of range: chip '%s' (%s [%s]) has %u lines (0..%u)",
                       what, offset, chip_descr, gpiod_chip_name(chip), chip_label(chip), n_lines,
                       n_lines > 0u ? n_lines - 1u : 0u);
    }
    struct gpiod_line *line = gpiod_chip_get_line(chip, (unsigned)offset);
    if (line == NULL) {
        return ft_fail(err, FT_ERR_IO, "GPIO chip '%s': line %d: gpiod_chip_get_line: %s",
                       chip_descr, offset, strerror(errno));
    }
    int rc = output ? gpiod_line_request_output(line, FT_GPIO_CONSUMER, 0)
                    : gpiod_line_request_both_edges_events(line, FT_GPIO_CONSUMER);
    if (rc != 0) {
        int e = errno;
        if (e == EBUSY) {
            (void)gpiod_line_update(line); /* fresh consumer name */
            const char *user = gpiod_line_consumer(line);
            return ft_fail(err, FT_ERR_IO,
                           "GPIO %s line %d on chip '%s' (%s) is busy (used by '%s')", what,
                           offset, chip_descr, gpiod_chip_name(chip),
                           user != NULL ? user : "another consumer");
        }
        return ft_fail(err, FT_ERR_IO, "GPIO %s line %d on chip '%s' (%s): request: %s", what,
                       offset, chip_descr, gpiod_chip_name(chip), strerror(e));
    }
    *line_out = line;
    return FT_OK;
}

ft_status ft_plat_gpio_open(ft_gpio_port *g, const char *chip, const int *in_lines,
                            uint32_t in_count, int out_line, ft_error *err)
{
    if (g == NULL) {
        return ft_fail(err, FT_ERR_ARG, "GPIO open: NULL port");
    }
    *g = (ft_gpio_port){0};
    if (chip == NULL || chip[0] == '\0') {
        return ft_fail(err, FT_ERR_ARG, "GPIO open: no chip name");
    }
    if (in_count > FT_GPIO_LINES_MAX || (in_count > 0u && in_lines == NULL)) {
        return ft_fail(err, FT_ERR_ARG, "GPIO chip '%s': %u input lines, at most %u", chip,
                       (unsigned)in_count, (unsigned)FT_GPIO_LINES_MAX);
    }
    if (in_count == 0u && out_line < 0) {
        return ft_fail(err, FT_ERR_ARG, "GPIO chip '%s': no lines to open", chip);
    }
    for (uint32_t i = 0; i < in_count; ++i) {
        for (uint32_t k = 0; k < i; ++k) {
            if (in_lines[k] == in_lines[i]) {
                return ft_fail(err, FT_ERR_CONFIG, "GPIO chip '%s': line %d is given twice",
                               chip, in_lines[i]);
            }
        }
        if (out_line >= 0 && in_lines[i] == out_line) {
            return ft_fail(err, FT_ERR_CONFIG,
                           "GPIO chip '%s': line %d is both an input and the output", chip,
                           out_line);
        }
    }

    errno = 0;
    struct gpiod_chip *c = gpiod_chip_open_lookup(chip);
    if (c == NULL) {
        int e = errno;
        if (e == ENOENT || e == ENODEV || e == ENOTTY || e == 0) {
            return ft_fail(err, FT_ERR_IO,
                           "GPIO chip '%s' not found (no /dev/gpiochipN with that name, number, "
                           "path or label%s%s)",
                           chip, e != 0 ? ": " : "", e != 0 ? strerror(e) : "");
        }
        return ft_fail(err, FT_ERR_IO, "GPIO chip '%s': gpiod_chip_open_lookup: %s", chip,
                       strerror(e));
    }
    g->chip = c;
    g_events_realtime = kernel_stamps_realtime();

    for (uint32_t i = 0; i < in_count; ++i) {
        struct gpiod_line *line = NULL;
        ft_status s = request_line(g, chip, in_lines[i], 0, &line, err);
        if (s != FT_OK) {
            release_all(g);
            return s;
        }
        g->in_lines[i] = line;
        g->in_count = i + 1u;
        int fd = gpiod_line_event_get_fd(line);
        int fl = fd >= 0 ? fcntl(fd, F_GETFL) : -1;
        if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0) {
            int e = fd >= 0 ? errno : EBADF;
            release_all(g);
            return ft_fail(err, FT_ERR_IO,
                           "GPIO input line %d on chip '%s': event descriptor O_NONBLOCK: %s",
                           in_lines[i], chip, strerror(e));
        }
    }
    if (out_line >= 0) {
        struct gpiod_line *line = NULL;
        ft_status s = request_line(g, chip, out_line, 1, &line, err);
        if (s != FT_OK) {
            release_all(g);
            return s;
        }
        g->out_line = line;
        g->out_level = 0;
    }
    return FT_OK;
}

ft_status ft_plat_gpio_levels(ft_gpio_port *g, int *levels, ft_error *err)
{
    if (g == NULL || levels == NULL || g->chip == NULL) {
        return ft_fail(err, FT_ERR_ARG, "GPIO levels: NULL argument or closed port");
    }
    for (uint32_t i = 0; i < g->in_count; ++i) {
        struct gpiod_line *line = (struct gpiod_line *)g->in_lines[i];
        int v = gpiod_line_get_value(line);
        if (v < 0) {
            return ft_fail(err, FT_ERR_IO, "GPIO line %u on %s: get value: %s",
                           gpiod_line_offset(line), gpiod_chip_name((struct gpiod_chip *)g->chip),
                           strerror(errno));
        }
        levels[i] = v != 0;
    }
    return FT_OK;
}

/* Reads up to max events of slot i into out (max <= FT_GPIO_READ_BATCH). */
static ft_status read_slot(ft_gpio_port *g, uint32_t i, ft_gpio_edge *out, uint32_t max,
                           uint32_t *got, ft_error *err)
{
    struct gpiod_line *line = (struct gpiod_line *)g->in_lines[i];
    struct gpiod_line_event ev[FT_GPIO_READ_BATCH];
    *got = 0;
    if (max == 0u) {
        return FT_OK;
    }
    int fd = gpiod_line_event_get_fd(line);
    int n = -1;
    for (uint32_t tries = 0; tries < FT_GPIO_EINTR_MAX; ++tries) {
        n = gpiod_line_event_read_fd_multiple(fd, ev, max);
        if (n >= 0 || errno != EINTR) {
            break;
        }
    }
    if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) {
            return FT_OK;
        }
        return ft_fail(err, FT_ERR_IO, "GPIO line %u on %s: read events: %s",
                       gpiod_line_offset(line), gpiod_chip_name((struct gpiod_chip *)g->chip),
                       strerror(errno));
    }
    int64_t real_minus_mono = 0;
    if (g_events_realtime) {
        uint64_t m1 = clock_ns(CLOCK_MONOTONIC);
        uint64_t r = clock_ns(CLOCK_REALTIME);
        uint64_t m2 = clock_ns(CLOCK_MONOTONIC);
        real_minus_mono = (int64_t)(r - (m1 + (m2 - m1) / 2u));
    }
    for (int k = 0; k < n && (uint32_t)k < max; ++k) {
        int64_t t = (int64_t)((uint64_t)ev[k].ts.tv_sec * FT_NS_PER_S + (uint64_t)ev[k].ts.tv_nsec);
        t -= real_minus_mono;
        out[k].slot = i;
        out[k].rising = ev[k].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
        out[k].t_ns = t > 0 ? (uint64_t)t : 0u;
    }
    *got = (uint32_t)n;
    return FT_OK;
}

ft_status ft_plat_gpio_read_edges(ft_gpio_port *g, ft_gpio_edge *out, uint32_t cap,
                                  uint32_t *got, ft_error *err)
{
    if (got != NULL) {
        *got = 0;
    }
    if (g == NULL || got == NULL || (out == NULL && cap > 0u) || g->chip == NULL) {
        return ft_fail(err, FT_ERR_ARG, "GPIO read edges: NULL argument or closed port");
    }
    if (g->in_count == 0u || cap == 0u) {
        return FT_OK;
    }
    /* Pass 0: a fair share per line; pass 1: the rest of cap in slot order.
     * Per line and pass at most ceil(limit / 16) reads, each of which
     * returns >= 1 event or ends that line (EAGAIN). */
    uint32_t n = 0;
    uint32_t share = cap / g->in_count;
    if (share == 0u) {
        share = 1u;
    }
    int drained[FT_GPIO_LINES_MAX] = {0};
    for (int pass = 0; pass < 2 && n < cap; ++pass) {
        for (uint32_t i = 0; i < g->in_count && n < cap; ++i) {
            uint32_t limit = pass == 0 ? share : cap - n;
            uint32_t reads_max = limit / FT_GPIO_READ_BATCH + 1u;
            for (uint32_t r = 0; r < reads_max && !drained[i] && limit > 0u && n < cap; ++r) {
                uint32_t want = limit < cap - n ? limit : cap - n;
                if (want > FT_GPIO_READ_BATCH) {
                    want = FT_GPIO_READ_BATCH;
                }
                uint32_t k = 0;
                ft_status s = read_slot(g, i, &out[n], want, &k, err);
                if (s != FT_OK) {
                    *got = n;
                    g->events += n;
                    return s;
                }
                n += k;
                limit -= k;
                if (k < want) {
                    drained[i] = 1;
                }
            }
        }
    }
    /* Insertion sort by time (stable: a line's own order is kept). */
    for (uint32_t i = 1; i < n; ++i) {
        ft_gpio_edge e = out[i];
        uint32_t j = i;
        while (j > 0u && out[j - 1u].t_ns > e.t_ns) {
            out[j] = out[j - 1u];
            --j;
        }
        out[j] = e;
    }
    g->events += n;
    *got = n;
    return FT_OK;
}

ft_status ft_plat_gpio_set_output(ft_gpio_port *g, int level, ft_error *err)
{
    if (g == NULL || g->chip == NULL) {
        return ft_fail(err, FT_ERR_ARG, "GPIO set output: NULL argument or closed port");
    }
    if (g->out_line == NULL) {
        return ft_fail(err, FT_ERR_ARG, "GPIO set output: no output line was opened");
    }
    struct gpiod_line *line = (struct gpiod_line *)g->out_line;
    int v = level != 0;
    if (gpiod_line_set_value(line, v) != 0) {
        return ft_fail(err, FT_ERR_IO, "GPIO output line %u on %s: set value %d: %s",
                       gpiod_line_offset(line), gpiod_chip_name((struct gpiod_chip *)g->chip), v,
                       strerror(errno));
    }
    g->out_level = v;
    return FT_OK;
}

void ft_plat_gpio_close(ft_gpio_port *g)
{
    if (g == NULL) {
        return;
    }
    release_all(g);
    g->out_level = 0;
}
