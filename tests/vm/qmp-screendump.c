/* qmp-screendump.c - takes a screendump of a running qemu through its QMP
 * socket (run-vm.sh with FT_VM_DISPLAY: OUTDIR/qmp.sock): the scanout of the
 * display device as a binary PPM, written by qemu itself.
 *   qmp-screendump SOCKET OUT.ppm
 * Prints the time the command took. Exit 0 on {"return": {}}, 1 otherwise.
 * Every read is bounded (10 s receive timeout, 64 lines per reply). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

static char g_buf[65536];
static size_t g_len;

/* One line (without the newline) into line[cap]; 0 on EOF/timeout. */
static int read_line(int fd, char *line, size_t cap)
{
    for (;;) {
        char *nl = memchr(g_buf, '\n', g_len);
        if (nl != NULL) {
            size_t n = (size_t)(nl - g_buf);
            size_t keep = n < cap - 1u ? n : cap - 1u;
            memcpy(line, g_buf, keep);
            line[keep] = '\0';
            memmove(g_buf, nl + 1, g_len - n - 1u);
            g_len -= n + 1u;
            return 1;
        }
        if (g_len == sizeof g_buf) {
            g_len = 0; /* an absurdly long line: drop it */
        }
        ssize_t r = read(fd, g_buf + g_len, sizeof g_buf - g_len);
        if (r <= 0) {
            return 0;
        }
        g_len += (size_t)r;
    }
}

/* Sends cmd and reads lines until the reply (not an asynchronous event). */
static int execute(int fd, const char *cmd, char *reply, size_t cap)
{
    size_t n = strlen(cmd);
    if (write(fd, cmd, n) != (ssize_t)n) {
        return 0;
    }
    for (int i = 0; i < 64; ++i) {
        if (!read_line(fd, reply, cap)) {
            return 0;
        }
        if (strstr(reply, "\"return\"") != NULL || strstr(reply, "\"error\"") != NULL) {
            return 1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    char line[4096];
    if (argc != 3 || strchr(argv[2], '"') != NULL || strchr(argv[2], '\\') != NULL) {
        fprintf(stderr, "usage: qmp-screendump SOCKET OUT.ppm (no quotes in the path)\n");
        return 2;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    if (fd < 0 || strlen(argv[1]) >= sizeof addr.sun_path) {
        fprintf(stderr, "qmp-screendump: bad socket path %s\n", argv[1]);
        return 1;
    }
    memcpy(addr.sun_path, argv[1], strlen(argv[1]) + 1u);
    struct timeval tv = {10, 0};
    (void)setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    if (connect(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        fprintf(stderr, "qmp-screendump: connect %s: %s\n", argv[1], strerror(errno));
        return 1;
    }
    if (!read_line(fd, line, sizeof line) || strstr(line, "\"QMP\"") == NULL) {
        fprintf(stderr, "qmp-screendump: no QMP greeting\n");
        return 1;
    }
    if (!execute(fd, "{\"execute\": \"qmp_capabilities\"}\n", line, sizeof line) ||
        strstr(line, "\"return\"") == NULL) {
        fprintf(stderr, "qmp-screendump: qmp_capabilities: %s\n", line);
        return 1;
    }
    char cmd[1200];
    int n = snprintf(cmd, sizeof cmd,
                     "{\"execute\": \"screendump\", \"arguments\": {\"filename\": \"%s\"}}\n",
                     argv[2]);
    if (n < 0 || (size_t)n >= sizeof cmd) {
        fprintf(stderr, "qmp-screendump: path too long\n");
        return 1;
    }
    if (!execute(fd, cmd, line, sizeof line) || strstr(line, "\"return\"") == NULL) {
        fprintf(stderr, "qmp-screendump: screendump: %s\n", line);
        return 1;
    }
    close(fd);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("qmp-screendump: %s in %.1f ms\n", argv[2],
           (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6);
    return 0;
}
