/* platform-check.c - runs INSIDE the test VM (tests/vm/guest-platform.sh):
 * platform/can_socketcan.c and platform/gpio_gpiod.c against a real vcan
 * interface and the gpio-sim chip.
 *
 *   platform-check CAN_IF GPIO_CHIP SIM_SYSFS WORKDIR
 *     CAN_IF     vcan0
 *     GPIO_CHIP  chip as ft_plat_gpio_open takes it (the label ft-gpio-sim)
 *     SIM_SYSFS  gpio-sim's directory with sim_gpioN/{pull,value}
 *     WORKDIR    writable directory for the canplayer log
 *
 * CAN: (a) filters pass exactly the 311/321 data frames (cansend), remote
 * frames are counted as ignored, timestamps lie between the send and the
 * read on the monotonic base; timestamp accuracy against frames this program
 * sends itself; the kernel drop counter when the receive buffer overflows;
 * (b) error texts; (c) canplayer replays 200 frames at 1 kHz:
 * all received in order, none dropped, receive latency measured.
 * GPIO: (d) edges from gpio-sim pulls with monotonic kernel stamps, levels,
 * a burst of edges in one read, the output followed by gpio-sim's value;
 * (e) error texts (chip not found, busy, out of range).
 * Prints "platform-check: ok: ..." lines with the measured numbers; exits 1
 * after the first failed group with "platform-check: FAIL: ...". */
#define _GNU_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <net/if.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "core/platform_api.h"
#include "input/debounce.h"

extern char **environ;

#define ID_PITCH 311u   /* 0x137, CANaerospace body pitch angle */
#define ID_HEADING 321u /* 0x141, heading angle */
#define REPLAY_FRAMES 200u
#define MS 1000000ull
#define US 1000ull

static int g_failed;
static const char *g_sim;

#define FAIL(...)                                          \
    do {                                                   \
        fprintf(stderr, "platform-check: FAIL: ");         \
        fprintf(stderr, __VA_ARGS__);                      \
        fputc('\n', stderr);                               \
        g_failed = 1;                                      \
        return 1;                                          \
    } while (0)

#define EXPECT(cond, ...)     \
    do {                      \
        if (!(cond)) {        \
            FAIL(__VA_ARGS__); \
        }                     \
    } while (0)

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* Sorts v and prints min/median/p99/max in microseconds. */
static void print_us(const char *what, uint64_t *v, size_t n)
{
    if (n == 0) {
        return;
    }
    qsort(v, n, sizeof v[0], cmp_u64);
    printf("platform-check:   %s (n=%zu): min %.1f us, median %.1f us, p99 %.1f us, max %.1f us\n",
           what, n, (double)v[0] / 1e3, (double)v[n / 2] / 1e3,
           (double)v[(n * 99) / 100] / 1e3, (double)v[n - 1] / 1e3);
}

/* Reads until `want` frames are in out[] or timeout_ms passes (poll on the
 * port's socket between reads). */
static uint32_t can_wait(ft_can_port *p, ft_can_frame *out, uint32_t want, uint32_t timeout_ms,
                         ft_error *err, ft_status *st)
{
    uint32_t have = 0;
    uint64_t end = ft_plat_monotonic_ns() + (uint64_t)timeout_ms * MS;
    *st = FT_OK;
    while (have < want) {
        uint32_t got = 0;
        *st = ft_plat_can_read(p, out + have, want - have, &got, err);
        if (*st != FT_OK) {
            return have;
        }
        have += got;
        uint64_t now = ft_plat_monotonic_ns();
        if (have >= want || now >= end) {
            break;
        }
        struct pollfd pf = {.fd = p->fd, .events = POLLIN};
        (void)poll(&pf, 1, (int)((end - now) / MS) + 1);
    }
    return have;
}

/* ---- (a) filters, ignored frames, timestamps --------------------------------- */
static int check_can_filters(const char *ifname)
{
    ft_can_port p;
    ft_error err = {0};
    /* duplicate id on purpose: merged into one filter pair */
    const uint16_t ids[3] = {ID_PITCH, ID_HEADING, ID_PITCH};
    ft_status s = ft_plat_can_open(&p, ifname, ids, 3, &err);
    EXPECT(s == FT_OK, "ft_plat_can_open(%s): %s", ifname, err.text);

    /* frame, expected to pass? */
    static const struct {
        const char *text;
        int pass;
        uint32_t id;
        uint8_t dlc;
        uint8_t b0;
    } send[] = {
        {"137#1122334455667788", 1, ID_PITCH, 8, 0x11},
        {"3E7#0102", 0, 0, 0, 0},          /* 999: not mapped */
        {"141#AABBCCDD", 1, ID_HEADING, 4, 0xAA},
        {"137#R", 0, 0, 0, 0},             /* remote request for 311: ignored */
        {"00000137#01", 0, 0, 0, 0},       /* extended id 0x137: filtered */
        {"138#01", 0, 0, 0, 0},            /* neighbour id */
        {"141#01", 1, ID_HEADING, 1, 0x01},
    };
    uint64_t last_t = 0;
    uint32_t delivered = 0;
    for (size_t i = 0; i < sizeof send / sizeof send[0]; ++i) {
        uint64_t t_before = ft_plat_monotonic_ns();
        /* cansend runs while we wait in poll(), so the read follows the
         * frame's arrival, not cansend's exit */
        pid_t pid;
        char *argv[] = {"cansend", (char *)ifname, (char *)send[i].text, NULL};
        int rc = posix_spawnp(&pid, "cansend", NULL, NULL, argv, environ);
        EXPECT(rc == 0, "spawn cansend: %s", strerror(rc));
        ft_can_frame f[4];
        uint32_t want = send[i].pass ? 1u : 0u;
        uint32_t got = 0;
        if (want == 1u) {
            got = can_wait(&p, f, 1, 2000, &err, &s);
        }
        uint64_t t_read = ft_plat_monotonic_ns();
        int status = -1;
        EXPECT(waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0,
               "cansend %s %s failed (status %d)", ifname, send[i].text, status);
        if (want == 0u) {
            /* must not pass: cansend is done, look for 50 ms more */
            got = can_wait(&p, f, 4, 50, &err, &s);
        }
        EXPECT(s == FT_OK, "ft_plat_can_read: %s", err.text);
        EXPECT(got == want, "after cansend %s: read %u frames, want %u", send[i].text, got, want);
        if (got == 1u) {
            EXPECT(f[0].can_id == send[i].id && f[0].extended == 0u && f[0].dlc == send[i].dlc &&
                       f[0].data[0] == send[i].b0,
                   "cansend %s: got id %u ext %u dlc %u data[0] %02X", send[i].text,
                   (unsigned)f[0].can_id, f[0].extended, f[0].dlc, f[0].data[0]);
            EXPECT(f[0].dlc == 8u || f[0].data[f[0].dlc] == 0u, "bytes past dlc not zero");
            EXPECT(f[0].t_ns >= t_before && f[0].t_ns <= t_read,
                   "cansend %s: timestamp %llu not between send %llu and read %llu",
                   send[i].text, (unsigned long long)f[0].t_ns, (unsigned long long)t_before,
                   (unsigned long long)t_read);
            EXPECT(t_read - f[0].t_ns < 50u * MS, "timestamp %.3f ms before the read (>= 50 ms)",
                   (double)(t_read - f[0].t_ns) / 1e6);
            EXPECT(f[0].t_ns > last_t, "timestamps not increasing");
            last_t = f[0].t_ns;
            ++delivered;
        }
    }
    EXPECT(delivered == 3u && p.rx_frames == 3u, "delivered %u, rx_frames %llu, want 3", delivered,
           (unsigned long long)p.rx_frames);
    EXPECT(p.rx_ignored == 1u, "rx_ignored %llu, want 1 (the remote frame)",
           (unsigned long long)p.rx_ignored);
    EXPECT(p.rx_dropped == 0u, "rx_dropped %llu", (unsigned long long)p.rx_dropped);
    printf("platform-check: ok: %s filters: 311/321 data frames only (999, 0x138, extended 0x137 "
           "filtered; 1 remote frame counted in rx_ignored); timestamps increasing, between "
           "cansend and read\n",
           ifname);

    /* Accuracy: frames sent by this program from a second socket; the
     * kernel stamps a vcan frame inside the sending write(), so a correct
     * conversion puts it in [before write, after write]. */
    int tx = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    EXPECT(tx >= 0, "socket(AF_CAN): %s", strerror(errno));
    struct sockaddr_can a;
    memset(&a, 0, sizeof a);
    a.can_family = AF_CAN;
    a.can_ifindex = (int)if_nametoindex(ifname);
    EXPECT(bind(tx, (struct sockaddr *)&a, sizeof a) == 0, "bind tx: %s", strerror(errno));
    enum { N_ACC = 200 };
    static uint64_t outside[N_ACC], inside[N_ACC], width[N_ACC], lat[N_ACC];
    uint32_t n_early = 0, n_late = 0;
    for (int i = 0; i < N_ACC; ++i) {
        struct can_frame cf;
        memset(&cf, 0, sizeof cf);
        cf.can_id = (i & 1) ? ID_HEADING : ID_PITCH;
        cf.len = 8;
        cf.data[3] = (uint8_t)i;
        uint64_t t0 = ft_plat_monotonic_ns();
        ssize_t w = write(tx, &cf, sizeof cf);
        uint64_t t1 = ft_plat_monotonic_ns();
        EXPECT(w == (ssize_t)sizeof cf, "write: %s", strerror(errno));
        ft_can_frame f;
        uint32_t got = can_wait(&p, &f, 1, 1000, &err, &s);
        uint64_t t2 = ft_plat_monotonic_ns();
        EXPECT(s == FT_OK && got == 1u && f.data[3] == (uint8_t)i, "self-sent frame %d not read",
               i);
        outside[i] = f.t_ns < t0 ? t0 - f.t_ns : (f.t_ns > t1 ? f.t_ns - t1 : 0u);
        n_early += f.t_ns < t0;
        n_late += f.t_ns > t1;
        inside[i] = f.t_ns >= t0 ? f.t_ns - t0 : 0u;
        width[i] = t1 - t0;
        lat[i] = t2 - f.t_ns;
    }
    (void)close(tx);
    printf("platform-check: ok: timestamp accuracy, %d frames sent by this program "
           "(kernel stamp vs the write() that sent it, on the monotonic base):\n",
           N_ACC);
    printf("platform-check:   stamps before the write: %u, after it: %u\n", n_early, n_late);
    print_us("stamp outside [before write, after write]", outside, N_ACC);
    print_us("stamp - before write", inside, N_ACC);
    print_us("write() duration", width, N_ACC);
    print_us("read done - stamp", lat, N_ACC);
    EXPECT(outside[N_ACC - 1] <= 200u * US,
           "a stamp lies %.1f us outside its write() (conversion error)",
           (double)outside[N_ACC - 1] / 1e3);
    ft_plat_can_close(&p);
    EXPECT(p.fd == -1, "close left fd %d", p.fd);
    ft_plat_can_close(&p); /* twice is harmless */
    return 0;
}

/* ---- receive buffer overflow: the kernel drop counter ------------------------- */
/* Sends N_FLOOD frames without reading: what does not fit in the
 * receive buffer is dropped by the kernel, and delivered + rx_dropped must
 * account for every frame. Prints how many frames the buffer holds. */
static int check_can_overflow(const char *ifname)
{
    enum { N_FLOOD = 8000 }; /* more than the 2 MiB receive queue holds */
    ft_can_port p;
    ft_error err = {0};
    const uint16_t ids[1] = {ID_PITCH};
    EXPECT(ft_plat_can_open(&p, ifname, ids, 1, &err) == FT_OK, "open: %s", err.text);
    int tx = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    EXPECT(tx >= 0, "socket(AF_CAN): %s", strerror(errno));
    struct sockaddr_can a;
    memset(&a, 0, sizeof a);
    a.can_family = AF_CAN;
    a.can_ifindex = (int)if_nametoindex(ifname);
    EXPECT(bind(tx, (struct sockaddr *)&a, sizeof a) == 0, "bind tx: %s", strerror(errno));
    for (int i = 0; i < N_FLOOD; ++i) {
        struct can_frame cf;
        memset(&cf, 0, sizeof cf);
        cf.can_id = ID_PITCH;
        cf.len = 8;
        cf.data[2] = (uint8_t)(i >> 8);
        cf.data[3] = (uint8_t)i;
        EXPECT(write(tx, &cf, sizeof cf) == (ssize_t)sizeof cf, "write %d: %s", i,
               strerror(errno));
    }
    (void)close(tx);
    static ft_can_frame f[64];
    uint32_t total = 0, calls = 0, first_lost = 0;
    for (;;) {
        uint32_t got = 0;
        EXPECT(ft_plat_can_read(&p, f, 64, &got, &err) == FT_OK, "read: %s", err.text);
        ++calls;
        for (uint32_t k = 0; k < got; ++k) {
            uint32_t seq = (uint32_t)f[k].data[2] << 8 | f[k].data[3];
            EXPECT(seq == total + k, "frame %u has sequence %u: not the oldest first", total + k,
                   seq);
        }
        total += got;
        if (got == 0u || calls > N_FLOOD) {
            break;
        }
    }
    first_lost = total;
    EXPECT(p.rx_dropped > 0u && total + p.rx_dropped == (uint64_t)N_FLOOD,
           "flood: delivered %u + rx_dropped %llu != %d sent", total,
           (unsigned long long)p.rx_dropped, N_FLOOD);
    printf("platform-check: ok: %d frames sent without reading: the receive buffer held "
           "%u (the oldest), rx_dropped %llu = the rest (newest dropped; SO_RXQ_OVFL + SO_MEMINFO); delivered + dropped = sent\n",
           N_FLOOD, first_lost, (unsigned long long)p.rx_dropped);
    ft_plat_can_close(&p);
    return 0;
}

/* ---- (b) error texts ------------------------------------------------------------ */
static int expect_open_error(const char *ifname, const uint16_t *ids, uint32_t n, ft_status want,
                             const char *text)
{
    ft_can_port p;
    ft_error err = {0};
    ft_status s = ft_plat_can_open(&p, ifname, ids, n, &err);
    EXPECT(s == want && strstr(err.text, text) != NULL && p.fd == -1,
           "open '%s': status %s, text '%s'; want %s and '%s'", ifname, ft_status_str(s),
           err.text, ft_status_str(want), text);
    printf("platform-check: ok: error: %s\n", err.text);
    return 0;
}

static int check_can_errors(void)
{
    const uint16_t ids[2] = {ID_PITCH, ID_HEADING};
    uint16_t many[FT_CAN_FILTERS_MAX + 1u];
    for (uint32_t i = 0; i <= FT_CAN_FILTERS_MAX; ++i) {
        many[i] = (uint16_t)(0x100u + i);
    }
    const uint16_t bad[1] = {0x800};
    if (expect_open_error("vcan9", ids, 2, FT_ERR_IO, "CAN interface 'vcan9' not found") ||
        expect_open_error("lo", ids, 2, FT_ERR_IO, "'lo' is not a CAN interface") ||
        expect_open_error("vcan0", bad, 1, FT_ERR_ARG, "not an 11-bit id") ||
        expect_open_error("vcan0", many, FT_CAN_FILTERS_MAX + 1u, FT_ERR_ARG, "at most 32") ||
        expect_open_error("vcan0", ids, 0, FT_ERR_ARG, "no CAN ids") ||
        expect_open_error("a-very-long-interface-name", ids, 2, FT_ERR_ARG, "longer than 15")) {
        return 1;
    }
    /* the full 32 ids are fine */
    ft_can_port p;
    ft_error err = {0};
    EXPECT(ft_plat_can_open(&p, "vcan0", many, FT_CAN_FILTERS_MAX, &err) == FT_OK,
           "open with %u ids: %s", (unsigned)FT_CAN_FILTERS_MAX, err.text);
    ft_plat_can_close(&p);
    return 0;
}

/* ---- (c) canplayer: 200 frames at 1 kHz ----------------------------------------- */
static int check_can_replay(const char *ifname, const char *workdir)
{
    char log_path[512];
    int n = snprintf(log_path, sizeof log_path, "%s/replay-1khz.log", workdir);
    EXPECT(n > 0 && (size_t)n < sizeof log_path, "workdir path too long");
    FILE *fp = fopen(log_path, "w");
    EXPECT(fp != NULL, "%s: %s", log_path, strerror(errno));
    for (uint32_t i = 0; i < REPLAY_FRAMES; ++i) {
        /* 6-decimal timestamps 1 ms apart; byte 3 = CANaerospace message code */
        fprintf(fp, "(1700000000.%06u) %s %03X#0A02%02X%02X%02X%02X0000\n", (unsigned)(i * 1000u),
                ifname, (i & 1u) ? 0x141u : 0x137u, (unsigned)(i >> 8), (unsigned)(i & 0xFFu),
                (unsigned)(i & 0xFFu), (unsigned)(i >> 8));
    }
    EXPECT(fclose(fp) == 0, "%s: %s", log_path, strerror(errno));

    ft_can_port p;
    ft_error err = {0};
    const uint16_t ids[2] = {ID_PITCH, ID_HEADING};
    EXPECT(ft_plat_can_open(&p, ifname, ids, 2, &err) == FT_OK, "open: %s", err.text);

    pid_t pid;
    char *argv[] = {"canplayer", "-I", log_path, NULL};
    int rc = posix_spawnp(&pid, "canplayer", NULL, NULL, argv, environ);
    EXPECT(rc == 0, "spawn canplayer: %s", strerror(rc));

    static ft_can_frame f[REPLAY_FRAMES + 8u];
    static uint64_t lat[REPLAY_FRAMES];
    uint32_t have = 0, reads = 0;
    ft_status s = FT_OK;
    uint64_t end = ft_plat_monotonic_ns() + 20000u * MS;
    while (have < REPLAY_FRAMES && ft_plat_monotonic_ns() < end) {
        struct pollfd pf = {.fd = p.fd, .events = POLLIN};
        (void)poll(&pf, 1, 100);
        uint32_t got = 0;
        /* cap 16: a display-frame-sized batch, so long queues take several reads */
        s = ft_plat_can_read(&p, f + have, 16, &got, &err);
        uint64_t now = ft_plat_monotonic_ns();
        if (s != FT_OK) {
            break;
        }
        for (uint32_t k = 0; k < got && have + k < REPLAY_FRAMES; ++k) {
            lat[have + k] = now - f[have + k].t_ns;
        }
        have += got;
        reads += got > 0u;
    }
    int status = 0;
    (void)waitpid(pid, &status, 0);
    /* anything beyond the 200? */
    uint32_t extra = 0;
    (void)ft_plat_can_read(&p, f + have, 8, &extra, &err);
    EXPECT(s == FT_OK, "read: %s", err.text);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 0, "canplayer exited with status %d",
           status);
    EXPECT(have == REPLAY_FRAMES && extra == 0u, "received %u (+%u) of %u frames, rx_dropped %llu",
           have, extra, REPLAY_FRAMES, (unsigned long long)p.rx_dropped);
    EXPECT(p.rx_dropped == 0u, "kernel dropped %llu frames", (unsigned long long)p.rx_dropped);
    uint64_t gap_min = UINT64_MAX, gap_max = 0;
    for (uint32_t i = 0; i < REPLAY_FRAMES; ++i) {
        EXPECT(f[i].can_id == ((i & 1u) ? ID_HEADING : ID_PITCH) && f[i].dlc == 8u &&
                   f[i].data[3] == (uint8_t)i && f[i].data[2] == (uint8_t)(i >> 8),
               "frame %u out of order or damaged (id %u, byte3 %u)", i, (unsigned)f[i].can_id,
               f[i].data[3]);
        if (i > 0) {
            EXPECT(f[i].t_ns >= f[i - 1].t_ns, "timestamps go back at frame %u", i);
            uint64_t gap = f[i].t_ns - f[i - 1].t_ns;
            gap_min = gap < gap_min ? gap : gap_min;
            gap_max = gap > gap_max ? gap : gap_max;
        }
    }
    double span_ms = (double)(f[REPLAY_FRAMES - 1].t_ns - f[0].t_ns) / 1e6;
    printf("platform-check: ok: canplayer %u frames at 1 kHz: all received in order, "
           "rx_dropped %llu, %u non-empty reads; stamp span %.1f ms (log: %.1f ms), "
           "gaps min %.3f ms max %.3f ms\n",
           REPLAY_FRAMES, (unsigned long long)p.rx_dropped, reads, span_ms,
           (double)(REPLAY_FRAMES - 1u), (double)gap_min / 1e6, (double)gap_max / 1e6);
    print_us("receive latency, read return - kernel stamp (poll wake-up included)", lat,
             REPLAY_FRAMES);
    ft_plat_can_close(&p);
    return 0;
}

/* ---- GPIO ----------------------------------------------------------------------- */
static int sim_write(unsigned line, const char *what)
{
    char path[512];
    snprintf(path, sizeof path, "%s/sim_gpio%u/pull", g_sim, line);
    FILE *fp = fopen(path, "w");
    if (fp == NULL) {
        fprintf(stderr, "platform-check: %s: %s\n", path, strerror(errno));
        return -1;
    }
    int ok = fputs(what, fp) >= 0;
    ok = (fclose(fp) == 0) && ok;
    if (!ok) {
        fprintf(stderr, "platform-check: write '%s' to %s: %s\n", what, path, strerror(errno));
        return -1;
    }
    return 0;
}

static int sim_value(unsigned line)
{
    char path[512];
    snprintf(path, sizeof path, "%s/sim_gpio%u/value", g_sim, line);
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        return -1;
    }
    int v = -1;
    if (fscanf(fp, "%d", &v) != 1) {
        v = -1;
    }
    fclose(fp);
    return v;
}

static uint32_t gpio_wait(ft_gpio_port *g, ft_gpio_edge *out, uint32_t want, uint32_t timeout_ms,
                          ft_error *err, ft_status *st)
{
    uint32_t have = 0;
    uint64_t end = ft_plat_monotonic_ns() + (uint64_t)timeout_ms * MS;
    *st = FT_OK;
    for (;;) {
        uint32_t got = 0;
        *st = ft_plat_gpio_read_edges(g, out + have, FT_GPIO_EVENTS_MAX - have, &got, err);
        if (*st != FT_OK) {
            return have;
        }
        have += got;
        if (have >= want || ft_plat_monotonic_ns() >= end) {
            return have;
        }
        ft_plat_sleep_ms(1);
    }
}

static int check_gpio(const char *chip)
{
    ft_gpio_port g;
    ft_error err = {0};
    ft_status s;
    /* idle: line 0 low, line 1 high */
    EXPECT(sim_write(0, "pull-down") == 0 && sim_write(1, "pull-up") == 0, "set initial pulls");
    const int in[2] = {0, 1};
    s = ft_plat_gpio_open(&g, chip, in, 2, 7, &err);
    EXPECT(s == FT_OK, "ft_plat_gpio_open(%s, 0 1, out 7): %s", chip, err.text);
    int lv[2] = {-1, -1};
    EXPECT(ft_plat_gpio_levels(&g, lv, &err) == FT_OK, "levels: %s", err.text);
    EXPECT(lv[0] == 0 && lv[1] == 1, "initial levels %d %d, want 0 1", lv[0], lv[1]);
    ft_gpio_edge e[FT_GPIO_EVENTS_MAX];
    uint32_t got = gpio_wait(&g, e, 1, 20, &err, &s);
    EXPECT(s == FT_OK && got == 0u, "edges before any change: %u (%s)", got, err.text);

    /* Debounce 0 + active low over the real edges: logical = !physical. */
    ft_debounce db;
    EXPECT(ft_debounce_init(&db, 2, 0, 1, lv, ft_plat_monotonic_ns(), &err) == FT_OK, "debounce");

    /* Each step: flip one pull, expect exactly that edge, stamped between
     * the sysfs write and the read, and the levels to follow. */
    enum { STEPS = 8 };
    uint64_t lag[STEPS], real_off_min = UINT64_MAX;
    int level[2] = {0, 1};
    for (int k = 0; k < STEPS; ++k) {
        unsigned line = (unsigned)(k & 1);
        int to = !level[line];
        uint64_t t0 = ft_plat_monotonic_ns();
        EXPECT(sim_write(line, to ? "pull-up" : "pull-down") == 0, "sysfs write");
        got = gpio_wait(&g, e, 1, 2000, &err, &s);
        uint64_t t1 = ft_plat_monotonic_ns();
        struct timespec rt;
        clock_gettime(CLOCK_REALTIME, &rt);
        uint64_t real = (uint64_t)rt.tv_sec * 1000000000ull + (uint64_t)rt.tv_nsec;
        EXPECT(s == FT_OK, "read edges: %s", err.text);
        EXPECT(got == 1u, "step %d (line %u -> %d): %u edges, want 1", k, line, to, got);
        EXPECT(e[0].slot == line && e[0].rising == to, "step %d: edge slot %u rising %d", k,
               e[0].slot, e[0].rising);
        EXPECT(e[0].t_ns >= t0 && e[0].t_ns <= t1,
               "step %d: edge stamp %llu not between write %llu and read %llu: not on the "
               "CLOCK_MONOTONIC base",
               k, (unsigned long long)e[0].t_ns, (unsigned long long)t0,
               (unsigned long long)t1);
        uint64_t d = real > e[0].t_ns ? real - e[0].t_ns : e[0].t_ns - real;
        real_off_min = d < real_off_min ? d : real_off_min;
        lag[k] = e[0].t_ns - t0;
        level[line] = to;
        EXPECT(ft_plat_gpio_levels(&g, lv, &err) == FT_OK, "levels: %s", err.text);
        EXPECT(lv[0] == level[0] && lv[1] == level[1], "levels %d %d, want %d %d", lv[0], lv[1],
               level[0], level[1]);
        ft_debounce_change c;
        EXPECT(ft_debounce_edge(&db, e[0].slot, e[0].rising, e[0].t_ns, &c) == 1 &&
                   c.active == !to && ft_debounce_active(&db, line) == !to,
               "debounce 0 / active low did not follow the edge");
    }
    EXPECT(g.events == (uint64_t)STEPS, "g.events %llu", (unsigned long long)g.events);
    printf("platform-check: ok: %s: %d edges on lines 0/1 (rising and falling), each stamped "
           "between the sysfs write and the read; levels follow; debounced (0 ms, active low) "
           "logical levels follow\n",
           chip, STEPS);
    printf("platform-check:   edge stamps are CLOCK_MONOTONIC (CLOCK_REALTIME differs by >= "
           "%.0f s)\n",
           (double)real_off_min / 1e9);
    print_us("edge stamp - sysfs write start", lag, STEPS);

    /* A burst without reading: 6 edges on line 0 and 3 on line 1, read in
     * one call, sorted by time, alternating per line. 5 ms apart: gpio-sim
     * (irq_sim) drops an edge that comes while the v1 line-event IRQ thread
     * of the previous one has not run yet (the IRQ is masked, ONESHOT), and
     * that thread reads the level to tell rising from falling. */
    for (int k = 0; k < 6; ++k) {
        EXPECT(sim_write(0, (k & 1) ? "pull-down" : "pull-up") == 0, "sysfs write");
        ft_plat_sleep_ms(5);
        if (k < 3) {
            EXPECT(sim_write(1, (k & 1) ? "pull-up" : "pull-down") == 0, "sysfs write");
            ft_plat_sleep_ms(5);
        }
    }
    ft_plat_sleep_ms(20);
    got = 0;
    s = ft_plat_gpio_read_edges(&g, e, FT_GPIO_EVENTS_MAX, &got, &err);
    EXPECT(s == FT_OK && got == 9u, "burst: %u edges in one read, want 9 (%s)", got, err.text);
    int expect_rise[2] = {1, 0};
    for (uint32_t k = 0; k < got; ++k) {
        EXPECT(k == 0 || e[k].t_ns >= e[k - 1].t_ns, "burst not sorted by time at %u", k);
        EXPECT(e[k].rising == expect_rise[e[k].slot], "burst: line %u edge %u wrong direction",
               e[k].slot, k);
        expect_rise[e[k].slot] = !expect_rise[e[k].slot];
    }
    EXPECT(ft_plat_gpio_levels(&g, lv, &err) == FT_OK && lv[0] == 0 && lv[1] == 0,
           "after the burst levels %d %d, want 0 0", lv[0], lv[1]);
    printf("platform-check: ok: burst of 9 edges on 2 lines read in one call, sorted by time, "
           "directions alternate per line\n");

    /* Output: toggle 10 times, gpio-sim's value follows. */
    EXPECT(sim_value(7) == 0, "output line 7 not driven low at open (value %d)", sim_value(7));
    for (int k = 0; k < 10; ++k) {
        int v = !(k & 1);
        EXPECT(ft_plat_gpio_set_output(&g, v, &err) == FT_OK, "set_output: %s", err.text);
        EXPECT(sim_value(7) == v && g.out_level == v, "toggle %d: sim_gpio7/value %d, want %d", k,
               sim_value(7), v);
    }
    printf("platform-check: ok: output line 7 toggled 10 times, sim_gpio7/value followed\n");

    /* (e) errors while the lines are held */
    ft_gpio_port h;
    const int busy[1] = {1};
    s = ft_plat_gpio_open(&h, chip, busy, 1, -1, &err);
    EXPECT(s == FT_ERR_IO && strstr(err.text, "is busy (used by 'fixterrain')") != NULL &&
               h.chip == NULL,
           "second request of line 1: %s '%s'", ft_status_str(s), err.text);
    printf("platform-check: ok: error: %s\n", err.text);
    ft_plat_gpio_close(&g);
    EXPECT(g.chip == NULL && g.in_count == 0u && g.out_line == NULL, "close left state");
    ft_plat_gpio_close(&g);

    const int range[2] = {2, 8};
    s = ft_plat_gpio_open(&h, chip, range, 2, -1, &err);
    EXPECT(s == FT_ERR_CONFIG && strstr(err.text, "line 8 out of range") != NULL &&
               strstr(err.text, "has 8 lines (0..7)") != NULL && h.chip == NULL,
           "line 8: %s '%s'", ft_status_str(s), err.text);
    printf("platform-check: ok: error: %s\n", err.text);
    s = ft_plat_gpio_open(&h, "ft-no-such-chip", in, 2, -1, &err);
    EXPECT(s == FT_ERR_IO && strstr(err.text, "GPIO chip 'ft-no-such-chip' not found") != NULL,
           "missing chip: %s '%s'", ft_status_str(s), err.text);
    printf("platform-check: ok: error: %s\n", err.text);
    const int twice[2] = {3, 3};
    s = ft_plat_gpio_open(&h, chip, twice, 2, -1, &err);
    EXPECT(s == FT_ERR_CONFIG && strstr(err.text, "given twice") != NULL, "twice: '%s'", err.text);
    s = ft_plat_gpio_open(&h, chip, in, 2, 1, &err);
    EXPECT(s == FT_ERR_CONFIG && strstr(err.text, "both an input and the output") != NULL,
           "in+out: '%s'", err.text);
    /* everything released: the same lines can be opened again (by path) */
    char devpath[64];
    snprintf(devpath, sizeof devpath, "/dev/%s", getenv("FT_GPIO_CHIP") ? getenv("FT_GPIO_CHIP") : "gpiochip0");
    s = ft_plat_gpio_open(&h, devpath, in, 2, 7, &err);
    EXPECT(s == FT_OK, "reopen by path %s after close: %s", devpath, err.text);
    ft_plat_gpio_close(&h);
    printf("platform-check: ok: lines released by close and failed opens (reopened via %s)\n",
           devpath);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s CAN_IF GPIO_CHIP SIM_SYSFS WORKDIR\n", argv[0]);
        return 2;
    }
    signal(SIGPIPE, SIG_IGN);
    setvbuf(stdout, NULL, _IOLBF, 0);
    g_sim = argv[3];
    uint64_t t0 = ft_plat_monotonic_ns();
    if (check_can_filters(argv[1]) || check_can_overflow(argv[1]) || check_can_errors() || check_can_replay(argv[1], argv[4]) ||
        check_gpio(argv[2])) {
        return 1;
    }
    printf("platform-check: all checks passed in %.2f s\n",
           (double)(ft_plat_monotonic_ns() - t0) / 1e9);
    return g_failed;
}
