/* thread_team.c — gb_thread_team_run and its barrier (thread_team.h). */
#include "thread_team.h"

#include <pthread.h>
#include <sched.h>

#include "progress.h"

enum { MAX_THREADS = 64 };

/* How long a thread at a barrier spins before it sleeps: about the
 * imbalance of a collapse's phases, far shorter than a phase one thread
 * does alone. Waking a sleeping thread costs tens of microseconds in a
 * virtual machine (an interrupt between processors). The spin yields the
 * processor at each turn, so that on a loaded machine it does not keep a
 * thread of its own team waiting. */
static const double SPIN_SECONDS = 50e-6;

struct gb_thread_team {
    pthread_mutex_t mutex;
    pthread_cond_t changed;     /* started or generation changed */
    gb_team_function function;
    void *context;
    int thread_count;           /* final once started is set */
    int started;
    unsigned arrived;           /* threads at the barrier (atomic) */
    unsigned generation;        /* barriers passed (atomic; changed under mutex) */
};

typedef struct member {
    gb_thread_team *team;
    int thread;
} member;

/* A started thread waits until the team's size is known. */
static void *run_member(void *argument)
{
    member *m = argument;
    gb_thread_team *team = m->team;
    pthread_mutex_lock(&team->mutex);
    while (!team->started)
        pthread_cond_wait(&team->changed, &team->mutex);
    pthread_mutex_unlock(&team->mutex);
    team->function(team->context, team, m->thread, team->thread_count);
    return NULL;
}

void gb_thread_team_run(gb_team_function function, void *context, int thread_count)
{
    if (thread_count < 1)
        thread_count = 1;
    if (thread_count > MAX_THREADS)
        thread_count = MAX_THREADS;
    gb_thread_team team = {.function = function, .context = context};
    pthread_mutex_init(&team.mutex, NULL);
    pthread_cond_init(&team.changed, NULL);
    pthread_t threads[MAX_THREADS];
    member members[MAX_THREADS];
    int count = 1;
    for (int t = 1; t < thread_count; ++t) {
        members[count] = (member){&team, count};
        if (pthread_create(&threads[count], NULL, run_member, &members[count]) == 0)
            ++count;
    }
    pthread_mutex_lock(&team.mutex);
    team.thread_count = count;
    team.started = 1;
    pthread_cond_broadcast(&team.changed);
    pthread_mutex_unlock(&team.mutex);
    function(context, &team, 0, count);
    for (int t = 1; t < count; ++t)
        pthread_join(threads[t], NULL);
    pthread_cond_destroy(&team.changed);
    pthread_mutex_destroy(&team.mutex);
}

static void wait_at_barrier(gb_thread_team *team, double spin_seconds)
{
    if (team->thread_count == 1)
        return;
    unsigned generation = __atomic_load_n(&team->generation, __ATOMIC_ACQUIRE);
    if (__atomic_add_fetch(&team->arrived, 1, __ATOMIC_ACQ_REL) ==
        (unsigned)team->thread_count) {
        /* the last to arrive opens the barrier: none can arrive at the next
         * one before it sees the new generation, so arrived is reset first */
        __atomic_store_n(&team->arrived, 0, __ATOMIC_RELAXED);
        pthread_mutex_lock(&team->mutex);
        __atomic_store_n(&team->generation, generation + 1, __ATOMIC_RELEASE);
        pthread_cond_broadcast(&team->changed);
        pthread_mutex_unlock(&team->mutex);
        return;
    }
    double give_up = 0.0;
    for (unsigned spin = 0; spin_seconds > 0.0; ++spin) {
        if (__atomic_load_n(&team->generation, __ATOMIC_ACQUIRE) != generation)
            return;
        sched_yield();
        if (spin % 16 == 0) {
            double now = gb_seconds();
            if (!give_up)
                give_up = now + spin_seconds;
            else if (now > give_up)
                break;
        }
    }
    pthread_mutex_lock(&team->mutex);
    while (__atomic_load_n(&team->generation, __ATOMIC_ACQUIRE) == generation)
        pthread_cond_wait(&team->changed, &team->mutex);
    pthread_mutex_unlock(&team->mutex);
}

void gb_thread_team_wait(gb_thread_team *team)
{
    wait_at_barrier(team, SPIN_SECONDS);
}

void gb_thread_team_wait_long(gb_thread_team *team)
{
    wait_at_barrier(team, 0.0);
}
