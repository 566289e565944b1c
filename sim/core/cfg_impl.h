/* cfg_impl.h — the CfgNode representation, shared by cfg.c (loading,
 * access, unknown keys) and cfg_get.c (typed getters, overrides, merge).
 * Not part of the public API: include sim/core/cfg.h instead.
 */
#ifndef PGSIM_CORE_CFG_IMPL_H
#define PGSIM_CORE_CFG_IMPL_H

#include "sim/core/cfg.h"

typedef struct {
    char *key;
    const char *file; /* of the key (interned): overrides add keys */
    int line, col;    /* of the key */
    CfgNode *value;   /* owned */
    gboolean read;    /* a consumer looked the key up */
} CfgEntry;

struct CfgNode {
    CfgKind kind;
    const char *file; /* interned */
    int line, col;    /* 1-based */
    char *text;       /* CFG_SCALAR */
    gboolean quoted;  /* written quoted: always a string */
    GPtrArray *items; /* CFG_MAP: CfgEntry *; CFG_SEQ: CfgNode * */
    GPtrArray *asked; /* CFG_MAP: interned keys consumers asked for */
};

CfgNode *cfg_node_new(CfgKind kind, const char *file, int line, int col);
/* Replaces *dst's contents by *src's and frees the src shell. */
void cfg_node_assign(CfgNode *dst, CfgNode *src);
CfgEntry *cfg_map_add(CfgNode *map, const char *key, const char *file, int line,
                      int col, CfgNode *value);
CfgEntry *cfg_map_find(const CfgNode *map, const char *key);
/* Decimal sequence index in a path component, or -1. */
gint64 cfg_path_index(const char *s, size_t len);

#endif
