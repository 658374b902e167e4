/* can_socketcan.c - CAN input over SocketCAN (one CAN_RAW socket).
 *
 * Open: socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW),
 * kernel filters, timestamp and drop-counter options, then bind to the
 * interface (an unbound CAN_RAW socket receives nothing, so no frame can
 * slip in before the filters are set).
 *
 * Filters (CAN_RAW_FILTER): per mapped id (11-bit) one filter
 *   { id, CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG }
 * which passes only standard data frames with exactly that id, plus one
 *   { id | CAN_RTR_FLAG, same mask }
 * which passes remote requests for that id, and CAN_RAW_ERR_FILTER =
 * CAN_ERR_MASK for error frames: those two kinds are never delivered, only
 * counted in rx_ignored, so a node polling our ids or a sick bus shows in
 * the counters instead of vanishing in the kernel. Other ids, extended
 * frames and CAN FD frames (CAN_RAW_FD_FRAMES stays off) are dropped by the
 * kernel and cost nothing here. Duplicate ids are merged.
 *
 * Read: recvmsg(MSG_DONTWAIT) in a loop bounded by cap + FT_CAN_NONDATA_MAX
 * iterations (EINTR retries included), until EAGAIN or cap data frames;
 * then one getsockopt(SO_MEMINFO) for the drop counter.
 *
 * Timestamps: SO_TIMESTAMPNS gives the kernel's receive time (taken when the
 * driver hands the frame to the stack, netif_rx) on CLOCK_REALTIME; there is
 * no monotonic socket timestamp. Each ft_plat_can_read samples
 * CLOCK_MONOTONIC, CLOCK_REALTIME, CLOCK_MONOTONIC and converts with
 *   t_mono = t_real - (real - (mono1 + mono2) / 2).
 * Error of that conversion, for a frame received age seconds before the
 * read:
 *   - sampling: +-(mono2 - mono1) / 2: under 1 us with the vDSO, <= 10 us
 *     unless preempted on all tries (then half the tightest bracket);
 *   - rate: the two clocks differ only by NTP/PTP slewing (<= 500 ppm by
 *     the kernel's limit), so <= 500e-6 * age (0.5 us per ms of queueing);
 *   - steps: a settimeofday/clock_settime or an NTP step of the realtime
 *     clock between receive and read shifts the frames read in that call by
 *     the step. Converted times later than the read time are clamped to it
 *     (a frame cannot be received in the future); earlier ones cannot be
 *     detected. Frames are normally read within a display period, so the
 *     window is one period per step.
 *   - the first socket in the system that asks for timestamps enables them
 *     through a deferred kernel work item; frames received before that
 *     work has run are stamped at recvmsg time (later than true), so a test
 *     of accuracy should not use the very first frames after boot.
 * A frame without a timestamp (should not happen) gets the read time.
 *
 * Drops: SO_RXQ_OVFL delivers the socket's cumulative drop counter
 * (sk_drops, 32-bit) with each frame, as it was when that frame was queued;
 * after the loop one getsockopt(SO_MEMINFO) reads the counter as it is now
 * (drops after the last queued frame would otherwise show only with the
 * next frame). rx_dropped is that counter widened to 64 bits: frames lost
 * because the receive buffer was full. The kernel then drops the NEWEST
 * frames; the default buffer (rmem_default 212992 bytes) holds about 280
 * CAN frames (measured on Debian's 6.1, x86_64), i.e. 0.3 s at 1 kHz;
 * SO_RCVBUF cannot raise it above rmem_max without CAP_NET_ADMIN, so it is
 * left alone.
 *
 * Errors carry the reason (strerror). recvmsg reporting ENETDOWN (the
 * interface went down; the socket keeps working when it comes back) or
 * ENODEV (the interface was removed; close and reopen) is an FT_ERR_IO with
 * that explanation. No heap: the socket and the stack only. */
#define _GNU_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <linux/sock_diag.h>
#include <net/if.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>

#include "core/platform_api.h"

#define FT_CAN_RCVBUF_BYTES (2 * 1024 * 1024) /* about 2700 frames */

/* Non-data frames (remote, error, odd sizes) one read may consume beyond
 * cap before it returns: a flood of them cannot hold the caller here. */
#define FT_CAN_NONDATA_MAX 64u
#define FT_NS_PER_S 1000000000ull
/* Clock pair sampling: retry when preempted between the reads (a bracket
 * wider than FT_CAN_CLOCK_GOOD_NS), keep the tightest. */
#define FT_CAN_CLOCK_TRIES 4u
#define FT_CAN_CLOCK_GOOD_NS 20000u

_Static_assert(sizeof(((ft_can_port *)0)->iface) == IFNAMSIZ, "iface holds IFNAMSIZ");

static uint64_t clock_ns(clockid_t id)
{
    struct timespec ts;
    if (clock_gettime(id, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * FT_NS_PER_S + (uint64_t)ts.tv_nsec;
}

static ft_status open_fail(ft_can_port *p, int fd, ft_error *err, ft_status s, const char *what,
                           int errnum)
{
    if (fd >= 0) {
        (void)close(fd);
    }
    p->fd = -1;
    return ft_fail(err, s, "CAN interface '%s': %s: %s", p->iface, what, strerror(errnum));
}

ft_status ft_plat_can_open(ft_can_port *p, const char *iface, const uint16_t *ids,
                           uint32_t id_count, ft_error *err)
{
    if (p == NULL) {
        return ft_fail(err, FT_ERR_ARG, "CAN open: NULL port");
    }
    *p = (ft_can_port){.fd = -1};
    if (iface == NULL || iface[0] == '\0') {
        return ft_fail(err, FT_ERR_ARG, "CAN open: no interface name");
    }
    size_t name_len = strlen(iface);
    if (name_len >= sizeof p->iface) {
        return ft_fail(err, FT_ERR_ARG, "CAN interface name '%.40s%s' is longer than %u characters",
                       iface, name_len > 40u ? "..." : "", (unsigned)(sizeof p->iface - 1u));
    }
    memcpy(p->iface, iface, name_len + 1u);
    if (ids == NULL || id_count == 0u) {
        return ft_fail(err, FT_ERR_ARG, "CAN interface '%s': no CAN ids to receive", iface);
    }
    if (id_count > FT_CAN_FILTERS_MAX) {
        return ft_fail(err, FT_ERR_ARG, "CAN interface '%s': %u ids, at most %u", iface,
                       (unsigned)id_count, (unsigned)FT_CAN_FILTERS_MAX);
    }

    /* Two filters per distinct id: data frames, remote requests. */
    struct can_filter flt[2u * FT_CAN_FILTERS_MAX];
    uint32_t n_ids = 0;
    for (uint32_t i = 0; i < id_count; ++i) {
        if (ids[i] > CAN_SFF_MASK) {
            return ft_fail(err, FT_ERR_ARG,
                           "CAN interface '%s': id %u (0x%X) is not an 11-bit id (max 0x7FF)",
                           iface, (unsigned)ids[i], (unsigned)ids[i]);
        }
        int dup = 0;
        for (uint32_t k = 0; k < n_ids && !dup; ++k) {
            dup = flt[2u * k].can_id == ids[i];
        }
        if (!dup) {
            const canid_t mask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
            flt[2u * n_ids] = (struct can_filter){.can_id = ids[i], .can_mask = mask};
            flt[2u * n_ids + 1u] =
                (struct can_filter){.can_id = ids[i] | CAN_RTR_FLAG, .can_mask = mask};
            ++n_ids;
        }
    }

    int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        int e = errno;
        if (e == EAFNOSUPPORT || e == EPROTONOSUPPORT || e == ESOCKTNOSUPPORT) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "CAN interface '%s': this kernel has no CAN support "
                           "(socket(AF_CAN): %s; modules can and can-raw)",
                           iface, strerror(e));
        }
        return open_fail(p, -1, err, FT_ERR_IO, "socket(AF_CAN, SOCK_RAW, CAN_RAW)", e);
    }
    errno = 0;
    unsigned ifindex = if_nametoindex(iface);
    if (ifindex == 0u) {
        int e = errno;
        (void)close(fd);
        if (e == ENODEV || e == 0 || e == ENXIO) {
            return ft_fail(err, FT_ERR_IO, "CAN interface '%s' not found", iface);
        }
        return ft_fail(err, FT_ERR_IO, "CAN interface '%s': if_nametoindex: %s", iface,
                       strerror(e));
    }
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, flt,
                   (socklen_t)(2u * n_ids * sizeof flt[0])) != 0) {
        return open_fail(p, fd, err, FT_ERR_IO, "setsockopt(CAN_RAW_FILTER)", errno);
    }
    can_err_mask_t err_mask = CAN_ERR_MASK;
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0) {
        return open_fail(p, fd, err, FT_ERR_IO, "setsockopt(CAN_RAW_ERR_FILTER)", errno);
    }
    int on = 1;
    if (setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) != 0) {
        return open_fail(p, fd, err, FT_ERR_IO, "setsockopt(SO_TIMESTAMPNS)", errno);
    }
    if (setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) != 0) {
        return open_fail(p, fd, err, FT_ERR_IO, "setsockopt(SO_RXQ_OVFL)", errno);
    }
    /* A larger receive queue rides out a slow frame (the default holds
     * about 278 frames: half a second of a CANaerospace attitude stream).
     * SO_RCVBUFFORCE needs CAP_NET_ADMIN; without it SO_RCVBUF is capped
     * by net.core.rmem_max. Neither failing is an error: drops are counted. */
    const int rcvbuf_bytes = FT_CAN_RCVBUF_BYTES;
    if (setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &rcvbuf_bytes, sizeof rcvbuf_bytes) != 0) {
        (void)setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf_bytes, sizeof rcvbuf_bytes);
    }
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = (int)ifindex;
    if (bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        int e = errno;
        if (e == ENODEV) {
            (void)close(fd);
            return ft_fail(err, FT_ERR_IO,
                           "CAN interface '%s' is not a CAN interface (bind: %s)", iface,
                           strerror(e));
        }
        return open_fail(p, fd, err, FT_ERR_IO, "bind", e);
    }
    p->fd = fd;
    return FT_OK;
}

/* Widens the kernel's cumulative 32-bit drop counter (sk_drops, wraps) into
 * rx_dropped; a stale (smaller) value is ignored. */
static void note_drops(ft_can_port *p, uint32_t drops)
{
    uint32_t delta = drops - (uint32_t)p->rx_dropped;
    if (delta != 0u && delta < 0x80000000u) {
        p->rx_dropped += delta;
    }
}

/* Control buffer for one SCM_TIMESTAMPNS and one SO_RXQ_OVFL message,
 * aligned for struct cmsghdr. */
typedef union ft_can_cmsg_buf {
    struct cmsghdr align;
    unsigned char bytes[CMSG_SPACE(sizeof(struct timespec)) + CMSG_SPACE(sizeof(uint32_t)) + 64u];
} ft_can_cmsg_buf;

ft_status ft_plat_can_read(ft_can_port *p, ft_can_frame *out, uint32_t cap, uint32_t *got,
                           ft_error *err)
{
    if (got != NULL) {
        *got = 0;
    }
    if (p == NULL || got == NULL || (out == NULL && cap > 0u)) {
        return ft_fail(err, FT_ERR_ARG, "CAN read: NULL argument");
    }
    if (p->fd < 0) {
        return ft_fail(err, FT_ERR_ARG, "CAN interface '%s': read on a closed port", p->iface);
    }
    if (cap == 0u) {
        return FT_OK;
    }
    /* realtime -> monotonic offset, sampled now (see the header comment):
     * the tightest of up to FT_CAN_CLOCK_TRIES brackets. */
    uint64_t mono2 = 0;
    int64_t real_minus_mono = 0;
    uint64_t best_width_ns = UINT64_MAX;
    for (uint32_t k = 0; k < FT_CAN_CLOCK_TRIES && best_width_ns > FT_CAN_CLOCK_GOOD_NS; ++k) {
        uint64_t m1 = clock_ns(CLOCK_MONOTONIC);
        uint64_t r = clock_ns(CLOCK_REALTIME);
        uint64_t m2 = clock_ns(CLOCK_MONOTONIC);
        if (m2 - m1 < best_width_ns) {
            best_width_ns = m2 - m1;
            real_minus_mono = (int64_t)(r - (m1 + (m2 - m1) / 2u));
            mono2 = m2;
        }
    }

    uint32_t n = 0;
    const uint32_t iterations_max =
        cap > UINT32_MAX - FT_CAN_NONDATA_MAX ? UINT32_MAX : cap + FT_CAN_NONDATA_MAX;
    for (uint32_t it = 0; it < iterations_max && n < cap; ++it) {
        struct can_frame cf;
        struct iovec iov = {.iov_base = &cf, .iov_len = sizeof cf};
        ft_can_cmsg_buf ctrl;
        struct msghdr msg;
        memset(&msg, 0, sizeof msg);
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        msg.msg_control = ctrl.bytes;
        msg.msg_controllen = sizeof ctrl.bytes;
        ssize_t nb = recvmsg(p->fd, &msg, MSG_DONTWAIT);
        if (nb < 0) {
            int e = errno;
            if (e == EAGAIN || e == EWOULDBLOCK) {
                break;
            }
            if (e == EINTR) {
                continue; /* counted against iterations_max */
            }
            *got = n;
            if (e == ENETDOWN) {
                return ft_fail(err, FT_ERR_IO,
                               "CAN interface '%s' went down (recvmsg: %s); reception resumes "
                               "when it is up again",
                               p->iface, strerror(e));
            }
            if (e == ENODEV) {
                return ft_fail(err, FT_ERR_IO,
                               "CAN interface '%s' was removed (recvmsg: %s); reopen it",
                               p->iface, strerror(e));
            }
            return ft_fail(err, FT_ERR_IO, "CAN interface '%s': recvmsg: %s", p->iface,
                           strerror(e));
        }
        uint64_t t_real_ns = 0;
        int have_ts = 0;
        for (struct cmsghdr *c = CMSG_FIRSTHDR(&msg); c != NULL; c = CMSG_NXTHDR(&msg, c)) {
            if (c->cmsg_level != SOL_SOCKET) {
                continue;
            }
            if (c->cmsg_type == SCM_TIMESTAMPNS &&
                c->cmsg_len >= CMSG_LEN(sizeof(struct timespec))) {
                struct timespec ts;
                memcpy(&ts, CMSG_DATA(c), sizeof ts);
                t_real_ns = (uint64_t)ts.tv_sec * FT_NS_PER_S + (uint64_t)ts.tv_nsec;
                have_ts = ts.tv_sec > 0 || ts.tv_nsec > 0;
            } else if (c->cmsg_type == SO_RXQ_OVFL && c->cmsg_len >= CMSG_LEN(sizeof(uint32_t))) {
                uint32_t drops;
                memcpy(&drops, CMSG_DATA(c), sizeof drops);
                note_drops(p, drops);
            }
        }
        if ((size_t)nb != sizeof cf || (msg.msg_flags & MSG_TRUNC) != 0 ||
            (cf.can_id & (CAN_ERR_FLAG | CAN_RTR_FLAG)) != 0u || cf.len > CAN_MAX_DLEN) {
            p->rx_ignored++;
            continue;
        }
        ft_can_frame *f = &out[n];
        memset(f, 0, sizeof *f);
        if ((cf.can_id & CAN_EFF_FLAG) != 0u) {
            f->extended = 1u; /* not passed by our filters; the decoder rejects it */
            f->can_id = cf.can_id & CAN_EFF_MASK;
        } else {
            f->can_id = cf.can_id & CAN_SFF_MASK;
        }
        f->dlc = cf.len;
        memcpy(f->data, cf.data, cf.len);
        uint64_t t = mono2;
        if (have_ts) {
            int64_t tm = (int64_t)t_real_ns - real_minus_mono;
            t = tm > 0 ? (uint64_t)tm : 0u;
        }
        if (!have_ts || t > mono2) {
            /* no stamp, or later than the clocks were sampled: the frame may
             * have arrived during this loop, or the realtime clock stepped
             * back; never later than now */
            uint64_t now = clock_ns(CLOCK_MONOTONIC);
            t = (!have_ts || t > now) ? now : t;
        }
        f->t_ns = t;
        ++n;
    }
    /* The drop count that came with the frames is the one from when each
     * was queued: drops after the last queued frame (a full buffer drops
     * the newest) only show with the next frame. SO_MEMINFO has the count
     * now. */
    uint32_t meminfo[SK_MEMINFO_VARS];
    socklen_t len = (socklen_t)sizeof meminfo;
    if (getsockopt(p->fd, SOL_SOCKET, SO_MEMINFO, meminfo, &len) == 0 &&
        len >= (socklen_t)((SK_MEMINFO_DROPS + 1) * sizeof meminfo[0])) {
        note_drops(p, meminfo[SK_MEMINFO_DROPS]);
    } /* else (kernel < 4.12): the per-frame count only, lagging as above */
    p->rx_frames += n;
    *got = n;
    return FT_OK;
}

void ft_plat_can_close(ft_can_port *p)
{
    if (p == NULL || p->fd < 0) {
        return;
    }
    (void)close(p->fd); /* Linux frees the descriptor even when close fails */
    p->fd = -1;
}
