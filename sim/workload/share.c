/* share.c — what consecutive runs may share (share.h): a hash table of
 * keyed objects, each with its free function.  O(1) per get and put. */
#include "sim/workload/share.h"

struct WlShare {
    GHashTable *kept; /* char * key -> Kept * */
};

typedef struct {
    void *obj;
    GDestroyNotify free_fn;
} Kept;

static void kept_free(gpointer p)
{
    Kept *k = p;
    if (k->free_fn && k->obj)
        k->free_fn(k->obj);
    g_free(k);
}

WlShare *wl_share_new(void)
{
    WlShare *s = g_new0(WlShare, 1);
    s->kept = g_hash_table_new_full(g_str_hash, g_str_equal, g_free,
                                    kept_free);
    return s;
}

void wl_share_free(WlShare *s)
{
    if (!s)
        return;
    g_hash_table_destroy(s->kept);
    g_free(s);
}

void *wl_share_get(WlShare *s, const char *key)
{
    const Kept *k = g_hash_table_lookup(s->kept, key);
    return k ? k->obj : NULL;
}

void wl_share_put(WlShare *s, const char *key, void *obj,
                  GDestroyNotify free_fn)
{
    Kept *k = g_new(Kept, 1);
    k->obj = obj;
    k->free_fn = free_fn;
    g_hash_table_replace(s->kept, g_strdup(key), k);
}
