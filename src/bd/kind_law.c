/* SPDX-License-Identifier: BSD-3-Clause */
/* Nonlinear law: out = phi(in_0, in_1, ...), an fb_law_ops of the graph.
 * Input 0 is the law's own input, the others its modulating values
 * (fb_bg_modulate). A law sees them as one vector xu (gathered into xu
 * unless there is one input); work holds its n x (n + m) Jacobian.
 * A switched law keeps its mode here. */
#include <stdlib.h>
#include <string.h>

#include "bd/kinds.h"

typedef struct law_content {
  const fb_law_ops *law; /* borrowed, as ctx */
  void *ctx;
  int mode;     /* active branch of a switched law */
  double *xu;   /* n + m gathered inputs */
  double *work; /* n x (n + m) Jacobian */
} law_content;

/* The components of all its inputs: n + m. */
static size_t law_width(const bd_block *b)
{
  size_t w = 0;
  for (size_t k = 0; k < b->nin; ++k)
    w += b->idim[k];
  return w;
}

/* The inputs of the block at the signals w, as its law sees them. */
static void law_input(const bd_block *b, const double *w, fb_law_in *in)
{
  const law_content *l = b->content;
  in->n = b->odim;
  in->m = law_width(b) - b->odim;
  in->mode = l->mode;
  if (b->nin == 1) {
    in->x = w + b->ioff[0];
    return;
  }
  for (size_t k = 0, c = 0; k < b->nin; c += b->idim[k++])
    memcpy(l->xu + c, w + b->ioff[k], b->idim[k] * sizeof *l->xu);
  in->x = l->xu;
}

static int law_eval(bd_block *b, double t, double *w)
{
  (void)t;
  const law_content *l = b->content;
  fb_law_in in;
  law_input(b, w, &in);
  return l->law->eval(l->ctx, &in, w + b->ooff);
}

/* The law's Jacobian into work; columns a law leaves alone are 0. */
static int law_jacobian(bd_block *b, const double *w)
{
  const law_content *l = b->content;
  fb_law_in in;
  law_input(b, w, &in);
  memset(l->work, 0, in.n * (in.n + in.m) * sizeof *l->work);
  return l->law->jacobian(l->ctx, &in, l->work);
}

static int law_jvp(bd_block *b, const double *w, double *dw)
{
  const law_content *l = b->content;
  const size_t n = b->odim;
  int rc = law_jacobian(b, w);
  if (rc)
    return rc;
  for (size_t i = 0; i < n; ++i)
    dw[b->ooff + i] = 0.0;
  for (size_t k = 0, c = 0; k < b->nin; ++k)
    for (size_t j = 0; j < b->idim[k]; ++j, ++c)
      for (size_t i = 0; i < n; ++i)
        dw[b->ooff + i] += l->work[c * n + i] * dw[b->ioff[k] + j];
  return 0;
}

static size_t law_nnz(const bd_block *b)
{
  return b->odim * (1 + law_width(b));
}

static int law_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  const law_content *l = b->content;
  const size_t n = b->odim;
  int rc = law_jacobian(b, w);
  if (rc) /* keep the pattern complete even when the values failed */
    memset(l->work, 0, n * law_width(b) * sizeof *l->work);
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_identity(&t, b->ooff, n);
  for (size_t k = 0, c = 0; k < b->nin; ++k)
    for (size_t j = 0; j < b->idim[k]; ++j, ++c)
      for (size_t i = 0; i < n; ++i)
        fb_bd_trip_put(&t, b->ooff + i, b->ioff[k] + j, -l->work[c * n + i], 0.0);
  return rc;
}

/* The own input has the output's size, each modulating input its
 * storage element's. */
static size_t law_input_dim(const bd_block *b, size_t k)
{
  return k == 0 ? b->odim : FB_NONE;
}

static int law_piecewise_linear(const bd_block *b)
{
  const law_content *l = b->content;
  return l->law->affine;
}

static size_t law_nguards(const bd_block *b)
{
  const law_content *l = b->content;
  return l->law->nguards;
}

static int law_guards(bd_block *b, const double *w, double *g)
{
  const law_content *l = b->content;
  fb_law_in in;
  law_input(b, w, &in);
  return l->law->guards(l->ctx, &in, g);
}

static int law_switch_mode(bd_block *b, const double *w, const int *sign, int *changed)
{
  law_content *l = b->content;
  fb_law_in in;
  law_input(b, w, &in);
  int mode = l->mode;
  int rc = l->law->switch_mode(l->ctx, &in, sign, &mode);
  if (!rc && mode != l->mode) {
    l->mode = mode;
    *changed = 1;
  }
  return rc;
}

static void law_free(void *content)
{
  law_content *l = content;
  if (!l)
    return;
  free(l->xu);
  free(l->work);
  free(l);
}

const bd_block_ops fb_bd_law_ops = {.kind = "law",
                                    .unit_rows = 1,
                                    .label_noun = "law",
                                    .eval = law_eval,
                                    .jvp = law_jvp,
                                    .nnz = law_nnz,
                                    .jac = law_jac,
                                    .free = law_free,
                                    .input_dim = law_input_dim,
                                    .piecewise_linear = law_piecewise_linear,
                                    .nguards = law_nguards,
                                    .guards = law_guards,
                                    .switch_mode = law_switch_mode};

int fb_bd_law_new(const fb_law_ops *law, void *ctx, size_t n, size_t m, bd_kind *out,
                  fb_err *err)
{
  law_content *l = calloc(1, sizeof *l);
  if (l) {
    l->law = law;
    l->ctx = ctx;
    l->work = malloc((n * (n + m) + 1) * sizeof *l->work);
    l->xu = malloc((n + m + 1) * sizeof *l->xu);
  }
  if (!l || !l->work || !l->xu) {
    law_free(l);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  out->ops = &fb_bd_law_ops;
  out->content = l;
  return FB_OK;
}
