/* degrade.h - keeps frames inside the frame budget when the scene is too
 * heavy, by coarsening the LOD, with hysteresis.
 *
 * Input per frame: the frame's measured time (LOD selection + draw + GPU
 * finish) against the budget (frame.budget_ms). Output: a LOD scale >= 1
 * that the method applies (bintree: tau_px * scale; pgrid: ray casting
 * only over gamma_px * scale; brute and pgm have no knob, ignore it and
 * the policy reports that).
 *   - over: a frame above FT_DEGRADE_HIGH of the budget (or a miss) raises
 *     the scale by FT_DEGRADE_STEP at once (a miss is already a failure),
 *     at most to max_scale;
 *   - under: FT_DEGRADE_CALM_FRAMES frames in a row below FT_DEGRADE_LOW of
 *     the budget lower it by one step, never below 1;
 *   - between the two bands nothing changes: the gap between LOW and HIGH
 *     (and the calm count) is the hysteresis that keeps the scale from
 *     oscillating every frame.
 * The error it bought is reported by the method (tau_achieved_px). */
#ifndef FT_DEGRADE_H
#define FT_DEGRADE_H

#include <stdint.h>

#define FT_DEGRADE_HIGH 0.90
#define FT_DEGRADE_LOW 0.55
#define FT_DEGRADE_STEP 1.5
#define FT_DEGRADE_CALM_FRAMES 30u

typedef struct ft_degrade {
    int enabled;
    double budget_ms;
    double max_scale;
    double scale;      /* current LOD scale, 1 = the scene's own setting */
    uint32_t calm;     /* frames in a row below the low band */
    uint32_t raises, lowers;
    uint32_t over_budget; /* frames above the budget (deadline misses) */
} ft_degrade;

void ft_degrade_init(ft_degrade *d, int enabled, double budget_ms, double max_scale);

/* Feeds one frame's time; returns 1 when the scale changed. */
int ft_degrade_frame(ft_degrade *d, double frame_ms);

#endif
