# scripts/gen-trace.awk — a synthetic replay trace for `make bench`
# (docs/traces.md): awk -v N=ACTIONS -f scripts/gen-trace.awk > T.pgt.
# 16 interleaved causal chains on the iPSC/2: a chain works on its
# processor, sends to the next one, whose arrival starts its next work.
# chains interleaved: chain c on processor c works, then sends to c+1
# (mod P), whose arrival makes the next step; N actions in all.
BEGIN {
    P = 16; print "pgsim-trace 1"; print "machine ipsc2"; print "procs " P; print "phase compute"
    print "at 0"; id = 0
    for (c = 0; c < P; c++) { print "w " c " 0 " (1000 + 37 * c) (id < N - P ? " +" : ""); last[c] = id++; at[c] = c; step[c] = 0 }
    while (id < N) {
        for (c = 0; c < P && id < N; c++) {
            print "on " last[c]
            p = at[c]
            if (step[c] % 2 == 0) { q = (p + 1) % P; print "s " p " " q " " (1024 + 64 * c) (id < N - P ? " +" : ""); at[c] = q }
            else print "w " p " 0 " (100000 + 371 * ((id * 7) % 13)) (id < N - P ? " +" : "")
            step[c]++; last[c] = id++
        }
    }
}
