/* SPDX-License-Identifier: BSD-3-Clause */
/* A model file's simulation (flexbond/model.h): one set-up for the
 * command's `sim` and the Python package, so both run the same diagram
 * from the same state. */
#include <stdlib.h>

#include "flexbond/model.h"

struct fb_model_sim {
  fb_bd *bd;  /* owned */
  double *x0; /* fb_bd_nstates(bd), owned */
};

int fb_model_sim_new(fb_model *m, fb_model_sim **out, fb_err *err)
{
  *out = NULL;
  fb_model_sim *ms = calloc(1, sizeof *ms);
  if (!ms)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a model's simulation");
  size_t nprobes = 0;
  const fb_probe_spec *probes = fb_model_probes(m, &nprobes);
  int rc = fb_bd_build(fb_model_graph(m), probes, nprobes, &ms->bd, err);
  fb_model_blame(m, err); /* a causality error: at its element's or bond's line */
  if (rc == FB_OK) {
    /* One more than the states, so that a stateless model allocates. */
    ms->x0 = malloc((fb_bd_nstates(ms->bd) + 1) * sizeof *ms->x0);
    rc = ms->x0 ? fb_model_initial_state(m, ms->bd, ms->x0, err)
                : fb_err_set(err, FB_ENOMEM, "out of memory for a model's initial state");
  }
  if (rc != FB_OK) {
    fb_model_sim_free(&ms);
    return rc;
  }
  *out = ms;
  return FB_OK;
}

void fb_model_sim_free(fb_model_sim **ms)
{
  if (!ms || !*ms)
    return;
  fb_bd_free(&(*ms)->bd);
  free((*ms)->x0);
  free(*ms);
  *ms = NULL;
}

const fb_bd *fb_model_sim_diagram(const fb_model_sim *ms)
{
  return ms->bd;
}

fb_sim_opts fb_model_sim_opts_with(const fb_model *m, double t_end, double rtol,
                                   double sample_rate)
{
  fb_sim_opts opts = *fb_model_sim_opts(m);
  if (t_end > 0)
    opts.t_end = t_end;
  if (rtol > 0)
    opts.rtol = rtol;
  if (sample_rate > 0)
    opts.sample_rate = sample_rate;
  fb_model_probes(m, &opts.noutputs);
  return opts;
}

int fb_model_sim_run(fb_model_sim *ms, const fb_sim_opts *opts, fb_result **res, fb_err *err)
{
  fb_sim_opts o = *opts;
  o.x0 = ms->x0;
  return fb_sim_run(ms->bd, &o, res, err);
}
