/* test_debounce.c - discrete input debouncing: bounces shorter than the
 * debounce time never show, a held level changes at exactly edge +
 * debounce_ms, active low inverts, debounce 0 passes every edge, lost edges,
 * reordered edges, samples, bad arguments. */
#include <stdint.h>
#include <string.h>

#include "input/debounce.h"
#include "test_util.h"

#define MS 1000000ull

static ft_debounce make(uint32_t n, uint32_t debounce_ms, int active_low, int level0)
{
    ft_debounce d;
    int levels[FT_DEBOUNCE_SLOTS_MAX];
    for (uint32_t i = 0; i < FT_DEBOUNCE_SLOTS_MAX; ++i) {
        levels[i] = level0;
    }
    ft_error err = {0};
    REQUIRE(ft_debounce_init(&d, n, debounce_ms, active_low, levels, 1000 * MS, &err) == FT_OK);
    return d;
}

static void test_bounces_ignored(void)
{
    ft_debounce d = make(2, 20, 0, 0);
    ft_debounce_change c[FT_DEBOUNCE_SLOTS_MAX];
    ft_debounce_change one;
    uint64_t t = 2000 * MS;
    /* A 19.999999 ms pulse and a burst of short bounces: nothing. */
    CHECK(ft_debounce_edge(&d, 0, 1, t, &one) == 0);
    CHECK(ft_debounce_edge(&d, 0, 0, t + 20 * MS - 1, &one) == 0);
    for (int k = 0; k < 50; ++k) {
        CHECK(ft_debounce_edge(&d, 0, (k & 1) == 0, t + 30 * MS + (uint64_t)k * MS, &one) == 0);
    }
    /* The burst ended low (k = 49 falling): the raw level equals the stable
     * one, so nothing is pending, however long we wait. */
    CHECK(ft_debounce_poll(&d, t + 10000 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 0);
    CHECK(ft_debounce_active(&d, 0) == 0);
    CHECK(d.changes == 0);
    /* Bounces on slot 1 that end high: the change comes debounce after the
     * LAST edge, not the first. */
    uint64_t u = 20000 * MS;
    CHECK(ft_debounce_edge(&d, 1, 1, u, &one) == 0);
    CHECK(ft_debounce_edge(&d, 1, 0, u + 3 * MS, &one) == 0);
    CHECK(ft_debounce_edge(&d, 1, 1, u + 5 * MS, &one) == 0);
    CHECK(ft_debounce_poll(&d, u + 24 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 0);
    CHECK(ft_debounce_poll(&d, u + 25 * MS - 1, c, FT_DEBOUNCE_SLOTS_MAX) == 0);
    REQUIRE(ft_debounce_poll(&d, u + 25 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 1);
    CHECK(c[0].slot == 1 && c[0].active == 1 && c[0].t_ns == u + 25 * MS);
    CHECK(ft_debounce_active(&d, 1) == 1 && ft_debounce_active(&d, 0) == 0);
}

static void test_exact_hold(void)
{
    ft_debounce d = make(1, 15, 0, 0);
    ft_debounce_change c[1];
    ft_debounce_change one;
    uint64_t t = 5000 * MS;
    CHECK(ft_debounce_edge(&d, 0, 1, t, &one) == 0);
    CHECK(ft_debounce_poll(&d, t + 15 * MS - 1, c, 1) == 0);
    CHECK(ft_debounce_active(&d, 0) == 0);
    REQUIRE(ft_debounce_poll(&d, t + 15 * MS, c, 1) == 1);
    CHECK(c[0].slot == 0 && c[0].active == 1 && c[0].t_ns == t + 15 * MS);
    CHECK(ft_debounce_active(&d, 0) == 1);
    CHECK(ft_debounce_poll(&d, t + 100 * MS, c, 1) == 0); /* reported once */

    /* The next edge itself reports the level before it when that had held
     * long enough, even without a poll in between; time stamp = edge +
     * debounce, not the time of the later edge. */
    uint64_t f = t + 200 * MS;
    CHECK(ft_debounce_edge(&d, 0, 0, f, &one) == 0);
    REQUIRE(ft_debounce_edge(&d, 0, 1, f + 15 * MS, &one) == 1);
    CHECK(one.active == 0 && one.t_ns == f + 15 * MS);
    CHECK(ft_debounce_active(&d, 0) == 0);
    REQUIRE(ft_debounce_poll(&d, f + 30 * MS, c, 1) == 1);
    CHECK(c[0].active == 1 && c[0].t_ns == f + 30 * MS);
    CHECK(d.changes == 3);
    /* cap 0: the change stays pending */
    CHECK(ft_debounce_edge(&d, 0, 0, f + 100 * MS, &one) == 0);
    CHECK(ft_debounce_poll(&d, f + 200 * MS, c, 0) == 0);
    REQUIRE(ft_debounce_poll(&d, f + 200 * MS, c, 1) == 1);
    CHECK(c[0].active == 0 && c[0].t_ns == f + 115 * MS);
}

static void test_active_low(void)
{
    /* active low, line idles high (pulled up): inactive. */
    ft_debounce d = make(3, 10, 1, 1);
    ft_debounce_change c[FT_DEBOUNCE_SLOTS_MAX];
    ft_debounce_change one;
    for (uint32_t i = 0; i < 3; ++i) {
        CHECK(ft_debounce_active(&d, i) == 0);
    }
    uint64_t t = 3000 * MS;
    CHECK(ft_debounce_edge(&d, 2, 0, t, &one) == 0); /* pulled low: going active */
    REQUIRE(ft_debounce_poll(&d, t + 10 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 1);
    CHECK(c[0].slot == 2 && c[0].active == 1);
    CHECK(ft_debounce_active(&d, 2) == 1 && ft_debounce_active(&d, 1) == 0);
    CHECK(ft_debounce_edge(&d, 2, 1, t + 50 * MS, &one) == 0);
    REQUIRE(ft_debounce_poll(&d, t + 60 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 1);
    CHECK(c[0].slot == 2 && c[0].active == 0 && c[0].t_ns == t + 60 * MS);
    /* active low with a line starting low: active from the start */
    ft_debounce e = make(1, 10, 1, 0);
    CHECK(ft_debounce_active(&e, 0) == 1);
}

static void test_debounce_zero(void)
{
    ft_debounce d = make(2, 0, 0, 0);
    ft_debounce_change c[FT_DEBOUNCE_SLOTS_MAX];
    ft_debounce_change one;
    uint64_t t = 7000 * MS;
    /* Every edge is a change at its own time, even 1 ns apart. */
    for (int k = 0; k < 20; ++k) {
        int rising = (k & 1) == 0;
        memset(&one, 0xAB, sizeof one);
        REQUIRE(ft_debounce_edge(&d, 1, rising, t + (uint64_t)k, &one) == 1);
        CHECK(one.slot == 1 && one.active == rising && one.t_ns == t + (uint64_t)k);
        CHECK(ft_debounce_active(&d, 1) == rising);
    }
    CHECK(d.changes == 20);
    CHECK(ft_debounce_poll(&d, t + 1000 * MS, c, FT_DEBOUNCE_SLOTS_MAX) == 0);
    /* Two edges at the same instant: both pass. */
    CHECK(ft_debounce_edge(&d, 0, 1, t, &one) == 1 && one.active == 1);
    CHECK(ft_debounce_edge(&d, 0, 0, t, &one) == 1 && one.active == 0);
    /* A repeated edge (the opposite one was lost) is not a change. */
    CHECK(ft_debounce_edge(&d, 0, 0, t + 1, &one) == 0);
    CHECK(d.repeated == 1);
    /* active low + debounce 0 */
    ft_debounce e = make(1, 0, 1, 1);
    CHECK(ft_debounce_edge(&e, 0, 0, t, &one) == 1 && one.active == 1);
    CHECK(ft_debounce_edge(&e, 0, 1, t + 5, &one) == 1 && one.active == 0);
}

static void test_lost_and_reordered_edges(void)
{
    ft_debounce d = make(1, 10, 0, 0);
    ft_debounce_change c[1];
    ft_debounce_change one;
    uint64_t t = 9000 * MS;
    CHECK(ft_debounce_edge(&d, 0, 1, t, &one) == 0);
    /* A second rising edge 8 ms later: a falling edge was lost in between, so
     * the line bounced and the hold restarts. */
    CHECK(ft_debounce_edge(&d, 0, 1, t + 8 * MS, &one) == 0);
    CHECK(d.repeated == 1);
    CHECK(ft_debounce_poll(&d, t + 10 * MS, c, 1) == 0);
    CHECK(ft_debounce_poll(&d, t + 18 * MS - 1, c, 1) == 0);
    REQUIRE(ft_debounce_poll(&d, t + 18 * MS, c, 1) == 1);
    CHECK(c[0].t_ns == t + 18 * MS && c[0].active == 1);
    /* An edge older than the slot's last one counts as happening then. */
    uint64_t u = t + 100 * MS;
    CHECK(ft_debounce_edge(&d, 0, 0, u, &one) == 0);
    CHECK(ft_debounce_edge(&d, 0, 1, u - 5 * MS, &one) == 0);
    CHECK(d.reordered == 1);
    CHECK(ft_debounce_poll(&d, u + 50 * MS, c, 1) == 0); /* raw back to 1 = stable */
    CHECK(ft_debounce_active(&d, 0) == 1);
    /* A sample equal to the raw level does not restart a hold; a different
     * one acts as an edge (repairs a lost edge). */
    uint64_t v = u + 1000 * MS;
    CHECK(ft_debounce_edge(&d, 0, 0, v, &one) == 0);
    CHECK(ft_debounce_sample(&d, 0, 0, v + 9 * MS, &one) == 0);
    REQUIRE(ft_debounce_sample(&d, 0, 0, v + 10 * MS, &one) == 1);
    CHECK(one.active == 0 && one.t_ns == v + 10 * MS);
    CHECK(ft_debounce_sample(&d, 0, 1, v + 20 * MS, &one) == 0); /* missed rising */
    REQUIRE(ft_debounce_poll(&d, v + 30 * MS, c, 1) == 1);
    CHECK(c[0].active == 1 && c[0].t_ns == v + 30 * MS);
    CHECK(d.repeated == 1);
    /* Bad slots are counted, not applied. */
    CHECK(ft_debounce_edge(&d, 1, 1, v, &one) == 0);
    CHECK(ft_debounce_sample(&d, 7, 1, v, &one) == 0);
    CHECK(d.bad_slot == 2 && ft_debounce_active(&d, 1) == 0);
}

static void test_bad_init(void)
{
    ft_debounce d;
    ft_error err = {0};
    int levels[FT_DEBOUNCE_SLOTS_MAX + 1] = {0};
    CHECK(ft_debounce_init(&d, 0, 10, 0, levels, 0, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "must be 1..8") != NULL);
    CHECK(ft_debounce_init(&d, FT_DEBOUNCE_SLOTS_MAX + 1, 10, 0, levels, 0, &err) == FT_ERR_ARG);
    CHECK(ft_debounce_init(&d, 1, FT_DEBOUNCE_MS_MAX + 1, 0, levels, 0, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "60000 ms") != NULL);
    CHECK(ft_debounce_init(&d, 1, 10, 0, NULL, 0, &err) == FT_ERR_ARG);
    CHECK(ft_debounce_init(&d, FT_DEBOUNCE_SLOTS_MAX, FT_DEBOUNCE_MS_MAX, 0, levels, 0, &err) ==
          FT_OK);
}

int main(void)
{
    test_bounces_ignored();
    test_exact_hold();
    test_active_low();
    test_debounce_zero();
    test_lost_and_reordered_edges();
    test_bad_init();
    return ft_test_result("test_debounce");
}
