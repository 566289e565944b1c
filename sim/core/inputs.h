/* inputs.h — the input files a run, sweep or reproduction read: each
 * model, scene, mesh, database and trace file by kind, path and SHA-256
 * of its bytes, for the provenance of every output (sim/output/
 * provenance.h).
 *
 * Files are noted where they are read (the one place that knows the path
 * and the bytes) into the collectors the callers opened on this thread,
 * innermost first: a scope, as GLib's g_main_context_push_thread_default
 * is, so no loader takes a parameter for it.  A run opens one around its
 * load and its execution (sim/run), a reproduction one around its paper's
 * runs (sim/reproduce): a file noted inside a run lands in both.  Nothing
 * is noted when no collector is open.  Entries are kept in first-read
 * order, one per (kind, path).  O(entries) per note.
 */
#ifndef PGSIM_CORE_INPUTS_H
#define PGSIM_CORE_INPUTS_H

#include <glib.h>

typedef struct {
    char *kind;   /* "model", "scene", "mesh", "database", "trace" */
    char *path;   /* relative to the data root that holds it
                     ("models/ipsc2.yaml"), else its absolute real path */
    char *sha256; /* hex, of the bytes read */
    gboolean shipped; /* a model from a shipped models/ folder (under a
                         data root, datapath.h); TRUE for other kinds */
} SimInput;

typedef struct SimInputs SimInputs;

/* A new empty collector (sim_inputs_free). */
SimInputs *sim_inputs_new(void);
void sim_inputs_free(SimInputs *in);
guint sim_inputs_len(const SimInputs *in); /* 0 for NULL */
const SimInput *sim_inputs_at(const SimInputs *in, guint i); /* borrowed */
/* Adds an entry unless (kind, path) is there (sha256 copied). */
void sim_inputs_add(SimInputs *in, const char *kind, const char *path,
                    const char *sha256, gboolean shipped);
/* Adds every entry of src to dst, in order. */
void sim_inputs_merge(SimInputs *dst, const SimInputs *src);

/* Opens `in` (borrowed, not NULL) as this thread's innermost collector;
 * sim_inputs_pop() closes it again (calls nest). */
void sim_inputs_push(SimInputs *in);
void sim_inputs_pop(SimInputs *in);

/* Notes a file read as `bytes` (len bytes) into every open collector. */
void sim_inputs_note_bytes(const char *kind, const char *path,
                           const void *bytes, gsize len);
/* The same for a file read elsewhere (found as sim_data_path() finds
 * it, and noted under that path): its bytes are mapped and hashed again
 * (an unreadable file is not noted). */
void sim_inputs_note_file(const char *kind, const char *path);

/* TRUE when the file at path lies in models/ under a data root
 * (datapath.h); the same for a folder. */
gboolean sim_inputs_model_shipped(const char *path);
gboolean sim_inputs_dir_shipped(const char *dir);

#endif
