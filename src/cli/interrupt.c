/* SIGINT and SIGTERM (see cli_interrupt_install in cli.h). The flag is
 * the one piece of process-wide state of the program: a signal handler
 * can reach nothing else. It is a lock-free atomic, which C11 7.14.1.1p5
 * lets a handler touch, rather than a volatile sig_atomic_t, because the
 * threads of a sweep read it too (C11 5.1.2.4: a volatile read from
 * another thread is a data race). */
#include <signal.h>
#include <stdatomic.h>
#include <string.h>

#include "cli.h"

_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "a signal handler needs a lock-free atomic flag");

static atomic_int interrupted;

static void on_signal(int sig)
{
  (void)sig;
  atomic_store(&interrupted, 1);
}

int cli_interrupt_install(void)
{
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  /* The handler is removed once it has run: a second Ctrl-C stops the
   * program at once (the staged files are then left behind in DIR's
   * hidden staging directory; the previous results still stand). */
  sa.sa_flags = SA_RESETHAND;
  return sigaction(SIGINT, &sa, NULL) == 0 && sigaction(SIGTERM, &sa, NULL) == 0 ? 0 : -1;
}

int cli_interrupted(void)
{
  return atomic_load(&interrupted) != 0;
}

int cli_check_interrupt(fb_err *err)
{
  if (!cli_interrupted())
    return FB_OK;
  return fb_err_set(err, FB_EINTR, "interrupted (SIGINT or SIGTERM)");
}
