/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond sweep across MPI ranks (sweep.h; docs/cluster.md).
 *
 * Rank 0 coordinates: it hands each rank one case at a time, the next in
 * grid order, and the next again when that rank's result comes back, so
 * a slow case holds up no one else. It also runs cases itself, on one
 * thread that takes them from the same study (fb_study_sweep_run); its
 * main thread is the only one that calls MPI (MPI_THREAD_FUNNELED). The
 * study layer runs every case (fb_study_sweep_run_case, on whichever
 * rank); this file is only the transport: which case goes to which rank,
 * and its outcome back. Every result is recorded in rank 0's study
 * (fb_study_sweep_record, _finish: journal, progress), and rank 0 writes the
 * files, so sweep.csv is the same as a run on one machine: each case is
 * computed by the same code from the same inputs, and its metrics cross
 * the network as the bytes of the doubles.
 *
 * Messages (tag: content): SWEEP_TAG_CASE: the case's index (uint64_t),
 * to a rank; SWEEP_TAG_STOP: nothing, to a rank; SWEEP_TAG_RESULT: from
 * a rank, a result_msg up to its error message's NUL. A message is never
 * longer than a result_msg, so neither side allocates. The ranks are
 * assumed to share one binary representation of integers and doubles
 * (one kind of node). */
#include <fcntl.h>
#include <mpi.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "sweep.h"

enum { SWEEP_TAG_CASE = 1, SWEEP_TAG_STOP, SWEEP_TAG_RESULT };

typedef struct result_msg {
  uint64_t index;
  int32_t status;
  int32_t rank;
  double wall_seconds;
  double metric[SWEEP_MAX_METRICS];
  int32_t at_value;
  char error[FB_ERR_MSG_MAX]; /* "" when ok */
} result_msg;

int sweep_mpi_init(int *rank, int *size, fb_err *err)
{
  int provided = 0;
  if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return fb_err_set(err, FB_EIO, "MPI_Init_thread failed");
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    return fb_err_set(err, FB_EIO,
                      "this MPI library does not let a threaded program call it from its main "
                      "thread (MPI_THREAD_FUNNELED)");
  }
  return FB_OK;
}

int sweep_mpi_agree(int ok, uint64_t fingerprint, int *bad_rank)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  uint64_t first_fingerprint = fingerprint;
  MPI_Bcast(&first_fingerprint, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  ok = ok && fingerprint == first_fingerprint;
  /* The smallest failing rank; INT32_MAX when none failed. */
  int mine = ok ? INT32_MAX : rank, first = INT32_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  *bad_rank = first;
  return first != INT32_MAX;
}

int sweep_mpi_silence(int rank)
{
  if (rank == 0)
    return -1;
  fflush(stderr);
  const int saved = dup(STDERR_FILENO);
  const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null >= 0) {
    dup2(null, STDERR_FILENO);
    close(null);
  }
  return saved;
}

void sweep_mpi_unsilence(int saved)
{
  if (saved < 0)
    return;
  fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(saved);
}

/* Polled, not a blocking receive: OpenMPI spins in a blocking one and
 * would take a core from rank 0's own worker. The pause between polls
 * doubles from 50 us to 2 ms while nothing comes, so that a result waits
 * at most 2 ms (a case takes 10 ms and more) and an idle coordinator
 * wakes 500 times a second. */
int sweep_mpi_wait(int tag)
{
  long nap_ns = 50000;
  for (;;) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &flag, &st);
    if (flag)
      return st.MPI_SOURCE;
    const struct timespec nap = {0, nap_ns};
    nanosleep(&nap, NULL);
    nap_ns = nap_ns < 1000000 ? 2 * nap_ns : 2000000;
  }
}

int sweep_mpi_agreed(int rank, uint64_t fingerprint, const char *files, int *exit_code)
{
  int bad_rank = 0;
  if (!sweep_mpi_agree(*exit_code == CLI_EXIT_OK, fingerprint, &bad_rank))
    return 1;
  fb_err err;
  if (rank == 0 && *exit_code == CLI_EXIT_OK)
    *exit_code = cli_report(fb_err_set(&err, FB_EIO,
                                       "rank %d could not set the study up, or read %s (do all "
                                       "nodes see the same scenario and files at the same "
                                       "paths?)",
                                       bad_rank, files),
                            &err);
  return 0;
}

int sweep_mpi_go(int go)
{
  MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return go;
}

/* Gives rank r its next case, or tells it to stop; 1 if it got a case. */
static int hand_out(fb_study_sweep *sw, int r)
{
  size_t i;
  if (!fb_study_sweep_next(sw, &i)) {
    MPI_Send(NULL, 0, MPI_BYTE, r, SWEEP_TAG_STOP, MPI_COMM_WORLD);
    return 0;
  }
  const uint64_t index = i;
  MPI_Send(&index, 1, MPI_UINT64_T, r, SWEEP_TAG_CASE, MPI_COMM_WORLD);
  return 1;
}

/* Receives the result that rank source sent into the study; its case's
 * index, or SIZE_MAX for a malformed message (which only a rank of
 * another flexbond would send). */
static size_t receive_result(fb_study_sweep *sw, int source)
{
  result_msg msg;
  MPI_Status st;
  MPI_Recv(&msg, (int)sizeof msg, MPI_BYTE, source, SWEEP_TAG_RESULT, MPI_COMM_WORLD, &st);
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  const size_t fixed = offsetof(result_msg, error);
  if (count < 0 || (size_t)count <= fixed || msg.error[(size_t)count - fixed - 1] != '\0' ||
      msg.index >= fb_study_sweep_ncases(sw))
    return SIZE_MAX;
  const fb_study_sweep_case c = {.status = msg.status,
                                 .at_value = msg.at_value,
                                 .error = msg.error[0] ? msg.error : NULL,
                                 .metric = msg.metric,
                                 .wall_seconds = msg.wall_seconds,
                                 .worker = msg.rank};
  fb_study_sweep_record(sw, (size_t)msg.index, &c);
  return (size_t)msg.index;
}

/* Rank 0's own cases, on a thread of their own. */
typedef struct local_run {
  fb_study_sweep *sw;
  int rc;
  fb_err err;
} local_run;

static void *local_worker(void *arg)
{
  local_run *l = arg;
  l->rc = fb_study_sweep_run(l->sw, 1, &l->err);
  return NULL;
}

int sweep_mpi_coordinate(const sweep_args *a, int size, fb_err *err)
{
  local_run l = {.sw = a->study, .rc = FB_OK};
  fb_err_clear(&l.err);
  pthread_t local;
  const int threaded = pthread_create(&local, NULL, local_worker, &l) == 0;
  int busy = 0;
  for (int r = 1; r < size; ++r)
    busy += hand_out(a->study, r);
  while (busy > 0) {
    const int source = sweep_mpi_wait(SWEEP_TAG_RESULT);
    const size_t i = receive_result(a->study, source);
    /* A rank that was interrupted (its case is not done) runs no more. */
    const int stopped = i != SIZE_MAX && !fb_study_sweep_case_done(a->study, i);
    if (i != SIZE_MAX)
      fb_study_sweep_finish(a->study, i);
    --busy;
    if (stopped)
      MPI_Send(NULL, 0, MPI_BYTE, source, SWEEP_TAG_STOP, MPI_COMM_WORLD);
    else
      busy += hand_out(a->study, source);
  }
  /* Without a thread of its own (pthread_create failed), rank 0 runs
   * what is left itself. */
  if (threaded)
    pthread_join(local, NULL);
  else
    local_worker(&l);
  if (l.rc != FB_OK)
    *err = l.err;
  return l.rc;
}

/* Sends case i's outcome c (nmetrics of them) to rank 0: up to the error
 * message's NUL. */
static void send_result(size_t i, const fb_study_sweep_case *c, size_t nmetrics, int rank)
{
  result_msg msg = {.index = i,
                    .status = c->status,
                    .rank = rank,
                    .wall_seconds = c->wall_seconds,
                    .at_value = c->at_value};
  memcpy(msg.metric, c->metric, nmetrics * sizeof *msg.metric);
  /* A failed case without its message lost it to a failed allocation. */
  const char *error = c->error ? c->error : (c->status != FB_OK ? "out of memory" : "");
  snprintf(msg.error, sizeof msg.error, "%s", error);
  const size_t size = offsetof(result_msg, error) + strlen(msg.error) + 1;
  MPI_Send(&msg, (int)size, MPI_BYTE, 0, SWEEP_TAG_RESULT, MPI_COMM_WORLD);
}

void sweep_mpi_work(const sweep_args *a)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (;;) {
    uint64_t index = 0;
    MPI_Status st;
    MPI_Recv(&index, 1, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    if (st.MPI_TAG != SWEEP_TAG_CASE)
      break;
    fb_study_sweep_run_case(a->study, (size_t)index);
    fb_study_sweep_case c;
    fb_study_sweep_case_get(a->study, (size_t)index, &c);
    send_result((size_t)index, &c, a->nmetrics, rank);
  }
}

int sweep_mpi_finish(int exit_code)
{
  MPI_Bcast(&exit_code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return exit_code;
}
