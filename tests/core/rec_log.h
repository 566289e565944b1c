/* rec_log.h — a test recorder (sim/core/record.h) and trace
 * (sim/core/trace.h) that write every call they hear of, one line each,
 * into one string the test compares whole: "compute @0 n3 p0 cost=5
 * end=15 h=1 -> 1", "begin 1 @15", "end 1", "hold L2 q:0->1 100 B
 * [0,100)" ...  Recorder ids count up from 1. */
#ifndef PGSIM_TESTS_REC_LOG_H
#define PGSIM_TESTS_REC_LOG_H

#include "sim/core/record.h"
#include "sim/core/trace.h"

typedef struct {
    SimRecorder rec; /* first: &log->rec is what the engine holds */
    SimTrace tr;     /* the trace; hands it to sim_engine_set_trace() */
    GString *text;
    uint64_t next_id;
} RecLog;

void rec_log_init(RecLog *log);
void rec_log_clear(RecLog *log);
/* Appends a line of the test's own (e.g. "done @15") to the log. */
void rec_log_note(RecLog *log, const char *fmt, ...) G_GNUC_PRINTF(2, 3);

#endif
