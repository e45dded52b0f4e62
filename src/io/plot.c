/* PNG figures of sampled results through gnuplot (http://gnuplot.info),
 * driven over a pipe with the data inline as a datablock. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "flexbond/io.h"

/* Writes s as a gnuplot single-quoted string ('' escapes a quote). */
static void put_quoted(FILE *fp, const char *s)
{
  fputc('\'', fp);
  for (; *s; ++s) {
    if (*s == '\'')
      fputc('\'', fp);
    fputc(*s, fp);
  }
  fputc('\'', fp);
}

static void write_script(FILE *gp, const fb_result *r, const size_t *cols, size_t ncols,
                         const char *title, const char *tmp_path)
{
  fputs("$data << EOD\n", gp);
  for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
    const double *row = fb_result_row(r, k);
    fprintf(gp, "%.10g", row[0]);
    for (size_t j = 0; j < ncols; ++j)
      fprintf(gp, " %.10g", row[cols[j] + 1]);
    fputc('\n', gp);
  }
  fputs("EOD\n", gp);
  size_t height = 220 * ncols + (title ? 40 : 0);
  fprintf(gp, "set terminal pngcairo size 900,%zu font 'Sans,9'\nset output ", height);
  put_quoted(gp, tmp_path);
  fputs("\nset termoption noenhanced\nset grid\nset key off\nset xlabel 't [s]'\n", gp);
  fprintf(gp, "set multiplot layout %zu,1", ncols);
  if (title) {
    fputs(" title ", gp);
    put_quoted(gp, title);
  }
  fputc('\n', gp);
  for (size_t j = 0; j < ncols; ++j) {
    const char *name = fb_result_col_name(r, cols[j] + 1);
    const char *unit = fb_result_col_unit(r, cols[j] + 1);
    size_t n = strlen(name) + strlen(unit) + 4;
    char *label = malloc(n);
    if (label) {
      snprintf(label, n, "%s [%s]", name, unit);
      fputs("set ylabel ", gp);
      put_quoted(gp, label);
      fputc('\n', gp);
      free(label);
    }
    fprintf(gp, "plot $data using 1:%zu with lines lw 1.5 lc rgb '#1f4e9a'\n", j + 2);
  }
  fputs("unset multiplot\nset output\n", gp);
}

int fb_plot_png(const fb_result *r, const size_t *cols, size_t ncols, const char *title,
                const char *path, fb_err *err)
{
  if (ncols == 0 || fb_result_nsamples(r) == 0)
    return fb_err_set(err, FB_EINVAL, "%s: nothing to plot", path);
  for (size_t j = 0; j < ncols; ++j)
    if (cols[j] + 1 >= fb_result_ncols(r))
      return fb_err_set(err, FB_EINVAL, "%s: no output column %zu", path, cols[j]);
  size_t n = strlen(path) + 32;
  char *tmp = malloc(n);
  if (!tmp)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  snprintf(tmp, n, "%s.tmp.%ld", path, (long)getpid());
  /* gnuplot's own messages go to its stderr; a non-zero exit is ours. */
  FILE *gp = popen("gnuplot", "w");
  if (!gp) {
    free(tmp);
    return fb_err_set(err, FB_EIO, "%s: cannot start gnuplot", path);
  }
  write_script(gp, r, cols, ncols, title, tmp);
  int status = pclose(gp);
  int rc = FB_OK;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    rc = fb_err_set(err, FB_EIO,
                    "%s: gnuplot failed (exit status %d); is gnuplot (Debian package "
                    "gnuplot-nox) installed?",
                    path, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  if (!rc && rename(tmp, path) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot rename the plot into place", path);
  if (rc)
    remove(tmp);
  free(tmp);
  return rc;
}
