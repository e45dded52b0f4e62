/* SPDX-License-Identifier: BSD-3-Clause */
/* A command's independent output jobs on a few threads (cli_jobs_run in
 * cli.h). Each job mostly waits for a child (gnuplot, dot), so two
 * threads halve the time of a run's figures on two cores. */
#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

#include "cli.h"

int cli_threads(void)
{
  return sysconf(_SC_NPROCESSORS_ONLN) > 1 ? 2 : 1;
}

typedef struct jobs {
  cli_outdir *od;
  const cli_job *job;
  size_t n;
  fb_err *errs; /* one per job */
  int *rc;      /* one per job; -1 not run */
  size_t next;  /* the next job to start, under lock */
  int failed;   /* a job has failed: start no more */
  pthread_mutex_t lock;
} jobs;

/* Takes the next job's index, or n when none is left to start. */
static size_t take(jobs *j)
{
  pthread_mutex_lock(&j->lock);
  const size_t i = j->failed || cli_interrupted() ? j->n : j->next;
  if (i < j->n)
    ++j->next;
  pthread_mutex_unlock(&j->lock);
  return i;
}

static void *work(void *arg)
{
  jobs *j = arg;
  for (size_t i = take(j); i < j->n; i = take(j)) {
    fb_err_clear(&j->errs[i]);
    j->rc[i] = j->job[i].run(j->od, j->job[i].ctx, &j->errs[i]);
    if (j->rc[i] != FB_OK) {
      pthread_mutex_lock(&j->lock);
      j->failed = 1;
      pthread_mutex_unlock(&j->lock);
    }
  }
  return NULL;
}

int cli_jobs_run(cli_outdir *od, const cli_job *job, size_t n, fb_err *err)
{
  if (n == 0)
    return FB_OK;
  jobs j = {od,
            job,
            n,
            calloc(n, sizeof *j.errs),
            malloc(n * sizeof *j.rc),
            0,
            0,
            PTHREAD_MUTEX_INITIALIZER};
  if (!j.errs || !j.rc) {
    free(j.errs);
    free(j.rc);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  for (size_t i = 0; i < n; ++i)
    j.rc[i] = -1;
  /* This thread works too; the others only where there are CPUs for them. */
  pthread_t helper;
  const int started =
      cli_threads() > 1 && n > 1 && pthread_create(&helper, NULL, work, &j) == 0;
  work(&j);
  if (started)
    pthread_join(helper, NULL);
  /* The first failure in the jobs' order, so that the message does not
   * depend on which thread came first; an interruption otherwise. */
  int rc = FB_OK;
  for (size_t i = 0; i < n && rc == FB_OK; ++i)
    if (j.rc[i] > 0) {
      *err = j.errs[i];
      rc = j.rc[i];
    }
  if (rc == FB_OK)
    rc = cli_check_interrupt(err);
  free(j.errs);
  free(j.rc);
  pthread_mutex_destroy(&j.lock);
  return rc;
}
