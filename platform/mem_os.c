/* mem_os.c - the one init-time reservation: anonymous, pre-faulted mmap (not
 * the heap), so frames never take a page fault on first touch either. */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <string.h>
#include <sys/mman.h>

#include "core/platform_api.h"

ft_status ft_plat_mem_reserve(size_t bytes, void **out, ft_error *err)
{
    *out = NULL;
    if (bytes == 0) {
        bytes = 4096; /* a scene with every budget at 0 still gets a valid base */
    }
    void *p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE,
                   -1, 0);
    if (p == MAP_FAILED) {
        return ft_fail(err, FT_ERR_BUDGET, "cannot reserve %zu bytes for the arena: %s", bytes,
                       strerror(errno));
    }
    *out = p;
    return FT_OK;
}

void ft_plat_mem_release(void *p, size_t bytes)
{
    if (p != NULL) {
        (void)munmap(p, bytes == 0 ? 4096 : bytes);
    }
}
