/* test_evq.c — the radix heap against a sorted reference.
 * Seqs grow with pushes, as the engine's do;
 * pushed times are never below the least pending time, as the engine's
 * are (it never schedules into the past). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/evq.h"
#include "sim/core/rng.h"
#include "tests/support.h"

static SimEvKey key(SimTime t, uint64_t seq)
{
    return (SimEvKey){.time = t, .seq = seq};
}

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

/* Random pushes (many equal times, spans from 0 to 2^40), pops and
 * replace_tops; after every operation the queue's least key must equal
 * the reference's least key. */
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
        SimTime now = ref->len ? g_array_index(ref, SimEvKey, 0).time : 0;
        uint64_t span = (uint64_t)1 << (sim_rng_below(&r, 5) * 10);
        if (ref->len == 0 || c < 5) {
            SimEvKey k = key(now + sim_rng_below(&r, 64) * (span / 64 + 1), seq);
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
            SimEvKey k = key(top.time + sim_rng_below(&r, 8), seq);
            seq++;
            assert_int_equal(sim_evq_top(q)->seq, top.seq);
            sim_evq_replace_top(q, k);
            g_array_remove_index(ref, 0);
            ref_insert(ref, k);
        }
        assert_int_equal(sim_evq_len(q), ref->len);
        if (ref->len) {
            assert_int_equal(sim_evq_top(q)->seq,
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
        sim_evq_push(q, key(5, 999 - s)); /* reversed */
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
        sim_evq_push(q, key((i * 7919) % 100000, i));
    SimTime last = 0;
    for (int i = 0; i < 100000; i++) {
        SimEvKey k = sim_evq_pop(q);
        assert_true(k.time >= last);
        last = k.time;
    }
    sim_evq_free(q);
}

/* A push below the least pending time after top() (the engine's case
 * after a run stopped at a time limit) re-buckets and still pops in
 * (time, seq) order; so do many events at one time (bucket 0 compaction). */
static void test_push_below_settled_and_same_time(void **state)
{
    (void)state;
    SimEvq *q = sim_evq_new();
    sim_evq_push(q, key(100, 0));
    sim_evq_push(q, key(300, 1));
    assert_int_equal(sim_evq_top(q)->time, 100);
    sim_evq_push(q, key(50, 2));
    sim_evq_push(q, key(100, 3));
    uint64_t want[] = {2, 0, 3, 1};
    for (int i = 0; i < 4; i++)
        assert_int_equal(sim_evq_pop(q).seq, want[i]);
    uint64_t seq = 10;
    sim_evq_push(q, key(7, seq));
    for (uint32_t i = 0; i < 20000; i++) { /* one time, a long chain */
        SimEvKey top = *sim_evq_top(q);
        assert_int_equal(top.seq, seq);
        sim_evq_replace_top(q, key(7, ++seq));
    }
    assert_int_equal(sim_evq_len(q), 1);
    assert_true(q->b[0].cap < 20000);
    sim_evq_free(q);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_heap_matches_sorted_reference),
        cmocka_unit_test(test_equal_times_pop_in_seq_order),
        cmocka_unit_test(test_grows_past_initial_capacity),
        cmocka_unit_test(test_push_below_settled_and_same_time),
    };
    return cmocka_run_group_tests_name("evq", tests, NULL, NULL);
}
