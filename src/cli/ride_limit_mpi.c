/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond ride-limit across MPI ranks (ride_limit.h; docs/ride-limit.md,
 * docs/cluster.md).
 *
 * Rank 0 searches (fb_study_ride_limit); each round's runs not yet done
 * are handed to the other ranks one at a time, the next when a rank's
 * result comes back, and rank 0 runs runs itself on a thread that takes
 * them from the same queue. Every run is made by the same code on every
 * rank (rl_run_round: the scenario read with the value, the speed and its
 * end, simulated, measured) and recorded on rank 0 (rl_record: journal,
 * progress), so ride_limit.csv is the one a single machine writes. The
 * job's set-up, agreement and end are sweep's (sweep_mpi.c).
 *
 * Messages (tag: content): RL_TAG_RUN: a run_msg, to a rank; RL_TAG_STOP:
 * nothing, to a rank; RL_TAG_DONE: from a rank, a done_msg up to its
 * error message's NUL. The ranks are assumed to share one binary
 * representation of integers and doubles (one kind of node). */
#include <math.h>
#include <mpi.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "ride_limit.h"
#include "sweep.h"

enum { RL_TAG_RUN = 11, RL_TAG_STOP, RL_TAG_DONE };

typedef struct run_msg {
  int32_t sys;
  uint64_t value;
  double speed; /* m/s */
} run_msg;

typedef struct done_msg {
  run_msg run;
  int32_t status;
  double metric, wall_seconds;
  char error[FB_ERR_MSG_MAX]; /* "" when ok */
} done_msg;

/* A round's runs, taken in order by the ranks and rank 0's thread. */
typedef struct round_queue {
  rl_args *a;
  const int *sys;
  const size_t *value;
  const double *speed;
  size_t n, next;
  pthread_mutex_t lock;
  int rc; /* the local thread's first failure */
  fb_err err;
} round_queue;

/* The next run into *i: 1, or 0 when none is left or the study was
 * interrupted. */
static int take(round_queue *q, size_t *i)
{
  pthread_mutex_lock(&q->lock);
  const int got = q->next < q->n && !cli_interrupted() && q->rc == FB_OK;
  if (got)
    *i = q->next++;
  pthread_mutex_unlock(&q->lock);
  return got;
}

/* Rank 0's own runs, one at a time, on one thread. */
static void *local_worker(void *arg)
{
  round_queue *q = arg;
  size_t i;
  fb_err err;
  while (take(q, &i)) {
    const int rc = rl_run_round(q->a, q->sys[i], &q->value[i], &q->speed[i], 1, &err);
    if (rc != FB_OK) {
      pthread_mutex_lock(&q->lock);
      if (q->rc == FB_OK) {
        q->rc = rc;
        q->err = err;
      }
      pthread_mutex_unlock(&q->lock);
    }
  }
  return NULL;
}

/* Gives rank r the queue's next run; 1 if it got one. */
static int hand_out(round_queue *q, int r)
{
  size_t i;
  if (!take(q, &i))
    return 0;
  const run_msg m = {q->sys[i], q->value[i], q->speed[i]};
  MPI_Send(&m, (int)sizeof m, MPI_BYTE, r, RL_TAG_RUN, MPI_COMM_WORLD);
  return 1;
}

/* Receives the result rank source sent and records it. */
static int receive(rl_args *a, int source, fb_err *err)
{
  done_msg msg;
  MPI_Status st;
  MPI_Recv(&msg, (int)sizeof msg, MPI_BYTE, source, RL_TAG_DONE, MPI_COMM_WORLD, &st);
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  const size_t fixed = offsetof(done_msg, error);
  if (count < 0 || (size_t)count <= fixed || msg.error[(size_t)count - fixed - 1] != '\0' ||
      msg.run.sys < 0 || (size_t)msg.run.sys >= a->nsystems || msg.run.value >= a->nvalues)
    return fb_err_set(err, FB_EIO, "rank %d sent a malformed result", source);
  if (msg.status == FB_EINTR) /* stopped there: not done, not recorded */
    return FB_EINTR;
  const rl_done d = {.sys = msg.run.sys,
                     .value = (size_t)msg.run.value,
                     .speed = msg.run.speed,
                     .status = msg.status,
                     .metric = msg.metric,
                     .wall_seconds = msg.wall_seconds,
                     .error = msg.error[0] ? msg.error : NULL};
  return rl_record(a, &d, source, err);
}

int rl_mpi_round(rl_args *a, const int *sys, const size_t *value, const double *speed, size_t n,
                 fb_err *err)
{
  round_queue q = {.a = a, .sys = sys, .value = value, .speed = speed, .n = n, .rc = FB_OK};
  pthread_mutex_init(&q.lock, NULL);
  fb_err_clear(&q.err);
  pthread_t local;
  const int threaded = pthread_create(&local, NULL, local_worker, &q) == 0;
  int busy = 0, rc = FB_OK;
  for (int r = 1; r < a->mpi_size; ++r)
    busy += hand_out(&q, r);
  while (busy > 0) {
    const int source = sweep_mpi_wait(RL_TAG_DONE); /* polled: sweep_mpi.c says why */
    fb_err got;
    const int r = receive(a, source, &got);
    if (r != FB_OK && rc == FB_OK) {
      rc = r;
      *err = got;
    }
    --busy;
    if (rc == FB_OK)
      busy += hand_out(&q, source);
  }
  if (threaded)
    pthread_join(local, NULL);
  else
    local_worker(&q);
  if (rc == FB_OK && q.rc != FB_OK) {
    rc = q.rc;
    *err = q.err;
  }
  pthread_mutex_destroy(&q.lock);
  if (rc == FB_OK || rc == FB_EINTR)
    rc = cli_check_interrupt(err) != FB_OK ? FB_EINTR : rc;
  return rc;
}

void rl_mpi_work(rl_args *a)
{
  for (;;) {
    run_msg m;
    MPI_Status st;
    MPI_Recv(&m, (int)sizeof m, MPI_BYTE, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    if (st.MPI_TAG != RL_TAG_RUN)
      break;
    done_msg msg = {.run = m, .status = FB_EIO, .metric = NAN, .wall_seconds = NAN};
    fb_err err;
    fb_err_clear(&err);
    const size_t v = (size_t)m.value;
    const double speed = m.speed;
    int rc = m.sys >= 0 && (size_t)m.sys < a->nsystems && v < a->nvalues
                 ? rl_run_round(a, m.sys, &v, &speed, 1, &err)
                 : fb_err_set(&err, FB_EIO, "rank 0 sent a malformed run");
    const rl_done *d = rc == FB_OK ? rl_find_done(a, m.sys, v, speed) : NULL;
    if (d) {
      msg.status = d->status;
      msg.metric = d->metric;
      msg.wall_seconds = d->wall_seconds;
      snprintf(msg.error, sizeof msg.error, "%s", d->error ? d->error : "");
    } else {
      msg.status = rc == FB_OK ? FB_EINTR : rc;
      snprintf(msg.error, sizeof msg.error, "%s", err.msg);
    }
    const size_t size = offsetof(done_msg, error) + strlen(msg.error) + 1;
    MPI_Send(&msg, (int)size, MPI_BYTE, 0, RL_TAG_DONE, MPI_COMM_WORLD);
  }
}

void rl_mpi_stop(int size)
{
  for (int r = 1; r < size; ++r)
    MPI_Send(NULL, 0, MPI_BYTE, r, RL_TAG_STOP, MPI_COMM_WORLD);
}
