/* test_xbar_names.c — crossbar link ids and names (sim/net/crossbar.c):
 * node i's input port is link 2i ("in<i>", node -> switch), its output
 * port link 2i + 1 ("out<i>", switch -> node); a route is in<src>,
 * out<dst>. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

static void test_crossbar_names(void **state)
{
    (void)state;
    NetTopo *x = net_crossbar_new(4);
    NetLinkId r[2];
    char name[16];
    assert_int_equal(x->ops->route(x->state, 3, 1, r), 2);
    assert_int_equal(r[0], 6);
    assert_int_equal(r[1], 3);
    x->ops->link_name(x->state, r[0], name, sizeof name);
    assert_string_equal(name, "in3");
    x->ops->link_name(x->state, r[1], name, sizeof name);
    assert_string_equal(name, "out1");
    x->ops->link_name(x->state, 0, name, sizeof name);
    assert_string_equal(name, "in0");
    x->ops->link_name(x->state, 7, name, sizeof name);
    assert_string_equal(name, "out3");
    uint64_t a, b;
    x->ops->link_ends(x->state, 6, &a, &b);
    assert_int_equal(a, 3);
    assert_int_equal(b, 4); /* the switch is vertex n */
    x->ops->link_ends(x->state, 3, &a, &b);
    assert_int_equal(a, 4);
    assert_int_equal(b, 1);
    net_topo_free(x);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crossbar_names),
    };
    return cmocka_run_group_tests_name("xbar_names", tests, NULL, NULL);
}
