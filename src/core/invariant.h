/* invariant.h - what must hold in the frame's code, and what a display does
 * when it does not.
 *
 * FT_INVARIANT(cond, what) states a condition no input can break (input is
 * validated and rejected with an ft_status; this is for the code's own
 * logic). When cond is false:
 *   - a build with FT_INVARIANT_ABORTS = 1 (Debug, where developers run)
 *     stops at once with the file, line and what: the bug is found where it
 *     happened;
 *   - every other build (deployment, and the tests, which check this path)
 *     latches the first fault (what, file, line) and carries on. From then
 *     on every frame is drawn with the fail-safe annunciation, "INTERNAL
 *     FAULT" and the what, over it (app.c), so a crew is told the display is
 *     no longer to be trusted rather than shown a picture that may be wrong
 *     or a frozen screen. The latch stays set until the process ends.
 *
 * The latch is the process's one fault record (a built-in-test fault flag):
 * it has to be reachable from any stage without threading a pointer through
 * every call, and nothing but ft_fault_* reads or writes it. */
#ifndef FT_INVARIANT_H
#define FT_INVARIANT_H

#include <stdint.h>

#ifndef FT_INVARIANT_ABORTS
#define FT_INVARIANT_ABORTS 0
#endif

#define FT_FAULT_TEXT_MAX 80u

typedef struct ft_fault {
    int latched;
    uint32_t count;                  /* failures seen, the first one kept */
    const char *what, *file;         /* string literals */
    int line;
} ft_fault;

/* Records a failed invariant (the first one is kept); aborts when abort_now. */
void ft_fault_raise(const char *what, const char *file, int line, int abort_now);
/* The latched fault, or NULL when every invariant has held. */
const ft_fault *ft_fault_latched(void);
/* "INTERNAL FAULT <what>" for the annunciation, into buf[FT_FAULT_TEXT_MAX]. */
const char *ft_fault_text(char *buf);
/* Clears the latch: for tests only (a display never clears it). */
void ft_fault_clear_for_test(void);

#define FT_INVARIANT(cond, what)                                                  \
    do {                                                                          \
        if (!(cond)) {                                                            \
            ft_fault_raise((what), __FILE__, __LINE__, FT_INVARIANT_ABORTS);     \
        }                                                                         \
    } while (0)

#endif
