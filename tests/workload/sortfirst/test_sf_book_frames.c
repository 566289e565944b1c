/* test_sf_book_frames.c — the sort-first book driven frame by frame on a
 * database worked out by hand, every field of every processor's work
 * checked against the counts of seed 000 §3.3.2 (push, pull, fixed and
 * dynamic masters) and §3.4 (max-set pointers).
 *
 * Structure "a" (3 triangles) is executed twice by the posted root, so
 * with chunks of at most 2 (unsorted) there are two chunks with two
 * instances each: chunk 0 (2 triangles, instances 0 and 1, master 0) and
 * chunk 1 (1 triangle, instances 2 and 3, master 1).  Four processors
 * share a 16 x 16 screen in 8 x 8 tiles (0 top left, 1 top right, 2
 * bottom left, 3 bottom right).  Each test places the instances' screen
 * rectangles by hand, so need[] is known, and runs the processors' sorts,
 * the deliveries and the render sets as a frame of sf_frame.c does;
 * then counts the §3.5 traversal (sf_trav.h) on the state reached. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/sortfirst/sf_book.h"
#include "sim/workload/sortfirst/sf_trav.h"

#define P 4

/* message, chunk, triangle, instance, cell, request, mastership, edit */
static const WlSfSizes Z = {64, 40, 36, 8, 4, 8, 16, 96};

typedef struct {
    SceneDb *src;
    WlSfDb *db;
    WlSfBook *b;
    WlSfBatch out[P][P];   /* what p sends q */
    WlSfBatch reply[P][P]; /* pull: p's answer to q */
    WlSfBookWork w[P];
    GArray *fresh[P];  /* chunks p received */
    GArray *render[P]; /* instances p renders */
} Rig;

static void add(SceneDb *db, guint sid, SceneElem e)
{
    assert_true(scene_db_append(db, sid, &e, NULL));
}

static void rig_init(Rig *r, WlSfBookkeeping bk, WlSfMigration mig,
                     WlSfMastership ms)
{
    memset(r, 0, sizeof *r);
    r->src = scene_db_new();
    guint root = scene_db_add_struct(r->src, "root");
    guint a = scene_db_add_struct(r->src, "a");
    for (int k = 0; k < 3; k++) {
        Vec3 t[3] = {vec3(k, 0, 0), vec3(k + 1, 0, 0), vec3(k, 1, 0)};
        add(r->src, a, scene_elem_prim(SCENE_EL_TRIANGLE, t, 3));
    }
    add(r->src, root, scene_elem_execute(a));
    add(r->src, root, scene_elem_execute(a));
    scene_db_post(r->src, root);
    GError *e = NULL;
    r->db = wl_sf_db_new(r->src, P, 2, WL_SF_CHUNK_UNSORTED, &e);
    assert_non_null(r->db);
    assert_int_equal(wl_sf_n_chunks(r->db), 2);
    assert_int_equal(wl_sf_n_insts(r->db), 4);
    for (guint i = 0; i < 4; i++)
        assert_int_equal(wl_sf_inst(r->db, i)->chunk, i / 2);
    assert_int_equal(wl_sf_chunk(r->db, 0)->polys, 2);
    assert_int_equal(wl_sf_chunk(r->db, 1)->polys, 1);
    WlSfRegions reg;
    wl_sf_regions_init(&reg, P, 16, 16);
    r->b = wl_sf_book_new(r->db, &reg, bk, &Z);
    wl_sf_book_set_policy(r->b, mig, ms);
    for (guint p = 0; p < P; p++) {
        for (guint q = 0; q < P; q++) {
            wl_sf_batch_init(&r->out[p][q]);
            wl_sf_batch_init(&r->reply[p][q]);
        }
        r->fresh[p] = g_array_new(FALSE, FALSE, sizeof(guint));
        r->render[p] = g_array_new(FALSE, FALSE, sizeof(guint));
    }
}

static void rig_clear(Rig *r)
{
    for (guint p = 0; p < P; p++) {
        for (guint q = 0; q < P; q++) {
            wl_sf_batch_clear(&r->out[p][q]);
            wl_sf_batch_clear(&r->reply[p][q]);
        }
        g_array_unref(r->fresh[p]);
        g_array_unref(r->render[p]);
    }
    wl_sf_book_free(r->b);
    wl_sf_db_free(r->db);
    scene_db_free(r->src);
}

/* Screen rectangles: a 2 x 2 pixel box inside one tile, across the two
 * bottom tiles, or off the screen. */
enum { T0, T1, T2, T3, BOTTOM, OFF };

static WlSfScreen at(int where)
{
    static const double box[][4] = {{2, 2, 4, 4},
                                    {10, 2, 12, 4},
                                    {2, 10, 4, 12},
                                    {10, 10, 12, 12},
                                    {2, 10, 12, 12}};
    if (where == OFF)
        return (WlSfScreen){.on = FALSE};
    const double *b = box[where];
    return (WlSfScreen){
        .on = TRUE, .x0 = b[0], .y0 = b[1], .x1 = b[2], .y1 = b[3]};
}

static void set_need(Rig *r, int i0, int i1, int i2, int i3)
{
    WlSfScreen s[4] = {at(i0), at(i1), at(i2), at(i3)};
    wl_sf_book_need_from(r->b, s);
}

/* Every processor's sort (push), then the deliveries, then the render
 * sets, as one frame of sf_frame.c. */
static void push_frame(Rig *r)
{
    for (guint p = 0; p < P; p++) {
        memset(&r->w[p], 0, sizeof r->w[p]);
        g_array_set_size(r->fresh[p], 0);
        g_array_set_size(r->render[p], 0);
    }
    for (guint p = 0; p < P; p++)
        wl_sf_book_sort(r->b, p, r->out[p], &r->w[p]);
    for (guint p = 0; p < P; p++)
        for (guint q = 0; q < P; q++) {
            if (q == p)
                continue;
            const WlSfBatch *bt = &r->out[p][q];
            assert_int_equal(bt->src, p);
            assert_int_equal(bt->dst, q);
            wl_sf_book_receive(r->b, bt, &r->w[q]);
            g_array_append_vals(r->fresh[q], bt->chunks->data, bt->chunks->len);
        }
    for (guint p = 0; p < P; p++)
        wl_sf_book_render_set(r->b, p, r->fresh[p], r->render[p], &r->w[p]);
}

/* The fields of WlSfBookWork, in order, but for edit_bytes. */
typedef struct {
    uint64_t mb, sb, nb, sc, sp, si, sby, rc, rp, ri, del, probe, req, hand,
        coll, hc, hp;
} Work;

static void expect_work(const Rig *r, guint p, Work x)
{
    const WlSfBookWork *w = &r->w[p];
    const uint64_t got[] = {w->master_boxes, w->slave_boxes,    w->new_boxes,
                            w->sent_chunks,  w->sent_polys,     w->sent_insts,
                            w->sent_bytes,   w->recv_chunks,    w->recv_polys,
                            w->recv_insts,   w->deleted_chunks, w->probe_boxes,
                            w->requested,    w->handed,         w->collected,
                            w->held_chunks,  w->held_polys};
    const uint64_t want[] = {x.mb,  x.sb,   x.nb,   x.sc, x.sp,  x.si,
                             x.sby, x.rc,   x.rp,   x.ri, x.del, x.probe,
                             x.req, x.hand, x.coll, x.hc, x.hp};
    static const char *const name[] = {
        "master_boxes", "slave_boxes", "new_boxes",  "sent_chunks",
        "sent_polys",   "sent_insts",  "sent_bytes", "recv_chunks",
        "recv_polys",   "recv_insts",  "deleted",    "probe_boxes",
        "requested",    "handed",      "collected",  "held_chunks",
        "held_polys"};
    for (guint k = 0; k < G_N_ELEMENTS(got); k++)
        if (got[k] != want[k])
            fail_msg("processor %u: %s %llu, expected %llu", p, name[k],
                     (unsigned long long)got[k], (unsigned long long)want[k]);
}

/* p renders exactly the instances of `set` (a bit per instance). */
static void expect_render(const Rig *r, guint p, unsigned set)
{
    unsigned got = 0;
    for (guint k = 0; k < r->render[p]->len; k++) {
        guint i = g_array_index(r->render[p], guint, k);
        assert_false(got & (1u << i)); /* once each */
        got |= 1u << i;
    }
    if (got != set)
        fail_msg("processor %u renders %#x, expected %#x", p, got, set);
}

static void expect_vec(const uint64_t *v, uint64_t a, uint64_t b, uint64_t c,
                       uint64_t d, const char *what)
{
    const uint64_t want[4] = {a, b, c, d};
    for (guint i = 0; i < 4; i++)
        if (v[i] != want[i])
            fail_msg("%s[%u] = %#llx, expected %#llx", what, i,
                     (unsigned long long)v[i], (unsigned long long)want[i]);
}

static void check_ok(const Rig *r)
{
    guint inst = 99, proc = 99;
    assert_true(wl_sf_book_check(r->b, &inst, &proc));
}

/* Max-set, push, fixed masters.  Frame 1: instance 0 in tile 0,
 * instance 1 in tile 1, instance 2 across tiles 2 and 3, instance 3 off.
 * Processor 0 (chunk 0's master) sends processor 1 the chunk (40 + 2 x
 * 36 B) and the pointer of instance 1 (8 B), 184 B with the header;
 * processor 1 sends chunk 1 (40 + 36 B) and instance 2's pointer to 2 and
 * to 3, 148 B each.  Every processor sends every other a message (64 B
 * header).  Frame 2: instance 0 moves to tile 1, 1 off, 2 to tile 2 only,
 * 3 to tile 0: processor 1 already holds chunk 0 and only gets instance
 * 0's pointer; processor 0 gets chunk 1 and instance 3's pointer;
 * processor 3 drops instance 2's pointer at its sort and, holding no
 * pointer of chunk 1, deletes the chunk at render (§3.4.3). */
static void test_maxset_push(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED);
    set_need(&r, T0, T1, BOTTOM, OFF);
    expect_vec(r.b->need, 1, 2, 12, 0, "need");
    push_frame(&r);
    /* Work: boxes (master, slave, new), sent (chunks, polys, pointers,
     * bytes), received (chunks, polys, pointers), deleted, probes,
     * requests, handed, collected, held (chunks, polys) */
    expect_work(&r, 0,
                (Work){2, 0, 0, 1, 2, 1, 312, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2});
    expect_work(&r, 1,
                (Work){2, 0, 1, 2, 2, 2, 360, 1, 2, 1, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 2,
                (Work){0, 0, 1, 0, 0, 0, 192, 1, 1, 1, 0, 0, 0, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 0, 1, 0, 0, 0, 192, 1, 1, 1, 0, 0, 0, 0, 0, 1, 1});
    expect_render(&r, 0, 1u << 0);
    expect_render(&r, 1, 1u << 1);
    expect_render(&r, 2, 1u << 2);
    expect_render(&r, 3, 1u << 2);
    expect_vec(r.b->held_inst, 1, 3, 14, 2, "held_inst");
    expect_vec(r.b->master_inst, 1, 3, 14, 2, "master_inst");
    assert_int_equal(r.b->held_data[0], 3);
    assert_int_equal(r.b->held_data[1], 14);
    assert_int_equal(r.b->master_data[0], 3);
    assert_int_equal(r.b->master_data[1], 14);
    check_ok(&r);
    /* memory: chunk 0's master keeps 1 + 2 vectors of 1 B, the chunk
     * (112 B) and two pointers; processor 1 chunk 1's 3 B of vectors,
     * both chunks (112 + 76) and three pointers */
    assert_int_equal(wl_sf_book_memory(r.b, 0), 3 + 112 + 16);
    assert_int_equal(wl_sf_book_memory(r.b, 1), 3 + 112 + 76 + 24);
    assert_int_equal(wl_sf_book_memory(r.b, 2), 76 + 8);
    set_need(&r, T1, OFF, T2, T0);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 1, 0, 0, 1, 200, 1, 1, 1, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 1,
                (Work){2, 1, 1, 1, 1, 1, 276, 0, 0, 1, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 2,
                (Work){0, 1, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 1, 0, 0, 0, 0, 192, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0});
    expect_render(&r, 0, 1u << 3);
    expect_render(&r, 1, 1u << 0);
    expect_render(&r, 2, 1u << 2);
    expect_render(&r, 3, 0);
    expect_vec(r.b->held_inst, 3, 1, 6, 3, "held_inst");
    assert_int_equal(r.b->held_data[1], 7);
    check_ok(&r);
    rig_clear(&r);
}

/* Min-set, push, fixed masters, the same two frames, then all off.
 * Min-set sends no pointers: a chunk carries its first instance in the
 * region (the header), and a new copy costs one box per instance at
 * render.  A slave copy goes when no instance needed it the frame
 * before (§3.3.2.1): processor 3's copy of chunk 1, needed in frame 1,
 * survives frame 2 and goes in frame 3; every other copy was needed in
 * frame 2 and stays. */
static void test_minset_push(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MINSET, WL_SF_PUSH, WL_SF_FIXED);
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 0, 1, 2, 0, 304, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2});
    expect_work(&r, 1,
                (Work){2, 0, 2, 2, 2, 0, 344, 1, 2, 0, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 2,
                (Work){0, 0, 2, 0, 0, 0, 192, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 0, 2, 0, 0, 0, 192, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1});
    /* the header names the first instance of the chunk in dst's region */
    assert_int_equal(r.out[0][1].insts->len, 1);
    assert_int_equal(g_array_index(r.out[0][1].insts, guint, 0), 1);
    assert_int_equal(g_array_index(r.out[1][3].insts, guint, 0), 2);
    assert_int_equal(r.out[0][1].polys, 2);
    assert_int_equal(r.out[1][2].polys, 1);
    expect_render(&r, 0, 1u << 0);
    expect_render(&r, 1, 1u << 1);
    expect_render(&r, 2, 1u << 2);
    expect_render(&r, 3, 1u << 2);
    assert_int_equal(wl_sf_book_memory(r.b, 0), 1 + 112);
    assert_int_equal(wl_sf_book_memory(r.b, 1), 1 + 112 + 76);
    set_need(&r, T1, OFF, T2, T0);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 2, 0, 0, 0, 192, 1, 1, 0, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 1,
                (Work){2, 2, 0, 1, 1, 0, 268, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 2,
                (Work){0, 2, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 2, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1});
    assert_int_equal(g_array_index(r.out[1][0].insts, guint, 0), 3);
    expect_render(&r, 0, 1u << 3);
    expect_render(&r, 1, 1u << 0);
    expect_render(&r, 2, 1u << 2);
    expect_render(&r, 3, 0);
    assert_int_equal(r.b->master_data[0], 3);
    assert_int_equal(r.b->master_data[1], 7);
    check_ok(&r);
    set_need(&r, OFF, OFF, OFF, OFF);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){2, 2, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 3,
                (Work){0, 2, 0, 0, 0, 0, 192, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0});
    expect_work(&r, 2,
                (Work){0, 2, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1});
    assert_int_equal(r.b->held_data[1], 7);
    for (guint p = 0; p < P; p++)
        expect_render(&r, p, 0);
    rig_clear(&r);
}

/* Dynamic mastership, max-set: in frame 2 chunk 0's master (0) needs
 * none of its instances, processor 1 does and holds a copy: mastership
 * goes to 1 (16 B and, max-set, 2 x (8 + 1) B of pointer vectors) and 0
 * deletes its copy.  Chunk 1's master (1) needs none either (instance 2
 * in tile 2, 3 in tile 0): the lowest holder needing it is 2. */
static void test_dynamic_maxset(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_DYNAMIC);
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    /* chunk 1's master (1) needs neither instance in frame 1: it hands
     * the mastership to 2, the lowest region needing it (none held it
     * before: uni & held is empty), sends 2 the chunk anyway */
    expect_work(&r, 1,
                (Work){2, 0, 1, 2, 2, 2, 360 + 16 + 2 * 9, 1, 2, 1, 1, 0, 0, 1,
                       0, 1, 2});
    assert_int_equal(wl_sf_book_master(r.b, 0), 0);
    assert_int_equal(wl_sf_book_master(r.b, 1), 2);
    assert_int_equal(r.out[1][2].masters->len, 1);
    assert_int_equal(r.out[1][3].masters->len, 0);
    assert_int_equal(r.b->held_data[1], 12);
    assert_int_equal(r.b->master_data[1], 12 | 4);
    expect_vec(r.b->master_inst, 1, 3, 12 | 4, 4, "master_inst");
    check_ok(&r);
    set_need(&r, T1, OFF, T2, T0);
    push_frame(&r);
    /* chunk 0: processor 0 hands over to 1 (held and needing it) */
    assert_int_equal(wl_sf_book_master(r.b, 0), 1);
    assert_int_equal(r.w[0].handed, 1);
    assert_int_equal(r.w[0].deleted_chunks, 1);
    assert_int_equal(r.w[0].sent_bytes, 64 + 8 + 16 + 2 * 9 + 64 + 64);
    assert_false(r.b->held_data[0] & 1);
    /* chunk 1: its master (2) needs instance 2 and keeps it */
    assert_int_equal(wl_sf_book_master(r.b, 1), 2);
    check_ok(&r);
    rig_clear(&r);
}

/* Dynamic mastership, min-set: chunk 1's master hands over as with
 * max-set, the message carrying 16 B and no pointer vectors; the new
 * master's copy vector is the regions needing the chunk. */
static void test_dynamic_minset(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MINSET, WL_SF_PUSH, WL_SF_DYNAMIC);
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    expect_work(
        &r, 1,
        (Work){2, 0, 2, 2, 2, 0, 344 + 16, 1, 2, 0, 1, 0, 0, 1, 0, 1, 2});
    expect_work(&r, 0,
                (Work){2, 0, 0, 1, 2, 0, 304, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2});
    assert_int_equal(wl_sf_book_master(r.b, 1), 2);
    assert_int_equal(r.b->master_data[1], 12);
    assert_int_equal(r.b->held_data[1], 12);
    assert_int_equal(r.b->master_data[0], 3);
    check_ok(&r);
    rig_clear(&r);
}

/* A pull frame: the sorts, each request served and its answer
 * received, then the render sets. */
static void pull_frame(Rig *r)
{
    for (guint p = 0; p < P; p++) {
        memset(&r->w[p], 0, sizeof r->w[p]);
        g_array_set_size(r->fresh[p], 0);
        g_array_set_size(r->render[p], 0);
    }
    for (guint p = 0; p < P; p++)
        wl_sf_book_pull_sort(r->b, p, r->out[p], &r->w[p]);
    for (guint p = 0; p < P; p++)
        for (guint q = 0; q < P; q++)
            if (q != p && r->out[p][q].chunks->len) {
                WlSfBatch *a = &r->reply[q][p];
                wl_sf_book_serve(r->b, &r->out[p][q], a, &r->w[q]);
                assert_int_equal(a->src, q);
                assert_int_equal(a->dst, p);
                wl_sf_book_receive(r->b, a, &r->w[p]);
                g_array_append_vals(r->fresh[p], a->chunks->data,
                                    a->chunks->len);
            }
    for (guint p = 0; p < P; p++)
        wl_sf_book_render_set(r->b, p, r->fresh[p], r->render[p], &r->w[p]);
}

/* Pull (min-set, fixed): a processor asks each master for the chunks it
 * needs but does not hold (8 B a chunk id after the 64 B header), and
 * tests the boxes of chunks it does not hold (probe boxes); the master
 * answers with the chunk data.  Processor 1 asks 0 for chunk 0, 2 and 3
 * ask 1 for chunk 1.  Frame 2: processor 0 asks 1 for chunk 1; 1 keeps
 * its copy of chunk 0 (needed in frame 1).  Frame 3 (nothing on
 * screen): 3 drops its copy of chunk 1, unneeded by it in frame 2; 2
 * keeps its copy, needed in frame 2. */
static void test_pull(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MINSET, WL_SF_PULL, WL_SF_FIXED);
    set_need(&r, T0, T1, BOTTOM, OFF);
    pull_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 0, 1, 2, 0, 176, 0, 0, 0, 0, 2, 0, 0, 0, 1, 2});
    expect_work(
        &r, 1,
        (Work){2, 0, 2, 2, 2, 0, 72 + 2 * 140, 1, 2, 0, 0, 2, 1, 0, 0, 2, 3});
    expect_work(&r, 2,
                (Work){0, 0, 2, 0, 0, 0, 72, 1, 1, 0, 0, 4, 1, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 0, 2, 0, 0, 0, 72, 1, 1, 0, 0, 4, 1, 0, 0, 1, 1});
    assert_int_equal(g_array_index(r.reply[0][1].insts, guint, 0), 1);
    expect_render(&r, 0, 1u << 0);
    expect_render(&r, 1, 1u << 1);
    expect_render(&r, 2, 1u << 2);
    expect_render(&r, 3, 1u << 2);
    check_ok(&r);
    set_need(&r, T1, OFF, T2, T0);
    pull_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 2, 0, 0, 0, 72, 1, 1, 0, 0, 2, 1, 0, 0, 2, 3});
    expect_work(&r, 1,
                (Work){2, 2, 0, 1, 1, 0, 140, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3});
    expect_work(&r, 3,
                (Work){0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1, 1});
    expect_render(&r, 0, 1u << 3);
    expect_render(&r, 3, 0);
    check_ok(&r);
    set_need(&r, OFF, OFF, OFF, OFF);
    pull_frame(&r);
    expect_work(&r, 2,
                (Work){0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1, 1});
    expect_work(&r, 3,
                (Work){0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 0});
    assert_int_equal(r.b->held_data[1], 7);
    rig_clear(&r);
}

/* ---- §3.5 traversal counts of the book's state (sf_trav.h) ----------- */

/* The max-set tree: node 0 the root (structure 0, no primitive), nodes
 * 1 and 2 its two executions of "a"; instances 0 and 2 (chunks 0, 1)
 * sit at node 1, 1 and 3 at node 2. */
static void expect_trav(const Rig *r, WlSfTravMode mode, uint64_t plain,
                        uint64_t flags, uint64_t culled, uint64_t both,
                        uint64_t boxes, uint64_t tests, const uint64_t *per)
{
    WlSfTrav t = {0};
    WlSfTravProc tp[P];
    memset(tp, 0xff, sizeof tp); /* cleared by the count */
    wl_sf_trav_count(r->b, mode, &t, tp);
    const uint64_t got[] = {t.plain, t.flags,        t.culled,
                            t.both,  t.boxes_culled, t.tests};
    const uint64_t want[] = {plain, flags, culled, both, boxes, tests};
    for (guint k = 0; k < G_N_ELEMENTS(got); k++)
        if (got[k] != want[k])
            fail_msg("%s: total %u: %llu, expected %llu",
                     wl_sf_trav_names[mode], k, (unsigned long long)got[k],
                     (unsigned long long)want[k]);
    for (guint p = 0; p < P; p++) {
        const uint64_t g[] = {tp[p].nodes, tp[p].tests, tp[p].master_culled,
                              tp[p].slave_culled};
        for (guint k = 0; k < 4; k++)
            if (g[k] != per[4 * p + k])
                fail_msg("%s: processor %u field %u: %llu, expected %llu",
                         wl_sf_trav_names[mode], p, k, (unsigned long long)g[k],
                         (unsigned long long)per[4 * p + k]);
    }
}

/* After max-set frame 1 of test_maxset_push, instances 0 and 2 (node 1)
 * on screen, node 2 off.  Marks: node 1 has chunk 0's master and copies
 * (processors 0, 1 by pointer) and chunk 1's (1, 2, 3): 15; node 2:
 * processors 0, 1 (instance 1's pointers, instance 3's master): 3;
 * the root gathers 15.  Flags: 4 + 4 + 2; culled scans nodes 0 and 1
 * (4 + 4); with flags 4 + 4.  Boxes culled at node 2: instance 1's
 * master (0) and slave (1), instance 3's master (1).  Volume tests:
 * every node is entered (its parent is on): culled 3 per processor;
 * with flags the processors marked at the node (nodes 0, 1: all; node
 * 2: 0 and 1). */
static void test_trav_maxset(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED);
    for (guint i = 0; i < 4; i++)
        assert_int_equal(wl_sf_inst(r.db, i)->node, 1 + i % 2);
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    set_need(&r, T0, OFF, T2, OFF);
    /* nodes, tests, master culled, slave culled per processor */
    static const uint64_t plain[] = {3, 0, 0, 0, 3, 0, 0, 0,
                                     3, 0, 0, 0, 3, 0, 0, 0};
    static const uint64_t flags[] = {3, 0, 0, 0, 3, 0, 0, 0,
                                     2, 0, 0, 0, 2, 0, 0, 0};
    static const uint64_t culled[] = {2, 3, 1, 0, 2, 3, 1, 1,
                                      2, 3, 0, 0, 2, 3, 0, 0};
    static const uint64_t both[] = {2, 3, 1, 0, 2, 3, 1, 1,
                                    2, 2, 0, 0, 2, 2, 0, 0};
    expect_trav(&r, WL_SF_TRAV_PLAIN, 12, 10, 8, 8, 3, 0, plain);
    expect_trav(&r, WL_SF_TRAV_FLAGS, 12, 10, 8, 8, 3, 0, flags);
    expect_trav(&r, WL_SF_TRAV_CULLED, 12, 10, 8, 8, 3, 12, culled);
    expect_trav(&r, WL_SF_TRAV_BOTH, 12, 10, 8, 8, 3, 10, both);
    /* the counts add to what the caller holds; per may be NULL */
    WlSfTrav t = {.plain = 100, .tests = 7};
    wl_sf_trav_count(r.b, WL_SF_TRAV_CULLED, &t, NULL);
    assert_int_equal(t.plain, 112);
    assert_int_equal(t.tests, 19);
    /* nothing on screen: only the root is entered (it has no parent);
     * its children, whose parent (node 0) failed its volume test, are
     * neither scanned nor tested.  Every chunk box is culled: instance
     * 0's master (0), 1's master (0) and slave (1), 2's master (1) and
     * slaves (2, 3), 3's master (1): 7 */
    set_need(&r, OFF, OFF, OFF, OFF);
    static const uint64_t none[] = {0, 1, 2, 0, 0, 1, 2, 1,
                                    0, 1, 0, 1, 0, 1, 0, 1};
    expect_trav(&r, WL_SF_TRAV_CULLED, 12, 10, 0, 0, 7, 4, none);
    expect_trav(&r, WL_SF_TRAV_BOTH, 12, 10, 0, 0, 7, 4, none);
    rig_clear(&r);
}

/* The same with min-set: a node's flag is its structure's (the root
 * holds no chunk: 0; "a": every processor mastering or holding one of
 * its chunks, 15), and a culled chunk's holders are its copies: chunk
 * 0's master 0 and copy 1, chunk 1's master 1 and copies 2, 3. */
static void test_trav_minset(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MINSET, WL_SF_PUSH, WL_SF_FIXED);
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    set_need(&r, T0, OFF, T2, OFF);
    static const uint64_t flags[] = {2, 0, 0, 0, 2, 0, 0, 0,
                                     2, 0, 0, 0, 2, 0, 0, 0};
    static const uint64_t both[] = {1, 3, 1, 0, 1, 3, 1, 1,
                                    1, 3, 0, 1, 1, 3, 0, 1};
    expect_trav(&r, WL_SF_TRAV_FLAGS, 12, 8, 8, 4, 5, 0, flags);
    expect_trav(&r, WL_SF_TRAV_BOTH, 12, 8, 8, 4, 5, 12, both);
    rig_clear(&r);
}

/* ---- edits: the instances renumbered (wl_sf_book_remap) -------------- */

/* The rig after frame 1 (instance 0 in tile 0, 1 in tile 1, 2 across
 * the bottom tiles, 3 off), pushed or pulled. */
static void frame1(Rig *r, WlSfBookkeeping bk, WlSfMigration mig)
{
    rig_init(r, bk, mig, WL_SF_FIXED);
    set_need(r, T0, T1, BOTTOM, OFF);
    if (mig == WL_SF_PULL)
        pull_frame(r);
    else
        push_frame(r);
}

/* need[] of n instances at the places `where`. */
static void set_need_n(Rig *r, guint n, const int *where)
{
    WlSfScreen s[4];
    for (guint i = 0; i < n; i++)
        s[i] = at(where[i]);
    wl_sf_book_need_from(r->b, s);
}

static void reinstance(Rig *r)
{
    GError *e = NULL;
    assert_true(wl_sf_db_reinstance(r->db, r->src, &e));
}

static void expect_remap(const WlSfRemapWork *w, const uint64_t *created,
                         const uint64_t *collected)
{
    for (guint p = 0; p < P; p++)
        if (w[p].ptr_created != created[p] ||
            w[p].ptr_collected != collected[p])
            fail_msg("processor %u: pointers created %llu collected %llu, "
                     "expected %llu, %llu", p,
                     (unsigned long long)w[p].ptr_created,
                     (unsigned long long)w[p].ptr_collected,
                     (unsigned long long)created[p],
                     (unsigned long long)collected[p]);
}

/* Max-set.  After frame 1 (pointers held: instance 0 by 0, 1 by 0 and
 * 1, 2 by 1, 2, 3, 3 by 1) the root is unposted: every instance is
 * obsolete, its pointers garbage-collected (0: 2, 1: 3, 2: 1, 3: 1).
 * In the next frame the chunks have no instance: the slave copies (1's
 * of chunk 0, 2's and 3's of chunk 1) hold no pointer and go at render,
 * counted as collected; the masters keep theirs.  Posting the root
 * again makes four new instances with their master's pointer only (0
 * and 1 create two each); in frame 3 (frame 1's places) the pointers
 * the masters send for them are edit bytes (0: one, 1: two). */
static void test_remap_unpost_post(void **st)
{
    (void)st;
    Rig r;
    frame1(&r, WL_SF_MAXSET, WL_SF_PUSH);
    expect_vec(r.b->held_inst, 1, 3, 14, 2, "held_inst");
    WlSfRemapWork w[P] = {{0}};
    assert_true(scene_db_unpost(r.src, 0));
    reinstance(&r);
    assert_int_equal(wl_sf_n_insts(r.db), 0);
    const gint64 none[1] = {0};
    wl_sf_book_remap(r.b, none, 4, w);
    expect_remap(w, (const uint64_t[]){0, 0, 0, 0},
                 (const uint64_t[]){2, 3, 1, 1});
    set_need_n(&r, 0, NULL);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){0, 0, 0, 0, 0, 0, 192, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2});
    expect_work(&r, 1,
                (Work){0, 0, 0, 0, 0, 0, 192, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1});
    expect_work(&r, 2,
                (Work){0, 0, 0, 0, 0, 0, 192, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0});
    expect_work(&r, 3,
                (Work){0, 0, 0, 0, 0, 0, 192, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0});
    assert_int_equal(r.b->held_data[0], 1);
    assert_int_equal(r.b->held_data[1], 2);
    memset(w, 0, sizeof w);
    scene_db_post(r.src, 0);
    reinstance(&r);
    assert_int_equal(wl_sf_n_insts(r.db), 4);
    const gint64 fresh[4] = {-1, -1, -1, -1};
    wl_sf_book_remap(r.b, fresh, 0, w);
    expect_remap(w, (const uint64_t[]){2, 2, 0, 0},
                 (const uint64_t[]){0, 0, 0, 0});
    expect_vec(r.b->held_inst, 1, 1, 2, 2, "held_inst");
    expect_vec(r.b->master_inst, 1, 1, 2, 2, "master_inst");
    set_need(&r, T0, T1, BOTTOM, OFF);
    push_frame(&r);
    expect_work(&r, 0,
                (Work){2, 0, 0, 1, 2, 1, 312, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2});
    expect_work(&r, 1,
                (Work){2, 0, 1, 2, 2, 2, 360, 1, 2, 1, 0, 0, 0, 0, 0, 2, 3});
    assert_int_equal(r.w[0].edit_bytes, 8);
    assert_int_equal(r.w[1].edit_bytes, 16);
    assert_int_equal(r.w[2].edit_bytes, 0);
    /* the next frame: nothing is new any more */
    set_need(&r, T0, T1, BOTTOM, T3);
    push_frame(&r);
    assert_int_equal(r.w[1].sent_insts, 1);
    assert_int_equal(r.w[1].edit_bytes, 0);
    check_ok(&r);
    rig_clear(&r);
}

/* A map that keeps three instances (new 0 is old 3, 1 old 2, 2 old 1)
 * and makes one new (3, chunk 1's: master 1): each survivor carries its
 * pointer vectors; max-set collects old 0's pointer (processor 0's) and
 * 1 creates the new one's; the min-set has no pointer work.  need[]
 * starts empty. */
static void test_remap_kept(void **st)
{
    (void)st;
    for (int bk = 0; bk <= 1; bk++) {
        Rig r;
        frame1(&r, bk ? WL_SF_MAXSET : WL_SF_MINSET, WL_SF_PUSH);
        WlSfRemapWork w[P] = {{0}};
        const gint64 map[4] = {3, 2, 1, -1};
        wl_sf_book_remap(r.b, map, 4, w);
        expect_remap(w, (const uint64_t[]){0, (uint64_t)bk, 0, 0},
                     (const uint64_t[]){(uint64_t)bk, 0, 0, 0});
        if (bk) {
            expect_vec(r.b->held_inst, 2, 14, 3, 2, "held_inst");
            expect_vec(r.b->master_inst, 2, 14, 3, 2, "master_inst");
        } else { /* the min-set's vectors stay its masters' bits */
            expect_vec(r.b->held_inst, 2, 2, 1, 2, "held_inst");
            expect_vec(r.b->master_inst, 2, 2, 1, 2, "master_inst");
        }
        expect_vec(r.b->need, 0, 0, 0, 0, "need");
        rig_clear(&r);
    }
}

/* The identity map (every instance kept, old 0 included): no pointer
 * work, every vector carried as it was, no instance fresh. */
static void test_remap_identity(void **st)
{
    (void)st;
    for (int bk = 0; bk <= 1; bk++) {
        Rig r;
        frame1(&r, bk ? WL_SF_MAXSET : WL_SF_MINSET, WL_SF_PUSH);
        uint64_t held[4], mast[4];
        memcpy(held, r.b->held_inst, sizeof held);
        memcpy(mast, r.b->master_inst, sizeof mast);
        WlSfRemapWork w[P] = {{0}};
        const gint64 map[4] = {0, 1, 2, 3};
        wl_sf_book_remap(r.b, map, 4, w);
        expect_remap(w, (const uint64_t[]){0, 0, 0, 0},
                     (const uint64_t[]){0, 0, 0, 0});
        expect_vec(r.b->held_inst, held[0], held[1], held[2], held[3],
                   "held_inst");
        expect_vec(r.b->master_inst, mast[0], mast[1], mast[2], mast[3],
                   "master_inst");
        for (guint i = 0; i < 4; i++)
            assert_int_equal(r.b->fresh[i], 0);
        rig_clear(&r);
    }
}

/* Min-set and pull: after frame 1 the root is unposted (no pointer
 * work: the min-set keeps none); a slave copy needed in frame 1 stays
 * through frame 2 and goes in frame 3 (a frame late), counted as
 * collected since its chunk has no instance left. */
static void test_remap_unpost_minset(void **st)
{
    (void)st;
    for (int pull = 0; pull <= 1; pull++) {
        Rig r;
        frame1(&r, WL_SF_MINSET, pull ? WL_SF_PULL : WL_SF_PUSH);
        WlSfRemapWork w[P] = {{0}};
        assert_true(scene_db_unpost(r.src, 0));
        reinstance(&r);
        const gint64 none[1] = {0};
        wl_sf_book_remap(r.b, none, 4, w);
        expect_remap(w, (const uint64_t[]){0, 0, 0, 0},
                     (const uint64_t[]){0, 0, 0, 0});
        uint64_t msg = pull ? 0 : 192;
        for (int f = 2; f <= 3; f++) {
            set_need_n(&r, 0, NULL);
            if (pull)
                pull_frame(&r);
            else
                push_frame(&r);
            uint64_t gone = f == 3;
            expect_work(&r, 0, (Work){0, 0, 0, 0, 0, 0, msg, 0, 0, 0, 0, 0,
                                      0, 0, 0, 1, 2});
            expect_work(&r, 1, (Work){0, 0, 0, 0, 0, 0, msg, 0, 0, 0, gone,
                                      0, 0, 0, gone, 2 - gone, 3 - 2 * gone});
            expect_work(&r, 2, (Work){0, 0, 0, 0, 0, 0, msg, 0, 0, 0, gone,
                                      0, 0, 0, gone, 1 - gone, 1 - gone});
        }
        assert_int_equal(r.b->held_data[0], 1);
        assert_int_equal(r.b->held_data[1], 2);
        rig_clear(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_maxset_push),
        cmocka_unit_test(test_minset_push),
        cmocka_unit_test(test_dynamic_maxset),
        cmocka_unit_test(test_dynamic_minset),
        cmocka_unit_test(test_pull),
        cmocka_unit_test(test_trav_maxset),
        cmocka_unit_test(test_trav_minset),
        cmocka_unit_test(test_remap_unpost_post),
        cmocka_unit_test(test_remap_kept),
        cmocka_unit_test(test_remap_identity),
        cmocka_unit_test(test_remap_unpost_minset),
    };
    return cmocka_run_group_tests_name("sf_book_frames", tests, NULL, NULL);
}
