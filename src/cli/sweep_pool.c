/* SPDX-License-Identifier: BSD-3-Clause */
/* Who runs which case of a sweep, and what happens when one finishes
 * (sweep.h). Cases are handed out one at a time in grid order, to
 * whichever thread (or MPI rank) asks next, so long and short cases
 * balance; a finished case goes to the journal and to the progress line
 * under one lock. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "sweep.h"

void sweep_pool_init(sweep_pool *p, const sweep_args *a, sweep_case *cases,
                     sweep_journal *journal)
{
  *p = (sweep_pool){.a = a, .cases = cases, .journal = journal};
  pthread_mutex_init(&p->lock, NULL);
  fb_err_clear(&p->journal_err);
}

void sweep_pool_destroy(sweep_pool *p)
{
  pthread_mutex_destroy(&p->lock);
}

int sweep_pool_take(sweep_pool *p, size_t *i)
{
  pthread_mutex_lock(&p->lock);
  while (p->next < p->a->ncases && p->cases[p->next].done)
    ++p->next;
  /* Once the journal cannot be written, a case run now would be lost to
   * --resume: none is started. */
  const int got = p->next < p->a->ncases && !cli_interrupted() && p->journal_rc == FB_OK;
  if (got)
    *i = p->next++;
  pthread_mutex_unlock(&p->lock);
  return got;
}

/* "flexbond sweep: case 3/12 (speed_kmh=15): ok, 1713 steps, 0.015 s". */
static void report_case(const sweep_pool *p, size_t i)
{
  const sweep_case *c = &p->cases[i];
  char label[512], where[32] = "";
  sweep_case_label(p->a, i, 0, label, sizeof label);
  if (p->a->mpi)
    snprintf(where, sizeof where, " on rank %d", c->rank);
  if (c->status == FB_OK)
    cli_say("flexbond sweep: case %zu/%zu (%s): ok%s, %.0f steps, %.3g s", i + 1, p->a->ncases,
            label, where, c->metric[sweep_metric_other(p->a, M_SOLVER_STEPS)], c->wall_seconds);
  else
    cli_say("flexbond sweep: case %zu/%zu (%s): failed%s: %s", i + 1, p->a->ncases, label,
            where, c->error ? c->error : "out of memory");
}

void sweep_pool_finish(sweep_pool *p, size_t i)
{
  sweep_case *c = &p->cases[i];
  pthread_mutex_lock(&p->lock);
  /* An interrupted case has not run: it stays to be resumed. */
  if (c->status == FB_EINTR) {
    free(c->error);
    c->error = NULL;
  } else {
    c->done = 1;
    ++p->finished;
    if (p->journal && p->journal_rc == FB_OK)
      p->journal_rc = sweep_journal_append(p->journal, i, c, &p->journal_err);
    if (!p->a->quiet)
      report_case(p, i);
  }
  pthread_mutex_unlock(&p->lock);
}

void *sweep_pool_worker(void *pool)
{
  sweep_pool *p = pool;
  size_t i;
  while (sweep_pool_take(p, &i)) {
    sweep_run_case(p->a, i, &p->cases[i]);
    sweep_pool_finish(p, i);
  }
  return NULL;
}

void sweep_pool_run(sweep_pool *p, size_t jobs)
{
  size_t left = 0;
  for (size_t i = 0; i < p->a->ncases; ++i)
    left += !p->cases[i].done;
  const size_t nthreads = jobs < left ? jobs : left;
  if (nthreads == 0)
    return;
  /* This thread is one of them; if a thread cannot be started, the
   * others do its share. */
  pthread_t *threads = nthreads > 1 ? malloc((nthreads - 1) * sizeof *threads) : NULL;
  size_t started = 0;
  while (threads && started + 1 < nthreads &&
         pthread_create(&threads[started], NULL, sweep_pool_worker, p) == 0)
    ++started;
  sweep_pool_worker(p);
  for (size_t t = 0; t < started; ++t)
    pthread_join(threads[t], NULL);
  free(threads);
}
