/* test_stderr.h - a test that checks what a call prints on stderr sends
 * stderr into a file around the call and reads it back. Needs
 * _POSIX_C_SOURCE (dup, dup2, fileno) before the first include. */
#ifndef FT_TEST_STDERR_H
#define FT_TEST_STDERR_H

#include <stdio.h>
#include <unistd.h>

#include "test_util.h"

typedef struct ft_test_stderr {
    int saved;  /* the real stderr */
    FILE *sink; /* the file it goes to meanwhile */
    const char *path;
} ft_test_stderr;

static inline void ft_test_stderr_begin(ft_test_stderr *c, const char *path)
{
    fflush(stderr);
    c->path = path;
    c->saved = dup(2);
    REQUIRE(c->saved >= 0);
    c->sink = fopen(path, "wb");
    REQUIRE(c->sink != NULL);
    REQUIRE(dup2(fileno(c->sink), 2) >= 0);
}

/* Puts stderr back and leaves what was printed in msg (cap bytes, NUL-terminated). */
static inline void ft_test_stderr_end(ft_test_stderr *c, char *msg, size_t cap)
{
    fflush(stderr);
    REQUIRE(dup2(c->saved, 2) >= 0);
    close(c->saved);
    fclose(c->sink);
    FILE *f = fopen(c->path, "rb");
    REQUIRE(f != NULL);
    const size_t n = fread(msg, 1, cap - 1u, f);
    msg[n] = '\0';
    fclose(f);
}

#endif
