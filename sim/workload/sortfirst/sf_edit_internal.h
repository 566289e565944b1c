/* sf_edit_internal.h — the editor's state, shared by sf_edit.c (the
 * frame's edits, the matrix/execute/post kinds and the max-set match)
 * and sf_edit_struct.c (structure, primitive, colour and execute
 * add/delete edits).  Users include sf_edit.h.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_EDIT_INTERNAL_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_EDIT_INTERNAL_H

#include "sim/workload/sortfirst/sf_edit.h"

/* No structure open. */
#define WL_SF_NO_STRUCT G_MAXUINT

struct WlSfEdit {
    SceneDb *db;      /* owned: the edited copy (every element tagged) */
    WlSfDb *sf;       /* borrowed */
    WlSfEditSpec spec;
    SimRng *rng;      /* borrowed */
    GArray *serial;   /* guint per posted root (posting order): its posting */
    guint next_serial;
    GArray *unposted; /* guint structure ids, last unposted at the end */
    uint64_t applied[WL_SF_ED_N];
    uint64_t next_tag; /* the next element's tag */
    guint open;        /* the open structure, or WL_SF_NO_STRUCT */
    GArray *deleted;   /* guint8 per structure: deleted */
    GArray *dirty;     /* guint8 per structure: elements inserted,
                          deleted or primitives changed this frame */
};

/* sf_edit.c: every (structure, position) holding an element of `kind`
 * (GArray of guint pairs; deleted structures hold none). */
GArray *wl_sf_edit_elements_of(const SceneDb *db, SceneElemKind kind);

/* sf_edit_struct.c: the kinds from WL_SF_ED_CREATE on; FALSE when
 * there was nothing to act on. */
gboolean wl_sf_edit_struct_one(WlSfEdit *e, int kind);
/* sf_edit_struct.c: tags every element of e->db (1, 2, ...). */
void wl_sf_edit_tag_all(WlSfEdit *e);

#endif
