/* thread_team.h — a few threads that run one function in phases and meet
 * at a barrier between phases (pthreads): work split evenly, each phase
 * reading what every thread wrote in the one before (thin's collapse).
 *
 * Unlike gb_run_threads, whose threads never wait for each other, every
 * thread of a team must reach each barrier: so the team is as large as the
 * threads that could be started (at least the calling one, thread 0), and
 * the function is told that count. A thread waiting at a barrier spins for a
 * few microseconds, then sleeps, so that one thread working alone through a
 * long phase does not cost the others a core.
 *
 *   static void work(void *context, gb_thread_team *team, int thread, int count)
 *   {   ...phase 1, thread's share...; gb_thread_team_wait(team); ...phase 2...  }
 *   gb_thread_team_run(work, context, 2);
 *
 * The team lives for the one call; nothing is left allocated.
 */
#ifndef GB_THREAD_TEAM_H
#define GB_THREAD_TEAM_H

typedef struct gb_thread_team gb_thread_team;

typedef void (*gb_team_function)(void *context, gb_thread_team *team, int thread,
                                 int thread_count);

/* Calls function(context, team, t, count) on count threads at once, t = 0
 * on the calling thread, count the threads that could be started of the
 * thread_count asked for (at least 1); returns when all have returned. */
void gb_thread_team_run(gb_team_function function, void *context, int thread_count);

/* Returns once every thread of the team has called it: what any thread
 * wrote before it is visible to every thread after it. */
void gb_thread_team_wait(gb_thread_team *team);
/* The same barrier, for a thread that knows another has long work left
 * (one thread working alone): it sleeps at once, not spinning. */
void gb_thread_team_wait_long(gb_thread_team *team);

#endif
