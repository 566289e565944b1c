/* test_evq.c — the 4-ary heap against a sorted reference.
 * Slots are unique among pending keys, as the engine's pool makes them. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/evq.h"
#include "sim/core/rng.h"

/* Inserts k into the sorted reference, keeping it sorted. */
static void ref_insert(GArray *ref, SimEvKey k)
{
    guint lo = 0, hi = ref->len;
    while (lo < hi) {
        guint mid = (lo + hi) / 2;
        if (sim_evkey_less(g_array_index(ref, SimEvKey, mid), k))
            lo = mid + 1;
        else
            hi = mid;
    }
    g_array_insert_val(ref, lo, k);
}

/* Random pushes (many equal times), pops and replace_tops; after every
 * operation the heap's least key must equal the reference's least key. */
static void test_heap_matches_sorted_reference(void **state)
{
    (void)state;
    SimEvq *q = sim_evq_new();
    GArray *ref = g_array_new(FALSE, FALSE, sizeof(SimEvKey));
    SimRng r;
    sim_rng_init(&r, 42, 0);
    uint64_t seq = 0;
    for (int op = 0; op < 200000; op++) {
        uint64_t c = sim_rng_below(&r, 10);
        if (ref->len == 0 || c < 5) {
            SimEvKey k = {sim_rng_below(&r, 64), seq, (uint32_t)seq};
            seq++;
            sim_evq_push(q, k);
            ref_insert(ref, k);
        } else if (c < 8) {
            SimEvKey got = sim_evq_pop(q);
            SimEvKey want = g_array_index(ref, SimEvKey, 0);
            g_array_remove_index(ref, 0);
            assert_int_equal(got.seq, want.seq);
        } else {
            SimEvKey top = g_array_index(ref, SimEvKey, 0);
            SimEvKey k = {top.time + sim_rng_below(&r, 8), seq, (uint32_t)seq};
            seq++;
            assert_int_equal(sim_evq_top(q).seq, top.seq);
            sim_evq_replace_top(q, k);
            g_array_remove_index(ref, 0);
            ref_insert(ref, k);
        }
        assert_int_equal(sim_evq_len(q), ref->len);
        if (ref->len) {
            assert_int_equal(sim_evq_top(q).seq,
                             g_array_index(ref, SimEvKey, 0).seq);
        }
        if (op % 1000 == 999) { /* keep the O(n log n) reference cheap */
            while (ref->len > 300) {
                sim_evq_pop(q);
                g_array_remove_index(ref, 0);
            }
        }
    }
    g_array_free(ref, TRUE);
    sim_evq_free(q);
}

static void test_equal_times_pop_in_seq_order(void **state)
{
    (void)state;
    SimEvq *q = sim_evq_new();
    for (uint64_t s = 0; s < 1000; s++)
        sim_evq_push(q, (SimEvKey){5, 999 - s, (uint32_t)s}); /* reversed */
    for (uint64_t s = 0; s < 1000; s++)
        assert_int_equal(sim_evq_pop(q).seq, s);
    assert_int_equal(sim_evq_len(q), 0);
    sim_evq_free(q);
}

static void test_grows_past_initial_capacity(void **state)
{
    (void)state;
    SimEvq *q = sim_evq_new();
    for (uint64_t i = 0; i < 100000; i++)
        sim_evq_push(q, (SimEvKey){(i * 7919) % 100000, i, (uint32_t)i});
    SimTime last = 0;
    for (int i = 0; i < 100000; i++) {
        SimEvKey k = sim_evq_pop(q);
        assert_true(k.time >= last);
        last = k.time;
    }
    sim_evq_free(q);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_heap_matches_sorted_reference),
        cmocka_unit_test(test_equal_times_pop_in_seq_order),
        cmocka_unit_test(test_grows_past_initial_capacity),
    };
    return cmocka_run_group_tests_name("evq", tests, NULL, NULL);
}
