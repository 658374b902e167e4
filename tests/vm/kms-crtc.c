/* kms-crtc.c - runs in the test VM next to fixterrain's KMS path:
 *   kms-crtc watch CARD STOPFILE   keeps CARD open WITHOUT being the DRM
 *       master (it drops master if it got it by opening first), prints the
 *       state of every CRTC ("crtc ID fb FB mode WxH" or "... off"), waits
 *       for STOPFILE (at most 300 s), prints the state again. While it holds
 *       the card open, closing fixterrain is not the card's last close, so
 *       the kernel does not restore its console by itself: the CRTC state it
 *       prints afterwards is what fixterrain's own teardown left.
 *   kms-crtc master CARD STOPFILE  holds the DRM master until STOPFILE exists
 *       (so fixterrain must fail with "not the DRM master").
 * Prints "kms-crtc: ready" once its setup is done. Exit 0, 1 on errors. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

static int print_crtcs(int fd, const char *when)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (res == NULL) {
        fprintf(stderr, "kms-crtc: drmModeGetResources: %s\n", strerror(errno));
        return 0;
    }
    for (int i = 0; i < res->count_crtcs; ++i) {
        drmModeCrtc *c = drmModeGetCrtc(fd, res->crtcs[i]);
        if (c == NULL) {
            continue;
        }
        if (c->buffer_id != 0u && c->mode_valid) {
            printf("%s: crtc %u fb %u mode %ux%u\n", when, c->crtc_id, c->buffer_id,
                   c->mode.hdisplay, c->mode.vdisplay);
        } else {
            printf("%s: crtc %u fb %u off\n", when, c->crtc_id, c->buffer_id);
        }
        drmModeFreeCrtc(c);
    }
    drmModeFreeResources(res);
    fflush(stdout);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 4 || (strcmp(argv[1], "watch") != 0 && strcmp(argv[1], "master") != 0)) {
        fprintf(stderr, "usage: kms-crtc watch|master CARD STOPFILE\n");
        return 1;
    }
    const int master = strcmp(argv[1], "master") == 0;
    int fd = open(argv[2], O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        fprintf(stderr, "kms-crtc: open %s: %s\n", argv[2], strerror(errno));
        return 1;
    }
    if (master) {
        if (!drmIsMaster(fd) && drmSetMaster(fd) != 0) {
            fprintf(stderr, "kms-crtc: drmSetMaster: %s\n", strerror(errno));
            return 1;
        }
    } else if (drmIsMaster(fd) && drmDropMaster(fd) != 0) {
        fprintf(stderr, "kms-crtc: drmDropMaster: %s\n", strerror(errno));
        return 1;
    }
    if (!print_crtcs(fd, "before")) {
        return 1;
    }
    printf("kms-crtc: ready (%s)\n", master ? "holding the DRM master" : "not master");
    fflush(stdout);
    const struct timespec step = {0, 50000000L};
    for (int i = 0; i < 6000 && access(argv[3], F_OK) != 0; ++i) {
        (void)nanosleep(&step, NULL);
    }
    int ok = print_crtcs(fd, "after");
    close(fd);
    return ok ? 0 : 1;
}
