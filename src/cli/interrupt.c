/* SIGINT and SIGTERM (see cli_interrupt_install in cli.h). The flag is
 * the one piece of process-wide state of the program: a signal handler
 * can reach nothing else (C11 7.14.1.1: it may only assign to a volatile
 * sig_atomic_t object). */
#include <signal.h>
#include <string.h>

#include "cli.h"

static volatile sig_atomic_t interrupted;

static void on_signal(int sig)
{
  (void)sig;
  interrupted = 1;
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
  return interrupted != 0;
}

int cli_check_interrupt(fb_err *err)
{
  if (!interrupted)
    return FB_OK;
  return fb_err_set(err, FB_EINTR, "interrupted (SIGINT or SIGTERM)");
}
