/* Assembly of the vehicle from its fragments, the paper's seven outputs,
 * and the simulation protocol (see flexbond/vehicle.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"

static const char *const output_names[FB_NOUTPUTS] = {
    "tire_force_LF",  "spring_defl_RF", "torsion",      "driver_acc",
    "shock_power_LM", "tire_defl_RM",   "tire_power_LR"};
static const char *const output_units[FB_NOUTPUTS] = {"N", "m", "rad", "m/s^2", "W", "m", "W"};

const char *fb_vehicle_output_name(int k)
{
  return k >= 0 && k < FB_NOUTPUTS ? output_names[k] : NULL;
}

const char *fb_vehicle_output_unit(int k)
{
  return k >= 0 && k < FB_NOUTPUTS ? output_units[k] : NULL;
}

/* Adopts a fragment built by a constructor under instance name inst. */
static int adopt(fb_bg *bg, int rc, fb_bg **frag, const char *inst, fb_err *err)
{
  if (rc) {
    fb_err_prefix(err, "%s: ", inst);
    return rc;
  }
  return fb_bg_adopt(bg, frag, inst, err);
}

/* The fragments around the hull and the bonds between them. */
static int add_subsystems(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  fb_bg *frag = NULL;
  int rc =
      adopt(bg, fb_vehicle_mount(&s->driver, s->gravity, &frag, err), &frag, "driver", err);
  if (!rc)
    rc = adopt(bg, fb_vehicle_mount(&s->engine, s->gravity, &frag, err), &frag, "engine", err);
  for (int c = 0; !rc && c < FB_NCORNERS; ++c) {
    char inst[16];
    snprintf(inst, sizeof inst, "susp_%s", fb_corner_name(c));
    rc = adopt(bg, fb_vehicle_corner(&s->corner[c], s->gravity, &frag, err), &frag, inst, err);
  }
  if (!rc)
    rc = adopt(bg, fb_vehicle_road(s, &frag, err), &frag, "road", err);
  if (!rc)
    rc = adopt(bg, fb_vehicle_load(s, &frag, err), &frag, "load", err);
  /* The horizontal line of Fig. 5: eight scalar bonds into one multibond. */
  const size_t ones[FB_NATTACH] = {1, 1, 1, 1, 1, 1, 1, 1};
  if (!rc)
    rc = fb_bg_add_composite(bg, "attach", FB_NATTACH, ones, err);
  for (int c = 0; !rc && c < FB_NATTACH; ++c) {
    char from[32], to[32];
    const char *inst = c == FB_ATTACH_DRIVER   ? "driver"
                       : c == FB_ATTACH_ENGINE ? "engine"
                                               : NULL;
    if (inst)
      snprintf(from, sizeof from, "%s.hull", inst);
    else
      snprintf(from, sizeof from, "susp_%s.hull", fb_corner_name(c));
    snprintf(to, sizeof to, "attach.%d", c + 1);
    rc = fb_bg_connect(bg, NULL, from, to, err);
    if (!rc && !inst) {
      char road[32], wheel[32];
      snprintf(road, sizeof road, "road.%s", fb_corner_name(c));
      snprintf(wheel, sizeof wheel, "susp_%s.road", fb_corner_name(c));
      rc = fb_bg_connect(bg, NULL, road, wheel, err);
    }
  }
  if (!rc)
    rc = fb_bg_connect(bg, "b_attach", "attach.whole", "hull.attach", err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_load", "load.load", "hull.load", err);
  return rc;
}

void fb_vehicle_probes_free(fb_probe_spec **probes, size_t nprobes)
{
  if (!probes || !*probes)
    return;
  for (size_t i = 0; i < nprobes; ++i) {
    free((char *)(*probes)[i].target);
    free((double *)(*probes)[i].weights);
  }
  free(*probes);
  *probes = NULL;
}

/* The seven outputs as probes on the assembled graph (targets owned). */
static int make_probes(const fb_scenario *s, const fb_hull *hull, fb_probe_spec **out,
                       fb_err *err)
{
  fb_probe_spec *p = calloc(FB_NOUTPUTS, sizeof *p);
  if (!p)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  const struct {
    fb_probe_kind kind;
    const char *target;
  } spec[FB_NOUTPUTS] = {
      {FB_PROBE_EFFORT, "susp_LF.b_tire"},
      {FB_PROBE_STATE, "susp_RF.spring"},
      {hull->torsion_kind, NULL},
      {FB_PROBE_EFFORT, "driver.b_mass"},
      {FB_PROBE_POWER, "susp_LM.b_damper"},
      {FB_PROBE_STATE, "susp_RM.tire_spring"},
      {FB_PROBE_POWER, "susp_LR.b_tire_damper"},
  };
  int rc = FB_OK;
  for (int k = 0; k < FB_NOUTPUTS; ++k) {
    p[k].name = output_names[k];
    p[k].kind = spec[k].kind;
    p[k].component = -1;
    p[k].gain = 1.0;
    p[k].unit = output_units[k];
    char target[256];
    snprintf(target, sizeof target, "%s%s", spec[k].target ? "" : "hull.",
             spec[k].target ? spec[k].target : hull->torsion_target);
    p[k].target = fb_strdup(target);
    if (!p[k].target)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  /* Driver acceleration: the effort on the driver's mass over the mass
   * (the paper's gain block 1/m on e7). */
  p[3].gain = 1.0 / s->driver.mass;
  p[2].integrate = hull->torsion_integrate;
  p[2].nweights = hull->ntorsion;
  double *w = malloc(hull->ntorsion * sizeof *w);
  if (!w)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  else
    memcpy(w, hull->torsion_weights, hull->ntorsion * sizeof *w);
  p[2].weights = w;
  if (rc) {
    fb_vehicle_probes_free(&p, FB_NOUTPUTS);
    return rc;
  }
  *out = p;
  return FB_OK;
}

int fb_vehicle_assemble(const fb_scenario *s, fb_hull **hullp, fb_bg **out,
                        fb_probe_spec **probes, size_t *nprobes, fb_err *err)
{
  *out = NULL;
  *probes = NULL;
  *nprobes = 0;
  fb_hull *hull = *hullp;
  *hullp = NULL;
  fb_bg *bg = NULL;
  int rc = make_probes(s, hull, probes, err);
  if (!rc)
    rc = fb_bg_new(s->name ? s->name : "vehicle", &bg, err);
  if (!rc)
    rc = fb_bg_adopt(bg, &hull->graph, "hull", err);
  if (!rc)
    rc = add_subsystems(s, bg, err);
  fb_hull_free(&hull);
  if (rc) {
    fb_vehicle_probes_free(probes, FB_NOUTPUTS);
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  *nprobes = FB_NOUTPUTS;
  return FB_OK;
}

/* The six tires' normal reactions (compression positive), appended after
 * the seven outputs when contact is asked for: probes into cp (names and
 * targets in the caller's buffers). */
static void contact_probes(fb_probe_spec *cp, char (*targets)[32])
{
  static const char *const names[FB_NCORNERS] = {"contact_force_LF", "contact_force_RF",
                                                 "contact_force_LM", "contact_force_RM",
                                                 "contact_force_LR", "contact_force_RR"};
  for (int c = 0; c < FB_NCORNERS; ++c) {
    snprintf(targets[c], sizeof targets[c], "susp_%s.b_tire", fb_corner_name(c));
    cp[c] = (fb_probe_spec){names[c], FB_PROBE_EFFORT, targets[c], -1, 0, 1.0, "N", NULL, 0};
  }
}

/* fb_vehicle_build, with the contact forces as extra outputs if asked. */
static int vehicle_build(const fb_scenario *s, fb_system sys, int contact, fb_bg **graph,
                         fb_bd **bd, fb_err *err)
{
  *graph = NULL;
  *bd = NULL;
  fb_hull *hull = NULL;
  fb_fe_hull *fe = NULL;
  fb_probe_spec *probes = NULL, all[FB_NOUTPUTS + FB_NCORNERS];
  size_t nprobes = 0;
  int rc = fb_scenario_check(s, err);
  /* The only difference between System 1 and System 2 is this fragment. */
  if (!rc && sys == FB_SYSTEM_FLEXIBLE) {
    rc = fb_vehicle_fe_hull(s, &fe, err);
    if (!rc)
      rc = fb_vehicle_flexible_hull(s, fe, &hull, err);
    fb_fe_hull_free(&fe);
  } else if (!rc) {
    rc = fb_vehicle_rigid_hull(s, &hull, err);
  }
  if (!rc)
    rc = fb_vehicle_assemble(s, &hull, graph, &probes, &nprobes, err);
  if (!rc) {
    char targets[FB_NCORNERS][32];
    memcpy(all, probes, nprobes * sizeof *all);
    contact_probes(all + nprobes, targets);
    rc = fb_bd_build(*graph, all, nprobes + (contact ? FB_NCORNERS : 0), bd, err);
  }
  fb_vehicle_probes_free(&probes, nprobes);
  fb_hull_free(&hull);
  if (rc)
    fb_bg_free(graph);
  return rc;
}

int fb_vehicle_build(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_bd **bd,
                     fb_err *err)
{
  return vehicle_build(s, sys, 0, graph, bd, err);
}

int fb_vehicle_graph(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_probe_spec **probes,
                     size_t *nprobes, fb_err *err)
{
  *graph = NULL;
  *probes = NULL;
  *nprobes = 0;
  fb_hull *hull = NULL;
  fb_fe_hull *fe = NULL;
  fb_probe_spec *outputs = NULL;
  size_t nout = 0;
  int rc = fb_scenario_check(s, err);
  if (!rc && sys == FB_SYSTEM_FLEXIBLE) {
    rc = fb_vehicle_fe_hull(s, &fe, err);
    if (!rc)
      rc = fb_vehicle_flexible_hull(s, fe, &hull, err);
    fb_fe_hull_free(&fe);
  } else if (!rc) {
    rc = fb_vehicle_rigid_hull(s, &hull, err);
  }
  if (!rc)
    rc = fb_vehicle_assemble(s, &hull, graph, &outputs, &nout, err);
  fb_hull_free(&hull);
  fb_probe_spec *all = rc ? NULL : calloc(nout + FB_NCORNERS, sizeof *all);
  if (!rc && !all)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    char targets[FB_NCORNERS][32];
    memcpy(all, outputs, nout * sizeof *all);
    free(outputs); /* the strings moved to all */
    outputs = NULL;
    contact_probes(all + nout, targets);
    for (size_t k = nout; !rc && k < nout + FB_NCORNERS; ++k) {
      all[k].target = fb_strdup(all[k].target);
      if (!all[k].target)
        rc = fb_err_set(err, FB_ENOMEM, "out of memory");
    }
    *probes = all;
    *nprobes = nout + FB_NCORNERS;
  }
  fb_vehicle_probes_free(&outputs, nout);
  if (rc) {
    fb_vehicle_probes_free(probes, *nprobes);
    *nprobes = 0;
    fb_bg_free(graph);
  }
  return rc;
}

void fb_vehicle_sim_opts(const fb_scenario *s, fb_sim_opts *o)
{
  fb_sim_opts_default(o);
  o->t_end = s->t_end;
  o->rtol = s->rtol;
  o->atol = s->atol;
  o->max_step = s->max_step;
  o->max_steps = s->max_steps;
  o->sample_rate = s->sample_rate;
}

int fb_vehicle_simulate(const fb_scenario *s, fb_system sys, fb_result **out, fb_err *err)
{
  return fb_vehicle_simulate_progress(s, sys, NULL, NULL, out, err);
}

int fb_vehicle_simulate_progress(const fb_scenario *s, fb_system sys, fb_sim_progress_fn fn,
                                 void *ctx, fb_result **out, fb_err *err)
{
  *out = NULL;
  fb_bg *graph = NULL;
  fb_bd *bd = NULL;
  int rc = vehicle_build(s, sys, 1, &graph, &bd, err);
  double *x0 = NULL;
  if (!rc) {
    size_t n = fb_bd_nstates(bd);
    x0 = calloc(n + 1, sizeof *x0);
    if (!x0)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  if (!rc && s->initial == FB_INITIAL_STATIC) {
    double *zero = calloc(fb_bd_nstates(bd) + 1, sizeof *zero);
    rc = zero ? fb_sim_static_state(bd, 0.0, zero, x0, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(zero);
  }
  fb_sim_opts o;
  fb_vehicle_sim_opts(s, &o);
  o.x0 = x0;
  o.progress = fn;
  o.progress_ctx = ctx;
  if (!rc)
    rc = fb_sim_run(bd, &o, out, err);
  free(x0);
  fb_bd_free(&bd);
  fb_bg_free(&graph);
  return rc;
}
