/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal: serial N_Vectors with optimised per-element operations
 * (src/sim/nvector.c says why). */
#ifndef FLEXBOND_SIM_NVECTOR_H
#define FLEXBOND_SIM_NVECTOR_H

#include <stddef.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

/* A serial vector of n entries (N_VNew_Serial) whose linear sum, scaling,
 * elementwise and norm operations are flexbond's, each giving the serial
 * module's values bit for bit; its clones share them. NULL when out of
 * memory. The caller frees it with N_VDestroy. */
N_Vector fb_sim_nvector_new(size_t n, SUNContext ctx);

#endif
