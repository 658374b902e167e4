/* fuzz_driver.c - main() for a fuzz harness outside libFuzzer: runs
 * LLVMFuzzerTestOneInput once over every file in the directories (or files)
 * named on the command line, in name order, so the seed corpus and every
 * regression input run in each normal test run with any compiler.
 *
 * Usage: fuzz_regress_X DIR_OR_FILE...   Names starting with '.' are
 * skipped (.keep placeholders). Fails (exit 1) if an argument cannot be
 * read, or if no input at all was found: a test that ran nothing proves
 * nothing. A harness invariant that fails aborts the run. */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_util.h"

#define DRIVER_NAMES_MAX 4096u
#define DRIVER_PATH_MAX 4096u
#define DRIVER_INPUT_MAX ((size_t)64u << 20) /* no seed or regression input is near this */

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "fuzz driver: %s: %s\n", path, strerror(errno));
        return -1;
    }
    struct stat sb;
    if (fstat(fileno(f), &sb) != 0 || sb.st_size < 0 || (size_t)sb.st_size > DRIVER_INPUT_MAX) {
        fprintf(stderr, "fuzz driver: %s: cannot size it, or larger than %zu bytes\n", path,
                DRIVER_INPUT_MAX);
        fclose(f);
        return -1;
    }
    size_t n = (size_t)sb.st_size;
    /* Exactly n bytes (1 for an empty file), as libFuzzer hands them over, so
     * a sanitizer build catches a read past the input. */
    uint8_t *buf = (uint8_t *)malloc(n > 0u ? n : 1u);
    if (buf == NULL) {
        fclose(f);
        return -1;
    }
    size_t got = fread(buf, 1u, n, f);
    fclose(f);
    if (got != n) {
        fprintf(stderr, "fuzz driver: %s: read %zu of %zu bytes\n", path, got, n);
        free(buf);
        return -1;
    }
    fprintf(stderr, "fuzz driver: %s (%zu bytes)\n", path, n);
    (void)LLVMFuzzerTestOneInput(buf, n);
    free(buf);
    return 0;
}

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Runs every regular file in dir; returns the count, or -1 on an error. */
static long run_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        fprintf(stderr, "fuzz driver: %s: %s\n", dir, strerror(errno));
        return -1;
    }
    char *names[DRIVER_NAMES_MAX];
    size_t count = 0u;
    int failed = 0;
    for (struct dirent *e = readdir(d); e != NULL; e = readdir(d)) {
        if (e->d_name[0] == '.') {
            continue;
        }
        if (count == DRIVER_NAMES_MAX) {
            fprintf(stderr, "fuzz driver: %s: more than %u files\n", dir, DRIVER_NAMES_MAX);
            failed = 1;
            break;
        }
        size_t len = strlen(e->d_name);
        names[count] = (char *)malloc(len + 1u);
        if (names[count] == NULL) {
            failed = 1;
            break;
        }
        memcpy(names[count], e->d_name, len + 1u);
        ++count;
    }
    closedir(d);
    qsort(names, count, sizeof names[0], cmp_names);
    long ran = 0;
    for (size_t i = 0u; i < count; ++i) {
        char path[DRIVER_PATH_MAX];
        int w = snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        struct stat sb;
        if (!failed && w > 0 && (size_t)w < sizeof path && stat(path, &sb) == 0 &&
            S_ISREG(sb.st_mode)) {
            if (run_file(path) != 0) {
                failed = 1;
            } else {
                ++ran;
            }
        }
        free(names[i]);
    }
    return failed ? -1 : ran;
}

int main(int argc, char **argv)
{
    long total = 0;
    for (int i = 1; i < argc; ++i) {
        struct stat sb;
        if (stat(argv[i], &sb) != 0) {
            fprintf(stderr, "fuzz driver: %s: %s\n", argv[i], strerror(errno));
            return 1;
        }
        long n = 0;
        if (S_ISDIR(sb.st_mode)) {
            n = run_dir(argv[i]);
        } else {
            n = run_file(argv[i]) == 0 ? 1 : -1;
        }
        if (n < 0) {
            return 1;
        }
        fprintf(stderr, "fuzz driver: %ld input(s) from %s\n", n, argv[i]);
        total += n;
    }
    if (total == 0) {
        fprintf(stderr, "fuzz driver: no input found (usage: %s DIR_OR_FILE...)\n",
                argc > 0 ? argv[0] : "fuzz_driver");
        return 1;
    }
    printf("fuzz driver: %ld input(s) ran without a finding\n", total);
    return 0;
}
