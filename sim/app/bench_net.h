/* bench_net.h — `pgsim bench net`: network fidelities, speed against error
 * (bench_net.c).  argv[0] is "net"; returns the exit status. */
#ifndef PGSIM_APP_BENCH_NET_H
#define PGSIM_APP_BENCH_NET_H

int bench_net_main(int argc, char **argv);

#endif
